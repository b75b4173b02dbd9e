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
//! A run that fails leaves no directory behind that it created: when the last holder
//! releases the lock of a directory that did not exist before the lock was taken, the
//! directory (and the parents created with it) is removed if it is still empty, so a
//! failing command with `--out NEW` writes nothing, not even `NEW/` (docs: "nothing
//! written"). A directory that existed before is never removed.
//!
//! The thread holding a directory's lock may take it again (e.g. the dense life driver
//! and the writer of the life set, both inside `wearsim life`): the registry below counts
//! the holders, and the lock is released with the last one. Another thread of the same
//! process is refused like another process: the registry answers before `flock(2)` is
//! asked (which would refuse a second open file description even within one process), and
//! it once let any thread in, so two threads of one Python process (`wearsim.life` from a
//! thread pool, the GIL released) both ran into one directory.

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
    /// The thread that took the lock: only it may take it again.
    thread: std::thread::ThreadId,
    path: PathBuf,
    count: usize,
    /// The outermost directory this lock created (canonical), if it created any: removed
    /// with the empty directories below it, down to the locked one, on release.
    created: Option<PathBuf>,
}

/// The outermost ancestor of `dir` (itself included) that does not exist, if any.
fn missing_top(dir: &Path) -> Option<PathBuf> {
    let mut top = None;
    let mut p = Some(dir);
    while let Some(d) = p {
        if d.as_os_str().is_empty() || d.exists() {
            break;
        }
        top = Some(d.to_path_buf());
        p = d.parent();
    }
    top
}

/// Removes the empty directories from `dir` up to and including `top` (both canonical);
/// stops at the first that is not empty (or not removable), so nothing written is lost.
fn remove_empty(dir: &Path, top: &Path) {
    let mut d = Some(dir);
    while let Some(p) = d {
        if !p.starts_with(top) || std::fs::remove_dir(p).is_err() {
            break;
        }
        if p == top {
            break;
        }
        d = p.parent();
    }
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
        let top = missing_top(dir);
        std::fs::create_dir_all(dir).map_err(io("create directory", dir))?;
        let key = std::fs::canonicalize(dir).map_err(io("resolve directory", dir))?;
        let created = top.and_then(|t| std::fs::canonicalize(t).ok());
        let mut reg = registry().lock().unwrap_or_else(|e| e.into_inner());
        if let Some(h) = reg.get_mut(&key) {
            if h.thread != std::thread::current().id() {
                return Err(IoError::Locked {
                    path: dir.to_path_buf(),
                    owner: format!("pid {}, another thread of this process", std::process::id()),
                });
            }
            h.count += 1;
            return Ok(DirLock { key });
        }
        let path = key.join(LOCK_FILE);
        // Retry when the lock file was removed (released) between our open and our flock:
        // the lock must be on the file the path names.
        for _ in 0..100 {
            let opened = OpenOptions::new()
                .create(true)
                .truncate(false)
                .read(true)
                .write(true)
                .open(&path);
            let mut file = match opened {
                Ok(f) => f,
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    // A run that failed removed the directory it had created: make it again.
                    std::fs::create_dir_all(&key).map_err(io("create directory", dir))?;
                    continue;
                }
                Err(e) => {
                    return Err(io("create lock file (is the directory writable?)", &path)(
                        e,
                    ))
                }
            };
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
                    thread: std::thread::current().id(),
                    path,
                    count: 1,
                    created,
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
                if let Some(top) = &h.created {
                    remove_empty(&self.key, top);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_run_leaves_no_directory_it_created() {
        let tmp = tempfile::tempdir().unwrap();
        // Nothing written: the directory and the parent created with it are removed.
        let dir = tmp.path().join("new/out");
        drop(DirLock::try_acquire(&dir).unwrap());
        assert!(!tmp.path().join("new").exists());
        // Written to: kept, with its output, without the lock file.
        let lock = DirLock::try_acquire(&dir).unwrap();
        std::fs::write(dir.join("x.json"), "{}").unwrap();
        drop(lock);
        assert!(dir.join("x.json").exists());
        assert!(!dir.join(LOCK_FILE).exists());
        // A directory that existed before is never removed, even empty.
        let old = tmp.path().join("old");
        std::fs::create_dir(&old).unwrap();
        drop(DirLock::try_acquire(&old).unwrap());
        assert!(old.is_dir());
        // A nested holder does not remove it before the outer one releases.
        let dir2 = tmp.path().join("nested");
        let outer = DirLock::try_acquire(&dir2).unwrap();
        drop(DirLock::try_acquire(&dir2).unwrap());
        assert!(dir2.is_dir());
        drop(outer);
        assert!(!dir2.exists());
    }

    /// Another thread of the holding process is refused, as another process is; the
    /// holding thread may take the lock again, and once it is released another thread
    /// takes it.
    #[test]
    fn another_thread_of_this_process_is_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("out");
        let lock = DirLock::try_acquire(&dir).unwrap();
        let other = std::thread::scope(|s| s.spawn(|| DirLock::try_acquire(&dir).map(drop)).join());
        match other.expect("thread") {
            Err(IoError::Locked { owner, .. }) => {
                assert!(owner.contains("another thread"), "{owner}")
            }
            r => panic!("a second thread took the held lock: {r:?}"),
        }
        drop(DirLock::try_acquire(&dir).expect("the holding thread again"));
        drop(lock);
        let after = std::thread::scope(|s| s.spawn(|| DirLock::try_acquire(&dir).map(drop)).join());
        assert!(after.expect("thread").is_ok());
    }
}
