//! Exact solver: min-cost perfect matching on the sparse disc graph.
//!
//! Rows are source cells `u`, columns are destination cells `v = u + delta`, `|delta| <= R`,
//! edge cost `|M(u) - M(v + s)|` (integer). The identity is a perfect matching, so an
//! optimum exists. This is the successive-shortest-augmenting-path method of Jonker and
//! Volgenant (1987) on a sparse graph: column prices `p`, the invariant that every assigned
//! row's column minimises `c(i, j) - p(j)`, one Dijkstra per free row over reduced costs
//! (all non-negative by the invariant) that stops at the first free column, then the price
//! update `p(j) += d(j) - d_end` on scanned columns and augmentation along the path. With
//! integer costs the result is an exact optimum; ties are broken by the fixed row order and
//! the heap order `(distance, column)`, so the output is deterministic.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::Problem;

const NONE: usize = usize::MAX;

/// Solves `p` exactly; returns `target[u] = pi(u)`. `progress` receives the number of rows
/// assigned so far.
pub fn solve(p: &Problem, progress: &mut dyn FnMut(u64)) -> Vec<usize> {
    let nn = p.len();
    let mut price = vec![0i64; nn];
    let mut row_of_col = vec![NONE; nn];
    let mut col_of_row = vec![NONE; nn];
    let mut dist = vec![i64::MAX; nn];
    let mut pred = vec![NONE; nn];
    let mut scanned = vec![false; nn];
    let mut touched: Vec<usize> = Vec::new();
    let mut scanned_list: Vec<usize> = Vec::new();
    let mut heap: BinaryHeap<Reverse<(i64, usize)>> = BinaryHeap::new();

    for free in 0..nn {
        for k in 0..p.disc.len() {
            let j = p.neighbour(free, k);
            let d = p.cost(free, j) - price[j];
            if d < dist[j] {
                if dist[j] == i64::MAX {
                    touched.push(j);
                }
                dist[j] = d;
                pred[j] = free;
                heap.push(Reverse((d, j)));
            }
        }
        let (end, mu) = loop {
            let Some(Reverse((d, j))) = heap.pop() else {
                // Cannot happen: the identity matching always leaves a free column reachable.
                unreachable!("no augmenting path from row {free}");
            };
            if scanned[j] || d > dist[j] {
                continue;
            }
            scanned[j] = true;
            scanned_list.push(j);
            let i = row_of_col[j];
            if i == NONE {
                break (j, d);
            }
            let base = d - (p.cost(i, j) - price[j]);
            for k in 0..p.disc.len() {
                let jj = p.neighbour(i, k);
                if scanned[jj] {
                    continue;
                }
                let nd = base + p.cost(i, jj) - price[jj];
                if nd < dist[jj] {
                    if dist[jj] == i64::MAX {
                        touched.push(jj);
                    }
                    dist[jj] = nd;
                    pred[jj] = i;
                    heap.push(Reverse((nd, jj)));
                }
            }
        };
        for &j in &scanned_list {
            price[j] += dist[j] - mu;
        }
        // Augment along the predecessor chain back to the free row.
        let mut j = end;
        loop {
            let i = pred[j];
            row_of_col[j] = i;
            let prev = std::mem::replace(&mut col_of_row[i], j);
            if i == free {
                break;
            }
            j = prev;
        }
        for &j in &touched {
            dist[j] = i64::MAX;
            scanned[j] = false;
        }
        touched.clear();
        scanned_list.clear();
        heap.clear();
        if free % 256 == 255 {
            progress(free as u64 + 1);
        }
    }
    progress(nn as u64);
    col_of_row
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voidcluster::white;
    use blueshift_analysis::assets::Mask;

    /// Dense O(n^3) Hungarian (e-maxx formulation) as an independent reference.
    fn dense_hungarian(cost: &[Vec<i64>]) -> i64 {
        let n = cost.len();
        let inf = i64::MAX / 4;
        let (mut u, mut v) = (vec![0i64; n + 1], vec![0i64; n + 1]);
        let (mut pm, mut way) = (vec![0usize; n + 1], vec![0usize; n + 1]);
        for i in 1..=n {
            pm[0] = i;
            let mut j0 = 0;
            let mut minv = vec![inf; n + 1];
            let mut used = vec![false; n + 1];
            loop {
                used[j0] = true;
                let (i0, mut delta, mut j1) = (pm[j0], inf, 0);
                for j in 1..=n {
                    if !used[j] {
                        let cur = cost[i0 - 1][j - 1] - u[i0] - v[j];
                        if cur < minv[j] {
                            minv[j] = cur;
                            way[j] = j0;
                        }
                        if minv[j] < delta {
                            delta = minv[j];
                            j1 = j;
                        }
                    }
                }
                for j in 0..=n {
                    if used[j] {
                        u[pm[j]] += delta;
                        v[j] -= delta;
                    } else {
                        minv[j] -= delta;
                    }
                }
                j0 = j1;
                if pm[j0] == 0 {
                    break;
                }
            }
            loop {
                let j1 = way[j0];
                pm[j0] = pm[j1];
                j0 = j1;
                if j0 == 0 {
                    break;
                }
            }
        }
        (1..=n).map(|j| cost[pm[j] - 1][j - 1]).sum()
    }

    #[test]
    fn matches_dense_hungarian_on_small_problems() {
        for (seed, radius) in [(1u64, 1u32), (2, 2), (3, 3)] {
            let mask = Mask::new(16, white(16, seed)).unwrap();
            let p = Problem::new(&mask, (5, 3), radius).unwrap();
            let nn = p.len();
            let big = 1_000_000_000i64;
            let cost: Vec<Vec<i64>> = (0..nn)
                .map(|u| {
                    (0..nn)
                        .map(|v| if p.in_disc(u, v) { p.cost(u, v) } else { big })
                        .collect()
                })
                .collect();
            let reference = dense_hungarian(&cost);
            let target = solve(&p, &mut |_| {});
            let mut seen = vec![false; nn];
            for (u, &v) in target.iter().enumerate() {
                assert!(p.in_disc(u, v));
                assert!(!std::mem::replace(&mut seen[v], true));
            }
            assert_eq!(p.energy(&target) as i64, reference, "radius {radius}");
        }
    }
}
