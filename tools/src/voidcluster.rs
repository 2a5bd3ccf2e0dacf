//! Void-and-cluster dither masks (Ulichney 1993), 2D and spatio-temporal.
//!
//! **Energy.** Each minority pixel ("one") radiates `exp(-d^2 / (2 sigma^2))`, with `d` the
//! toroidal distance (wrap-around, so the tile repeats without seams). In the
//! spatio-temporal case the energy follows the scalar STBN construction (Wolfe et al. 2022):
//! a point radiates `exp(-dxy^2 / (2 sigma^2))` into its own slice and
//! `exp(-dt^2 / (2 sigma_t^2))` into the *same pixel* of the other slices (toroidal in t),
//! and nothing elsewhere. (A full 3D product kernel was tried first: its slices reached only
//! LF 0.028 for 64x64x32, against 0.00001 for 2D masks, because it trades spatial for
//! space-time blueness.) The spatial kernel is truncated to a window of radius `ceil(4 sigma)` (`exp(-8)` = 3e-4 of the
//! peak; clamped to `(side - 1) / 2` so the window never wraps onto itself). Adding or
//! removing a point updates only that window: `(2r + 1)^2` values (289 for sigma 1.9), plus
//! `2 r_t` values of the temporal line.
//!
//! **Search.** The tightest cluster (max energy over ones) and the largest void (min energy
//! over zeros) come from a per-row cache of each row's best candidate; an update marks the
//! window's rows dirty, a query rescans only dirty rows and then the `n` row bests. A step
//! costs `O(r^2 + r n + n)` instead of `O(n^2)`. Ties go to the lowest index, so the result
//! is a pure function of the parameters.
//!
//! **Phases.** 0: `m = round(density n^2)` random ones, relaxed by moving the tightest
//! cluster to the largest void until that move is a no-op. 1: from that prototype, remove
//! tightest clusters, ranks `m - 1` down to 0. 2 and 3: from the prototype again, fill largest
//! voids, ranks `m` up to `n^2 - 1`. Ulichney's phase 3 (tightest cluster of zeros after
//! inverting) picks the same pixel as "largest void of ones", because with a shift-invariant
//! kernel `E_zeros(x) = K - E_ones(x)` for a constant `K`; so phases 2 and 3 are one loop.
//!
//! **Spatio-temporal.** All `t` slices are ranked together: each rank step gives that rank
//! to one pixel in every slice (slices visited in the order `r mod t, r + 1 mod t, ...`),
//! always searching within the slice. Each slice is therefore a permutation of `0..n^2` and a
//! 2D blue-noise mask, while the temporal term of the energy pushes a pixel's values in
//! neighbouring slices apart (the scalar STBN idea of Wolfe et al. 2022).

use crate::rng::Pcg32;

/// Parameters of a void-and-cluster run.
#[derive(Clone, Debug, PartialEq)]
pub struct VcParams {
    /// Side of each slice (power of two, <= 256).
    pub n: usize,
    /// Number of slices; 1 for a 2D mask.
    pub frames: usize,
    /// Spatial Gaussian sigma in pixels.
    pub sigma: f64,
    /// Temporal Gaussian sigma in frames (ignored for 2D).
    pub sigma_t: f64,
    /// Initial density of ones.
    pub density: f64,
    /// PRNG seed of the initial pattern.
    pub seed: u64,
    /// Wrap the energy around the tile (always true for assets; false only to show seams).
    pub toroidal: bool,
}

impl VcParams {
    /// 2D defaults of docs/algorithm.md: sigma 1.9, density 0.1, toroidal.
    pub fn new_2d(n: usize, seed: u64) -> Self {
        VcParams {
            n,
            frames: 1,
            sigma: 1.9,
            sigma_t: 1.9,
            density: 0.1,
            seed,
            toroidal: true,
        }
    }
}

struct Field {
    n: usize,
    t: usize,
    r: i64,
    rt: i64,
    kxy: Vec<f64>,
    kt: Vec<f64>,
    toroidal: bool,
    energy: Vec<f64>,
    ones: Vec<bool>,
    /// Per row `(slice * n + y)`: (max energy over ones, x) and (min energy over zeros, x).
    row_max: Vec<(f64, usize)>,
    row_min: Vec<(f64, usize)>,
    dirty: Vec<bool>,
}

const NONE: usize = usize::MAX;

