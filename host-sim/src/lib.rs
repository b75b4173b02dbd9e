//! wearsim host library: scenario configuration, the simulation runner, measurement
//! readers and writers, signal analysis, and the figures the `wearsim` command prints.
pub mod analysis;
pub mod analyze;
pub mod capture;
pub mod cmd;
pub mod config;
pub mod cwru_benchmark;
pub mod effects;
pub mod features;
pub mod gap;
pub mod geometry;
pub mod io;
pub mod kinematics;
pub mod lanes;
pub mod life;
pub mod plot;
pub mod resolvable;
pub mod simulate;
pub mod summary;
pub mod sweep;
