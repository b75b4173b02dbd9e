//! The `wearsim` command: simulate scenarios, run lives, analyse measurements, diagnose
//! the sim-to-real gap. Everything lives in the library's command layer
//! (`wearsim_host::cmd`); exit codes: 0 success, 1 run failure, 2 bad input.

use std::process::ExitCode;

fn main() -> ExitCode {
    // Like other Unix filters, end quietly when the reader of our output goes away
    // (`wearsim … | head`) instead of failing a write to a closed pipe.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    wearsim_host::cmd::main()
}
