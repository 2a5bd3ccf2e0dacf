//! HBO+19 key optimisation: arrange per-pixel Owen-scrambling (and ranking) keys over a tile so
//! that the errors of neighbouring pixels, over a family of test integrands, differ; i.e. the
//! error is blue noise in screen space (Heitz et al. 2019, energy after Georgiev & Fajardo
//! 2016). The sampler itself is `blueshift_sampling::hbo19`.
//!
//! Every pixel gets an error vector: for each dimension pair p, each power-of-two prefix of
//! its spp samples, and each test integrand f over the pair's 2D point, the prefix's estimate
//! of f. (The reference integrals are left out: the energy only uses differences between
//! pixels, where they cancel.) The energy sums, over pixel pairs a, n at most `radius` apart,
//! `exp(-|a - n|^2 / sigma_i^2 - d(e_a, e_n) / sigma_s^2)` with `d` the RMS difference of the
//! error vectors: low when neighbours' errors differ. Annealing (anneal.rs) minimises it.

pub mod anneal;

use blueshift_sampling::hbo19::{KeyTable, hbo19_bits};
use blueshift_sampling::rng::to_unit;
use blueshift_sampling::sobol::direction_numbers;

use crate::rng::Pcg32;

/// A test integrand over the unit square.
#[derive(Clone, Copy, Debug)]
pub enum Integrand {
    /// 1 on one side of a line through `c` with normal `n` (visibility edges).
    Step { c: [f32; 2], n: [f32; 2] },
    /// `exp(-|x - c|^2 * k)` (smooth shading).
    Gauss { c: [f32; 2], k: f32 },
}

impl Integrand {
    pub fn eval(&self, x: [f32; 2]) -> f32 {
        match *self {
            Integrand::Step { c, n } => {
                f32::from(u8::from((x[0] - c[0]) * n[0] + (x[1] - c[1]) * n[1] > 0.0))
            }
            Integrand::Gauss { c, k } => {
                let (dx, dy) = (x[0] - c[0], x[1] - c[1]);
                (-(dx * dx + dy * dy) * k).exp()
            }
        }
    }
}

/// What to optimise.
#[derive(Clone, Debug)]
pub struct KeysParams {
    /// Tile edge (power of two, >= 16).
    pub tile: u32,
    /// Samples per pixel (power of two).
    pub spp: u32,
    /// Dimension pairs.
    pub pairs: u32,
    /// Test integrands per pair (half steps, half Gaussians).
    pub integrands: u32,
    /// Annealing proposals per pixel.
    pub iterations: u32,
    /// Annealing rounds (temperature steps; block grid re-offset each round).
    pub rounds: u32,
    pub sigma_i: f32,
    pub sigma_s: f32,
    /// Energy window radius in pixels.
    pub radius: i32,
    pub seed: u64,
}

impl KeysParams {
    /// Defaults for a tile and spp.
    pub fn new(tile: u32, spp: u32, pairs: u32, seed: u64) -> Self {
        Self {
            tile,
            spp,
            pairs,
            integrands: 16,
            iterations: 128,
            rounds: 64,
            sigma_i: 2.1,
            sigma_s: 1.0,
            radius: 5,
            seed,
        }
    }

    pub fn validate(&self) -> Result<(), String> {
        if !(16..=256).contains(&self.tile) || !self.tile.is_power_of_two() {
            return Err(format!(
                "tile {} is not a power of two in 16..=256",
                self.tile
            ));
        }
        if !(1..=256).contains(&self.spp) || !self.spp.is_power_of_two() {
            return Err(format!("spp {} is not a power of two in 1..=256", self.spp));
        }
        if !(1..=blueshift_sampling::hbo19::MAX_PAIRS).contains(&self.pairs) {
            return Err(format!("{} dimension pairs is outside 1..=16", self.pairs));
        }
        if !(2..=64).contains(&self.integrands) {
            return Err(format!("{} integrands is outside 2..=64", self.integrands));
        }
        if self.rounds == 0 {
            return Err("rounds must be at least 1".into());
        }
        Ok(())
    }

    /// Power-of-two prefixes 1, 2, .., spp.
    pub fn prefixes(&self) -> u32 {
        self.spp.trailing_zeros() + 1
    }

    /// Floats per pair in an error vector.
    pub fn slice_len(&self) -> usize {
        (self.prefixes() * self.integrands) as usize
    }

    /// Floats per error vector.
    pub fn vec_len(&self) -> usize {
        self.pairs as usize * self.slice_len()
    }
}

/// The integrands and evaluator of one optimisation.
pub struct Problem {
    pub params: KeysParams,
    /// `integrands[pair]`.
    pub integrands: Vec<Vec<Integrand>>,
    dirs: [[u32; 32]; 4],
    /// Window offsets (dx, dy) != 0 and their spatial weights.
    pub window: Vec<(i32, i32, f32)>,
}

impl Problem {
    pub fn new(params: KeysParams) -> Result<Self, String> {
        params.validate()?;
        let mut rng = Pcg32::new(params.seed ^ 0x1b0c_0f1e_5a11_d00d);
        let mut u = || rng.next_f64() as f32;
        let integrands = (0..params.pairs)
            .map(|_| {
                (0..params.integrands)
                    .map(|j| {
                        let c = [u(), u()];
                        if j % 2 == 0 {
                            let a = u() * std::f32::consts::TAU;
                            Integrand::Step {
                                c,
                                n: [a.cos(), a.sin()],
                            }
                        } else {
                            // Widths 0.1 .. 0.5 of the square.
                            let s = 0.1 + 0.4 * u();
                            Integrand::Gauss {
                                c,
                                k: 1.0 / (2.0 * s * s),
                            }
                        }
                    })
                    .collect()
            })
            .collect();
        let r = params.radius;
        let mut window = Vec::new();
        for dy in -r..=r {
            for dx in -r..=r {
                let d2 = (dx * dx + dy * dy) as f32;
                if (dx, dy) != (0, 0) && d2 <= (r * r) as f32 {
                    window.push((dx, dy, (-d2 / (params.sigma_i * params.sigma_i)).exp()));
                }
            }
        }
        Ok(Self {
            params,
            integrands,
            dirs: direction_numbers(),
            window,
        })
    }

