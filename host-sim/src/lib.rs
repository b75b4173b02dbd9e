//! wearsim host library: simulation front-end, measurement readers, signal analysis.
pub mod analysis;
pub mod io;
