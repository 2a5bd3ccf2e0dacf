//! FAST: filter-adapted spatio-temporal sampling (Donnelly, Wolfe, Bütepage & Valdés,
//! I3D 2024), written from the paper's description and the facts of its public
//! implementation (electronicarts/fastnoise). A texture of `n x n x T` sample values is
//! arranged so that the Monte Carlo error, after the spatial x temporal filter the renderer
//! applies, is as small as possible.
//!
//! **Loss.** For a step integrand `f_c(x) = [x < c]` with `c` uniform in (0, 1), the error of
//! the one-sample estimate at voxel `i` is `e_i = [x_i < c] - c`, and
//! `E[e_i e_j] = 1/3 + h(x_i) + h(x_j) - |x_i - x_j| / 2` with `h(x) = (x^2 - x) / 2`.
//! Filtering with a normalised filter `w` on the torus and averaging over output voxels
//! weights each pair by the filter's autocorrelation `A = w * w` (filter.rs), so the mean
//! squared filtered error is
//!
//! `MSE = 1/3 + (2/N) sum_i h(x_i) + L / (2N)`, with `L = -sum_{i,j} A(i - j) |x_i - x_j|`.
//!
//! The `h` term is fixed by the value histogram, so minimising `L` (FAST's pairwise loss
//! with the kernel `-|x - y|`; `-||x - y||` for 2D vectors) minimises the filtered error.
//! [`predicted_mse`] reports it; the benchmark (bench.rs) measures the same quantity, which
//! is the cross-check that the loss is right.
//!
//! **Per-pixel integrands** ([`Model::Pixel`], an addition to the paper). If each pixel has
//! its own independent threshold (fixed over time), voxels of different pixels only share
//! their conditional mean errors, `E[e_i e_j] = (x_i - 1/2)(x_j - 1/2)`: between pixels the
//! loss becomes the energy of the filtered, centred texture, while pairs within a pixel keep
//! `-|x - y|`. (For 2D values the dot product of the centred vectors is the analogous,
//! approximate, kernel.)
//!
//! **Values and invariants.** Values are stratified ranks: every slice is a permutation of
//! `0..n^2` (the `.r16` format of `blueshift_assets::StbnVolume`), rank `r` meaning the
//! scalar `(r + 0.5) / n^2`, or for `dims = 2` the centre of cell `(r mod n, r div n)` of an
//! `n x n` grid. In addition every pixel's `T` values fall one into each of `T` equal temporal
//! strata (scalar: `[k/T, (k+1)/T)`; 2D: the cells of a `gx x gy = T` grid), so a pixel's
//! values over time are also well stratified. [`stratified_init`] builds such a texture and
//! the optimiser (anneal.rs) only makes swaps that keep both properties.

pub mod anneal;
pub mod bench;
pub mod filter;
#[cfg(test)]
mod tests;

use rayon::prelude::*;
use thiserror::Error;

pub use filter::{Filter, Offset, Temporal};

use crate::rng::Pcg32;

/// Invalid FAST parameters or volumes.
#[derive(Debug, Error)]
pub enum FastError {
    #[error("--size {0}: must be a power of two in 4..=256 (ranks are stored as u16)")]
    Side(usize),
    #[error(
        "--frames {frames}: must be a power of two in 1..={max} (each pixel's values are \
         stratified into `frames` equal strata of the {area} ranks of a slice)"
    )]
    Frames {
        frames: usize,
        max: usize,
        area: usize,
    },
    #[error("--dims {0}: must be 1 (scalar values) or 2 (2D vectors)")]
    Dims(usize),
    #[error("--sigma {0}: must be a finite number > 0 (spatial Gaussian sigma in pixels)")]
    Sigma(f64),
    #[error("--alpha {0}: must be in (0, 1] (EMA blend factor)")]
    Alpha(f64),
    #[error("--sigma-t {0}: must be a finite number > 0 (temporal Gaussian sigma in frames)")]
    SigmaT(f64),
    #[error("--iterations and --rounds must be at least 1")]
    Zero,
    #[error("{0}")]
    Volume(String),
}

/// Which integrands the loss models (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Model {
    /// One step integrand for all voxels (the paper): kernel `-|x - y|` everywhere.
    Shared,
    /// An independent step integrand per pixel: filtered texture energy between pixels.
    Pixel,
}

/// What to optimise.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Side of each slice (power of two, 4..=256).
    pub n: usize,
    /// Slices (power of two, `<= min(256, n^2)`).
    pub frames: usize,
    /// 1 for scalars, 2 for 2D vectors.
    pub dims: usize,
    /// Spatial Gaussian sigma in pixels.
    pub sigma: f64,
    /// Temporal filter.
    pub temporal: Temporal,
    /// Integrand model of the loss.
    pub model: Model,
    /// Swap proposals per voxel, over the whole run.
    pub iterations: u32,
    /// Annealing rounds (temperature steps; the block grid moves every round).
    pub rounds: u32,
    /// PRNG seed (initial texture and proposals).
    pub seed: u64,
}