impl Field {
    fn new(p: &VcParams) -> Field {
        let n = p.n;
        let t = p.frames;
        let r = ((4.0 * p.sigma).ceil() as i64)
            .min((n as i64 - 1) / 2)
            .max(0);
        let rt = if t > 1 {
            ((4.0 * p.sigma_t).ceil() as i64)
                .min((t as i64 - 1) / 2)
                .max(0)
        } else {
            0
        };
        let side = 2 * r + 1;
        let mut kxy = Vec::with_capacity((side * side) as usize);
        for dy in -r..=r {
            for dx in -r..=r {
                kxy.push((-((dx * dx + dy * dy) as f64) / (2.0 * p.sigma * p.sigma)).exp());
            }
        }
        let kt = (-rt..=rt)
            .map(|d| (-((d * d) as f64) / (2.0 * p.sigma_t * p.sigma_t)).exp())
            .collect();
        let cells = n * n * t;
        Field {
            n,
            t,
            r,
            rt,
            kxy,
            kt,
            toroidal: p.toroidal,
            energy: vec![0.0; cells],
            ones: vec![false; cells],
            row_max: vec![(f64::NEG_INFINITY, NONE); n * t],
            row_min: vec![(f64::INFINITY, NONE); n * t],
            dirty: vec![true; n * t],
        }
    }

    /// Adds (`sign = 1`) or removes (`sign = -1`) a one at cell `idx`.
    fn splat(&mut self, idx: usize, sign: f64) {
        let n = self.n as i64;
        let t = self.t as i64;
        let (s, rem) = ((idx / (self.n * self.n)) as i64, idx % (self.n * self.n));
        let (y, x) = ((rem / self.n) as i64, (rem % self.n) as i64);
        self.ones[idx] = sign > 0.0;
        let side = (2 * self.r + 1) as usize;
        // Spatial term: the window inside the point's own slice.
        for (yi, dy) in (-self.r..=self.r).enumerate() {
            let yy = y + dy;
            if !self.toroidal && !(0..n).contains(&yy) {
                continue;
            }
            let yy = yy.rem_euclid(n);
            let row = (s * n + yy) as usize;
            self.dirty[row] = true;
            let base = row * self.n;
            let krow = &self.kxy[yi * side..(yi + 1) * side];
            for (xi, dx) in (-self.r..=self.r).enumerate() {
                let xx = x + dx;
                if !self.toroidal && !(0..n).contains(&xx) {
                    continue;
                }
                self.energy[base + xx.rem_euclid(n) as usize] += sign * krow[xi];
            }
        }
        // Temporal term: the same pixel in the other slices.
        for (ti, dt) in (-self.rt..=self.rt).enumerate() {
            if dt == 0 {
                continue;
            }
            let row = ((s + dt).rem_euclid(t) * n + y) as usize;
            self.dirty[row] = true;
            self.energy[row * self.n + x as usize] += sign * self.kt[ti];
        }
    }

    fn refresh_row(&mut self, row: usize) {
        let base = row * self.n;
        let mut best_max = (f64::NEG_INFINITY, NONE);
        let mut best_min = (f64::INFINITY, NONE);
        for x in 0..self.n {
            let e = self.energy[base + x];
            if self.ones[base + x] {
                if e > best_max.0 {
                    best_max = (e, x);
                }
            } else if e < best_min.0 {
                best_min = (e, x);
            }
        }
        self.row_max[row] = best_max;
        self.row_min[row] = best_min;
        self.dirty[row] = false;
    }

    /// Cell index of the tightest cluster (`cluster = true`) or largest void in slice `s`.
    fn best(&mut self, s: usize, cluster: bool) -> Option<usize> {
        let mut best = (
            if cluster {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            },
            NONE,
            0,
        );
        for y in 0..self.n {
            let row = s * self.n + y;
            if self.dirty[row] {
                self.refresh_row(row);
            }
            let (e, x) = if cluster {
                self.row_max[row]
            } else {
                self.row_min[row]
            };
            let better = if cluster { e > best.0 } else { e < best.0 };
            if x != NONE && better {
                best = (e, x, row);
            }
        }
        (best.1 != NONE).then(|| best.2 * self.n + best.1)
    }

    fn mark_all_dirty(&mut self) {
        self.dirty.iter_mut().for_each(|d| *d = true);
    }
}

/// Errors of mask generation.
#[derive(Debug, thiserror::Error)]
pub enum VcError {
    /// Parameters out of range.
    #[error("void-and-cluster: {0}")]
    Params(String),
}

