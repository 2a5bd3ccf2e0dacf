//! Retargeting permutations (docs/algorithm.md).
//!
//! The problem: find a permutation `pi` of the `n x n` torus with toroidal displacement
//! `d(u) = pi(u) - u` inside the Euclidean disc `|d|^2 <= R^2`, minimising
//! `E(pi) = sum_u |M(u) - M(pi(u) + s)|` (mask ranks, integer). The stored table holds
//! `d(u)`; [`blueshift_analysis::assets::RetargetTable`] documents how the runtime applies it
//! and why it maps mask frame `t` onto frame `t + 1` for the per-frame shift `s`.
//!
//! Two solvers: [`exact`] (min-cost bipartite matching on the sparse disc graph, optimal) and
//! [`anneal`] (simulated annealing with swaps, as in the paper).

pub mod anneal;
pub mod exact;

use blueshift_analysis::assets::Mask;

/// The plastic number `g`, root of `x^3 = x + 1` (R2 sequence).
pub const PLASTIC: f64 = 1.324_717_957_244_746;

/// Default per-frame shift `(round(n / g), round(n / g^2)) mod n`: (48, 36) for 64,
/// (97, 73) for 128, (24, 18) for 32.
pub fn default_shift(n: usize) -> (u32, u32) {
    let nf = n as f64;
    let sx = (nf / PLASTIC).round() as usize % n;
    let sy = (nf / (PLASTIC * PLASTIC)).round() as usize % n;
    (sx as u32, sy as u32)
}

/// Errors of the retarget solvers.
#[derive(Debug, thiserror::Error)]
pub enum RetargetError {
    /// Bad parameters.
    #[error("retarget: {0}")]
    Params(String),
}

/// One retargeting problem: a mask, a shift and a radius.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Mask side.
    pub n: usize,
    /// Per-frame shift `s`.
    pub shift: (u32, u32),
    /// Disc radius `R`.
    pub radius: u32,
    /// `M(u)`.
    mask: Vec<i64>,
    /// `M(v + s)`.
    shifted: Vec<i64>,
    /// Disc offsets `(dx, dy)`, `dx^2 + dy^2 <= R^2`, in row-major order of `(dy, dx)`.
    pub disc: Vec<(i32, i32)>,
}

impl Problem {
    /// Sets up the problem; requires `1 <= radius` and `2 radius < n` (the disc must not wrap
    /// onto itself) and a shift below `n`.
    pub fn new(mask: &Mask, shift: (u32, u32), radius: u32) -> Result<Problem, RetargetError> {
        let n = mask.n;
        if radius == 0 || 2 * radius as usize >= n || radius > 127 {
            return Err(RetargetError::Params(format!(
                "radius {radius} must be in 1..={} for a {n}x{n} mask (and <= 127)",
                (n - 1) / 2
            )));
        }
        if shift.0 as usize >= n || shift.1 as usize >= n {
            return Err(RetargetError::Params(format!(
                "shift {shift:?} must be below {n}"
            )));
        }
        let r = radius as i32;
        let mut disc = Vec::new();
        for dy in -r..=r {
            for dx in -r..=r {
                if dx * dx + dy * dy <= r * r {
                    disc.push((dx, dy));
                }
            }
        }
        let m: Vec<i64> = mask.ranks.iter().map(|&v| i64::from(v)).collect();
        let shifted = (0..n * n)
            .map(|v| {
                let (x, y) = (v % n, v / n);
                i64::from(mask.rank((x as u32 + shift.0) as i64, (y as u32 + shift.1) as i64))
            })
            .collect();
        Ok(Problem {
            n,
            shift,
            radius,
            mask: m,
            shifted,
            disc,
        })
    }

    /// `u + disc[k]` on the torus.
    #[inline]
    pub fn neighbour(&self, u: usize, k: usize) -> usize {
        self.add(u, self.disc[k])
    }

    /// `u + d` on the torus.
    #[inline]
    pub fn add(&self, u: usize, d: (i32, i32)) -> usize {
        let n = self.n as i32;
        let x = (u as i32 % n + d.0).rem_euclid(n);
        let y = (u as i32 / n + d.1).rem_euclid(n);
        (y * n + x) as usize
    }

    /// Toroidal displacement `v - u`, each component in `[-n/2, n/2)`.
    #[inline]
    pub fn displacement(&self, u: usize, v: usize) -> (i32, i32) {
        let n = self.n as i32;
        let h = n / 2;
        let dx = (v as i32 % n - u as i32 % n + h).rem_euclid(n) - h;
        let dy = (v as i32 / n - u as i32 / n + h).rem_euclid(n) - h;
        (dx, dy)
    }

    /// Whether `v` lies in the disc around `u`.
    #[inline]
    pub fn in_disc(&self, u: usize, v: usize) -> bool {
        let (dx, dy) = self.displacement(u, v);
        let r = self.radius as i32;
        dx * dx + dy * dy <= r * r
    }

    /// `|M(u) - M(v + s)|`.
    #[inline]
    pub fn cost(&self, u: usize, v: usize) -> i64 {
        (self.mask[u] - self.shifted[v]).abs()
    }

    /// Number of mask cells.
    pub fn len(&self) -> usize {
        self.n * self.n
    }

    /// Always false (masks have at least 4 cells).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// `E(pi)` for `target[u] = pi(u)`.
    pub fn energy(&self, target: &[usize]) -> u64 {
        target
            .iter()
            .enumerate()
            .map(|(u, &v)| self.cost(u, v) as u64)
            .sum()
    }

    /// Share of cells with `|M(u) - M(pi(u) + s)| <= 1%` of the value range `n^2 - 1`.
    pub fn matched_share(&self, target: &[usize]) -> f64 {
        let tol = 0.01 * (self.len() - 1) as f64;
        let ok = target
            .iter()
            .enumerate()
            .filter(|(u, v)| self.cost(*u, **v) as f64 <= tol)
            .count();
        ok as f64 / self.len() as f64
    }

    /// Converts `target` into the stored `(dx, dy)` offsets.
    pub fn offsets(&self, target: &[usize]) -> Vec<(i8, i8)> {
        target
            .iter()
            .enumerate()
            .map(|(u, &v)| {
                let (dx, dy) = self.displacement(u, v);
                (dx as i8, dy as i8)
            })
            .collect()
    }
}

/// Summary printed by the CLI and written to the README.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Energy of the identity (no retargeting).
    pub energy_identity: u64,
    /// Energy of the solution.
    pub energy: u64,
    /// Mean `|M(u) - M(pi(u) + s)|` in ranks.
    pub mean: f64,
    /// [`Problem::matched_share`] of the solution.
    pub matched_share: f64,
}

impl Summary {
    /// Evaluates `target` against the identity.
    pub fn new(p: &Problem, target: &[usize]) -> Summary {
        let identity: Vec<usize> = (0..p.len()).collect();
        let energy = p.energy(target);
        Summary {
            energy_identity: p.energy(&identity),
            energy,
            mean: energy as f64 / p.len() as f64,
            matched_share: p.matched_share(target),
        }
    }
}
