//! FAST's unit benchmark: how well a texture integrates step functions after the filter.
//!
//! Each trial draws a step integrand per pixel, estimates it at every voxel with that
//! voxel's value as the one sample, filters the errors with the spatial Gaussian and then
//! the EMA (or temporal Gaussian), and accumulates the squared filtered error. The filter is
//! linear and normalised, so this is the filtered estimate minus the filtered exact
//! integrals. The EMA is taken in its steady state on the looping texture (filter.rs),
//! which is what a renderer sees after the first few dozen frames.
//!
//! Integrands ([`Integrand`]): scalar values use `[x < c]` (integral `c`); 2D values use a
//! half-plane `[n . x < c]` with random direction `n` (integral: the clipped area).
//! `Const` shares one integrand over the screen and time, as in the paper's evaluation and
//! exactly the case the loss models (mod.rs); `Smooth` lets the threshold (2D: direction
//! and offset) vary as a low-frequency wave over the screen; `Pixel` draws an independent
//! integrand per pixel, so only each pixel's own values matter for its exact value, while
//! errors still average across pixels through the filter.

use rayon::prelude::*;

use super::{Filter, Volume};
use crate::rng::{Pcg32, splitmix64};

/// How the integrand varies over the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Integrand {
    /// One integrand everywhere.
    Const,
    /// Parameters vary as a random low-frequency wave over the screen.
    Smooth,
    /// An independent integrand per pixel.
    Pixel,
}

impl Integrand {
    /// All kinds, in table order.
    pub const ALL: [Integrand; 3] = [Integrand::Const, Integrand::Smooth, Integrand::Pixel];

    /// Column name.
    pub fn name(self) -> &'static str {
        match self {
            Integrand::Const => "const",
            Integrand::Smooth => "smooth",
            Integrand::Pixel => "pixel",
        }
    }
}

