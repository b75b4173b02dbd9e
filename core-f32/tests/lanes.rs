//! `core/tests/lanes.rs` in single precision (`Real = f32`): the same test source, run
//! against `wearsim-core-f32` (the lanes take the Hertz loads through the scalar
//! `f32` path with its cached inverse square roots).
extern crate wearsim_core_f32 as wearsim_core;

#[path = "../../core/tests/lanes.rs"]
mod lanes;
