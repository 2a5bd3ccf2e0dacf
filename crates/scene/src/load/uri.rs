//! Checks on external buffer and image URIs before the glTF reader opens them: the reader
//! panics on a percent-encoding that is not UTF-8, and would read a device file such as
//! `/dev/zero` (or a FIFO) forever.

use std::path::{Path, PathBuf};

/// Percent-decodes like the glTF reader does (`%XX` -> byte; malformed escapes are kept),
/// failing where the decoded bytes are not UTF-8 (where the reader would panic).
pub(crate) fn percent_decode(uri: &str) -> Result<String, String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%'
            && let (Some(h), Some(l)) = (
                b.get(i + 1).copied().and_then(hex),
                b.get(i + 2).copied().and_then(hex),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8(out).map_err(|_| "its percent-encoding does not decode to UTF-8".to_string())
}

/// The file an external URI names (as the glTF reader resolves it), or `None` when the reader
/// will not open a file for it (data URIs, other schemes, no base directory).
pub(crate) fn resolve(uri: &str, base: Option<&Path>) -> Result<Option<PathBuf>, String> {
    if uri.contains(':') {
        let file = uri
            .strip_prefix("file://")
            .or_else(|| uri.strip_prefix("file:"));
        return Ok(match (file, base) {
            (Some(f), Some(_)) => Some(PathBuf::from(f)),
            _ => None, // the reader reads no file for other schemes, nor without a base
        });
    }
    // The reader decodes a relative URI (and panics on bad UTF-8) even without a base.
    let decoded = percent_decode(uri)?;
    Ok(base.map(|b| b.join(decoded)))
}

/// Checks that an external URI names a regular file the reader can safely read (or is not a
/// file reference at all).
pub(crate) fn check(uri: &str, base: Option<&Path>) -> Result<(), String> {
    let Some(path) = resolve(uri, base)? else {
        return Ok(());
    };
    let meta = std::fs::metadata(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    if !meta.is_file() {
        return Err(format!("{} is not a regular file", path.display()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_decoding_matches_the_reader_and_rejects_non_utf8() {
        assert_eq!(percent_decode("a%20b.bin").as_deref(), Ok("a b.bin"));
        assert_eq!(percent_decode("100%.bin").as_deref(), Ok("100%.bin"));
        assert_eq!(percent_decode("%zz%4").as_deref(), Ok("%zz%4"));
        // A lone continuation byte: the glTF reader's `decode(..).unwrap()` panics on this.
        assert!(percent_decode("%FF.bin").is_err());
    }

    #[test]
    fn device_files_and_directories_are_rejected() {
        let dir = std::env::temp_dir();
        assert!(check("/dev/zero", Some(&dir)).is_err());
        assert!(check("file:///dev/zero", Some(&dir)).is_err());
        assert!(check(".", Some(&dir)).is_err());
        assert!(check("data:application/octet-stream;base64,AAAA", Some(&dir)).is_ok());
        assert!(check("/dev/zero", None).is_ok()); // the reader refuses it without a base
        // Fuzz finding (gltf target): the reader percent-decodes before looking at the base.
        assert!(check("%AA", None).is_err());
    }
}
