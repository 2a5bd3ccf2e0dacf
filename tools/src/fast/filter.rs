//! The separable filter a FAST texture is optimised for, and its autocorrelation.
//!
//! Everything lives on rings (the texture tiles in x, y and t), so a filter is a list of
//! taps indexed by offset modulo the ring length. Filtering a tiled error image with taps
//! `w` and averaging the squared result over the tile weights each pair of pixels by the
//! autocorrelation `a(d) = sum_i w(i) w(i + d)` of the taps; that is why the loss
//! (mod.rs) uses `a`, not `w` (FAST's "doubled" filter).

/// The temporal half of the filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Temporal {
    /// Exponential moving average `y_t = alpha s_t + (1 - alpha) y_{t-1}` (TAA). Its steady
    /// state on a texture that loops every `T` frames weights the frame `k` frames ago by
    /// `alpha (1 - alpha)^k / (1 - (1 - alpha)^T)`: the EMA wrapped toroidally in time.
    Ema {
        /// Blend factor in (0, 1].
        alpha: f64,
    },
    /// Symmetric Gaussian over frames (a denoiser that also sees later frames), wrapped.
    Gauss {
        /// Sigma in frames.
        sigma: f64,
    },
}

/// Taps of a sampled Gaussian (`exp(-i^2 / 2 sigma^2)` for `|i| <= ceil(3 sigma)`,
/// normalised to sum 1), folded onto a ring of `len`. Sampled rather than pixel-integrated
/// because the benchmark applies exactly these taps, so loss and measurement agree.
pub fn gaussian_ring(len: usize, sigma: f64) -> Vec<f64> {
    let r = (3.0 * sigma).ceil() as i64;
    let mut w = vec![0.0; len];
    let mut sum = 0.0;
    for i in -r..=r {
        let v = (-(i * i) as f64 / (2.0 * sigma * sigma)).exp();
        w[i.rem_euclid(len as i64) as usize] += v;
        sum += v;
    }
    w.iter_mut().for_each(|v| *v /= sum);
    w
}

/// Causal EMA taps on a ring of `len` frames: index `k` is the weight of the frame `k`
/// frames ago in the steady state (see [`Temporal::Ema`]); they sum to 1.
pub fn ema_ring(len: usize, alpha: f64) -> Vec<f64> {
    let keep = 1.0 - alpha;
    let norm = 1.0 - keep.powi(len as i32);
    (0..len)
        .map(|k| alpha * keep.powi(k as i32) / norm)
        .collect()
}

/// Circular autocorrelation `a(d) = sum_i w(i) w((i + d) mod len)`.
pub fn autocorr_ring(w: &[f64]) -> Vec<f64> {
    let n = w.len();
    (0..n)
        .map(|d| (0..n).map(|i| w[i] * w[(i + d) % n]).sum())
        .collect()
}

/// A spatial offset with its autocorrelation weight `a(dx) a(dy)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Offset {
    /// Signed offsets, in `-(n/2 - 1)..=n/2`.
    pub dx: i32,
    pub dy: i32,
    /// Weight.
    pub w: f64,
}

/// The product filter of one texture size: 1D spatial taps (used for x and y), temporal
/// taps, and their autocorrelations.
#[derive(Clone, Debug, PartialEq)]
pub struct Filter {
    /// Spatial taps on the ring of the side `n`.
    pub spatial: Vec<f64>,
    /// Temporal taps on the ring of `T` frames (index = frames ago for the EMA).
    pub temporal: Vec<f64>,
    /// Autocorrelation of `spatial`.
    pub acs: Vec<f64>,
    /// Autocorrelation of `temporal`.
    pub act: Vec<f64>,
}

impl Filter {
    /// The filter for an `n x n x frames` texture.
    pub fn new(n: usize, frames: usize, sigma: f64, temporal: Temporal) -> Filter {
        let spatial = gaussian_ring(n, sigma);
        let temporal = match temporal {
            Temporal::Ema { alpha } => ema_ring(frames, alpha),
            Temporal::Gauss { sigma } => gaussian_ring(frames, sigma),
        };
        Filter {
            acs: autocorr_ring(&spatial),
            act: autocorr_ring(&temporal),
            spatial,
            temporal,
        }
    }

    /// Side `n`.
    pub fn n(&self) -> usize {
        self.spatial.len()
    }

    /// Spatial autocorrelation offsets with weight above `eps` times the peak, each ring
    /// offset once. `eps = 0` keeps every nonzero one (the exact loss); the optimiser drops
    /// the tail to save time (its weights decay like `exp(-d^2 / 4 sigma^2)`).
    pub fn support(&self, eps: f64) -> Vec<Offset> {
        let n = self.n() as i32;
        let peak = self.acs[0] * self.acs[0];
        let signed = |d: i32| if d > n / 2 { d - n } else { d };
        let mut out = Vec::new();
        for y in 0..n {
            for x in 0..n {
                let w = self.acs[x as usize] * self.acs[y as usize];
                if w > eps * peak && w > 0.0 {
                    out.push(Offset {
                        dx: signed(x),
                        dy: signed(y),
                        w,
                    });
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taps_sum_to_one_and_autocorrelation_is_symmetric() {
        for w in [
            gaussian_ring(16, 1.0),
            ema_ring(8, 0.1),
            gaussian_ring(4, 3.0),
        ] {
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let a = autocorr_ring(&w);
            assert!((a.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            for d in 1..w.len() {
                assert!((a[d] - a[w.len() - d]).abs() < 1e-15);
                assert!(a[d] <= a[0] + 1e-15);
            }
        }
    }

    #[test]
    fn ema_ring_is_the_steady_state_of_the_recursion() {
        // Run y = alpha s + (1 - alpha) y over many loops of a T-periodic impulse train.
        let (t, alpha) = (8, 0.1);
        let w = ema_ring(t, alpha);
        let mut y = 0.0;
        let mut seen = vec![0.0; t];
        for f in 0..200 * t {
            y = alpha * f64::from(u8::from(f % t == 0)) + (1.0 - alpha) * y;
            seen[f % t] = y;
        }
        for k in 0..t {
            assert!((seen[k] - w[k]).abs() < 1e-12, "{k}: {} {}", seen[k], w[k]);
        }
    }

    #[test]
    fn support_keeps_each_ring_offset_once() {
        let f = Filter::new(16, 4, 1.0, Temporal::Ema { alpha: 0.2 });
        let s = f.support(0.0);
        assert!((s.iter().map(|o| o.w).sum::<f64>() - 1.0).abs() < 1e-12);
        let t = f.support(1e-3);
        assert!(t.len() < s.len() && t.iter().any(|o| (o.dx, o.dy) == (0, 0)));
    }
}