fn validate(p: &VcParams) -> Result<(), VcError> {
    if !(4..=256).contains(&p.n) || !p.n.is_power_of_two() {
        return Err(VcError::Params(format!(
            "size {} is not a power of two in 4..=256",
            p.n
        )));
    }
    if !(1..=1024).contains(&p.frames) {
        return Err(VcError::Params(format!(
            "frames {} not in 1..=1024",
            p.frames
        )));
    }
    if !(p.sigma.is_finite() && p.sigma > 0.1 && p.sigma <= 32.0) {
        return Err(VcError::Params(format!(
            "sigma {} not in (0.1, 32]",
            p.sigma
        )));
    }
    if p.frames > 1 && !(p.sigma_t.is_finite() && p.sigma_t > 0.1 && p.sigma_t <= 256.0) {
        return Err(VcError::Params(format!(
            "sigma-t {} not in (0.1, 256]",
            p.sigma_t
        )));
    }
    if !(p.density > 0.0 && p.density < 0.5) {
        return Err(VcError::Params(format!(
            "density {} not in (0, 0.5)",
            p.density
        )));
    }
    Ok(())
}

/// Runs void-and-cluster and returns `frames * n * n` ranks, slice-major; every slice is a
/// permutation of `0..n*n`. `progress` receives the number of ranks assigned per slice so
/// far (0..=n*n; phase 0 reports nothing).
pub fn void_and_cluster(p: &VcParams, progress: &mut dyn FnMut(u64)) -> Result<Vec<u16>, VcError> {
    validate(p)?;
    let (n, t) = (p.n, p.frames);
    let area = n * n;
    let m = ((p.density * area as f64).round() as usize).clamp(1, area - 1);
    let mut f = Field::new(p);
    let mut rng = Pcg32::new(p.seed);
    // Phase 0: random initial pattern, m ones per slice, then relaxation.
    for s in 0..t {
        let mut idx: Vec<usize> = (0..area).collect();
        rng.shuffle(&mut idx);
        for &i in &idx[..m] {
            f.splat(s * area + i, 1.0);
        }
    }
    let max_passes = 4 * area;
    for _ in 0..max_passes {
        let mut changed = false;
        for s in 0..t {
            let Some(c) = f.best(s, true) else {
                continue;
            };
            f.splat(c, -1.0);
            let v = f.best(s, false).unwrap_or(c);
            f.splat(v, 1.0);
            changed |= v != c;
        }
        if !changed {
            break;
        }
    }
    let proto_ones = f.ones.clone();
    let proto_energy = f.energy.clone();
    let mut ranks = vec![0u16; area * t];
    // Phase 1: remove tightest clusters, ranks m-1 down to 0.
    for rank in (0..m).rev() {
        for k in 0..t {
            let s = (rank + k) % t;
            let c = f
                .best(s, true)
                .ok_or_else(|| VcError::Params("phase 1 ran dry".into()))?;
            f.splat(c, -1.0);
            ranks[c] = rank as u16;
        }
        progress((m - rank) as u64);
    }
    // Phases 2 and 3: fill largest voids from the prototype, ranks m..n^2-1.
    f.ones = proto_ones;
    f.energy = proto_energy;
    f.mark_all_dirty();
    for rank in m..area {
        for k in 0..t {
            let s = (rank + k) % t;
            let v = f
                .best(s, false)
                .ok_or_else(|| VcError::Params("phase 2 ran dry".into()))?;
            f.splat(v, 1.0);
            ranks[v] = rank as u16;
        }
        progress((rank + 1) as u64);
    }
    Ok(ranks)
}

/// Bayer (ordered dither) matrix of side `n` (power of two):
/// `B_2k(x, y) = 4 B_k(x mod k, y mod k) + [[0, 2], [3, 1]][y / k][x / k]`.
pub fn bayer(n: usize) -> Vec<u16> {
    let mut m = vec![0u16];
    let mut k = 1;
    while k < n {
        let mut next = vec![0u16; 4 * k * k];
        for y in 0..2 * k {
            for x in 0..2 * k {
                let q = [[0u16, 2], [3, 1]][y / k][x / k];
                next[y * 2 * k + x] = 4 * m[(y % k) * k + x % k] + q;
            }
        }
        m = next;
        k *= 2;
    }
    m
}

/// White-noise mask: a uniformly random permutation of `0..n*n`.
pub fn white(n: usize, seed: u64) -> Vec<u16> {
    let mut v: Vec<u16> = (0..n * n).map(|i| i as u16).collect();
    Pcg32::new(seed).shuffle(&mut v);
    v
}
