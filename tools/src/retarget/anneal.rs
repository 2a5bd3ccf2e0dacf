//! Simulated annealing (the paper's solver, after Georgiev & Fajardo 2016; working choices of
//! docs/algorithm.md).
//!
//! Start from the identity. Each proposal picks a cell `u` and an offset `delta` of the disc
//! (uniformly), and proposes to swap the destinations of `u` and `w = u + delta`. A swap is
//! rejected if either cell's new destination leaves its own disc. Otherwise `dE` is the change
//! of `|M(u) - M(pi(u) + s)| + |M(w) - M(pi(w) + s)|`, accepted if `dE <= 0` or with
//! probability `exp(-dE / T)` (Metropolis). The temperature falls geometrically from `t0` to
//! `t1` (in rank units) over the fixed number of proposals, so the result depends only on the
//! parameters and the seed.

use super::Problem;
use crate::rng::Pcg32;

/// Annealing schedule.
#[derive(Clone, Debug, PartialEq)]
pub struct AnnealParams {
    /// Number of proposals.
    pub proposals: u64,
    /// Start temperature (ranks).
    pub t0: f64,
    /// End temperature (ranks).
    pub t1: f64,
    /// PRNG seed.
    pub seed: u64,
}

impl AnnealParams {
    /// Defaults for a mask of side `n`: `15000 n^2` proposals (61M for 64^2),
    /// `t0 = n^2 / 32`, `t1 = n^2 / 2048` (128 and 2 ranks for 64^2). Tuned on a 64^2
    /// mask: (t0, t1) = (128, 2) beat (16, 0.05), (64, 0.05), (256, 1) and (32, 3) at equal
    /// proposal counts.
    pub fn defaults(n: usize, seed: u64) -> Self {
        let a = (n * n) as f64;
        AnnealParams {
            proposals: 15_000 * (n * n) as u64,
            t0: a / 32.0,
            t1: a / 2048.0,
            seed,
        }
    }
}

/// Anneals `p`; returns `target[u] = pi(u)`. `progress` receives proposals done so far.
pub fn solve(p: &Problem, params: &AnnealParams, progress: &mut dyn FnMut(u64)) -> Vec<usize> {
    let nn = p.len();
    let mut target: Vec<usize> = (0..nn).collect();
    let mut rng = Pcg32::new(params.seed);
    let total = params.proposals.max(1);
    const CHUNK: u64 = 1 << 16;
    let t0 = params.t0.max(1e-9);
    let ratio = (params.t1.max(1e-9) / t0).ln();
    let mut done = 0u64;
    while done < total {
        let steps = CHUNK.min(total - done);
        let temp = t0 * (ratio * done as f64 / total as f64).exp();
        let inv_t = 1.0 / temp;
        for _ in 0..steps {
            let u = rng.below(nn as u32) as usize;
            let k = rng.below(p.disc.len() as u32) as usize;
            let w = p.neighbour(u, k);
            if w == u {
                continue;
            }
            let (a, b) = (target[u], target[w]);
            if !p.in_disc(u, b) || !p.in_disc(w, a) {
                continue;
            }
            let de = p.cost(u, b) + p.cost(w, a) - p.cost(u, a) - p.cost(w, b);
            if de <= 0 || rng.next_f64() < (-(de as f64) * inv_t).exp() {
                target[u] = b;
                target[w] = a;
            }
        }
        done += steps;
        progress(done);
    }
    target
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voidcluster::{VcParams, void_and_cluster};
    use blueshift_analysis::assets::Mask;

    #[test]
    fn annealing_lowers_energy_at_least_fivefold_and_stays_a_bijection() {
        // 32^2 blue-noise mask, radius 6, 2M proposals: the identity's energy is about
        // n^2 * n^2 / 3; annealing must cut it by >= 5x (it reaches ~20x), and the exact
        // solver must do at least as well.
        let mask = Mask::new(
            32,
            void_and_cluster(&VcParams::new_2d(32, 3), &mut |_| {}).unwrap(),
        )
        .unwrap();
        let p = Problem::new(&mask, (24, 18), 6).unwrap();
        let params = AnnealParams {
            proposals: 2_000_000,
            ..AnnealParams::defaults(32, 9)
        };
        let target = solve(&p, &params, &mut |_| {});
        let mut seen = vec![false; p.len()];
        for (u, &v) in target.iter().enumerate() {
            assert!(p.in_disc(u, v));
            assert!(!std::mem::replace(&mut seen[v], true));
        }
        let identity: Vec<usize> = (0..p.len()).collect();
        let (e0, e1) = (p.energy(&identity), p.energy(&target));
        assert!(e1 * 5 <= e0, "identity {e0}, annealed {e1}");
        let exact = super::super::exact::solve(&p, &mut |_| {});
        assert!(p.energy(&exact) <= e1);
    }
}
