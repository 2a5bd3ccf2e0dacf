//! GLB container pre-check, run before the bytes reach the glTF reader.
//!
//! Why: gltf 1.4.1's `Glb::from_slice` computes `header.length - 12` unchecked, so a declared
//! total length below 12 bytes panics (`attempt to subtract with overflow`, with debug
//! assertions on; it wraps to a huge length in release). The loader catches that panic, but
//! a clear error is better, and the fuzz targets must find nothing. The reader also walks the
//! chunks over the whole slice rather than over the declared length, so the check returns the
//! declared prefix for the reader to use: both then see the same chunks.
//!
//! Checked, in the reader's order: the 12-byte header (magic `glTF`, version 2, declared total
//! length between 12 and the byte count), then the two chunks the reader walks: a `JSON`
//! chunk first and, if bytes remain, a `BIN\0` chunk, each with its 8-byte header and data
//! inside the declared length. Chunks after the second are ignored by the reader and not
//! checked; neither is 4-byte alignment, which the reader does not rely on.

/// `glTF`, the first four bytes of every GLB file.
const MAGIC: &[u8; 4] = b"glTF";
const HEADER: usize = 12;
const CHUNK_HEADER: usize = 8;

/// For bytes starting with [`MAGIC`], checks the GLB structure and returns the bytes up to the
/// declared total length (the caller warns about any bytes after it). Other bytes (`.gltf`
/// JSON) are returned unchanged. The error names the problem.
pub(crate) fn check(bytes: &[u8]) -> Result<&[u8]> {
    if !bytes.starts_with(MAGIC) {
        return Ok(bytes);
    }
    if bytes.len() < HEADER {
        return Err(format!(
            "GLB file is {} bytes, shorter than the {HEADER}-byte header",
            bytes.len()
        ));
    }
    let version = u32_at(bytes, 4);
    if version != 2 {
        return Err(format!(
            "GLB header declares version {version}, only version 2 is supported"
        ));
    }
    let declared = u32_at(bytes, 8);
    let total = usize::try_from(declared).unwrap_or(usize::MAX);
    if total < HEADER {
        return Err(format!(
            "GLB header declares a total length of {declared} bytes, below the {HEADER}-byte \
             header"
        ));
    }
    if total > bytes.len() {
        return Err(format!(
            "GLB header declares a total length of {declared} bytes, but the file has only {} \
             bytes (truncated?)",
            bytes.len()
        ));
    }
    let glb = &bytes[..total];
    let mut offset = HEADER;
    for (index, (name, tag)) in [("JSON", b"JSON"), ("BIN", b"BIN\0")]
        .into_iter()
        .enumerate()
    {
        if index > 0 && offset == total {
            break; // the BIN chunk is optional
        }
        offset = check_chunk(glb, offset, index, name, tag)?;
    }
    Ok(glb)
}

/// Checks the header of chunk `index` (type `tag`, called `name`) at `offset` of `glb` (cut to
/// the declared length) and returns the offset just past the chunk's data.
fn check_chunk(
    glb: &[u8],
    offset: usize,
    index: usize,
    name: &str,
    tag: &[u8; 4],
) -> Result<usize> {
    let left = glb.len() - offset;
    if left < CHUNK_HEADER {
        return Err(format!(
            "GLB {name} chunk (chunk {index}) at byte {offset} needs an {CHUNK_HEADER}-byte \
             header, but only {left} bytes are left of the declared total length of {} bytes",
            glb.len()
        ));
    }
    let ty = &glb[offset + 4..offset + CHUNK_HEADER];
    if ty != tag {
        return Err(format!(
            "GLB chunk {index} at byte {offset} has type \"{}\", expected \"{}\" (a GLB holds a \
             JSON chunk first, then an optional BIN chunk)",
            ty.escape_ascii(),
            tag.escape_ascii()
        ));
    }
    let length = u32_at(glb, offset);
    let data = offset + CHUNK_HEADER;
    let end = usize::try_from(length)
        .ok()
        .and_then(|n| data.checked_add(n))
        .filter(|&end| end <= glb.len());
    end.ok_or_else(|| {
        format!(
            "GLB {name} chunk (chunk {index}) at byte {offset} declares {length} bytes of data, \
             past the declared total length of {} bytes ({} bytes left after its header)",
            glb.len(),
            glb.len() - data
        )
    })
}

/// A problem with the container, described for `SceneError::Glb`.
type Result<T> = std::result::Result<T, String>;