impl Params {
    /// Checks every parameter, naming the flag at fault.
    pub fn validate(&self) -> Result<(), FastError> {
        check_shape(self.n, self.frames, self.dims)?;
        if !(self.sigma.is_finite() && self.sigma > 0.0) {
            return Err(FastError::Sigma(self.sigma));
        }
        match self.temporal {
            Temporal::Ema { alpha } if !(alpha > 0.0 && alpha <= 1.0) => {
                return Err(FastError::Alpha(alpha));
            }
            Temporal::Gauss { sigma } if !(sigma.is_finite() && sigma > 0.0) => {
                return Err(FastError::SigmaT(sigma));
            }
            _ => {}
        }
        if self.iterations == 0 || self.rounds == 0 {
            return Err(FastError::Zero);
        }
        Ok(())
    }

    /// The filter these parameters describe.
    pub fn filter(&self) -> Filter {
        Filter::new(self.n, self.frames, self.sigma, self.temporal)
    }
}

/// Checks side, frame count and dimension of a texture.
pub fn check_shape(n: usize, frames: usize, dims: usize) -> Result<(), FastError> {
    if !(4..=256).contains(&n) || !n.is_power_of_two() {
        return Err(FastError::Side(n));
    }
    let max = 256.min(n * n);
    if !(1..=max).contains(&frames) || !frames.is_power_of_two() {
        return Err(FastError::Frames {
            frames,
            max,
            area: n * n,
        });
    }
    if !(1..=2).contains(&dims) {
        return Err(FastError::Dims(dims));
    }
    Ok(())
}

/// The value of rank `r` in a slice of side `n` (module docs); `[x, 0]` for scalars.
pub fn decode(dims: usize, n: usize, r: u16) -> [f32; 2] {
    let r = usize::from(r);
    if dims == 1 {
        [(r as f32 + 0.5) / (n * n) as f32, 0.0]
    } else {
        [(r % n) as f32 + 0.5, (r / n) as f32 + 0.5].map(|v| v / n as f32)
    }
}

/// Inverse of [`decode`].
pub fn encode(dims: usize, n: usize, v: [f32; 2]) -> u16 {
    let cell = |x: f32, k: usize| (x * k as f32 - 0.5).round() as usize;
    (if dims == 1 {
        cell(v[0], n * n)
    } else {
        cell(v[1], n) * n + cell(v[0], n)
    }) as u16
}

/// The temporal strata grid `(gx, gy)` for 2D values: `gx * gy = frames`, as square as
/// possible.
pub fn strata_grid(frames: usize) -> (usize, usize) {
    let gx = 1 << frames.trailing_zeros().div_ceil(2);
    (gx, frames / gx)
}

/// The temporal stratum (`0..frames`) of a value.
pub fn stratum(dims: usize, frames: usize, v: [f32; 2]) -> usize {
    let bin = |x: f32, k: usize| ((x * k as f32) as usize).min(k - 1);
    if dims == 1 {
        bin(v[0], frames)
    } else {
        let (gx, gy) = strata_grid(frames);
        bin(v[1], gy) * gx + bin(v[0], gx)
    }
}

/// A texture being optimised: values per pixel, component and frame,
/// `vals[(pixel * dims + d) * frames + t]`, so that a pixel's values over time (what one
/// term of the loss reads) are contiguous.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    pub n: usize,
    pub frames: usize,
    pub dims: usize,
    pub vals: Vec<f32>,
}

impl Volume {
    /// From slice-major ranks (`(t * n + y) * n + x`, the `.r16` order).
    pub fn from_ranks(n: usize, frames: usize, dims: usize, ranks: &[u16]) -> Volume {
        let a = n * n;
        let mut vals = vec![0.0; a * dims * frames];
        for (i, &r) in ranks.iter().enumerate() {
            let (t, p) = (i / a, i % a);
            let v = decode(dims, n, r);
            for (d, &x) in v.iter().enumerate().take(dims) {
                vals[(p * dims + d) * frames + t] = x;
            }
        }
        Volume {
            n,
            frames,
            dims,
            vals,
        }
    }

    /// Value of pixel `p` in frame `t`.
    pub fn get(&self, p: usize, t: usize) -> [f32; 2] {
        let base = p * self.dims * self.frames + t;
        let y = if self.dims == 2 {
            self.vals[base + self.frames]
        } else {
            0.0
        };
        [self.vals[base], y]
    }

    /// Slice-major ranks.
    pub fn ranks(&self) -> Vec<u16> {
        let a = self.n * self.n;
        (0..a * self.frames)
            .map(|i| encode(self.dims, self.n, self.get(i % a, i / a)))
            .collect()
    }

