//! Radial averages, the low-frequency fraction `LF` and Ulichney's anisotropy.

use crate::Spectrum;

/// The `LF` cut-off of docs/results.md: 0.125 cycles/pixel.
pub const LF_CUTOFF: f64 = 0.125;

/// Radially averaged spectrum.
///
/// Bin `k` (`k = 0..=n/2`) holds every spectrum bin whose radius `r = |f|` in cycles/pixel
/// rounds to `k / n`, i.e. `r` in `[(k - 0.5)/n, (k + 0.5)/n)`. Bin 0 is DC alone. Bins past
/// `n/2` (the corners of the square spectrum, `0.5 < r <= 0.707`) are dropped, so every ring
/// is a full circle.
#[derive(Clone, Debug, PartialEq)]
pub struct RadialProfile {
    /// Ring centre `k / n`, cycles/pixel.
    pub freq: Vec<f64>,
    /// Mean power over the ring.
    pub power: Vec<f64>,
    /// Number of spectrum bins in the ring.
    pub count: Vec<usize>,
    /// Ulichney's anisotropy `10 log10(s^2 / mean^2)` in dB, `s^2` the unbiased variance of
    /// the power over the ring; NaN for rings of fewer than 2 bins or zero mean.
    pub anisotropy_db: Vec<f64>,
}

impl RadialProfile {
    /// Mean ring power over rings whose centre lies in `[lo, hi]` cycles/pixel.
    pub fn band_mean(&self, lo: f64, hi: f64) -> f64 {
        let (s, c) = self
            .freq
            .iter()
            .zip(&self.power)
            .filter(|(f, _)| **f >= lo && **f <= hi)
            .fold((0.0, 0usize), |(s, c), (_, p)| (s + p, c + 1));
        if c == 0 { f64::NAN } else { s / c as f64 }
    }
}

/// Radial average of a DC-centred spectrum (see [`RadialProfile`]).
pub fn radial_profile(s: &Spectrum) -> RadialProfile {
    let n = s.n;
    let bins = n / 2 + 1;
    let mut sum = vec![0.0; bins];
    let mut sum2 = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for y in 0..n {
        for x in 0..n {
            let (fx, fy) = s.freq(x, y);
            let k = ((fx * fx + fy * fy).sqrt() * n as f64).round() as usize;
            if k < bins {
                let p = s.power[y * n + x];
                sum[k] += p;
                sum2[k] += p * p;
                count[k] += 1;
            }
        }
    }
    let mut power = Vec::with_capacity(bins);
    let mut anisotropy_db = Vec::with_capacity(bins);
    for k in 0..bins {
        let c = count[k] as f64;
        let mean = if count[k] > 0 { sum[k] / c } else { 0.0 };
        power.push(mean);
        let a = if count[k] >= 2 && mean > 0.0 {
            let var = ((sum2[k] - c * mean * mean) / (c - 1.0)).max(0.0);
            10.0 * (var / (mean * mean)).log10()
        } else {
            f64::NAN
        };
        anisotropy_db.push(a);
    }
    RadialProfile {
        freq: (0..bins).map(|k| k as f64 / n as f64).collect(),
        power,
        count,
        anisotropy_db,
    }
}

/// Share of the spectrum's power at radius `0 < r < cutoff` cycles/pixel, over the power of
/// every non-DC bin (corners included). White noise gives the area fraction
/// `pi * cutoff^2` (0.049 for [`LF_CUTOFF`]); ideal blue noise gives ~0. Returns 0 for an
/// all-zero spectrum.
pub fn low_frequency_fraction(s: &Spectrum, cutoff: f64) -> f64 {
    let n = s.n;
    let (mut low, mut total) = (0.0, 0.0);
    for y in 0..n {
        for x in 0..n {
            let (fx, fy) = s.freq(x, y);
            let r2 = fx * fx + fy * fy;
            if r2 == 0.0 {
                continue;
            }
            let p = s.power[y * n + x];
            total += p;
            if r2 < cutoff * cutoff {
                low += p;
            }
        }
    }
    if total > 0.0 { low / total } else { 0.0 }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{Gray, Window, power_spectrum};

    /// Uniform white noise in [-0.5, 0.5) from SplitMix64 (test helper).
    pub(crate) fn white_noise(w: usize, h: usize, seed: u64) -> Gray {
        let mut s = seed;
        Gray::from_fn(w, h, |_, _| {
            s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = s;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            ((z >> 40) as f32 / (1u64 << 24) as f32) - 0.5
        })
    }

    #[test]
    fn white_noise_lf_is_the_area_fraction() {
        // 512^2 white noise, 64 Hann tiles of 64^2. Expected: the share of non-DC bins with
        // r < 0.125, 196/4095 = 0.0479 (pi/64 = 0.0491 in the continuum). Tolerance 0.004.
        let img = white_noise(512, 512, 11);
        let s = power_spectrum(&img, 64, Window::Hann).unwrap();
        let lf = low_frequency_fraction(&s, LF_CUTOFF);
        let bins = (0..64i64 * 64)
            .filter(|i| {
                let (x, y) = (i % 64 - 32, i / 64 - 32);
                x * x + y * y > 0 && x * x + y * y < 64
            })
            .count() as f64
            / 4095.0;
        assert!((lf - bins).abs() < 0.004, "LF {lf} vs {bins}");
        assert!((lf - 0.049).abs() < 0.005, "LF {lf}");
    }

    #[test]
    fn sinusoid_lands_in_its_ring() {
        // Frequency (10, 5)/64: r = 11.18/64 -> ring 11. Hann spreads an on-bin tone over (9..=11, 4..=6): rings 10..=13.
        let f = (10.0 / 64.0, 5.0 / 64.0);
        let img = Gray::from_fn(128, 128, |x, y| {
            (2.0 * std::f64::consts::PI * (f.0 * x as f64 + f.1 * y as f64)).cos() as f32
        });
        for window in [Window::Hann, Window::None] {
            let s = power_spectrum(&img, 64, window).unwrap();
            let r = radial_profile(&s);
            let ring_energy: Vec<f64> = r
                .power
                .iter()
                .zip(&r.count)
                .map(|(p, c)| p * *c as f64)
                .collect();
            let best = (1..r.power.len())
                .max_by(|&a, &b| ring_energy[a].total_cmp(&ring_energy[b]))
                .unwrap();
            assert_eq!(best, 11, "{window:?}");
            let total: f64 = ring_energy.iter().sum();
            let near: f64 = ring_energy[10..=13].iter().sum();
            assert!(near / total > 0.99, "{window:?}: {}", near / total);
        }
    }

    #[test]
    fn white_noise_rings_are_isotropic() {
        // Averaged over 64 tiles, each bin's power has relative variance ~1/64, so the
        // anisotropy of rings >= 8 sits near 10 log10(1/64) = -18 dB; allow up to -12 dB.
        let img = white_noise(512, 512, 5);
        let s = power_spectrum(&img, 64, Window::None).unwrap();
        let r = radial_profile(&s);
        for k in 8..=32 {
            assert!(
                r.anisotropy_db[k] < -12.0,
                "ring {k}: {}",
                r.anisotropy_db[k]
            );
        }
        assert_eq!(r.count[0], 1);
        assert!(r.anisotropy_db[0].is_nan());
    }
}
