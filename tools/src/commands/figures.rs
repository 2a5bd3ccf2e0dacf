//! `figures`: the thesis-style comparison figures (white / blue / Bayer).

use std::path::PathBuf;

use anyhow::Context;
use blueshift_analysis::assets::Mask;
use blueshift_analysis::{
    Gray, LF_CUTOFF, low_frequency_fraction, periodogram, plot_radial_profiles, save_spectrum_png,
};

use super::spectrum::normalised_series;
use super::{save_png, upscale};
use crate::dither::dither_image;
use crate::voidcluster::{self, VcParams};

/// `figures` flags.
#[derive(Debug, clap::Args)]
pub struct FiguresArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "out/figures")]
    pub out: PathBuf,
    /// Mask side.
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Seed of the blue and white masks.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Stacks images vertically with an 8-pixel mid-gray gap.
fn stacked(imgs: &[image::GrayImage]) -> image::GrayImage {
    let gap = 8;
    let w = imgs.iter().map(|i| i.width()).max().unwrap_or(0);
    let h =
        imgs.iter().map(|i| i.height()).sum::<u32>() + gap * imgs.len().saturating_sub(1) as u32;
    let mut out = image::GrayImage::from_pixel(w, h, image::Luma([128]));
    let mut y0 = 0;
    for img in imgs {
        for (x, y, p) in img.enumerate_pixels() {
            out.put_pixel(x, y0 + y, *p);
        }
        y0 += img.height() + gap;
    }
    out
}

pub(crate) fn figures(a: &FiguresArgs) -> anyhow::Result<()> {
    let n = a.size;
    if !(4..=256).contains(&n) || !n.is_power_of_two() {
        anyhow::bail!("--size {n}: must be a power of two in 4..=256");
    }
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let blue = voidcluster::void_and_cluster(&VcParams::new_2d(n, a.seed), &mut |_| {})?;
    let masks = [
        ("white", Mask::new(n, voidcluster::white(n, a.seed))?),
        ("blue", Mask::new(n, blue)?),
        ("bayer", Mask::new(n, voidcluster::bayer(n))?),
    ];
    let scale = (256 / n).max(1) as u32;
    let mut series = Vec::new();
    for (name, m) in &masks {
        let g = Gray::from(m);
        let tex = image::GrayImage::from_fn(n as u32, n as u32, |x, y| {
            image::Luma([(g.at(x as usize, y as usize) * 255.0).round() as u8])
        });
        save_png(
            image::DynamicImage::ImageLuma8(upscale(&tex, scale)),
            &a.out.join(format!("{name}_texture.png")),
        )?;
        let s = periodogram(&g)?;
        save_spectrum_png(&s, &a.out.join(format!("{name}_spectrum.png")))?;
        println!("{name:>6}: LF {:.5}", low_frequency_fraction(&s, LF_CUTOFF));
        series.push(normalised_series(name, &s));
    }
    plot_radial_profiles(
        &series,
        &format!("{n}x{n} masks: radially averaged periodogram"),
        &a.out.join("radial_profiles.png"),
    )?;
    // Gradient, brightness 0 (left) to 1 (right); the rule takes p = 1 - brightness.
    let (w, h) = (512usize, 64usize);
    let p = Gray::from_fn(w, h, |x, _| 1.0 - x as f32 / (w - 1) as f32);
    let gradient = image::GrayImage::from_fn(w as u32, h as u32, |x, _| {
        image::Luma([(x as f32 / (w - 1) as f32 * 255.0).round() as u8])
    });
    let mut rows = vec![gradient];
    rows.extend(masks.iter().map(|(_, m)| dither_image(&p, m)));
    save_png(
        image::DynamicImage::ImageLuma8(stacked(&rows)),
        &a.out.join("dither_gradient.png"),
    )?;
    println!(
        "wrote {}: {{white,blue,bayer}}_{{texture,spectrum}}.png, radial_profiles.png, \
         dither_gradient.png (rows: gradient, white, blue, Bayer)",
        a.out.display()
    );
    Ok(())
}
