//! Exclusive use of an output directory.
//!
//! Every command that writes an output set takes a [`DirLock`] on its directory before it
//! does any work: an advisory `flock(2)` on `<dir>/.wearsim.lock` (holding the pid of the
//! owner, for the message). A second run into the same directory while the first holds it
//! is refused with [`IoError::Locked`] (exit 2, naming the directory and the owner), so two
//! runs can never leave a set mixed from both. The kernel releases the lock when its holder
//! exits in any way (`kill -9` included), so there is no stale lock to clean up; the file
//! itself is removed when the lock is released normally. Taking the lock also proves that
//! the directory can be created and written, before the work starts.
//!
//! A process may take the lock of a directory it already holds (e.g. the dense life driver
//! and the writer of the life set): the registry below counts the holders, and the lock is
//! released with the last one.

use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::os::unix::fs::MetadataExt;
use std::os::unix::io::AsRawFd;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use super::error::IoError;

/// Name of the lock file in a locked directory.
pub const LOCK_FILE: &str = ".wearsim.lock";

struct Held {
    file: File,
    path: PathBuf,
    count: usize,
}

fn registry() -> &'static Mutex<HashMap<PathBuf, Held>> {
    static R: OnceLock<Mutex<HashMap<PathBuf, Held>>> = OnceLock::new();
    R.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Exclusive use of an output directory for as long as the value lives (see the module docs).
#[derive(Debug)]
pub struct DirLock {
    key: PathBuf,
}

impl DirLock {
    /// Creates `dir` if needed and takes its lock without waiting. Fails with
    /// [`IoError::Locked`] if another process holds it, and with [`IoError::Io`] if the
    /// directory cannot be created or written.
    pub fn try_acquire(dir: &Path) -> Result<DirLock, IoError> {
        let io = |op: &'static str, path: &Path| {
            let path = path.to_path_buf();
            move |source| IoError::Io { path, op, source }
        };
        std::fs::create_dir_all(dir).map_err(io("create directory", dir))?;
        let key = std::fs::canonicalize(dir).map_err(io("resolve directory", dir))?;
        let mut reg = registry().lock().unwrap_or_else(|e| e.into_inner());
        if let Some(h) = reg.get_mut(&key) {
            h.count += 1;
            return Ok(DirLock { key });
        }
        let path = key.join(LOCK_FILE);
        // Retry when the lock file was removed (released) between our open and our flock:
        // the lock must be on the file the path names.
        for _ in 0..100 {
            let mut file = OpenOptions::new()
                .create(true)
                .truncate(false)
                .read(true)
                .write(true)
                .open(&path)
                .map_err(io("create lock file (is the directory writable?)", &path))?;
            // SAFETY: flock on a file descriptor we own; no memory is passed.
            let rc = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
            if rc != 0 {
                let err = std::io::Error::last_os_error();
                if err.kind() == std::io::ErrorKind::WouldBlock {
                    let owner = std::fs::read_to_string(&path).unwrap_or_default();
                    return Err(IoError::Locked {
                        path: dir.to_path_buf(),
                        owner: owner.trim().to_string(),
                    });
                }
                return Err(io("lock", &path)(err));
            }
            let same = match (file.metadata(), std::fs::metadata(&path)) {
                (Ok(a), Ok(b)) => a.ino() == b.ino() && a.dev() == b.dev(),
                _ => false,
            };
            if !same {
                continue;
            }
            file.set_len(0).map_err(io("write", &path))?;
            writeln!(file, "pid {}", std::process::id()).map_err(io("write", &path))?;
            reg.insert(
                key.clone(),
                Held {
                    file,
                    path,
                    count: 1,
                },
            );
            return Ok(DirLock { key });
        }
        Err(IoError::Locked {
            path: dir.to_path_buf(),
            owner: "a run that keeps replacing the lock file".into(),
        })
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let mut reg = registry().lock().unwrap_or_else(|e| e.into_inner());
        let last = match reg.get_mut(&self.key) {
            Some(h) => {
                h.count -= 1;
                h.count == 0
            }
            None => false,
        };
        if last {
            if let Some(h) = reg.remove(&self.key) {
                // Removed while still locked, then unlocked by closing: a waiter that opened
                // the old file sees it is gone and retries on a fresh one.
                let _ = std::fs::remove_file(&h.path);
                drop(h.file);
            }
        }
    }
}
