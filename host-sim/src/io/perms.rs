//! Permissions of the files the command writes. Outputs are written to temporary files
//! and renamed into place (see [`super::write`]); a temporary file is created mode 0600 by
//! default, which the rename would keep, so every output would be private whatever the
//! user's umask. Creating the temporary with mode 0666 lets the kernel apply the umask,
//! exactly as for a file created directly (0644 under the usual umask 022).

/// A [`tempfile::Builder`] whose files are created like ordinary new files: mode
/// `0o666 & !umask` on Unix (the kernel applies the umask at creation); the platform
/// default elsewhere.
pub fn output_builder<'a, 'b>() -> tempfile::Builder<'a, 'b> {
    let mut b = tempfile::Builder::new();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b
}

/// Checks, before any work, that the one output file `path` given by `flag` can be written
/// when the work is done: its directory exists and takes a new file, and `path` is not a
/// directory. The message names the flag and the path; nothing is left behind (the probe
/// file is removed when dropped).
pub fn check_output_file(flag: &str, path: &std::path::Path) -> Result<(), String> {
    let shown = path.display();
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    if parent.is_some_and(|p| !p.is_dir()) {
        return Err(format!(
            "{flag} {shown}: its directory does not exist (create it first, or choose another {flag})"
        ));
    }
    if path.is_dir() {
        return Err(format!(
            "{flag} {shown}: is a directory (the output is one file: name one inside it)"
        ));
    }
    let dir = parent.unwrap_or(std::path::Path::new("."));
    output_builder().tempfile_in(dir).map(drop).map_err(|e| {
        format!(
            "{flag} {shown}: its directory {} cannot take a file ({e})",
            dir.display()
        )
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn an_output_file_is_checked_before_the_work() {
        let d = tempfile::tempdir().unwrap();
        let ok = d.path().join("t.md");
        assert!(super::check_output_file("--out", &ok).is_ok());
        assert!(!ok.exists(), "the check wrote the file");
        assert_eq!(
            std::fs::read_dir(d.path()).unwrap().count(),
            0,
            "the probe file stayed"
        );
        let e = super::check_output_file("--markdown", d.path()).unwrap_err();
        assert!(
            e.starts_with("--markdown ") && e.contains("is a directory"),
            "{e}"
        );
        let e = super::check_output_file("--out", &d.path().join("no/t.md")).unwrap_err();
        assert!(e.contains("its directory does not exist"), "{e}");
        let file = d.path().join("f");
        std::fs::write(&file, "x").unwrap();
        let e = super::check_output_file("--out", &file.join("t.md")).unwrap_err();
        assert!(e.contains("does not exist"), "{e}");
    }
}
