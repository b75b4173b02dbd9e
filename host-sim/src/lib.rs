//! wearsim host library: scenario configuration, the simulation runner, measurement
//! readers and writers, signal analysis, and the figures the `wearsim` command prints.
//!
//! Without the default `app` feature only the measurement readers and writers ([`io`],
//! [`capture`]), the signal analysis they use ([`analysis`]) and the bearing geometry
//! ([`geometry`]) are built, without the plotting, Parquet and command-line dependencies:
//! the fuzz targets (`host-sim/fuzz`) need only those, and building the rest with their
//! instrumentation took 5 of the fuzz step's 13 minutes in CI.
/// The version of the wearsim library (the workspace's), as stamped in sweep indexes
/// (`wearsim_version`) and reported by `wearsim --version` and Python's
/// `wearsim.__version__`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub mod analysis;
#[cfg(feature = "app")]
pub mod analyze;
#[cfg(feature = "app")]
pub mod cancel;
pub mod capture;
#[cfg(feature = "app")]
pub mod cmd;
#[cfg(feature = "app")]
pub mod config;
#[cfg(feature = "app")]
pub mod cwru_benchmark;
#[cfg(feature = "app")]
pub mod effects;
#[cfg(feature = "app")]
pub mod features;
#[cfg(feature = "app")]
pub mod gap;
pub mod geometry;
pub mod io;
#[cfg(feature = "app")]
pub mod kinematics;
#[cfg(feature = "app")]
pub mod lanes;
#[cfg(feature = "app")]
pub mod life;
#[cfg(feature = "app")]
pub mod plot;
#[cfg(feature = "app")]
pub mod resolvable;
#[cfg(feature = "app")]
pub mod simulate;
#[cfg(feature = "app")]
pub mod summary;
#[cfg(feature = "app")]
pub mod sweep;