    /// Writes the error-vector slice of `pair` for `key` into `out` (prefix-major).
    pub fn eval_pair(&self, key: [u32; 2], pair: u32, out: &mut [f32]) {
        let p = &self.params;
        let fs = &self.integrands[pair as usize];
        let mut sums = vec![0.0f32; fs.len()];
        let mut next = 1;
        let mut k = 0;
        for i in 0..p.spp {
            let x = [
                to_unit(hbo19_bits(key, p.pairs, 0, i, 2 * pair, &self.dirs)),
                to_unit(hbo19_bits(key, p.pairs, 0, i, 2 * pair + 1, &self.dirs)),
            ];
            for (s, f) in sums.iter_mut().zip(fs) {
                *s += f.eval(x);
            }
            if i + 1 == next {
                let inv = 1.0 / next as f32;
                let row = &mut out[k * fs.len()..(k + 1) * fs.len()];
                for (o, s) in row.iter_mut().zip(&sums) {
                    *o = s * inv;
                }
                next *= 2;
                k += 1;
            }
        }
    }

    /// The error vector of a pixel with `keys` (one per pair).
    pub fn eval_pixel(&self, keys: &[[u32; 2]], out: &mut [f32]) {
        let s = self.params.slice_len();
        for (pair, k) in keys.iter().enumerate() {
            self.eval_pair(*k, pair as u32, &mut out[pair * s..(pair + 1) * s]);
        }
    }

    /// One energy term from a squared error-vector distance.
    #[inline]
    pub fn term(&self, w: f32, dist_sq: f32) -> f32 {
        let inv_k = 1.0 / self.params.vec_len() as f32;
        w * (-(dist_sq * inv_k).sqrt() / (self.params.sigma_s * self.params.sigma_s)).exp()
    }

    /// Total energy of a tile of error vectors (each unordered pair once; f64, fixed order).
    pub fn energy(&self, vecs: &[f32]) -> f64 {
        use rayon::prelude::*;
        let t = self.params.tile as i32;
        let k = self.params.vec_len();
        let half: Vec<_> = self
            .window
            .iter()
            .filter(|(dx, dy, _)| (*dy, *dx) > (0, 0))
            .collect();
        let per_pixel: Vec<f64> = (0..t * t)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % t, i / t);
                let a = &vecs[i as usize * k..(i as usize + 1) * k];
                half.iter()
                    .map(|&&(dx, dy, w)| {
                        let n = ((y + dy).rem_euclid(t) * t + (x + dx).rem_euclid(t)) as usize;
                        let b = &vecs[n * k..(n + 1) * k];
                        f64::from(self.term(w, sq_dist(a, b)))
                    })
                    .sum()
            })
            .collect();
        per_pixel.iter().sum()
    }

    /// Mean low-frequency fraction (toroidal periodogram, LF_CUTOFF) over the components
    /// of the error vectors as images: about 0.045 for white noise, lower is bluer.
    pub fn mean_lf(&self, vecs: &[f32]) -> f64 {
        use blueshift_analysis::{Gray, LF_CUTOFF, low_frequency_fraction, periodogram};
        use rayon::prelude::*;
        let (t, k) = (self.params.tile as usize, self.params.vec_len());
        let lfs: Vec<f64> = (0..k)
            .into_par_iter()
            .map(|c| {
                let px: Vec<f32> = (0..t * t).map(|i| vecs[i * k + c]).collect();
                let mean = px.iter().sum::<f32>() / px.len() as f32;
                let g = Gray::new(t, t, px.iter().map(|v| v - mean).collect());
                match g.and_then(|g| periodogram(&g)) {
                    Ok(s) => low_frequency_fraction(&s, LF_CUTOFF),
                    Err(_) => f64::NAN,
                }
            })
            .collect();
        let ok: Vec<f64> = lfs.into_iter().filter(|v| v.is_finite()).collect();
        ok.iter().sum::<f64>() / ok.len().max(1) as f64
    }

    /// Error vectors of all pixels for `keys`.
    pub fn vectors(&self, keys: &[[u32; 2]]) -> Vec<f32> {
        use rayon::prelude::*;
        let (pairs, k) = (self.params.pairs as usize, self.params.vec_len());
        let mut vecs = vec![0.0f32; keys.len() / pairs * k];
        vecs.par_chunks_mut(k)
            .zip(keys.par_chunks(pairs))
            .for_each(|(v, kk)| self.eval_pixel(kk, v));
        vecs
    }

    /// Initial keys: hashed scrambles, ranks `pixel mod spp` (balanced; swaps keep the
    /// multiset).
    pub fn initial_keys(&self) -> Vec<[u32; 2]> {
        let p = &self.params;
        let mut rng = Pcg32::new(p.seed ^ (u64::from(p.spp) << 32) ^ 0x6b65_7973);
        (0..p.tile * p.tile)
            .flat_map(|px| (0..p.pairs).map(move |_| px % p.spp))
            .map(|rank| [rng.next_u32(), rank])
            .collect()
    }

    /// Wraps optimised keys as a table.
    pub fn table(&self, keys: Vec<[u32; 2]>) -> Result<KeyTable, String> {
        let p = &self.params;
        KeyTable::new(p.tile, p.spp, p.pairs, keys)
    }
}

#[inline]
pub fn sq_dist(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}
