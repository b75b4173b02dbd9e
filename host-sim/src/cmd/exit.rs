//! Exit codes of `wearsim`, decided here and nowhere else: 0 success; 2 bad input (an
//! argument, a configuration value, an unreadable or invalid input file: the message names
//! the field and its allowed range); 1 the run failed (I/O while writing, a numerical
//! failure); 130 stopped by an in-process caller ([`crate::cancel`]). Errors are printed once, as `wearsim: error: <message>` on stderr.

use std::process::ExitCode;

/// Exit code of a bad input.
pub const BAD_INPUT: u8 = 2;
/// Exit code of a failed run.
pub const RUN_FAILED: u8 = 1;
/// Exit code of a run stopped by its caller ([`crate::cancel`]; 128 + SIGINT, as a shell
/// reports a process ended by Ctrl-C).
pub const INTERRUPTED: u8 = 130;

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
    /// Stopped by the caller (exit code [`INTERRUPTED`]; see [`crate::cancel`]).
    pub fn interrupted() -> Self {
        CliError {
            code: INTERRUPTED,
            message: crate::cancel::MESSAGE.to_string(),
        }
    }
}

impl From<crate::cancel::Interrupted> for CliError {
    fn from(_: crate::cancel::Interrupted) -> Self {
        CliError::interrupted()
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
            eprintln!("wearsim: error: {}", compact_numbers(&message));
            ExitCode::from(code)
        }
    }
}

/// Longest decimal number a message shows as written; longer ones (`--duration 1e-300`
/// formatted by `{}` has 300 digits) are shown in exponent form.
pub const LONGEST_NUMBER: usize = 24;

/// `message` with every decimal number longer than [`LONGEST_NUMBER`] characters written
/// in exponent form (the shortest that reads back to the same `f64`); everything else as
/// it was. A number is a run of digits with at most one `.`, not preceded by a letter,
/// digit, `_` or `.`.
pub fn compact_numbers(message: &str) -> String {
    let b = message.as_bytes();
    let mut out = String::with_capacity(message.len());
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit()
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || matches!(b[i - 1], b'_' | b'.')));
        if starts {
            let mut j = i;
            let mut dot = false;
            while j < b.len() && (b[j].is_ascii_digit() || (b[j] == b'.' && !dot)) {
                dot |= b[j] == b'.';
                j += 1;
            }
            let token = &message[i..j];
            match token.parse::<f64>() {
                Ok(v) if token.len() > LONGEST_NUMBER && v.is_finite() => {
                    out.push_str(&format!("{v:e}"));
                }
                _ => out.push_str(token),
            }
            i = j;
        } else {
            let c = message[i..].chars().next().unwrap_or(' ');
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// Prints a command-line parse result that is not a command (an error: exit 2; `--help`
/// or `--version`: exit 0).
pub fn usage(e: &clap::Error) -> ExitCode {
    let code = if e.use_stderr() { BAD_INPUT } else { 0 };
    let _ = e.print();
    ExitCode::from(code)
}

#[cfg(test)]
mod tests {
    use super::compact_numbers;

    #[test]
    fn long_numbers_are_written_in_exponent_form() {
        let tiny = format!("duration = {} is out of range", 1e-300_f64);
        assert_eq!(compact_numbers(&tiny), "duration = 1e-300 is out of range");
        let huge = format!("--rpm = {} rpm, allowed 1..=100000", 1e300_f64);
        assert_eq!(
            compact_numbers(&huge),
            "--rpm = 1e300 rpm, allowed 1..=100000"
        );
        let keep = "sensor.noise = 100.00000000000001 (file 2004.02.12.10.32.39, x123456789012345678901234567, µm)";
        assert_eq!(compact_numbers(keep), keep);
        assert_eq!(
            compact_numbers("-0.000000000000000000000000001 ü"),
            "-1e-27 ü"
        );
    }
}
