//! External buffer and image URIs, resolved as the glTF reader resolves them and checked
//! before anything is opened: the reader panics on a percent-encoding that is not UTF-8, and
//! a scene must not read files outside its own directory unless the caller allows it
//! ([`crate::LoadOptions::allow_outside_paths`]).

use std::path::{Component, Path, PathBuf};

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

/// Why an external URI is not read.
#[derive(Debug, PartialEq)]
pub(crate) enum Refused {
    /// It leads outside the scene directory `dir` (`reason` says how).
    Outside { dir: PathBuf, reason: String },
    /// Anything else: the message.
    Other(String),
}

impl From<String> for Refused {
    fn from(message: String) -> Self {
        Refused::Other(message)
    }
}

/// The file an external URI names, resolved against `base` (the scene directory) as the glTF
/// reader resolves it, or `None` for a data URI. Unless `allow_outside`, the file must lie in
/// `base`: an absolute path, a `file:` URI, `..` that climbs out of `base`, or a symlink whose
/// target lies outside it (compared after canonicalizing) is refused. A file that does not
/// exist is left for the caller to report.
pub(crate) fn locate(
    uri: &str,
    base: Option<&Path>,
    allow_outside: bool,
) -> Result<Option<PathBuf>, Refused> {
    if uri.starts_with("data:") {
        return Ok(None);
    }
    let dir = || base.map(scene_dir).unwrap_or_default();
    let outside = |reason: &str| Refused::Outside {
        dir: dir(),
        reason: reason.to_string(),
    };
    let file = if uri.contains(':') {
        let Some(f) = uri
            .strip_prefix("file://")
            .or_else(|| uri.strip_prefix("file:"))
        else {
            return Err(Refused::Other("unsupported URI scheme".into()));
        };
        if !allow_outside {
            return Err(outside("it is a file: URI"));
        }
        PathBuf::from(f)
    } else {
        // Decoded first: `%2e%2e/` is `../` to the reader.
        let decoded = PathBuf::from(percent_decode(uri)?);
        if !allow_outside {
            if decoded.has_root() {
                return Err(outside("it is an absolute path"));
            }
            if climbs_out(&decoded) {
                return Err(outside("'..' climbs out of it"));
            }
        }
        match base {
            Some(b) => b.join(decoded),
            None => decoded,
        }
    };
    let Some(base) = base else {
        return Err(Refused::Other(
            "external files cannot be read for a scene loaded from memory".into(),
        ));
    };
    if !allow_outside && let Ok(target) = file.canonicalize() {
        let dir = scene_dir(base);
        if !target.starts_with(&dir) {
            let reason = format!("through a symlink it is {}", target.display());
            return Err(Refused::Outside { dir, reason });
        }
    }
    Ok(Some(file))
}

/// The scene directory, canonical where it can be.
fn scene_dir(base: &Path) -> PathBuf {
    let base = if base.as_os_str().is_empty() {
        Path::new(".")
    } else {
        base
    };
    base.canonicalize().unwrap_or_else(|_| base.to_path_buf())
}

/// Whether the relative path `p` goes above its start with `..`.
fn climbs_out(p: &Path) -> bool {
    let mut depth = 0i64;
    for c in p.components() {
        match c {
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            _ => {}
        }
        if depth < 0 {
            return true;
        }
    }
    false
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
    fn paths_outside_the_scene_directory_are_refused_unless_allowed() {
        let dir = tempfile::tempdir().expect("tempdir");
        let scene = dir.path().join("scene");
        std::fs::create_dir_all(scene.join("sub")).expect("mkdir");
        std::fs::write(dir.path().join("outside.bin"), b"x").expect("write");
        std::fs::write(scene.join("inside.bin"), b"x").expect("write");
        let base = Some(scene.as_path());
        let reason = |uri: &str| match locate(uri, base, false) {
            Err(Refused::Outside { reason, .. }) => reason,
            other => panic!("{uri}: {other:?}"),
        };
        assert_eq!(reason("../outside.bin"), "'..' climbs out of it");
        assert_eq!(reason("sub/../../outside.bin"), "'..' climbs out of it");
        assert_eq!(reason("%2e%2e/outside.bin"), "'..' climbs out of it");
        assert_eq!(reason("/etc/passwd"), "it is an absolute path");
        assert_eq!(reason("file:///etc/passwd"), "it is a file: URI");
        assert_eq!(reason("file:inside.bin"), "it is a file: URI");
        for uri in [
            "inside.bin",
            "sub/../inside.bin",
            "./inside.bin",
            "missing.bin",
        ] {
            let want = scene.join(percent_decode(uri).expect("utf-8"));
            assert_eq!(locate(uri, base, false), Ok(Some(want)), "{uri}");
        }
        assert_eq!(
            locate("../outside.bin", base, true),
            Ok(Some(scene.join("../outside.bin")))
        );
        assert_eq!(
            locate("file:///etc/passwd", base, true),
            Ok(Some(PathBuf::from("/etc/passwd")))
        );
        assert_eq!(locate("data:,abc", base, false), Ok(None));
        assert!(matches!(
            locate("http://x/a.bin", base, true),
            Err(Refused::Other(_))
        ));
        // Without a base nothing external is read, and bad percent-encoding is still caught
        // (fuzz finding: the reader decodes before it looks at the base).
        assert!(matches!(
            locate("a.bin", None, false),
            Err(Refused::Other(_))
        ));
        assert!(matches!(locate("%AA", None, true), Err(Refused::Other(_))));
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_count_where_they_lead() {
        let dir = tempfile::tempdir().expect("tempdir");
        let scene = dir.path().join("scene");
        std::fs::create_dir_all(&scene).expect("mkdir");
        std::fs::write(dir.path().join("outside.bin"), b"x").expect("write");
        std::fs::write(scene.join("inside.bin"), b"x").expect("write");
        let link = |target: &Path, name: &str| {
            std::os::unix::fs::symlink(target, scene.join(name)).expect("symlink")
        };
        link(&dir.path().join("outside.bin"), "out.bin");
        link(&scene.join("inside.bin"), "in.bin");
        link(dir.path(), "up");
        let base = Some(scene.as_path());
        for uri in ["out.bin", "up/outside.bin"] {
            match locate(uri, base, false) {
                Err(Refused::Outside { reason, .. }) => {
                    assert!(reason.starts_with("through a symlink it is "), "{reason}");
                    assert!(reason.ends_with("outside.bin"), "{reason}");
                }
                other => panic!("{uri}: {other:?}"),
            }
            assert!(locate(uri, base, true).is_ok(), "{uri}");
        }
        assert_eq!(
            locate("in.bin", base, false),
            Ok(Some(scene.join("in.bin")))
        );
    }
}
