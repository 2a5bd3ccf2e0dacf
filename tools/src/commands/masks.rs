//! `mask`, `bayer` and `white`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use blueshift_analysis::assets::{Mask, StbnVolume, save_mask, save_stbn};

use super::{bar, ensure_parent, save_png};
use crate::quality::mask_quality;
use crate::voidcluster::{self, VcParams};

/// `mask` flags.
#[derive(Debug, clap::Args)]
pub struct MaskArgs {
    /// Side of the mask (power of two, 4..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Gaussian energy sigma in pixels.
    #[arg(long, default_value_t = 1.9)]
    pub sigma: f64,
    /// Initial density of the binary pattern.
    #[arg(long, default_value_t = 0.1)]
    pub density: f64,
    /// Number of slices; > 1 makes a spatio-temporal mask.
    #[arg(long, default_value_t = 1)]
    pub frames: usize,
    /// Temporal energy sigma in frames (spatio-temporal only).
    #[arg(long, default_value_t = 1.9)]
    pub sigma_t: f64,
    /// PRNG seed of the initial pattern.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output `.r16`; a 16-bit PNG preview is written beside it (`.png`).
    #[arg(long)]
    pub out: PathBuf,
}

/// `bayer` flags.
#[derive(Debug, clap::Args)]
pub struct BayerArgs {
    /// Side (power of two, 2..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Output `.r16` (plus `.png` preview).
    #[arg(long)]
    pub out: PathBuf,
}

/// `white` flags.
#[derive(Debug, clap::Args)]
pub struct WhiteArgs {
    /// Side (power of two, 2..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// PRNG seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output `.r16` (plus `.png` preview).
    #[arg(long)]
    pub out: PathBuf,
}

/// The PNG preview path beside an `.r16`.
pub(crate) fn preview_path(out: &Path) -> PathBuf {
    out.with_extension("png")
}

/// 16-bit grayscale PNG of raw ranks, slices stacked vertically (`n x n*frames`).
pub(crate) fn save_preview(ranks: &[u16], n: usize, path: &Path) -> anyhow::Result<()> {
    let h = (ranks.len() / n) as u32;
    let img =
        image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(n as u32, h, ranks.to_vec())
            .context("preview buffer size")?;
    save_png(image::DynamicImage::ImageLuma16(img), path)
}

fn write_2d(mask: &Mask, out: &Path) -> anyhow::Result<()> {
    ensure_parent(out)?;
    save_mask(mask, out)?;
    save_preview(&mask.ranks, mask.n, &preview_path(out))?;
    let q = mask_quality(mask)?;
    println!(
        "{}: {n}x{n} ranks, LF {:.5}, peak/high-band {:.2}",
        out.display(),
        q.lf,
        q.peak_ratio,
        n = mask.n
    );
    Ok(())
}

fn check_side(n: usize) -> anyhow::Result<()> {
    if !(2..=256).contains(&n) || !n.is_power_of_two() {
        bail!("--size {n}: must be a power of two in 2..=256 (ranks are stored as u16)");
    }
    Ok(())
}

pub(crate) fn mask(a: &MaskArgs) -> anyhow::Result<()> {
    let p = VcParams {
        n: a.size,
        frames: a.frames,
        sigma: a.sigma,
        sigma_t: a.sigma_t,
        density: a.density,
        seed: a.seed,
        toroidal: true,
    };
    let start = Instant::now();
    let pb = bar((a.size * a.size) as u64, "void-and-cluster");
    let ranks = voidcluster::void_and_cluster(&p, &mut |k| pb.set_position(k))?;
    pb.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    if a.frames == 1 {
        write_2d(&Mask::new(a.size, ranks)?, &a.out)?;
    } else {
        let v = StbnVolume::new(a.size, a.frames, ranks)?;
        ensure_parent(&a.out)?;
        save_stbn(&v, &a.out)?;
        save_preview(&v.ranks, v.n, &preview_path(&a.out))?;
        let mut worst: f64 = 0.0;
        for s in 0..v.t {
            worst = worst.max(mask_quality(&v.slice(s)?)?.lf);
        }
        let tlf = crate::quality::temporal_lf(&v);
        println!(
            "{}: {} slices of {n}x{n}, worst slice LF {worst:.5}, temporal LF {tlf:.4} \
             (white: share of bins with |f| < 0.125)",
            a.out.display(),
            v.t,
            n = v.n
        );
    }
    println!(
        "void-and-cluster {}x{}x{}: {secs:.2} s",
        a.size, a.size, a.frames
    );
    Ok(())
}

pub(crate) fn bayer(a: &BayerArgs) -> anyhow::Result<()> {
    check_side(a.size)?;
    write_2d(&Mask::new(a.size, voidcluster::bayer(a.size))?, &a.out)
}

pub(crate) fn white(a: &WhiteArgs) -> anyhow::Result<()> {
    check_side(a.size)?;
    write_2d(
        &Mask::new(a.size, voidcluster::white(a.size, a.seed))?,
        &a.out,
    )
}
