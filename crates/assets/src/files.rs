//! Opening files that input names (a scene and its buffers and images, an environment map, a
//! camera path, mask assets): only regular files, and never more bytes than the caller wants.
//!
//! A FIFO blocks `open` until a writer appears, and `/dev/zero` or `/dev/urandom` never end:
//! the file type is checked before the file is opened, and again on the opened file (in case
//! the path was replaced in between). Reads are bounded (`Read::take`), so a file that grows
//! while it is read costs no more than the limit.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Opens `path` for reading if it is a regular file (symlinks are followed). A directory,
/// FIFO, socket or device is refused with an error that says which, before it is opened.
/// The error does not name `path`: the caller does, as with any `io::Error`.
pub fn open_regular(path: &Path) -> io::Result<File> {
    check_regular(&std::fs::metadata(path)?)?;
    let file = File::open(path)?;
    check_regular(&file.metadata()?)?;
    Ok(file)
}

/// Reads all of the regular file `path` if it holds at most `max_bytes` bytes; a larger one is
/// refused (`ErrorKind::FileTooLarge`) without being read. See [`open_regular`].
pub fn read_regular(path: &Path, max_bytes: u64) -> io::Result<Vec<u8>> {
    let file = open_regular(path)?;
    let len = file.metadata()?.len();
    if len > max_bytes {
        return Err(too_large(len, max_bytes));
    }
    // One byte past the limit tells a file that grew since its size was taken.
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64, max_bytes));
    }
    Ok(bytes)
}

/// Reads exactly the first `n` bytes of the regular file `path` (the rest, if any, is not
/// read). A shorter file is an error that says it is empty or how many bytes it has.
pub fn read_prefix(path: &Path, n: u64) -> io::Result<Vec<u8>> {
    let file = open_regular(path)?;
    // The capacity comes from the file, not from `n`, which input declares.
    let len = file.metadata()?.len();
    let mut bytes = Vec::with_capacity(len.min(n) as usize);
    file.take(n).read_to_end(&mut bytes)?;
    if (bytes.len() as u64) < n {
        return Err(io::Error::new(
            io::ErrorKind::UnexpectedEof,
            short_of(bytes.len() as u64, n, "the file"),
        ));
    }
    Ok(bytes)
}

/// `"{what} is empty, but byteLength declares N bytes"` or `"{what} has M bytes, ..."`.
pub fn short_of(got: u64, declared: u64, what: &str) -> String {
    let has = if got == 0 {
        format!("{what} is empty")
    } else {
        format!("{what} has only {got} bytes")
    };
    format!("{has}, but byteLength declares {declared} bytes (truncated?)")
}

fn too_large(len: u64, max: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!("the file has {len} bytes, over the limit of {max} bytes"),
    )
}

fn check_regular(meta: &std::fs::Metadata) -> io::Result<()> {
    let ty = meta.file_type();
    if ty.is_file() {
        return Ok(());
    }
    let what = if ty.is_dir() {
        "a directory"
    } else {
        special_kind(&ty)
    };
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("not a regular file ({what})"),
    ))
}

#[cfg(unix)]
fn special_kind(ty: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if ty.is_fifo() {
        "a FIFO"
    } else if ty.is_socket() {
        "a socket"
    } else if ty.is_char_device() {
        "a character device"
    } else if ty.is_block_device() {
        "a block device"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special_kind(_: &std::fs::FileType) -> &'static str {
    "a special file"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_directories_are_refused_without_reading() {
        let e = read_regular(Path::new("/dev/zero"), 16).unwrap_err();
        assert_eq!(e.to_string(), "not a regular file (a character device)");
        let dir = std::env::temp_dir();
        let e = open_regular(&dir).unwrap_err();
        assert_eq!(e.to_string(), "not a regular file (a directory)");
        assert_eq!(
            open_regular(&dir.join("no-such-file-here"))
                .unwrap_err()
                .kind(),
            io::ErrorKind::NotFound
        );
    }

    #[test]
    fn limits_are_kept() {
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("ten.bin");
        std::fs::write(&p, [7u8; 10]).expect("write");
        assert_eq!(read_regular(&p, 10).expect("fits"), [7; 10]);
        let e = read_regular(&p, 9).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::FileTooLarge);
        assert_eq!(
            e.to_string(),
            "the file has 10 bytes, over the limit of 9 bytes"
        );
        assert_eq!(read_prefix(&p, 4).expect("prefix"), [7; 4]);
        let e = read_prefix(&p, 12).unwrap_err();
        assert_eq!(
            e.to_string(),
            "the file has only 10 bytes, but byteLength declares 12 bytes (truncated?)"
        );
        std::fs::write(&p, []).expect("write");
        let e = read_prefix(&p, 12).unwrap_err();
        assert!(e.to_string().starts_with("the file is empty"), "{e}");
    }
}