/// Area of `{x in [0,1]^2 : n . x < c}` (clip the square, shoelace).
pub fn halfplane_area(n: [f64; 2], c: f64) -> f64 {
    let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let f = |p: [f64; 2]| n[0] * p[0] + n[1] * p[1] - c;
    let mut poly: Vec<[f64; 2]> = Vec::with_capacity(5);
    for i in 0..4 {
        let (a, b) = (sq[i], sq[(i + 1) % 4]);
        let (fa, fb) = (f(a), f(b));
        if fa < 0.0 {
            poly.push(a);
        }
        if (fa < 0.0) != (fb < 0.0) {
            let s = fa / (fa - fb);
            poly.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]);
        }
    }
    let k = poly.len();
    (0..k)
        .map(|i| {
            let (p, q) = (poly[i], poly[(i + 1) % k]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum::<f64>()
        .abs()
        / 2.0
}

/// One step integrand: `[x < c]` for scalars (`dir` unused), `[dir . x < c]` for 2D.
#[derive(Clone, Copy, Debug)]
struct Step {
    dir: [f64; 2],
    c: f64,
    exact: f64,
}

impl Step {
    /// From two numbers in [0, 1): the threshold (scalar) or angle and offset (2D).
    fn new(dims: usize, u: f64, v: f64) -> Step {
        if dims == 1 {
            return Step {
                dir: [1.0, 0.0],
                c: u,
                exact: u,
            };
        }
        let a = std::f64::consts::TAU * u;
        let dir = [a.cos(), a.sin()];
        // Offsets spread uniformly over the square's projection onto `dir`.
        let lo = dir[0].min(0.0) + dir[1].min(0.0);
        let hi = dir[0].max(0.0) + dir[1].max(0.0);
        let c = lo + v * (hi - lo);
        Step {
            dir,
            c,
            exact: halfplane_area(dir, c),
        }
    }

    fn error(&self, x: [f32; 2]) -> f64 {
        let s = self.dir[0] * f64::from(x[0]) + self.dir[1] * f64::from(x[1]);
        f64::from(u8::from(s < self.c)) - self.exact
    }
}

/// The integrand of every pixel for one trial.
fn integrands(kind: Integrand, dims: usize, n: usize, rng: &mut Pcg32) -> Vec<Step> {
    match kind {
        Integrand::Const => vec![Step::new(dims, rng.next_f64(), rng.next_f64()); n * n],
        Integrand::Pixel => (0..n * n)
            .map(|_| Step::new(dims, rng.next_f64(), rng.next_f64()))
            .collect(),
        Integrand::Smooth => {
            // A wave of 1 or 2 periods per tile (so it tiles), amplitude 0.45 around a random
            // centre, wrapped into [0, 1).
            let mut wave = || {
                let k = [rng.below(5) as f64 - 2.0, rng.below(2) as f64 + 1.0];
                let (phase, centre) = (std::f64::consts::TAU * rng.next_f64(), rng.next_f64());
                move |x: usize, y: usize| {
                    let arg =
                        std::f64::consts::TAU * (k[0] * x as f64 + k[1] * y as f64) / n as f64;
                    (centre + 0.45 * (arg + phase).sin()).rem_euclid(1.0)
                }
            };
            let (fu, fv) = (wave(), wave());
            (0..n * n)
                .map(|p| Step::new(dims, fu(p % n, p / n), fv(p % n, p / n)))
                .collect()
        }
    }
}

/// Sum of squared filtered errors of one trial.
fn trial(vol: &Volume, filter: &Filter, steps: &[Step]) -> f64 {
    let (n, tn) = (vol.n, vol.frames);
    let taps: Vec<(usize, f64)> = filter
        .spatial
        .iter()
        .copied()
        .enumerate()
        .filter(|&(_, w)| w > 0.0)
        .collect();
    let ttaps: Vec<(usize, f64)> = filter.temporal.iter().copied().enumerate().collect();
    // errors, then spatially filtered errors, slice-major: [t][y][x]
    let mut e = vec![0.0f64; n * n * tn];
    for t in 0..tn {
        for p in 0..n * n {
            e[t * n * n + p] = steps[p].error(vol.get(p, t));
        }
    }
    let mut tmp = vec![0.0f64; n * n];
    for slice in e.chunks_exact_mut(n * n) {
        for y in 0..n {
            for x in 0..n {
                tmp[y * n + x] = taps
                    .iter()
                    .map(|&(k, w)| w * slice[y * n + (x + n - k) % n])
                    .sum();
            }
        }
        for y in 0..n {
            for x in 0..n {
                slice[y * n + x] = taps
                    .iter()
                    .map(|&(k, w)| w * tmp[((y + n - k) % n) * n + x])
                    .sum();
            }
        }
    }
    let mut total = 0.0;
    for p in 0..n * n {
        for t in 0..tn {
            let y: f64 = ttaps
                .iter()
                .map(|&(k, w)| w * e[((t + tn - k) % tn) * n * n + p])
                .sum();
            total += y * y;
        }
    }
    total
}

/// RMSE over all voxels of the filtered error for `trials` random integrands of `kind`.
/// Deterministic for a given seed (trial `i` uses its own PRNG stream).
pub fn filtered_rmse(
    vol: &Volume,
    filter: &Filter,
    kind: Integrand,
    trials: u32,
    seed: u64,
) -> f64 {
    let sums: Vec<f64> = (0..trials)
        .into_par_iter()
        .map(|i| {
            let mut s = seed ^ u64::from(i).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            let mut rng = Pcg32::new(splitmix64(&mut s));
            let steps = integrands(kind, vol.dims, vol.n, &mut rng);
            trial(vol, filter, &steps)
        })
        .collect();
    let voxels = (vol.n * vol.n * vol.frames) as f64;
    (sums.iter().sum::<f64>() / (voxels * f64::from(trials.max(1)))).sqrt()
}

/// A white-noise texture: every slice an independent random permutation of the ranks.
pub fn white_ranks(n: usize, frames: usize, seed: u64) -> Vec<u16> {
    let mut rng = Pcg32::new(seed ^ 0x0001_7e57);
    let mut out = Vec::with_capacity(n * n * frames);
    for _ in 0..frames {
        let mut s: Vec<u16> = (0..n * n).map(|r| r as u16).collect();
        rng.shuffle(&mut s);
        out.extend(s);
    }
    out
}
