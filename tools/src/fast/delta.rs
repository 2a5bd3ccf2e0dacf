//! The loss change of one swap, without recomputing the loss.
//!
//! Swapping `x_i` and `x_j` (same slice) changes `L` (mod.rs) by
//! `-2 (S_i - S_j - 2 A(0) |x_i - x_j| + A(i - j) c)`, where
//! `S_i = sum_k A(i - k) D(k)` runs over the whole neighbourhood of `i` in space and all
//! frames, `D(k) = K(x_i, x_k) - K(x_j, x_k)` with the kernel between the positions of `i`
//! and `k` (`|x_j - x_k| - |x_i - x_k|` for FAST's `-|x - y|`), and `S_j` likewise around `j`.
//! Voxels `i` and `j` themselves are in both sums; the last two terms take them out again
//! (`c = 2 |x_i - x_j|` for `-|x - y|`, `2 |x_i - x_j|^2` for the per-pixel product kernel).
//! A neighbour pixel's `T` values are contiguous, so each spatial offset is one short loop
//! against the temporal autocorrelation row of frame `t`, written in eight lanes so that it
//! vectorises with a fixed summation order (bit-identical results on every run). Cost: two
//! neighbourhoods (about 90 offsets for sigma 1) of `T` values; a full recomputation reads
//! the whole texture. The tests check it against the recomputed loss.

use super::{Block, GLOBAL, Setup};
use crate::fast::Model;

/// `sum_u at[u] f(c[u])` in eight lanes, so that it vectorises while the summation order
/// (hence the result) stays fixed.
fn lanes8(c: &[f32], at: &[f32], f: impl Fn(f32) -> f32) -> f32 {
    let mut acc = [0.0f32; 8];
    for (c, a) in c.chunks_exact(8).zip(at.chunks_exact(8)) {
        for ((s, &c), &a) in acc.iter_mut().zip(c).zip(a) {
            *s += a * f(c);
        }
    }
    let tail = c.chunks_exact(8).remainder();
    let mut sum: f32 = acc.iter().sum();
    for (&c, &a) in tail.iter().zip(at.chunks_exact(8).remainder()) {
        sum += a * f(c);
    }
    sum
}

/// `sum_u at[u] (|xj - c[u]| - |xi - c[u]|)`.
fn col_scalar(col: &[f32], at: &[f32], xi: f32, xj: f32) -> f32 {
    lanes8(col, at, |c| (xj - c).abs() - (xi - c).abs())
}

/// The 2D-vector version of [`col_scalar`] (Euclidean distances).
fn col_vec2(cx: &[f32], cy: &[f32], at: &[f32], xi: [f32; 2], xj: [f32; 2]) -> f32 {
    let term = |x: f32, y: f32, a: f32| {
        let dj = ((xj[0] - x).powi(2) + (xj[1] - y).powi(2)).sqrt();
        let di = ((xi[0] - x).powi(2) + (xi[1] - y).powi(2)).sqrt();
        a * (dj - di)
    };
    let mut acc = [0.0f32; 8];
    for ((x, y), a) in cx
        .chunks_exact(8)
        .zip(cy.chunks_exact(8))
        .zip(at.chunks_exact(8))
    {
        for (k, s) in acc.iter_mut().enumerate() {
            *s += term(x[k], y[k], a[k]);
        }
    }
    let mut sum: f32 = acc.iter().sum();
    let rem = cx.len() - cx.len() % 8;
    for u in rem..cx.len() {
        sum += term(cx[u], cy[u], at[u]);
    }
    sum
}

/// `sum_u at[u] (c[u] - 1/2)`.
fn centred_dot(c: &[f32], at: &[f32]) -> f32 {
    lanes8(c, at, |c| c - 0.5)
}

/// The [`Model::Pixel`] column term between pixels: `D = -2 (xj - xi) . (c[u] - 1/2)`.
fn col_product(col: &[f32], at: &[f32], frames: usize, xi: [f32; 2], xj: [f32; 2]) -> f32 {
    col.chunks_exact(frames)
        .zip(xi.iter().zip(&xj))
        .map(|(c, (&xi, &xj))| -2.0 * (xj - xi) * centred_dot(c, at))
        .sum()
}

/// `S_l` of the module docs for the swap `xi <-> xj` in the frame whose row is `at`.
fn side_sum(
    s: &Setup,
    blk: &Block,
    vol: &[f32],
    l: usize,
    at: &[f32],
    xi: [f32; 2],
    xj: [f32; 2],
) -> f64 {
    let (len, k) = (s.dims * s.frames, s.offsets.len());
    let mut total = 0.0f64;
    for (i, (&code, &w)) in blk.table[l * k..(l + 1) * k].iter().zip(&s.ws).enumerate() {
        let col = if code & GLOBAL != 0 {
            let g = (code & !GLOBAL) as usize;
            &vol[g * len..(g + 1) * len]
        } else {
            let c = code as usize;
            &blk.vals[c * len..(c + 1) * len]
        };
        let c = if s.model == Model::Pixel && i != s.self_index {
            col_product(col, at, s.frames, xi, xj)
        } else if s.dims == 1 {
            col_scalar(col, at, xi[0], xj[0])
        } else {
            col_vec2(&col[..s.frames], &col[s.frames..], at, xi, xj)
        };
        total += f64::from(w * c);
    }
    total
}

/// Change of `L` when local pixels `a` and `b` swap their values of frame `t`.
pub(super) fn delta(s: &Setup, blk: &Block, vol: &[f32], a: usize, b: usize, t: usize) -> f64 {
    let at = &s.at_rot[t * s.frames..(t + 1) * s.frames];
    let (xi, xj) = (blk.get(s, a, t), blk.get(s, b, t));
    let si = side_sum(s, blk, vol, a, at, xi, xj);
    let sj = side_sum(s, blk, vol, b, at, xi, xj);
    let dist = f64::from(((xi[0] - xj[0]).powi(2) + (xi[1] - xj[1]).powi(2)).sqrt());
    let (ga, gb) = (blk.pixels[a], blk.pixels[b]);
    let n = s.n;
    let (dx, dy) = ((gb % n + n - ga % n) % n, (gb / n + n - ga / n) % n);
    let a_ij = s.ws_dense[dy * n + dx] * s.act0;
    let a_00 = s.ws_dense[0] * s.act0;
    // Minus the change of voxel j's term in S_i and voxel i's in S_j (both in the kernel
    // between pixels): 2 |xi - xj| for -|x - y|, 2 |xi - xj|^2 for the per-pixel product.
    let cross = match s.model {
        Model::Shared => 2.0 * dist,
        Model::Pixel => 2.0 * dist * dist,
    };
    -2.0 * (si - sj - 2.0 * a_00 * dist + a_ij * cross)
}
