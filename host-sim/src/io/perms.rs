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
