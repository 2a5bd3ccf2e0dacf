//! Parallel, deterministic simulated annealing of the key arrangement.
//!
//! A move picks two pixels a, b of one block and one dimension pair, and either swaps their
//! keys of that pair (the error slices just trade places) or, for spp > 1, only their ranks
//! (which reorders the samples and so changes the prefix errors). Each round re-offsets a grid
//! of B x B blocks and visits the blocks in four colours; blocks of one colour are B (more
//! than the energy radius) apart, so their moves never read each other's pixels and run in
//! parallel. Every
//! block has its own PRNG stream derived from (seed, round, colour, block), so the result does
//! not depend on the number of threads.

use rayon::prelude::*;

use super::{Problem, sq_dist};
use crate::rng::{Pcg32, splitmix64};

/// Result of an optimisation.
pub struct Outcome {
    pub keys: Vec<[u32; 2]>,
    pub energy_initial: f64,
    pub energy_final: f64,
    /// [`Problem::mean_lf`] before and after.
    pub lf_initial: f64,
    pub lf_final: f64,
    pub accepted: u64,
    pub proposals: u64,
}

/// One block's working copy: keys and error vectors of its B x B pixels.
struct Block {
    /// Tile coordinates of local pixel 0; edge B; tile edge.
    origin: (usize, usize),
    edge: usize,
    tile: usize,
    /// Global pixel index of each local pixel (row by row from the origin, toroidally).
    pixels: Vec<usize>,
    keys: Vec<[u32; 2]>,
    vecs: Vec<f32>,
    accepted: u64,
}

/// Block edge for a tile: 16, or half the tile (always > the radius 5..7 used here).
fn block_edge(tile: u32) -> u32 {
    16.min(tile / 2)
}

/// Runs the annealing; `progress(round)` after each round.
pub fn optimise(p: &Problem, progress: &mut dyn FnMut(u32)) -> Outcome {
    let prm = &p.params;
    let (t, pairs, k) = (prm.tile, prm.pairs as usize, prm.vec_len());
    let mut keys = p.initial_keys();
    let mut vecs = p.vectors(&keys);
    let energy_initial = p.energy(&vecs);
    let lf_initial = p.mean_lf(&vecs);
    let b = block_edge(t);
    let nb = t / b;
    let moves = (u64::from(prm.iterations) * u64::from(b * b)).div_ceil(u64::from(prm.rounds));
    let t0 = initial_temperature(p, &keys, &vecs);
    let mut sm = prm.seed ^ 0xa22e_a1ed;
    let mut accepted = 0;
    for round in 0..prm.rounds {
        let frac = f64::from(round) / f64::from(prm.rounds.max(2) - 1);
        let temp = t0 * 1e-3f64.powf(frac);
        let off = splitmix64(&mut sm);
        let (ox, oy) = ((off as u32) % b, ((off >> 32) as u32) % b);
        for colour in 0..4u32 {
            let (cx, cy) = (colour % 2, colour / 2);
            let blocks: Vec<(u32, u32)> = (0..nb)
                .flat_map(|by| (0..nb).map(move |bx| (bx, by)))
                .filter(|&(bx, by)| bx % 2 == cx && by % 2 == cy)
                .collect();
            let done: Vec<Block> = blocks
                .par_iter()
                .map(|&(bx, by)| {
                    let stream = u64::from(round) << 40
                        ^ u64::from(colour) << 32
                        ^ u64::from(by * nb + bx)
                        ^ prm.seed.rotate_left(17);
                    let mut blk = load_block(p, &keys, &vecs, (ox + bx * b, oy + by * b), b);
                    anneal_block(p, &mut blk, &vecs, moves, temp, Pcg32::new(stream));
                    blk
                })
                .collect();
            for blk in done {
                accepted += blk.accepted;
                for (l, &g) in blk.pixels.iter().enumerate() {
                    keys[g * pairs..(g + 1) * pairs]
                        .copy_from_slice(&blk.keys[l * pairs..(l + 1) * pairs]);
                    vecs[g * k..(g + 1) * k].copy_from_slice(&blk.vecs[l * k..(l + 1) * k]);
                }
            }
        }
        progress(round + 1);
    }
    Outcome {
        energy_final: p.energy(&vecs),
        lf_final: p.mean_lf(&vecs),
        lf_initial,
        energy_initial,
        keys,
        accepted,
        proposals: moves * u64::from(nb * nb) * u64::from(prm.rounds),
    }
}

fn load_block(p: &Problem, keys: &[[u32; 2]], vecs: &[f32], o: (u32, u32), b: u32) -> Block {
    let (t, pairs, k) = (p.params.tile, p.params.pairs as usize, p.params.vec_len());
    let pixels: Vec<usize> = (0..b * b)
        .map(|l| (((o.1 + l / b) % t) * t + (o.0 + l % b) % t) as usize)
        .collect();
    Block {
        origin: ((o.0 % t) as usize, (o.1 % t) as usize),
        edge: b as usize,
        tile: t as usize,
        keys: pixels
            .iter()
            .flat_map(|&g| keys[g * pairs..(g + 1) * pairs].iter().copied())
            .collect(),
        vecs: pixels
            .iter()
            .flat_map(|&g| vecs[g * k..(g + 1) * k].iter().copied())
            .collect(),
        pixels,
        accepted: 0,
    }
}

/// Mean |energy change| of random whole-tile proposals: the starting temperature.
fn initial_temperature(p: &Problem, keys: &[[u32; 2]], vecs: &[f32]) -> f64 {
    let t = p.params.tile;
    let blk = load_block(p, keys, vecs, (0, 0), t);
    let mut rng = Pcg32::new(p.params.seed ^ 0x7e3f);
    let n = 256;
    let sum: f64 = (0..n)
        .map(|_| {
            let mv = propose(p, &blk, t * t, &mut rng);
            delta(p, &blk, vecs, &mv).abs()
        })
        .sum();
    (sum / f64::from(n)).max(1e-9)
}

