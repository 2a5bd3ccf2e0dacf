//! Mask quality checks used by the tests, the `spectrum` command and the README.

use blueshift_analysis::assets::Mask;
use blueshift_analysis::{
    Gray, LF_CUTOFF, RadialProfile, Spectrum, Window, low_frequency_fraction, periodogram,
    power_spectrum, radial_profile,
};

/// High band used as the reference level: rings from 0.25 to 0.5 cycles/pixel.
pub const HIGH_BAND: (f64, f64) = (0.25, 0.5);

/// Spectral summary of a mask tile (values `rank / (n^2 - 1)`, toroidal periodogram).
#[derive(Clone, Debug)]
pub struct MaskQuality {
    /// The periodogram.
    pub spectrum: Spectrum,
    /// Its radial profile.
    pub profile: RadialProfile,
    /// `LF` of the periodogram.
    pub lf: f64,
    /// Largest ring power (rings >= 1) over the high-band mean.
    pub peak_ratio: f64,
}

/// Periodogram, radial profile, `LF` and peak ratio of a mask tile.
pub fn mask_quality(mask: &Mask) -> blueshift_analysis::Result<MaskQuality> {
    let spectrum = periodogram(&Gray::from(mask))?;
    let profile = radial_profile(&spectrum);
    let lf = low_frequency_fraction(&spectrum, LF_CUTOFF);
    let high = profile.band_mean(HIGH_BAND.0, HIGH_BAND.1);
    let peak = profile.power[1..].iter().cloned().fold(0.0, f64::max);
    Ok(MaskQuality {
        spectrum,
        profile,
        lf,
        peak_ratio: peak / high,
    })
}

/// Seam check of a tile.
///
/// Tile the mask 2x2 (side `2n`, seams through the centre), take its Hann-windowed spectrum
/// as one `2n` tile (the window is largest at the central seams, and the tiling is *not*
/// treated as periodic), and compare the mean power of the axis bins (`kx = 0` or `ky = 0`,
/// DC excluded) with the mean power of all other bins, both at radius `< 0.25` cycles/pixel.
/// A seam is a line discontinuity, whose energy lies on an axis line; a seamless tile gives a
/// ratio near 1 (measured 0.6-1.6 for void-and-cluster masks); the tests require `< 2.5`.
pub fn seam_ratio(mask: &Mask) -> blueshift_analysis::Result<f64> {
    let tiled: Gray = Gray::from(mask).tiled(2, 2);
    let s = power_spectrum(&tiled, 2 * mask.n, Window::Hann)?;
    let n = s.n;
    let (mut axis, mut na, mut off, mut no) = (0.0, 0usize, 0.0, 0usize);
    for y in 0..n {
        for x in 0..n {
            let (fx, fy) = s.freq(x, y);
            let r2 = fx * fx + fy * fy;
            if r2 == 0.0 || r2 >= 0.25 * 0.25 {
                continue;
            }
            let p = s.power[y * n + x];
            if fx == 0.0 || fy == 0.0 {
                axis += p;
                na += 1;
            } else {
                off += p;
                no += 1;
            }
        }
    }
    Ok((axis / na as f64) / (off / no as f64))
}

/// Temporal low-frequency fraction of a spatio-temporal mask: for every pixel, the DFT power
/// of its rank sequence over the `t` slices (mean removed), summed over pixels; the share at
/// `0 < |f| < 0.125` cycles/frame. White noise gives the share of such bins (6/31 = 0.19 for
/// `t = 32`); a well spread sequence gives much less.
pub fn temporal_lf(v: &blueshift_analysis::assets::StbnVolume) -> f64 {
    let (n, t) = (v.n, v.t);
    if t < 2 {
        return 0.0;
    }
    let area = n * n;
    let mut power = vec![0.0f64; t];
    let mut seq = vec![0.0f64; t];
    for px in 0..area {
        for (s, val) in seq.iter_mut().enumerate() {
            *val = f64::from(v.ranks[s * area + px]);
        }
        let mean = seq.iter().sum::<f64>() / t as f64;
        for (k, p) in power.iter_mut().enumerate().skip(1) {
            let (mut re, mut im) = (0.0, 0.0);
            for (s, val) in seq.iter().enumerate() {
                let a = -2.0 * std::f64::consts::PI * (k * s) as f64 / t as f64;
                re += (val - mean) * a.cos();
                im += (val - mean) * a.sin();
            }
            *p += re * re + im * im;
        }
    }
    let (mut low, mut total) = (0.0, 0.0);
    for (k, p) in power.iter().enumerate().skip(1) {
        let f = k.min(t - k) as f64 / t as f64;
        total += p;
        if f < 0.125 {
            low += p;
        }
    }
    if total > 0.0 { low / total } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voidcluster::{VcParams, bayer, void_and_cluster, white};

    fn vc(n: usize, seed: u64, toroidal: bool) -> Mask {
        let p = VcParams {
            toroidal,
            ..VcParams::new_2d(n, seed)
        };
        Mask::new(n, void_and_cluster(&p, &mut |_| {}).unwrap()).unwrap()
    }

    #[test]
    fn void_and_cluster_is_blue_white_is_not() {
        let q = mask_quality(&vc(64, 1, true)).unwrap();
        assert!(q.lf < 0.005, "LF {}", q.lf);
        assert!(q.peak_ratio < 2.0, "peak {}", q.peak_ratio);
        let w = mask_quality(&Mask::new(64, white(64, 1)).unwrap()).unwrap();
        assert!((w.lf - 0.049).abs() < 0.015, "white LF {}", w.lf);
        let b = mask_quality(&Mask::new(64, bayer(64)).unwrap()).unwrap();
        assert!(b.peak_ratio > 2.0, "Bayer has spikes: {}", b.peak_ratio);
    }

    #[test]
    fn seam_check_passes_toroidal_and_catches_non_toroidal_masks() {
        let good = seam_ratio(&vc(32, 4, true)).unwrap();
        let bad = seam_ratio(&vc(32, 4, false)).unwrap();
        assert!(good < 2.5, "toroidal mask seam ratio {good}");
        assert!(bad > 2.5, "non-toroidal mask seam ratio {bad}");
    }
}
