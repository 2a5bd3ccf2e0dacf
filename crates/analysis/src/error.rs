//! The crate's error type.

use std::path::PathBuf;

/// Everything that can go wrong in this crate. Paths are named in the message.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// An image could not be decoded or encoded.
    #[error("{path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The codec error.
        source: image::ImageError,
    },
    /// An argument is out of range (image too small, bad tile size, ...).
    #[error("invalid argument: {0}")]
    Invalid(String),
    /// Drawing a plot failed.
    #[error("plot: {0}")]
    Plot(String),
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
