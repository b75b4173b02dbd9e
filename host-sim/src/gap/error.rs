//! Errors of the gap diagnosis, classified for the command layer
//! ([`crate::cmd::exit`] maps them to exit codes).

/// Why a gap diagnosis or its report could not be done.
#[derive(Debug, thiserror::Error)]
pub enum GapError {
    /// Bad input: an argument, a record, its label or metadata, the output folder. The
    /// message names the field and what is allowed.
    #[error("{0}")]
    Input(String),
    /// The diagnosis or its report failed (a simulation, a fit, writing a file).
    #[error("{0}")]
    Run(String),
    /// A figure could not be written.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

impl GapError {
    /// Bad input.
    pub fn input(e: impl std::fmt::Display) -> Self {
        GapError::Input(e.to_string())
    }
    /// The run failed.
    pub fn run(e: impl std::fmt::Display) -> Self {
        GapError::Run(e.to_string())
    }
}
