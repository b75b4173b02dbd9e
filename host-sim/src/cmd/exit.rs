//! Exit codes of `wearsim`, decided here and nowhere else: 0 success; 2 bad input (an
//! argument, a configuration value, an unreadable or invalid input file: the message names
//! the field and its allowed range); 1 the run failed (I/O while writing, a numerical
//! failure). Errors are printed once, as `wearsim: error: <message>` on stderr.

use std::process::ExitCode;

/// Exit code of a bad input.
pub const BAD_INPUT: u8 = 2;
/// Exit code of a failed run.
pub const RUN_FAILED: u8 = 1;

/// An error with the process exit code it maps to.
#[derive(Debug)]
pub struct CliError {
    /// 1 = the run failed, 2 = bad input.
    pub code: u8,
    /// One-line message naming the offending field, file or argument.
    pub message: String,
}

impl CliError {
    /// Bad input (exit code 2).
    pub fn input(e: impl std::fmt::Display) -> Self {
        CliError {
            code: BAD_INPUT,
            message: e.to_string(),
        }
    }
    /// Run failure (exit code 1).
    pub fn run(e: impl std::fmt::Display) -> Self {
        CliError {
            code: RUN_FAILED,
            message: e.to_string(),
        }
    }
}

impl From<crate::plot::PlotError> for CliError {
    fn from(e: crate::plot::PlotError) -> Self {
        match e {
            crate::plot::PlotError::Folder { .. } => CliError::input(e),
            crate::plot::PlotError::Draw { .. } => CliError::run(e),
        }
    }
}

impl From<crate::analyze::AnalyzeError> for CliError {
    fn from(e: crate::analyze::AnalyzeError) -> Self {
        match e {
            crate::analyze::AnalyzeError::Input(m) => CliError::input(m),
            crate::analyze::AnalyzeError::Run(m) => CliError::run(m),
        }
    }
}

impl From<crate::gap::GapError> for CliError {
    fn from(e: crate::gap::GapError) -> Self {
        match e {
            crate::gap::GapError::Input(m) => CliError::input(m),
            crate::gap::GapError::Run(m) => CliError::run(m),
            crate::gap::GapError::Plot(p) => p.into(),
        }
    }
}

impl From<crate::capture::CaptureError> for CliError {
    fn from(e: crate::capture::CaptureError) -> Self {
        use crate::capture::CaptureError as E;
        match e {
            E::Input(_) | E::Stream(_) => CliError::input(e),
            E::Mismatch(_) | E::Write(_) => CliError::run(e),
        }
    }
}

/// Prints the error of a finished command, if any, and returns its exit code.
pub fn finish(result: Result<(), CliError>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError { code, message }) => {
            eprintln!("wearsim: error: {message}");
            ExitCode::from(code)
        }
    }
}

/// Prints a command-line parse result that is not a command (an error: exit 2; `--help`
/// or `--version`: exit 0).
pub fn usage(e: &clap::Error) -> ExitCode {
    let code = if e.use_stderr() { BAD_INPUT } else { 0 };
    let _ = e.print();
    ExitCode::from(code)
}
