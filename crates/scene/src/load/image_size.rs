//! An image's size from its encoded header, before it is decoded: a few hundred bytes of PNG
//! can declare 60,000 x 60,000 texels, and the decision to use the image must not cost them.
//! The bytes are found as the glTF reader finds them (buffer view, data URI or file).

use super::Ctx;
use gltf::image::Source;
use image::ImageReader;
use std::io::{BufRead, Cursor, Seek};
use std::path::Path;

/// `(width, height)` that the image's header declares. `base` is the directory of external
/// files (the caller has checked their URIs, and that a view lies inside its buffer).
pub(super) fn declared(source: Source, base: &Path, ctx: &Ctx) -> Result<(u32, u32), String> {
    match source {
        Source::View { view, .. } => {
            let data = ctx
                .buffers
                .get(view.buffer().index())
                .map_or(&[][..], |d| &d.0);
            let bytes = data
                .get(view.offset()..view.offset() + view.length())
                .ok_or_else(|| format!("bufferView {} is out of range", view.index()))?;
            from_header(Cursor::new(bytes))
        }
        Source::Uri { uri, .. } => {
            if let Some(rest) = uri.strip_prefix("data:") {
                // As the reader splits it: the payload follows `;base64,` if present.
                let payload = rest.split(";base64,").nth(1).unwrap_or(rest);
                let bytes = base64::decode(payload).map_err(|e| e.to_string())?;
                return from_header(Cursor::new(bytes));
            }
            let path = super::uri::resolve(uri, Some(base))?
                .ok_or_else(|| "unsupported URI scheme".to_string())?;
            let file =
                std::fs::File::open(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            from_header(std::io::BufReader::new(file))
        }
    }
}

/// Reads the header only (no decoder limits apply: nothing is allocated for the texels).
fn from_header(reader: impl BufRead + Seek) -> Result<(u32, u32), String> {
    let mut reader = ImageReader::new(reader)
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    if reader.format().is_none() {
        return Err("unsupported image format".into());
    }
    reader.no_limits();
    reader.into_dimensions().map_err(|e| e.to_string())
}
