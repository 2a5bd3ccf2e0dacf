//! SAH BVH invariants.

mod common;

use blueshift_scene::bvh::MAX_LEAF_SIZE;
use blueshift_scene::gpu::BVH_STACK_SIZE;
use blueshift_scene::{Aabb, Bvh};
use common::triangle_soup;
use glam::Vec3;

fn bounds(tris: &[[Vec3; 3]]) -> Vec<Aabb> {
    tris.iter().map(|t| Aabb::from_points(t)).collect()
}

#[test]
fn tiny_inputs() {
    assert!(Bvh::build(&[]).nodes.is_empty());
    for n in 1..=9 {
        let tris = triangle_soup(n, 1.0, 0.1, n as u64);
        let bvh = Bvh::build(&tris);
        bvh.validate(&bounds(&tris)).unwrap();
        if n == 1 {
            assert_eq!(bvh.nodes.len(), 1);
            assert_eq!(bvh.nodes[0].count, 1);
        }
    }
}

#[test]
fn random_soup_invariants() {
    // Large enough to take the parallel paths (join and parallel binning).
    let tris = triangle_soup(100_000, 10.0, 0.05, 42);
    let bvh = Bvh::build(&tris);
    let b = bounds(&tris);
    bvh.validate(&b).unwrap();
    assert!(bvh.depth < BVH_STACK_SIZE);
    assert!(bvh.nodes.iter().all(|n| n.count as usize <= MAX_LEAF_SIZE));
    // Root box is exactly the scene bounds.
    let mut all = Aabb::EMPTY;
    b.iter().for_each(|x| all.grow(x));
    assert_eq!(
        (bvh.nodes[0].aabb_min, bvh.nodes[0].aabb_max),
        (all.min, all.max)
    );
    // Regression guard. Small triangles spread through a volume give an inherently high SAH
    // cost (~ sum over levels of 2^(level/3), about 130 here, vs 100000 for a linear scan).
    assert!(bvh.sah_cost() < 160.0, "SAH cost {}", bvh.sah_cost());
}

#[test]
fn build_is_deterministic() {
    let tris = triangle_soup(20_000, 5.0, 0.2, 7);
    let a = Bvh::build(&tris);
    let b = Bvh::build(&tris);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.order, b.order);
}

#[test]
fn clustered_and_degenerate_layouts() {
    // Many triangles sharing one centroid plus a far cluster, and long thin slivers.
    let mut tris = Vec::new();
    for i in 0..500 {
        let s = 0.01 * (1 + i % 5) as f32;
        tris.push([
            Vec3::new(-s, 0.0, 0.0),
            Vec3::new(s, 0.0, 0.0),
            Vec3::new(0.0, s, 0.0),
        ]);
    }
    for i in 0..500 {
        let x = 1000.0 + i as f32 * 1e-3;
        tris.push([
            Vec3::new(x, 0.0, 0.0),
            Vec3::new(x, 100.0, 0.0),
            Vec3::new(x, 0.0, 1e-4),
        ]);
    }
    let bvh = Bvh::build(&tris);
    bvh.validate(&bounds(&tris)).unwrap();
}

#[test]
fn validate_catches_broken_trees() {
    let tris = triangle_soup(64, 2.0, 0.1, 3);
    let b = bounds(&tris);
    let good = Bvh::build(&tris);
    let mut bad = good.clone();
    bad.order.swap(0, 1);
    bad.order[1] = bad.order[0];
    assert!(bad.validate(&b).is_err());
    let mut bad = good.clone();
    bad.nodes[1].aabb_max += Vec3::splat(100.0);
    assert!(bad.validate(&b).is_err());
    let mut bad = good;
    let leaf = bad.nodes.iter().position(|n| n.count > 0).unwrap();
    bad.nodes[leaf].count -= 1;
    assert!(bad.validate(&b).is_err());
}