/// The little-endian `u32` at `offset`; the caller has checked that 4 bytes are there.
fn u32_at(bytes: &[u8], offset: usize) -> u32 {
    let mut b = [0; 4];
    b.copy_from_slice(&bytes[offset..offset + 4]);
    u32::from_le_bytes(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A GLB with the given JSON text and binary chunk (none if empty), padded as the spec asks.
    fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
        let value: serde_json::Value = serde_json::from_str(json).expect("json");
        let bytes = crate::presets::glb(&value, bin);
        assert_eq!(check(&bytes), Ok(&bytes[..]));
        bytes
    }

    fn set_u32(bytes: &mut [u8], offset: usize, value: u32) {
        bytes[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    }

    const MINIMAL: &str = r#"{"asset":{"version":"2.0"}}"#;

    #[test]
    fn valid_glb_and_json_pass() {
        let json_only = glb(MINIMAL, &[]);
        assert_eq!(json_only.len(), 12 + 8 + 28);
        let with_bin = glb(MINIMAL, &[1, 2, 3, 4, 5]);
        assert_eq!(with_bin.len(), 12 + 8 + 28 + 8 + 8);
        assert_eq!(check(MINIMAL.as_bytes()), Ok(MINIMAL.as_bytes()));
        assert_eq!(check(b""), Ok(&b""[..]));
        // Bytes after the declared length are cut off (the loader warns about them).
        let mut long = json_only.clone();
        long.extend_from_slice(b"trailing junk");
        assert_eq!(check(&long), Ok(&json_only[..]));
    }

    #[test]
    fn header_problems_are_named() {
        let good = glb(MINIMAL, &[]);
        let cases: [(&[u8], &str); 3] = [
            (
                b"glTF",
                "GLB file is 4 bytes, shorter than the 12-byte header",
            ),
            (
                b"glTF\x01\0\0\0\x30\0\0\0",
                "GLB header declares version 1, only version 2 is supported",
            ),
            (
                b"glTF\x02\0\0\0\x05\0\0\0",
                "GLB header declares a total length of 5 bytes, below the 12-byte header",
            ),
        ];
        for (bytes, message) in cases {
            assert_eq!(check(bytes), Err(message.to_string()));
        }
        let mut too_long = good.clone();
        set_u32(&mut too_long, 8, u32::MAX);
        assert_eq!(
            check(&too_long),
            Err(
                "GLB header declares a total length of 4294967295 bytes, but the file has \
                 only 48 bytes (truncated?)"
                    .into()
            )
        );
        // The version is checked before the length (the reader subtracts first).
        let mut old = good;
        set_u32(&mut old, 4, 1);
        set_u32(&mut old, 8, 0);
        assert!(check(&old).is_err_and(|e| e.contains("version 1")));
    }

    #[test]
    fn chunk_problems_are_named() {
        let good = glb(MINIMAL, &[7; 8]);
        let mut json_long = good.clone();
        set_u32(&mut json_long, 12, u32::MAX);
        assert_eq!(
            check(&json_long),
            Err(
                "GLB JSON chunk (chunk 0) at byte 12 declares 4294967295 bytes of data, past \
                 the declared total length of 64 bytes (44 bytes left after its header)"
                    .into()
            )
        );
        let mut bin_long = good.clone();
        set_u32(&mut bin_long, 48, 9);
        assert_eq!(
            check(&bin_long),
            Err(
                "GLB BIN chunk (chunk 1) at byte 48 declares 9 bytes of data, past the \
                 declared total length of 64 bytes (8 bytes left after its header)"
                    .into()
            )
        );
        let mut bin_first = good.clone();
        bin_first[16..20].copy_from_slice(b"BIN\0");
        assert_eq!(
            check(&bin_first),
            Err(
                "GLB chunk 0 at byte 12 has type \"BIN\\x00\", expected \"JSON\" (a GLB holds \
                 a JSON chunk first, then an optional BIN chunk)"
                    .into()
            )
        );
        // Declared length cut inside the BIN chunk's header.
        let mut cut = good;
        set_u32(&mut cut, 8, 52);
        assert_eq!(
            check(&cut),
            Err(
                "GLB BIN chunk (chunk 1) at byte 48 needs an 8-byte header, but only 4 bytes \
                 are left of the declared total length of 52 bytes"
                    .into()
            )
        );
        let header_only = b"glTF\x02\0\0\0\x0c\0\0\0";
        assert!(check(header_only).is_err_and(|e| e.contains("GLB JSON chunk (chunk 0)")));
    }
}
