//! The crate's error type.

use std::path::{Path, PathBuf};

/// Everything that can go wrong reading, writing or loading an asset. Paths are named in the
/// message.
#[derive(Debug, thiserror::Error)]
pub enum AssetError {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A file has the wrong size, header or content.
    #[error("{path}: {reason}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// An argument is out of range (bad side, not a permutation, ...).
    #[error("invalid argument: {0}")]
    Invalid(String),
    /// An HBO+19 key table could not be read or is malformed.
    #[error(transparent)]
    Keys(#[from] blueshift_sampling::hbo19::KeysError),
    /// Assets that are each valid do not fit together (a retarget table made for another
    /// mask size, key tables of different tiles).
    #[error("{0}")]
    Mismatch(String),
    /// An asset a configuration needs is not loaded (no HBO+19 key tables).
    #[error("{0}")]
    Missing(String),
}

/// `Result` with this crate's [`AssetError`].
pub type Result<T, E = AssetError> = std::result::Result<T, E>;

impl AssetError {
    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        AssetError::Io {
            path: path.to_path_buf(),
            source,
        }
    }

    pub(crate) fn format(path: &Path, reason: impl Into<String>) -> Self {
        AssetError::Format {
            path: path.to_path_buf(),
            reason: reason.into(),
        }
    }
}

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so a
/// failure never leaves a half-written output. The parent directory must exist.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(dir).map_err(|e| AssetError::io(path, e))?;
    tmp.write_all(bytes).map_err(|e| AssetError::io(path, e))?;
    #[cfg(unix)]
    {
        // NamedTempFile is created 0600; outputs are ordinary files.
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .map_err(|e| AssetError::io(path, e))?;
    }
    // On disk before the rename, so a crash leaves the old file or the new one, never part.
    tmp.as_file()
        .sync_all()
        .map_err(|e| AssetError::io(path, e))?;
    tmp.persist(path)
        .map_err(|e| AssetError::io(path, e.error))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_leaves_no_temp_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        write_atomic(&dir.path().join("a.bin"), b"hello").expect("write");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .expect("read dir")
            .map(|e| e.expect("entry").file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.bin")]);
        assert_eq!(
            std::fs::read(dir.path().join("a.bin")).expect("read"),
            b"hello"
        );
        assert!(write_atomic(&dir.path().join("missing/b.bin"), b"x").is_err());
    }
}
