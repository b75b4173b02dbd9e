//! Whitespace-separated text as single-space-separated text, for the CSV reader: the
//! layout of `numpy.savetxt` (one space) and of MATLAB's `save -ascii` (values right-aligned
//! in 16-character fields, runs of spaces, a leading space), which the `csv` crate, whose
//! delimiter is one byte, would read as empty cells.
//! And [`LineCap`]: a bound on the length of a line, for the same reader.

use std::io::{self, Read};

/// A [`Read`] adapter that drops spaces and tabs at the start and end of every line and
/// turns every run of them inside a line into one space; line ends and every other byte
/// pass unchanged (so line numbers in messages stay those of the file).
#[derive(Debug)]
pub struct SpaceRuns<R> {
    inner: R,
    /// Whether a space or tab was seen since the last byte written on this line.
    pending: bool,
    /// Whether the current line has had a byte written yet.
    in_line: bool,
    /// Bytes read from `inner` and not yet passed on.
    buf: Vec<u8>,
    /// Position of the next unread byte of `buf`.
    at: usize,
}

impl<R: Read> SpaceRuns<R> {
    /// Wraps `inner`.
    pub fn new(inner: R) -> Self {
        SpaceRuns {
            inner,
            pending: false,
            in_line: false,
            buf: vec![0; 8192],
            at: 8192,
        }
    }
}

impl<R: Read> Read for SpaceRuns<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let mut n = 0;
        while n < out.len() {
            if self.at >= self.buf.len() {
                self.buf.resize(8192, 0);
                let k = self.inner.read(&mut self.buf)?;
                self.buf.truncate(k);
                self.at = 0;
                if k == 0 {
                    break;
                }
            }
            let Some(&b) = self.buf.get(self.at) else {
                break;
            };
            match b {
                b' ' | b'\t' => {
                    self.pending = self.in_line;
                    self.at += 1;
                }
                b'\n' | b'\r' => {
                    self.pending = false;
                    self.in_line = false;
                    out[n] = b;
                    n += 1;
                    self.at += 1;
                }
                _ if self.pending => {
                    // The run's one space first; the byte itself on the next turn.
                    self.pending = false;
                    out[n] = b' ';
                    n += 1;
                }
                _ => {
                    self.in_line = true;
                    out[n] = b;
                    n += 1;
                    self.at += 1;
                }
            }
        }
        Ok(n)
    }
}

/// Longest line the CSV reader takes, bytes (1 MiB: thousands of columns of full-precision
/// numbers). The `csv` crate holds a whole record in memory, so a file without line ends
/// (`/dev/zero`, a binary file named `.csv`) grew without bound.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// A [`Read`] adapter that fails with [`io::ErrorKind::FileTooLarge`] once a line runs
/// past `max` bytes without a `\n`; every byte passes unchanged.
#[derive(Debug)]
pub struct LineCap<R> {
    inner: R,
    /// Bytes since the last line end.
    in_line: usize,
    max: usize,
}

impl<R: Read> LineCap<R> {
    /// Wraps `inner`, allowing lines of up to `max` bytes.
    pub fn new(inner: R, max: usize) -> Self {
        LineCap {
            inner,
            in_line: 0,
            max,
        }
    }
}

impl<R: Read> Read for LineCap<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let k = self.inner.read(out)?;
        for &b in &out[..k] {
            if b == b'\n' {
                self.in_line = 0;
            } else {
                self.in_line += 1;
                if self.in_line > self.max {
                    return Err(io::Error::new(
                        io::ErrorKind::FileTooLarge,
                        format!("a line of more than {} bytes", self.max),
                    ));
                }
            }
        }
        Ok(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn squeeze(s: &str, chunk: usize) -> String {
        let mut r = SpaceRuns::new(s.as_bytes());
        let mut out = vec![];
        let mut buf = vec![0; chunk];
        loop {
            let k = r.read(&mut buf).unwrap();
            if k == 0 {
                break;
            }
            out.extend_from_slice(&buf[..k]);
        }
        String::from_utf8(out).unwrap()
    }

    /// MATLAB `save -ascii` lines, a tab inside a run, CRLF ends and a blank line: one
    /// space between values, none at either end, every line end kept — read through
    /// buffers of every small size (a run split across two reads).
    #[test]
    fn runs_become_one_space_and_lines_keep_their_ends() {
        let s = "   1.0000000e+00  -1.4000000e-01\r\n  2.0 \t 3.0  \n\n4 5\n";
        for chunk in 1..8 {
            assert_eq!(
                squeeze(s, chunk),
                "1.0000000e+00 -1.4000000e-01\r\n2.0 3.0\n\n4 5\n"
            );
        }
    }
}
