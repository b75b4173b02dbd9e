//! `core/tests/serde_config.rs` in single precision (`Real = f32`): the same test source, run
//! against `wearsim-core-f32` (with `--features serde`).
extern crate wearsim_core_f32 as wearsim_core;

#[path = "../../core/tests/serde_config.rs"]
mod serde_config;
