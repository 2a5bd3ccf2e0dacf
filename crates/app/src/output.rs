//! Atomic image output: write to a temporary file in the same directory, then rename, so a
//! failed or interrupted run never leaves a half-written file under the final name.
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// The one atomic writer of the workspace (temporary file in the same directory, then
/// rename).
pub use blueshift_assets::write_atomic;

/// Encodes RGBA8 pixels as PNG (in memory).
pub fn png_rgba8(width: u32, height: u32, rgba: &[u8]) -> Result<Vec<u8>> {
    let img = image::RgbaImage::from_raw(width, height, rgba.to_vec()).context("pixel count")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)?;
    Ok(out.into_inner())
}

/// Encodes linear RGB (alpha ignored) as a float EXR (in memory).
pub fn exr_rgb32f(width: u32, height: u32, rgba: &[[f32; 4]]) -> Result<Vec<u8>> {
    let data: Vec<f32> = rgba.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    let img = image::Rgb32FImage::from_raw(width, height, data).context("pixel count")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::OpenExr)?;
    Ok(out.into_inner())
}

/// An output directory from [`prepare_dir`]. If this run created it and it is still empty when
/// dropped (the run failed before writing anything), it is removed again.
#[must_use = "dropping the guard removes the directory it created while it is empty"]
#[derive(Debug)]
pub struct OutputDir {
    created: Option<PathBuf>,
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if let Some(dir) = &self.created {
            let _ = std::fs::remove_dir(dir); // fails, as it should, unless empty
        }
    }
}

/// Creates `dir` (and parents) and checks it is writable, naming it on failure.
pub fn prepare_dir(dir: &Path) -> Result<OutputDir> {
    let created = (!dir.exists()).then(|| dir.to_path_buf());
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create output directory {}", dir.display()))?;
    let guard = OutputDir { created };
    let probe = dir.join(format!(".blueshift-write-test.{}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("output directory {} is not writable", dir.display()))?;
    let _ = std::fs::remove_file(probe);
    Ok(guard)
}
