//! Error power spectra (docs/results.md, "How the numbers are measured").
//!
//! **Normalisation.** For a tile `e` of side `n` with window `w`, after subtracting the tile's
//! mean `m`:
//!
//! `P(k) = |sum_x w(x) (e(x) - m) exp(-2 pi i k.x / n)|^2 / sum_x w(x)^2`.
//!
//! White noise of variance `v` then has `E[P(k)] = v` at every non-DC frequency, windowed or
//! not: the spectrum is flat at the variance. Without a window (`Window::None`) Parseval gives
//! `sum_k P(k) = sum_x (e(x) - m)^2`, i.e. the mean of `P` over all bins is the tile's variance.
//!
//! **Layout.** A [`Spectrum`] is DC-centred: bin `(x, y)` holds frequency
//! `(kx, ky) = (x - n/2, y - n/2)`, i.e. `(kx / n, ky / n)` cycles/pixel, so DC sits at
//! `(n/2, n/2)` and frequencies run from `-0.5` to `0.5 - 1/n`.

use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::{Error, Gray, Result};

/// The window applied to each tile before the FFT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Window {
    /// Separable periodic Hann window `w(x, y) = h(x) h(y)`, `h(i) = 0.5 - 0.5 cos(2 pi i / n)`
    /// (docs/results.md: error images, which are not periodic).
    Hann,
    /// No window: the periodogram of a periodic tile (masks, docs/algorithm.md).
    None,
}

/// A DC-centred power spectrum of square tiles of side `n` (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// Tile side.
    pub n: usize,
    /// `n * n` powers, row-major, DC at `(n/2, n/2)`.
    pub power: Vec<f64>,
}

impl Spectrum {
    /// Frequency of bin `(x, y)` in cycles/pixel.
    pub fn freq(&self, x: usize, y: usize) -> (f64, f64) {
        let h = (self.n / 2) as f64;
        let n = self.n as f64;
        ((x as f64 - h) / n, (y as f64 - h) / n)
    }

    /// Power at integer frequency `(kx, ky)` (any integers, taken modulo `n`).
    pub fn at(&self, kx: i64, ky: i64) -> f64 {
        let n = self.n as i64;
        let x = (kx + n / 2).rem_euclid(n) as usize;
        let y = (ky + n / 2).rem_euclid(n) as usize;
        self.power[y * self.n + x]
    }

    /// Mean power over every bin except DC.
    pub fn mean_ac_power(&self) -> f64 {
        let dc = (self.n / 2) * self.n + self.n / 2;
        let total: f64 = self.power.iter().sum::<f64>() - self.power[dc];
        total / (self.power.len() - 1).max(1) as f64
    }
}

/// Averages tile spectra over many tiles and images (e.g. over the frames of a report window).
pub struct SpectrumAccumulator {
    n: usize,
    window: Vec<f64>,
    norm: f64,
    fft: Arc<dyn Fft<f64>>,
    sum: Vec<f64>,
    count: usize,
}

impl std::fmt::Debug for SpectrumAccumulator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectrumAccumulator")
            .field("n", &self.n)
            .field("count", &self.count)
            .finish()
    }
}

