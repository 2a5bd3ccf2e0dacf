//! Binned-SAH bounding volume hierarchy, flattened into [`BvhNode`]s.
//!
//! Build: 16 bins over the centroid bounds on all three axes, SAH cost
//! `1 + (A_l N_l + A_r N_r) / A` against a leaf cost `N`; leaves hold at most
//! [`MAX_LEAF_SIZE`] triangles. The triangle index array is partitioned in place (no sorting);
//! subtrees above [`PARALLEL_THRESHOLD`] triangles are built in parallel with `rayon::join`,
//! and the binning of very large nodes is itself parallel. The tree depth is capped at
//! [`BVH_STACK_SIZE`](crate::gpu::BVH_STACK_SIZE) (object-median splits take over near the
//! cap), so the fixed traversal stack of `bvh.glsl` can never overflow.
//!
//! Layout: see [`BvhNode`]. Node 0 is the root; children of an interior node are adjacent and
//! allocated in depth-first pre-order; leaves reference contiguous triangle ranges of the
//! reordered triangle array ([`Bvh::order`] maps them back to the input).

mod build;

use crate::Aabb;
use crate::gpu::{BVH_STACK_SIZE, BvhNode};
use glam::Vec3;

/// Most triangles in one leaf.
pub const MAX_LEAF_SIZE: usize = 4;
// bvh.glsl packs a node's triangle count into 3 bits of a traversal-stack entry, the node
// texels into NODE_COUNT_BITS bits next to its skip link.
const _: () = assert!(MAX_LEAF_SIZE < 8 && MAX_LEAF_SIZE < 1 << crate::gpu::NODE_COUNT_BITS);
/// Subtrees with more triangles than this are built with `rayon::join`.
pub const PARALLEL_THRESHOLD: usize = 4096;

/// A built BVH.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<BvhNode>,
    /// `order[i]` is the input index of the triangle stored at position `i`.
    pub order: Vec<u32>,
    /// Depth of the deepest leaf (root = 0).
    pub depth: u32,
}

impl Bvh {
    /// Builds over triangles given by their three vertices.
    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        Self::build_with(triangles.len(), |i| Aabb::from_points(&triangles[i]))
    }

    /// Builds over arbitrary primitives given by their bounds.
    pub fn build_from_bounds(bounds: &[Aabb]) -> Bvh {
        Self::build_with(bounds.len(), |i| bounds[i])
    }

    /// Builds over `n` primitives, primitive `i` bounded by `bounds(i)`: no copy of the
    /// primitives or of their boxes is made (the scene's triangles are read where they are).
    pub fn build_with(n: usize, bounds: impl Fn(usize) -> Aabb + Sync) -> Bvh {
        build::build(n, bounds)
    }

    /// Checks the invariants the traversal relies on, against the primitive bounds in *input*
    /// order: every primitive is in exactly one leaf, leaf boxes contain their primitives,
    /// child boxes lie inside their parent, children are adjacent and after their parent,
    /// the skip links thread the tree (see [`BvhNode`]) and the depth fits the traversal stack.
    pub fn validate(&self, bounds: &[Aabb]) -> Result<(), String> {
        let n = bounds.len();
        if self.order.len() != n {
            return Err(format!(
                "order has {} entries for {n} primitives",
                self.order.len()
            ));
        }
        let mut seen = vec![false; n];
        for &o in &self.order {
            let o = o as usize;
            if o >= n || std::mem::replace(&mut seen[o], true) {
                return Err(format!("order entry {o} is out of range or repeated"));
            }
        }
        if n == 0 {
            return if self.nodes.is_empty() {
                Ok(())
            } else {
                Err("nodes without primitives".into())
            };
        }
        let mut covered = vec![0u32; n];
        // (node, depth, the skip link it must have)
        let mut stack = vec![(0usize, 0u32, 0u32)];
        let mut visited = 0usize;
        let mut max_depth = 0;
        while let Some((i, depth, skip)) = stack.pop() {
            visited += 1;
            max_depth = max_depth.max(depth);
            let node = self.nodes.get(i).ok_or(format!("node {i} out of range"))?;
            if node.skip != skip {
                return Err(format!("node {i} skips to {}, not {skip}", node.skip));
            }
            let b = node_box(node);
            if node.is_leaf() {
                let (first, count) = (node.left_first as usize, node.count as usize);
                if first + count > n || count > MAX_LEAF_SIZE {
                    return Err(format!("leaf {i} has bad range {first}+{count}"));
                }
                for (k, c) in covered.iter_mut().enumerate().skip(first).take(count) {
                    *c += 1;
                    if !b.contains(&bounds[self.order[k] as usize]) {
                        return Err(format!("leaf {i} box does not contain triangle {k}"));
                    }
                }
            } else {
                let l = node.left_first as usize;
                if l <= i || l + 1 >= self.nodes.len() {
                    return Err(format!("interior node {i} has bad children {l}, {}", l + 1));
                }
                for (c, s) in [(l, l as u32 + 1), (l + 1, skip)] {
                    if !b.contains(&node_box(&self.nodes[c])) {
                        return Err(format!("child {c} box is not inside parent {i}"));
                    }
                    stack.push((c, depth + 1, s));
                }
            }
        }
        if let Some(k) = covered.iter().position(|&c| c != 1) {
            return Err(format!("triangle slot {k} is in {} leaves", covered[k]));
        }
        if visited != self.nodes.len() {
            return Err(format!("{} nodes unreachable", self.nodes.len() - visited));
        }
        if max_depth != self.depth || max_depth >= BVH_STACK_SIZE {
            return Err(format!("depth {max_depth} (recorded {})", self.depth));
        }
        Ok(())
    }

    /// SAH cost of the tree (traversal cost 1, intersection cost 1), for diagnostics.
    pub fn sah_cost(&self) -> f32 {
        let Some(root) = self.nodes.first() else {
            return 0.0;
        };
        let root_area = node_box(root).half_area().max(f32::MIN_POSITIVE);
        self.nodes
            .iter()
            .map(|n| {
                let a = node_box(n).half_area() / root_area;
                if n.is_leaf() { a * n.count as f32 } else { a }
            })
            .sum()
    }
}

pub(crate) fn node_box(n: &BvhNode) -> Aabb {
    Aabb {
        min: n.aabb_min,
        max: n.aabb_max,
    }
}
