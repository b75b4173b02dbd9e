//! MATLAB level-5 MAT-file reader and the CWRU bearing-data loader.
//!
//! # Why not the `matfile` crate
//!
//! `matfile` 0.5 was evaluated (source read, version 0.5.0) and not used, because on malformed
//! input it can panic or allocate without bound, which the readers of this crate must never do:
//!
//! * numeric matrices: `dimensions.iter().product::<i32>()` overflows (a panic with overflow
//!   checks on, e.g. in test builds) for large or hostile dimensions, and the product is then cast
//!   `as usize`, so negative dimensions turn into huge counts;
//! * `flags.class.numeric_data_type().unwrap()` on the class byte read from the file;
//! * `miCOMPRESSED` elements are inflated with `read_to_end` without any limit (a zlib bomb
//!   allocates until the process dies), and decoder errors are printed with `eprintln!`;
//! * every error is a `nom` `ErrorKind::Tag` without offset or reason, so a user cannot tell
//!   "truncated" from "unsupported"; it also pulls in `nom`, `libflate` and
//!   `enum-primitive-derive` for what is a few hundred lines of format.
//!
//! This module therefore implements the subset of the format the measured data needs
//! (MathWorks, "MAT-File Format", Level 5): the 128-byte header (either byte order, `IM` or
//! `MI`), `miMATRIX` elements of the numeric classes (double, single, int8..uint64; real part
//! only; complex arrays are reported as unsupported), small-data-element tags, `miCOMPRESSED`
//! (zlib, via `flate2`, inflated size capped at 1032 x the compressed size, the deflate maximum),
//! char, struct and cell arrays (read into a tree), and lists sparse and object arrays without
//! reading them. Every read is
//! bounds-checked against the buffer, sizes are checked against the file size before anything is
//! allocated, and no code path panics on any input (property-tested in `tests/integration/io_fuzz.rs`).
//!
//! # CWRU files
//!
//! [`read_cwru`] loads one channel of a Case Western Reserve University bearing-data file
//! (see `/work/shared/data/cwru/README.md`): variables `Xnnn_DE_time`, `Xnnn_FE_time`,
//! `Xnnn_BA_time` (N x 1 double, acceleration, assumed g) and `XnnnRPM` (1 x 1, rpm). Variables
//! are selected by suffix, preferring the one whose number matches the record number of the file
//! name (some CWRU files hold other records' variables too). The sample rate is not stored in the
//! files; it comes from the name (`12k_` = 12 kHz, `48k_` = 48 kHz, `normal_*` = 48 kHz) or from
//! the caller.
//!
//! # Layout and bounds
//!
//! [`v5`] parses the format's elements (with the per-file bounds of [`Budget`]), [`tree`]
//! reads files as MATLAB writes them (structs, cells, chars, every numeric class) as a tree of
//! named values, [`variables`] lists its top level flat (the one parse, seen as variables),
//! [`resolve`] recognises the layout (CWRU, MFPT, Paderborn, generic) and turns one channel into
//! a record with the file's metadata, [`cwru`] loads CWRU records by the original rules, and
//! [`fixture`] writes the small MAT files the tests use.

pub mod cwru;
pub mod fixture;
pub mod resolve;
pub mod tree;
pub mod v5;
pub mod variables;

pub use cwru::*;
pub use fixture::{mat5_bytes, mat5_compress, mat5_tree_bytes, FixtureValue};
pub use resolve::{read_mat_record, recognise, MatLayout};
pub use tree::{numeric_arrays, parse_mat_tree, read_mat_tree, ArrayInfo, MatNode, MatValue};
pub use v5::{Budget, MatClass, MAX_DECOMPRESSED_PER_FILE, MAX_SAMPLES_PER_FILE};
pub use variables::{list_mat_variables, parse_mat, read_mat, MatVariable};

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tree_tests;
