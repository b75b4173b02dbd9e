//! Register-level sensor demo (filled in below).
use super::{State, NB};
use wearsim_core::Model;

/// Runs the demo.
pub fn run(_model: &Model, _seed: u64, _state: &mut Option<State<NB>>) {}