/// A proposed move: local pixels, pair, and the new keys and error slices of both.
struct Move {
    a: usize,
    b: usize,
    pair: usize,
    ka: [u32; 2],
    kb: [u32; 2],
    sa: Vec<f32>,
    sb: Vec<f32>,
}

fn propose(p: &Problem, blk: &Block, n: u32, rng: &mut Pcg32) -> Move {
    let (pairs, s) = (p.params.pairs as usize, p.params.slice_len());
    let k = p.params.vec_len();
    let a = rng.below(n) as usize;
    let b = (a + 1 + rng.below(n - 1) as usize) % n as usize;
    let pair = rng.below(pairs as u32) as usize;
    let (oa, ob) = (blk.keys[a * pairs + pair], blk.keys[b * pairs + pair]);
    let slice = |l: usize| blk.vecs[l * k + pair * s..l * k + (pair + 1) * s].to_vec();
    if p.params.spp > 1 && rng.below(2) == 0 {
        let (ka, kb) = ([oa[0], ob[1]], [ob[0], oa[1]]);
        let (mut sa, mut sb) = (vec![0.0; s], vec![0.0; s]);
        p.eval_pair(ka, pair as u32, &mut sa);
        p.eval_pair(kb, pair as u32, &mut sb);
        Move {
            a,
            b,
            pair,
            ka,
            kb,
            sa,
            sb,
        }
    } else {
        Move {
            a,
            b,
            pair,
            ka: ob,
            kb: oa,
            sa: slice(b),
            sb: slice(a),
        }
    }
}

impl Block {
    /// The error vector of global pixel `g`: the block's copy if it is one of its pixels.
    fn vec_of<'a>(&'a self, vecs: &'a [f32], k: usize, g: usize) -> &'a [f32] {
        let t = self.tile;
        let lx = (g % t + t - self.origin.0) % t;
        let ly = (g / t + t - self.origin.1) % t;
        if lx < self.edge && ly < self.edge {
            let l = ly * self.edge + lx;
            &self.vecs[l * k..(l + 1) * k]
        } else {
            &vecs[g * k..(g + 1) * k]
        }
    }
}

/// Energy change of `mv` (terms between a or b and their window neighbours).
fn delta(p: &Problem, blk: &Block, vecs: &[f32], mv: &Move) -> f64 {
    let k = p.params.vec_len();
    let s = p.params.slice_len();
    let t = p.params.tile as i32;
    let r = mv.pair * s..(mv.pair + 1) * s;
    let (ga, gb) = (blk.pixels[mv.a], blk.pixels[mv.b]);
    let va = &blk.vecs[mv.a * k..(mv.a + 1) * k];
    let vb = &blk.vecs[mv.b * k..(mv.b + 1) * k];
    let mut d = 0.0f64;
    for (g, v, new) in [(ga, va, &mv.sa), (gb, vb, &mv.sb)] {
        let (x, y) = ((g as i32) % t, (g as i32) / t);
        for &(dx, dy, w) in &p.window {
            let n = ((y + dy).rem_euclid(t) * t + (x + dx).rem_euclid(t)) as usize;
            if n == ga || n == gb {
                continue;
            }
            let vn = blk.vec_of(vecs, k, n);
            let old = sq_dist(v, vn);
            let new_sq =
                old - sq_dist(&v[r.clone()], &vn[r.clone()]) + sq_dist(new, &vn[r.clone()]);
            d += f64::from(p.term(w, new_sq.max(0.0)) - p.term(w, old));
        }
    }
    // The (a, b) term itself, if they are neighbours.
    let (xa, ya) = ((ga as i32) % t, (ga as i32) / t);
    let (xb, yb) = ((gb as i32) % t, (gb as i32) / t);
    let wrap = |v: i32| {
        if v > t / 2 {
            v - t
        } else if v < -t / 2 {
            v + t
        } else {
            v
        }
    };
    let (dx, dy) = (wrap(xb - xa), wrap(yb - ya));
    if let Some(&(_, _, w)) = p.window.iter().find(|o| (o.0, o.1) == (dx, dy)) {
        let old = sq_dist(va, vb);
        let new_sq = old - sq_dist(&va[r.clone()], &vb[r.clone()]) + sq_dist(&mv.sa, &mv.sb);
        d += f64::from(p.term(w, new_sq.max(0.0)) - p.term(w, old));
    }
    d
}

fn anneal_block(p: &Problem, blk: &mut Block, vecs: &[f32], moves: u64, temp: f64, mut rng: Pcg32) {
    let (pairs, k, s) = (
        p.params.pairs as usize,
        p.params.vec_len(),
        p.params.slice_len(),
    );
    let b = block_edge(p.params.tile);
    let n = b * b;
    for _ in 0..moves {
        let mv = propose(p, blk, n, &mut rng);
        let d = delta(p, blk, vecs, &mv);
        if d <= 0.0 || rng.next_f64() < (-d / temp).exp() {
            blk.keys[mv.a * pairs + mv.pair] = mv.ka;
            blk.keys[mv.b * pairs + mv.pair] = mv.kb;
            let r = |l: usize| l * k + mv.pair * s..l * k + (mv.pair + 1) * s;
            blk.vecs[r(mv.a)].copy_from_slice(&mv.sa);
            blk.vecs[r(mv.b)].copy_from_slice(&mv.sb);
            blk.accepted += 1;
        }
    }
}
