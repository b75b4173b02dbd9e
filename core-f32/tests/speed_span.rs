//! `core/tests/speed_span.rs` in single precision (`Real = f32`): the same test source, run
//! against `wearsim-core-f32`.
extern crate wearsim_core_f32 as wearsim_core;

#[path = "../../core/tests/speed_span.rs"]
mod speed_span;
