// Shared by the file-reader targets: the readers take paths (they resolve sidecars next to
// the file), so each input is written to one file per process in a private temporary
// directory and read back. A reader may return any error, never panic, abort or allocate
// without bound (libFuzzer's -rss_limit_mb and -malloc_limit_mb catch the latter).

use std::path::PathBuf;
use std::sync::OnceLock;

/// The file `name` in this process's scratch directory, holding `data`.
pub fn scratch(name: &str, data: &[u8]) -> PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    let dir = DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("wearsim-fuzz-{}", std::process::id()));
        let _ = std::fs::create_dir_all(&d);
        d
    });
    let p = dir.join(name);
    let _ = std::fs::write(&p, data);
    p
}
