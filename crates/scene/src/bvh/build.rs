//! The binned-SAH builder (see the module docs of [`super`]).

use super::{Bvh, MAX_LEAF_SIZE, PARALLEL_THRESHOLD};
use crate::Aabb;
use crate::gpu::{BVH_STACK_SIZE, BvhNode};
use glam::Vec3;
use rayon::prelude::*;

const BINS: usize = 16;
/// Nodes with more primitives than this compute bounds and bins in parallel.
const PARALLEL_BINNING: usize = 1 << 16;
const CHUNK: usize = 1 << 13;
/// Deepest allowed leaf: the traversal stack holds at most one entry per level.
const MAX_DEPTH: usize = BVH_STACK_SIZE as usize - 1;

/// A primitive reference: its bounds and input index, 28 bytes. The builder partitions these
/// records themselves (not indices into side arrays), so every pass over a node reads memory
/// sequentially instead of gathering from random places.
#[derive(Clone, Copy)]
struct PrimRef {
    min: Vec3,
    index: u32,
    max: Vec3,
}

impl PrimRef {
    #[inline]
    fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
    #[inline]
    fn bounds(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }
}

enum Node {
    Leaf {
        bounds: Aabb,
        start: u32,
        count: u32,
    },
    Inner {
        bounds: Aabb,
        children: Box<[Node; 2]>,
    },
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

type Bins = [[Bin; BINS]; 3];

const EMPTY_BINS: Bins = [[Bin {
    bounds: Aabb::EMPTY,
    count: 0,
}; BINS]; 3];

/// Builds over `n` primitives whose bounds `bounds(i)` gives: the primitive references are
/// made from it directly, with no array of boxes (or of triangles) in between.
pub(super) fn build(n: usize, bounds: impl Fn(usize) -> Aabb + Sync) -> Bvh {
    if n == 0 {
        return Bvh::default();
    }
    let mut refs: Vec<PrimRef> = (0..n)
        .into_par_iter()
        .map(|i| {
            let b = bounds(i);
            PrimRef {
                min: b.min,
                index: i as u32,
                max: b.max,
            }
        })
        .collect();
    let (root_bounds, root_centroids) = node_bounds(&refs);
    let root = build_node(&mut refs, root_bounds, root_centroids, 0, 0);
    let order = refs.par_iter().map(|r| r.index).collect();
    drop(refs);
    let mut nodes = Vec::with_capacity(2 * n.div_ceil(2));
    nodes.push(BvhNode::default());
    let mut depth = 0;
    flatten(&root, &mut nodes, 0, 0, 0, &mut depth);
    Bvh {
        nodes,
        order,
        depth,
    }
}

/// Levels of object-median splits needed to bring `n` primitives down to leaves.
fn median_levels(n: usize) -> usize {
    let leaves = n.div_ceil(MAX_LEAF_SIZE);
    (usize::BITS - (leaves - 1).leading_zeros()) as usize
}

/// Node bounds of one side of a split: primitive bounds and centroid bounds.
type SideBounds = (Aabb, Aabb);

fn build_node(
    idx: &mut [PrimRef],
    bounds: Aabb,
    centroid_bounds: Aabb,
    start: usize,
    depth: usize,
) -> Node {
    let n = idx.len();
    let leaf = Node::Leaf {
        bounds,
        start: start as u32,
        count: n as u32,
    };
    if n == 1 {
        return leaf;
    }
    // Splitting by SAH may leave a child nearly as large as this node; allow it only while a
    // median fallback below that child still fits under MAX_DEPTH.
    let sah_allowed = depth + 1 + median_levels(n) <= MAX_DEPTH;
    let extent = centroid_bounds.extent();
    let mut mid = 0;
    let mut sides: Option<(SideBounds, SideBounds)> = None;
    if sah_allowed && extent.max_element() > 0.0 {
        let scale = Vec3::select(
            extent.cmpgt(Vec3::ZERO),
            Vec3::splat(BINS as f32) / extent,
            Vec3::ZERO,
        );
        let cmin = centroid_bounds.min;
        let bins = bin_all(idx, cmin, scale);
        if let Some((axis, split, cost)) = best_split(&bins, extent) {
            let area = bounds.half_area();
            let split_cost = if area > 0.0 {
                1.0 + cost / area
            } else {
                f32::INFINITY
            };
            if n <= MAX_LEAF_SIZE && n as f32 <= split_cost {
                return leaf;
            }
            let (m, s) = (cmin[axis], scale[axis]);
            let (m_, l_, r_) = partition(idx, |r| bin_index(r.centroid()[axis], m, s) <= split);
            mid = m_;
            sides = Some((l_, r_));
        }
    }
    if mid == 0 || mid == n {
        if n <= MAX_LEAF_SIZE {
            return leaf;
        }
        mid = n / 2;
        let axis = extent.max_position();
        idx.select_nth_unstable_by(mid, |a, b| {
            a.centroid()[axis].total_cmp(&b.centroid()[axis])
        });
        sides = None;
    }
    let (l, r) = idx.split_at_mut(mid);
    let ((lb, lc), (rb, rc)) = match sides {
        Some(s) => s,
        None => (node_bounds(l), node_bounds(r)),
    };
    let (a, b) = if n > PARALLEL_THRESHOLD {
        rayon::join(
            || build_node(l, lb, lc, start, depth + 1),
            || build_node(r, rb, rc, start + mid, depth + 1),
        )
    } else {
        (
            build_node(l, lb, lc, start, depth + 1),
            build_node(r, rb, rc, start + mid, depth + 1),
        )
    };
    Node::Inner {
        bounds,
        children: Box::new([a, b]),
    }
}

/// Bounds of the primitives and of their centroids.
fn node_bounds(idx: &[PrimRef]) -> (Aabb, Aabb) {
    let seq = |idx: &[PrimRef]| {
        let (mut b, mut c) = (Aabb::EMPTY, Aabb::EMPTY);
        for r in idx {
            b.grow(&r.bounds());
            c.grow_point(r.centroid());
        }
        (b, c)
    };
    if idx.len() > PARALLEL_BINNING {
        idx.par_chunks(CHUNK).map(seq).reduce(
            || (Aabb::EMPTY, Aabb::EMPTY),
            |x, y| (x.0.union(&y.0), x.1.union(&y.1)),
        )
    } else {
        seq(idx)
    }
}

#[inline]
fn bin_index(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BINS - 1)
}

