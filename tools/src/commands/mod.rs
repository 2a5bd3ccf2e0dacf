//! Implementations of the subcommands.

pub mod assets;
pub(crate) mod dither;
pub(crate) mod fast;
pub(crate) mod figures;
pub mod keys;
pub(crate) mod masks;
pub(crate) mod retarget;
pub(crate) mod scene;
pub mod sky;
pub(crate) mod spectrum;

use std::path::Path;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};

/// A progress bar on stderr (hidden when stderr is not a terminal).
pub(crate) fn bar(len: u64, msg: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    if let Ok(style) =
        ProgressStyle::with_template("{msg:>14} [{elapsed_precise}] {wide_bar} {pos}/{len} ({eta})")
    {
        pb.set_style(style);
    }
    pb.set_message(msg.to_string());
    pb
}

/// Encodes `img` as PNG and writes it atomically.
pub(crate) fn save_png(img: image::DynamicImage, path: &Path) -> anyhow::Result<()> {
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)
        .with_context(|| format!("encoding {}", path.display()))?;
    blueshift_assets::write_atomic(path, buf.get_ref())?;
    Ok(())
}

/// Creates the parent directory of `path` if needed.
pub(crate) fn ensure_parent(path: &Path) -> anyhow::Result<()> {
    if let Some(p) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(p).with_context(|| format!("creating {}", p.display()))?;
    }
    Ok(())
}

/// Nearest-neighbour upscale of an 8-bit gray image by an integer factor.
pub(crate) fn upscale(img: &image::GrayImage, f: u32) -> image::GrayImage {
    image::GrayImage::from_fn(img.width() * f, img.height() * f, |x, y| {
        *img.get_pixel(x / f, y / f)
    })
}