    /// Whether every pixel has exactly one value in each temporal stratum.
    pub fn temporally_stratified(&self) -> bool {
        (0..self.n * self.n).all(|p| {
            let mut seen = vec![false; self.frames];
            (0..self.frames).all(|t| {
                !std::mem::replace(
                    &mut seen[stratum(self.dims, self.frames, self.get(p, t))],
                    true,
                )
            })
        })
    }
}

/// FAST's starting point with temporal strata: every slice a permutation of the ranks and
/// every pixel one value per stratum. Pixels are shuffled into groups of `T`; pixel `c` of
/// group `g` visits the strata in the order `P_g(t + c mod T)`, with `P_g` a random
/// permutation per group, so each group puts each stratum on exactly one pixel per slice.
/// Within a slice, the ranks of a stratum are then dealt at random to its `n^2 / T` pixels.
pub fn stratified_init(n: usize, frames: usize, dims: usize, seed: u64) -> Vec<u16> {
    let a = n * n;
    let mut rng = Pcg32::new(seed);
    let mut order: Vec<usize> = (0..a).collect();
    rng.shuffle(&mut order);
    // strata[p * frames + t]
    let mut strata = vec![0usize; a * frames];
    for group in order.chunks_exact(frames) {
        let mut perm: Vec<usize> = (0..frames).collect();
        rng.shuffle(&mut perm);
        for (c, &p) in group.iter().enumerate() {
            for t in 0..frames {
                strata[p * frames + t] = perm[(t + c) % frames];
            }
        }
    }
    let mut members: Vec<Vec<u16>> = vec![Vec::new(); frames];
    for r in 0..a {
        members[stratum(dims, frames, decode(dims, n, r as u16))].push(r as u16);
    }
    let mut ranks = vec![0u16; a * frames];
    for t in 0..frames {
        let mut pools = members.clone();
        pools.iter_mut().for_each(|p| rng.shuffle(p));
        for p in 0..a {
            ranks[t * a + p] = pools[strata[p * frames + t]].pop().unwrap_or_default();
        }
    }
    ranks
}

/// Minus the kernel `K(a, b)` of the loss between two voxels (module docs): `|a - b|` for
/// the same pixel or [`Model::Shared`], `-2 (a - 1/2) . (b - 1/2)` between pixels for
/// [`Model::Pixel`] (twice `E[e_a e_b]`, like `|a - b|`).
fn neg_kernel(model: Model, same_pixel: bool, a: [f32; 2], b: [f32; 2], dims: usize) -> f64 {
    let (a, b) = (a.map(f64::from), b.map(f64::from));
    if same_pixel || model == Model::Shared {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
    } else {
        let c = |v: f64| v - 0.5;
        -2.0 * (c(a[0]) * c(b[0]) + if dims == 2 { c(a[1]) * c(b[1]) } else { 0.0 })
    }
}

/// FAST's pairwise loss `L = sum_{i,j} A(i - j) K(x_i, x_j)` (module docs) over the spatial
/// offsets `support` and all frame pairs, divided by the voxel count.
pub fn pair_loss(vol: &Volume, filter: &Filter, support: &[Offset], model: Model) -> f64 {
    let (n, tn) = (vol.n as i32, vol.frames);
    let per_pixel: Vec<f64> = (0..vol.n * vol.n)
        .into_par_iter()
        .map(|p| {
            let (x, y) = (p as i32 % n, p as i32 / n);
            let mut s = 0.0;
            for o in support {
                let q = ((y + o.dy).rem_euclid(n) * n + (x + o.dx).rem_euclid(n)) as usize;
                for t in 0..tn {
                    let a = vol.get(p, t);
                    let row: f64 = (0..tn)
                        .map(|u| {
                            let k = neg_kernel(model, p == q, a, vol.get(q, u), vol.dims);
                            filter.act[(u + tn - t) % tn] * k
                        })
                        .sum();
                    s += o.w * row;
                }
            }
            -s
        })
        .collect();
    per_pixel.iter().sum::<f64>() / (vol.vals.len() / vol.dims) as f64
}

/// The mean squared filtered error of a scalar texture for step integrands with uniform
/// thresholds, shared by all voxels ([`Model::Shared`], the benchmark's `const` integrand)
/// or drawn per pixel ([`Model::Pixel`], the benchmark's `pixel`), from its exact loss
/// `loss = pair_loss(vol, filter, &filter.support(0.0), model)`.
pub fn predicted_mse(vol: &Volume, filter: &Filter, model: Model, loss: f64) -> f64 {
    let h = vol
        .vals
        .iter()
        .map(|&x| f64::from(x) * (f64::from(x) - 1.0) / 2.0)
        .sum::<f64>()
        / vol.vals.len() as f64;
    // The histogram terms come from pairs within a pixel only in the per-pixel model.
    let same = match model {
        Model::Shared => 1.0,
        Model::Pixel => filter.acs[0] * filter.acs[0],
    };
    same * (1.0 / 3.0 + 2.0 * h) + loss / 2.0
}
