//! `dither`: threshold an image against a tiled mask (see `crate::dither` for the rule).

use std::path::PathBuf;

use anyhow::Context;
use blueshift_analysis::Gray;
use blueshift_analysis::assets::{Mask, load_mask};
use clap::ValueEnum;

use super::{ensure_parent, save_png};
use crate::dither::dither_image;
use crate::voidcluster;

/// How image values map to the thesis' gray level `p` (probability of black).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GrayIs {
    /// Pixel value is brightness: `p = 1 - value` (output looks like the input).
    Brightness,
    /// Pixel value is `p` itself (black where mask <= value).
    Darkness,
}

/// `dither` flags.
#[derive(Debug, clap::Args)]
pub struct DitherArgs {
    /// Grayscale or RGB image (RGB is reduced to luminance).
    pub image: PathBuf,
    /// Mask `.r16`.
    #[arg(long)]
    pub mask: PathBuf,
    /// Output PNG.
    #[arg(long)]
    pub out: PathBuf,
    /// Meaning of pixel values.
    #[arg(long, value_enum, default_value_t = GrayIs::Brightness)]
    pub gray_is: GrayIs,
    /// Write the mask's result, a Bayer and a white-noise mask of the same side, side by side.
    #[arg(long)]
    pub compare: bool,
    /// Seed of the white-noise mask for --compare.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Places images side by side with an 8-pixel mid-gray gap.
pub(crate) fn side_by_side(imgs: &[image::GrayImage]) -> image::GrayImage {
    let gap = 8;
    let h = imgs.iter().map(|i| i.height()).max().unwrap_or(0);
    let w = imgs.iter().map(|i| i.width()).sum::<u32>() + gap * imgs.len().saturating_sub(1) as u32;
    let mut out = image::GrayImage::from_pixel(w, h, image::Luma([128]));
    let mut x0 = 0;
    for img in imgs {
        for (x, y, p) in img.enumerate_pixels() {
            out.put_pixel(x0 + x, y, *p);
        }
        x0 += img.width() + gap;
    }
    out
}

pub(crate) fn dither(a: &DitherArgs) -> anyhow::Result<()> {
    let img = Gray::load(&a.image)?;
    let mask = load_mask(&a.mask)?;
    let p = match a.gray_is {
        GrayIs::Brightness => Gray::new(img.w, img.h, img.data.iter().map(|v| 1.0 - v).collect())?,
        GrayIs::Darkness => img,
    };
    let out = if a.compare {
        let n = mask.n;
        let bayer = Mask::new(n, voidcluster::bayer(n))?;
        let white = Mask::new(n, voidcluster::white(n, a.seed))?;
        side_by_side(&[
            dither_image(&p, &mask),
            dither_image(&p, &bayer),
            dither_image(&p, &white),
        ])
    } else {
        dither_image(&p, &mask)
    };
    ensure_parent(&a.out)?;
    save_png(image::DynamicImage::ImageLuma8(out), &a.out)
        .with_context(|| format!("writing {}", a.out.display()))?;
    println!(
        "{}{}",
        a.out.display(),
        if a.compare {
            ": mask | Bayer | white"
        } else {
            ""
        }
    );
    Ok(())
}
