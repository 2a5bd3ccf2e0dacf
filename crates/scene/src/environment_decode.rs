//! A map file's texels, decoded into the one buffer the map keeps: `.hdr` by the scanline
//! decoder (`hdr`), `.exr` by the `exr` crate (`exr`). The size is checked from the header
//! before any pixel is decoded.

use super::{EnvMapError, MAX_ENV_SIDE, MAX_ENV_TEXELS, exr, hdr};
use crate::DeviceLimits;
use crate::gpu::{LIGHT_PARAMS_TEXELS, SCENE_TEXELS_WIDTH};
use glam::Vec3;
use std::path::Path;

/// A map of `width x height` texels is within the limits: 2x1 to [`MAX_ENV_SIDE`] a side,
/// at most [`MAX_ENV_TEXELS`] in all, and, with a `device`, within its light image: the map's
/// texels and its row table (one per row) beside the one light record the image always holds
/// (`SceneGpu::texel_sources`).
pub(super) fn check_size(
    path: &Path,
    width: u32,
    height: u32,
    device: Option<&DeviceLimits>,
) -> Result<(), EnvMapError> {
    let sides = (2..=MAX_ENV_SIDE).contains(&width) && (1..=MAX_ENV_SIDE).contains(&height);
    let texels = u64::from(width) * u64::from(height);
    if !(sides && texels <= MAX_ENV_TEXELS) {
        return Err(EnvMapError::Size {
            path: path.to_path_buf(),
            width,
            height,
        });
    }
    if let Some(d) = device {
        let image = u64::from(SCENE_TEXELS_WIDTH) * u64::from(d.max_image_dimension_2d);
        let room = image.saturating_sub(u64::from(LIGHT_PARAMS_TEXELS));
        let needed = texels + u64::from(height);
        if needed > room {
            return Err(EnvMapError::OverDevice {
                path: path.to_path_buf(),
                width,
                height,
                texels: needed,
                room,
                rows: d.max_image_dimension_2d,
            });
        }
    }
    Ok(())
}

/// `f()`, its error or panic as a decode error: the decoders read untrusted bytes (`exr` is
/// third-party code).
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
    device: Option<&DeviceLimits>,
) -> Result<(u32, u32, Vec<Vec3>), EnvMapError> {
    if format == image::ImageFormat::Hdr {
        let (width, height, data) = guarded(path, || hdr::header(bytes))?;
        check_size(path, width, height, device)?;
        let texels = guarded(path, || hdr::pixels(data, width, height))?;
        return Ok((width, height, texels));
    }
    let layer = guarded(path, || exr::header(bytes))?;
    check_size(path, layer.width, layer.height, device)?;
    let texels = guarded(path, || exr::pixels(bytes, &layer))?;
    Ok((layer.width, layer.height, texels))
}