impl SpectrumAccumulator {
    /// An empty accumulator for tiles of side `tile` (>= 2; docs/results.md uses 64).
    pub fn new(tile: usize, window: Window) -> Result<Self> {
        if tile < 2 {
            return Err(Error::Invalid(format!("tile size {tile} < 2")));
        }
        let h: Vec<f64> = (0..tile)
            .map(|i| match window {
                Window::Hann => {
                    0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / tile as f64).cos()
                }
                Window::None => 1.0,
            })
            .collect();
        let mut w = Vec::with_capacity(tile * tile);
        for y in 0..tile {
            for x in 0..tile {
                w.push(h[x] * h[y]);
            }
        }
        let norm = w.iter().map(|v| v * v).sum::<f64>();
        let fft = FftPlanner::new().plan_fft_forward(tile);
        Ok(SpectrumAccumulator {
            n: tile,
            window: w,
            norm,
            fft,
            sum: vec![0.0; tile * tile],
            count: 0,
        })
    }

    /// Tile side.
    pub fn tile(&self) -> usize {
        self.n
    }

    /// Number of tiles accumulated so far.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Adds every full tile of `img` (partial tiles at the right and bottom are ignored) and
    /// returns how many were added. Fails if the image is smaller than one tile.
    pub fn add_image(&mut self, img: &Gray) -> Result<usize> {
        let n = self.n;
        let (tx, ty) = (img.w / n, img.h / n);
        if tx == 0 || ty == 0 {
            return Err(Error::Invalid(format!(
                "image {}x{} is smaller than one {n}x{n} tile",
                img.w, img.h
            )));
        }
        let origins: Vec<(usize, usize)> = (0..ty)
            .flat_map(|j| (0..tx).map(move |i| (i * n, j * n)))
            .collect();
        // Fixed chunks summed in order: the result does not depend on the thread count.
        let partial: Vec<Vec<f64>> = origins
            .par_chunks(8)
            .map(|chunk| {
                let mut acc = vec![0.0; n * n];
                let mut buf = vec![Complex::new(0.0, 0.0); n * n];
                let mut tr = buf.clone();
                for &(ox, oy) in chunk {
                    self.tile_power(img, ox, oy, &mut buf, &mut tr, &mut acc);
                }
                acc
            })
            .collect();
        for p in partial {
            for (s, v) in self.sum.iter_mut().zip(p) {
                *s += v;
            }
        }
        self.count += origins.len();
        Ok(origins.len())
    }

    /// Adds the power of the tile at `(ox, oy)` to `acc` (DC-centred layout).
    fn tile_power(
        &self,
        img: &Gray,
        ox: usize,
        oy: usize,
        buf: &mut [Complex<f64>],
        tr: &mut [Complex<f64>],
        acc: &mut [f64],
    ) {
        let n = self.n;
        let mut mean = 0.0;
        for y in 0..n {
            for x in 0..n {
                mean += f64::from(img.at(ox + x, oy + y));
            }
        }
        mean /= (n * n) as f64;
        for y in 0..n {
            for x in 0..n {
                let v = (f64::from(img.at(ox + x, oy + y)) - mean) * self.window[y * n + x];
                buf[y * n + x] = Complex::new(v, 0.0);
            }
        }
        self.fft.process(buf); // rows: buf[y * n + kx]
        for y in 0..n {
            for kx in 0..n {
                tr[kx * n + y] = buf[y * n + kx];
            }
        }
        self.fft.process(tr); // columns: tr[kx * n + ky]
        let h = n / 2;
        for kx in 0..n {
            for ky in 0..n {
                let p = tr[kx * n + ky].norm_sqr() / self.norm;
                acc[((ky + h) % n) * n + (kx + h) % n] += p;
            }
        }
    }

    /// The mean spectrum over all tiles added so far.
    pub fn mean(&self) -> Result<Spectrum> {
        if self.count == 0 {
            return Err(Error::Invalid("no tiles accumulated".into()));
        }
        let c = self.count as f64;
        Ok(Spectrum {
            n: self.n,
            power: self.sum.iter().map(|s| s / c).collect(),
        })
    }
}

/// Mean spectrum over the full `tile`-sized tiles of one image.
pub fn power_spectrum(img: &Gray, tile: usize, window: Window) -> Result<Spectrum> {
    let mut acc = SpectrumAccumulator::new(tile, window)?;
    acc.add_image(img)?;
    acc.mean()
}

/// Toroidal periodogram of a square, periodic image (a mask tile): mean removed, no window,
/// one tile covering the whole image.
pub fn periodogram(img: &Gray) -> Result<Spectrum> {
    if img.w != img.h {
        return Err(Error::Invalid(format!(
            "periodogram needs a square tile, got {}x{}",
            img.w, img.h
        )));
    }
    power_spectrum(img, img.w, Window::None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radial::tests::white_noise;

    #[test]
    fn white_noise_spectrum_is_flat_at_the_variance() {
        // Uniform [-0.5, 0.5): variance 1/12. 16 Hann tiles of 64^2; the mean over non-DC bins
        // must be within 3% of 1/12, and the mean over any 8x8 block of bins within 15%.
        let img = white_noise(256, 256, 7);
        for window in [Window::Hann, Window::None] {
            let s = power_spectrum(&img, 64, window).unwrap();
            let v = 1.0 / 12.0;
            assert!((s.mean_ac_power() / v - 1.0).abs() < 0.03, "{window:?}");
            for by in 0..8 {
                for bx in 0..8 {
                    let mut m = 0.0;
                    for y in 0..8 {
                        for x in 0..8 {
                            m += s.power[(by * 8 + y) * 64 + bx * 8 + x];
                        }
                    }
                    m /= 64.0;
                    if (bx, by) != (4, 4) {
                        assert!(
                            (m / v - 1.0).abs() < 0.15,
                            "{window:?} block {bx},{by}: {m}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn unwindowed_parseval_holds() {
        let img = white_noise(32, 32, 3);
        let s = periodogram(&img).unwrap();
        let mean = img.mean();
        let var: f64 = img
            .data
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / 1024.0;
        let mean_p = s.power.iter().sum::<f64>() / 1024.0;
        assert!((mean_p - var).abs() < 1e-9 * var.max(1.0));
    }

    #[test]
    fn too_small_image_is_an_error() {
        let img = Gray::new(10, 100, vec![0.0; 1000]).unwrap();
        assert!(power_spectrum(&img, 64, Window::Hann).is_err());
    }
}
