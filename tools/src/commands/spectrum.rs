//! `spectrum`: spectra, radial profiles and LF of images and masks.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use blueshift_analysis::assets::{load_mask, load_stbn};
use blueshift_analysis::{
    Gray, LF_CUTOFF, RadialSeries, Spectrum, SpectrumAccumulator, Window, low_frequency_fraction,
    plot_radial_profiles, radial_profile, save_spectrum_png,
};

use crate::quality::HIGH_BAND;

/// `spectrum` flags.
#[derive(Debug, clap::Args)]
pub struct SpectrumArgs {
    /// PNG/EXR images or `.r16` masks.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Tile side for images (Hann-windowed tiles, docs/results.md).
    #[arg(long, default_value_t = 64)]
    pub tile: usize,
    /// Treat square images as periodic tiles: unwindowed periodogram of the whole image.
    #[arg(long)]
    pub periodic: bool,
    /// Read `.r16` inputs as spatio-temporal volumes with this slice side (averages the
    /// slices' periodograms).
    #[arg(long)]
    pub stbn_size: Option<usize>,
}

/// A spectrum with a description of how it was computed.
pub(crate) struct Analysed {
    pub spectrum: Spectrum,
    pub method: String,
}

/// Masks (`.r16`): toroidal periodogram (averaged over slices for volumes). Images: Hann
/// tiles of `tile` (shrunk to the largest power of two that fits), or one periodogram.
pub(crate) fn analyse(
    path: &Path,
    tile: usize,
    periodic: bool,
    stbn: Option<usize>,
) -> anyhow::Result<Analysed> {
    let is_r16 = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("r16"));
    if is_r16 {
        let (n, slices): (usize, Vec<Gray>) = match stbn {
            Some(n) => {
                let v = load_stbn(path, n)?;
                let s = (0..v.t)
                    .map(|s| v.slice(s).map(|m| Gray::from(&m)))
                    .collect::<Result<_, _>>()?;
                (n, s)
            }
            None => {
                let m = load_mask(path)?;
                (m.n, vec![Gray::from(&m)])
            }
        };
        let mut acc = SpectrumAccumulator::new(n, Window::None)?;
        for g in &slices {
            acc.add_image(g)?;
        }
        let method = format!("periodogram {n}x{n}, {} slice(s)", slices.len());
        return Ok(Analysed {
            spectrum: acc.mean()?,
            method,
        });
    }
    let img = Gray::load(path)?;
    if periodic {
        if img.w != img.h {
            bail!(
                "{}: --periodic needs a square image, got {}x{}",
                path.display(),
                img.w,
                img.h
            );
        }
        return Ok(Analysed {
            spectrum: blueshift_analysis::periodogram(&img)?,
            method: format!("periodogram {}x{}", img.w, img.h),
        });
    }
    let side = img.w.min(img.h);
    if side < 2 {
        bail!("{}: image {}x{} too small", path.display(), img.w, img.h);
    }
    let fit = 1usize << (usize::BITS - 1 - side.leading_zeros());
    let t = tile.min(fit).max(2);
    let mut acc = SpectrumAccumulator::new(t, Window::Hann)?;
    let tiles = acc.add_image(&img)?;
    Ok(Analysed {
        spectrum: acc.mean()?,
        method: format!("Hann {t}x{t} tiles x{tiles}"),
    })
}

/// Radial profile relative to the mean non-DC power (white noise is flat at 1).
pub(crate) fn normalised_series(name: &str, s: &Spectrum) -> RadialSeries {
    let r = radial_profile(s);
    let m = s.mean_ac_power();
    let scale = if m > 0.0 { 1.0 / m } else { 1.0 };
    RadialSeries {
        name: name.to_string(),
        freq: r.freq,
        power: r.power.iter().map(|p| p * scale).collect(),
    }
}

pub(crate) fn spectrum(a: &SpectrumArgs) -> anyhow::Result<()> {
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let mut series = Vec::new();
    let mut names = HashSet::new();
    println!("{:<24} {:>9} {:>10}  method", "input", "LF", "peak/high");
    for (i, path) in a.inputs.iter().enumerate() {
        let res = analyse(path, a.tile, a.periodic, a.stbn_size)?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let name = if names.insert(stem.clone()) {
            stem
        } else {
            format!("{i}_{stem}")
        };
        save_spectrum_png(&res.spectrum, &a.out.join(format!("{name}_spectrum.png")))?;
        let lf = low_frequency_fraction(&res.spectrum, LF_CUTOFF);
        let s = normalised_series(&name, &res.spectrum);
        let high = radial_profile(&res.spectrum).band_mean(HIGH_BAND.0, HIGH_BAND.1);
        let peak = radial_profile(&res.spectrum).power[1..]
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        println!("{name:<24} {lf:>9.5} {:>10.2}  {}", peak / high, res.method);
        series.push(s);
    }
    let chart = a.out.join("radial.png");
    plot_radial_profiles(
        &series,
        "Radially averaged power (relative to mean)",
        &chart,
    )?;
    println!("wrote {} and <input>_spectrum.png", chart.display());
    Ok(())
}
