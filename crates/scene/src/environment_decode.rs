//! A map file's texels, decoded into the one buffer the map keeps: `.hdr` by the scanline
//! decoder (`hdr`), `.exr` by the `image` crate, its RGB float buffer taken over without a
//! copy. The size is checked from the header before any pixel is decoded.

use super::{EnvMapError, MAX_ENV_SIDE, MAX_ENV_TEXELS, hdr};
use glam::Vec3;
use std::path::Path;

/// What the `image` decoder (`.exr`) may allocate for a map's pixels: 4 f32 channels (OpenEXR RGBA, the
/// most any decoder asks for) of the largest map. (The `image` crate's default, 512 MiB,
/// refused a 16384 x 4096 `.hdr` as "Memory limit exceeded".)
pub(super) const MAX_ENV_DECODE_BYTES: u64 = MAX_ENV_TEXELS * 16;

/// A map of `width x height` texels is within the limits: 2x1 to [`MAX_ENV_SIDE`] a side,
/// at most [`MAX_ENV_TEXELS`] in all.
pub(super) fn check_size(path: &Path, width: u32, height: u32) -> Result<(), EnvMapError> {
    let sides = (2..=MAX_ENV_SIDE).contains(&width) && (1..=MAX_ENV_SIDE).contains(&height);
    if sides && u64::from(width) * u64::from(height) <= MAX_ENV_TEXELS {
        return Ok(());
    }
    Err(EnvMapError::Size {
        path: path.to_path_buf(),
        width,
        height,
    })
}

/// The decoder's limits for a map within [`check_size`]: its sides, and memory for the
/// pixels of the largest map ([`MAX_ENV_DECODE_BYTES`]).
pub(super) fn decode_limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_ENV_SIDE);
    limits.max_image_height = Some(MAX_ENV_SIDE);
    limits.max_alloc = Some(MAX_ENV_DECODE_BYTES);
    limits
}

/// `f()`, its error or panic as a decode error: the decoders read untrusted bytes (`image`'s
/// are third-party code).
fn guarded<T>(path: &Path, f: impl FnOnce() -> Result<T, String>) -> Result<T, EnvMapError> {
    let decode = |message: String| EnvMapError::Decode {
        path: path.to_path_buf(),
        message,
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))
        .map_err(|_| decode("the decoder failed on malformed data".into()))?
        .map_err(decode)
}

/// `(width, height, texels)` of a map file of `format` (`Hdr` or `OpenExr`), as stored:
/// non-finite or negative texels are the caller's to clean.
pub(super) fn texels(
    path: &Path,
    bytes: &[u8],
    format: image::ImageFormat,
) -> Result<(u32, u32, Vec<Vec3>), EnvMapError> {
    let decode = |message: String| EnvMapError::Decode {
        path: path.to_path_buf(),
        message,
    };
    if format == image::ImageFormat::Hdr {
        let (width, height, data) = guarded(path, || hdr::header(bytes))?;
        check_size(path, width, height)?;
        let texels = guarded(path, || hdr::pixels(data, width, height))?;
        return Ok((width, height, texels));
    }
    let reader = |limits: image::Limits| {
        let mut r = image::ImageReader::with_format(std::io::Cursor::new(bytes), format);
        r.limits(limits);
        r
    };
    // The size from the header, checked against the map limits before anything is decoded
    // (and named as they are, not as a decoder's "limit exceeded").
    let (width, height) = guarded(path, || {
        reader(image::Limits::no_limits())
            .into_dimensions()
            .map_err(|e| e.to_string())
    })?;
    check_size(path, width, height)?;
    let decoded = std::panic::catch_unwind(|| reader(decode_limits()).decode())
        .map_err(|_| decode("the decoder failed on malformed data".into()))?
        .map_err(|e| match e {
            image::ImageError::Limits(l) => decode(format!(
                "{l} (the limit is {} MiB, what a {MAX_ENV_SIDE}x{} RGBA float map needs)",
                MAX_ENV_DECODE_BYTES >> 20,
                MAX_ENV_SIDE / 2
            )),
            e => decode(e.to_string()),
        })?;
    // The header's size again, as decoded.
    check_size(path, decoded.width(), decoded.height())?;
    let (width, height) = (decoded.width(), decoded.height());
    let rgb = decoded.into_rgb32f().into_raw();
    // The decoder's buffer becomes the map's (a copy only if its capacity is not whole texels).
    let texels = bytemuck::allocation::try_cast_vec(rgb).unwrap_or_else(|(_, rgb)| {
        rgb.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect()
    });
    Ok((width, height, texels))
}