fn bin_all(idx: &[PrimRef], cmin: Vec3, scale: Vec3) -> Bins {
    let seq = |idx: &[PrimRef]| {
        let mut bins = EMPTY_BINS;
        for r in idx {
            let c = r.centroid();
            let b = r.bounds();
            for (axis, axis_bins) in bins.iter_mut().enumerate() {
                let bin = &mut axis_bins[bin_index(c[axis], cmin[axis], scale[axis])];
                bin.count += 1;
                bin.bounds.grow(&b);
            }
        }
        bins
    };
    if idx.len() > PARALLEL_BINNING {
        idx.par_chunks(CHUNK).map(seq).reduce(
            || EMPTY_BINS,
            |mut x, y| {
                for (xa, ya) in x.iter_mut().zip(&y) {
                    for (xb, yb) in xa.iter_mut().zip(ya) {
                        xb.count += yb.count;
                        xb.bounds.grow(&yb.bounds);
                    }
                }
                x
            },
        )
    } else {
        seq(idx)
    }
}

/// The cheapest split `(axis, last bin of the left side, A_l N_l + A_r N_r)`.
fn best_split(bins: &Bins, extent: Vec3) -> Option<(usize, usize, f32)> {
    let mut best: Option<(usize, usize, f32)> = None;
    for (axis, axis_bins) in bins.iter().enumerate() {
        if extent[axis] <= 0.0 {
            continue;
        }
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for k in (1..BINS).rev() {
            acc.grow(&axis_bins[k].bounds);
            cnt += axis_bins[k].count;
            right_area[k] = acc.half_area();
            right_count[k] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for k in 0..BINS - 1 {
            acc.grow(&axis_bins[k].bounds);
            cnt += axis_bins[k].count;
            if cnt == 0 || right_count[k + 1] == 0 {
                continue;
            }
            let cost = acc.half_area() * cnt as f32 + right_area[k + 1] * right_count[k + 1] as f32;
            if best.is_none_or(|b| cost < b.2) {
                best = Some((axis, k, cost));
            }
        }
    }
    best
}

/// In-place partition; returns how many elements satisfy `left`, and the bounds of both sides
/// (computed on the way, so children need no extra pass over their primitives).
fn partition(
    idx: &mut [PrimRef],
    left: impl Fn(&PrimRef) -> bool,
) -> (usize, SideBounds, SideBounds) {
    let (mut lb, mut lc, mut rb, mut rc) = (Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY);
    let (mut i, mut j) = (0, idx.len());
    while i < j {
        let r = idx[i];
        if left(&r) {
            lb.grow(&r.bounds());
            lc.grow_point(r.centroid());
            i += 1;
        } else {
            rb.grow(&r.bounds());
            rc.grow_point(r.centroid());
            j -= 1;
            idx.swap(i, j);
        }
    }
    (i, (lb, lc), (rb, rc))
}

fn flatten(
    node: &Node,
    nodes: &mut Vec<BvhNode>,
    slot: usize,
    skip: u32,
    depth: u32,
    max_depth: &mut u32,
) {
    match node {
        Node::Leaf {
            bounds,
            start,
            count,
        } => {
            *max_depth = (*max_depth).max(depth);
            nodes[slot] = BvhNode {
                aabb_min: bounds.min,
                left_first: *start,
                aabb_max: bounds.max,
                count: *count,
                skip,
            };
        }
        Node::Inner { bounds, children } => {
            let first = nodes.len();
            nodes.push(BvhNode::default());
            nodes.push(BvhNode::default());
            nodes[slot] = BvhNode {
                aabb_min: bounds.min,
                left_first: first as u32,
                aabb_max: bounds.max,
                count: 0,
                skip,
            };
            let right = first as u32 + 1;
            flatten(&children[0], nodes, first, right, depth + 1, max_depth);
            flatten(&children[1], nodes, first + 1, skip, depth + 1, max_depth);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_levels_bound() {
        assert_eq!(median_levels(1), 0);
        assert_eq!(median_levels(4), 0);
        assert_eq!(median_levels(5), 1);
        assert_eq!(median_levels(8), 1);
        assert_eq!(median_levels(9), 2);
        assert_eq!(median_levels(1 << 20), 18);
    }

    #[test]
    fn identical_boxes_still_split_into_small_leaves() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        let bvh = Bvh::build_from_bounds(&vec![b; 1000]);
        bvh.validate(&vec![b; 1000]).unwrap();
    }

    #[test]
    fn adversarial_distribution_respects_depth_cap() {
        // Exponentially spaced boxes make SAH peel off one primitive per level.
        let bounds: Vec<Aabb> = (0..3000)
            .map(|i| {
                let x = 1.02f32.powi(i);
                Aabb {
                    min: Vec3::new(x, 0.0, 0.0),
                    max: Vec3::new(x * 1.001, 1.0, 1.0),
                }
            })
            .collect();
        let bvh = Bvh::build_from_bounds(&bounds);
        bvh.validate(&bounds).unwrap();
        assert!(bvh.depth < BVH_STACK_SIZE);
    }
}
