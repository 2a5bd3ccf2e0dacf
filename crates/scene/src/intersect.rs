//! CPU ray/BVH intersection, the twin of `shaders/include/bvh.glsl`.
//!
//! Same closest-hit traversal (fixed stack, near child first, far child pushed with its entry
//! distance; the GLSL keeps the current node's `left_first`/`count` in registers and pushes
//! those, where this code keeps node indices: the same nodes in the same order), same
//! stackless occlusion traversal (skip links), same ray/box slab test, same Möller–Trumbore
//! operation order (no fused multiply-adds on either side: the GLSL marks these computations
//! `precise`). Closest hit is the smallest `t` in `[tmin, tmax]`, ties broken by the smaller
//! triangle index, so the BVH and the brute-force loop agree exactly.

use crate::geometry::{cross, dot};
use crate::gpu::{BVH_STACK_SIZE, BvhNode, GpuTriangle, HIT_MISS, Hit, Ray};
use glam::Vec3;

/// Box exit distances, and the current closest `t` they are compared with, are scaled up by
/// this (about 16 ulp) so that rounding in the slab test or in Möller–Trumbore's `t` never
/// culls a box holding a triangle at (or within rounding of) the closest hit. Same literal in
/// bvh.glsl.
pub(crate) const BOX_TFAR_SCALE: f32 = 1.000_002;
/// Direction components smaller than this are replaced by +-this before inverting.
pub(crate) const MIN_DIR_COMPONENT: f32 = 1e-30;

/// `1 / dir` with zero (and tiny) components replaced by +-1e-30, so the slab test never
/// computes `0 * inf`.
#[inline]
pub(crate) fn safe_inverse(d: Vec3) -> Vec3 {
    let s = |x: f32| {
        if x.abs() < MIN_DIR_COMPONENT {
            if x >= 0.0 {
                MIN_DIR_COMPONENT
            } else {
                -MIN_DIR_COMPONENT
            }
        } else {
            x
        }
    };
    Vec3::new(1.0 / s(d.x), 1.0 / s(d.y), 1.0 / s(d.z))
}

/// Slab test. Returns the entry distance if the box overlaps `[tmin, tmax]`.
#[inline]
pub(crate) fn box_entry(
    min: Vec3,
    max: Vec3,
    origin: Vec3,
    inv: Vec3,
    tmin: f32,
    tmax: f32,
) -> Option<f32> {
    let t0 = (min - origin) * inv;
    let t1 = (max - origin) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    let tnear = near.x.max(near.y).max(near.z).max(tmin);
    let tfar = (far.x.min(far.y).min(far.z) * BOX_TFAR_SCALE).min(tmax * BOX_TFAR_SCALE);
    (tnear <= tfar).then_some(tnear)
}

/// Möller–Trumbore. Returns `(t, u, v)` for `tmin <= t <= tmax`; edges count as inside.
#[inline]
pub fn intersect_triangle(ray: &Ray, tri: &GpuTriangle, tmax: f32) -> Option<(f32, f32, f32)> {
    let pvec = cross(ray.dir, tri.e2);
    let det = dot(tri.e1, pvec);
    if det == 0.0 {
        return None;
    }
    let inv_det = 1.0 / det;
    let tvec = ray.origin - tri.v0;
    let u = dot(tvec, pvec) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qvec = cross(tvec, tri.e1);
    let v = dot(ray.dir, qvec) * inv_det;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let t = dot(tri.e2, qvec) * inv_det;
    (t >= ray.tmin && t <= tmax).then_some((t, u, v))
}

/// Closest hit through the BVH.
pub fn closest_hit(nodes: &[BvhNode], triangles: &[GpuTriangle], ray: &Ray) -> Option<Hit> {
    closest_hit_counted(nodes, triangles, ray, &mut TraversalCounts::default())
}

/// The iterations of bvh.glsl's closest-hit loops for the rays traced so far (the shader's
/// `TRACE_LOOP_CLOSEST_*` counts per lane): the loop over descents (one, plus one per node
/// popped), interior nodes, triangles tested and stack entries popped.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TraversalCounts {
    pub descents: u64,
    pub interior: u64,
    pub triangles: u64,
    pub pops: u64,
}

/// [`closest_hit`], adding its loop iterations to `counts`.
pub fn closest_hit_counted(
    nodes: &[BvhNode],
    triangles: &[GpuTriangle],
    ray: &Ray,
    counts: &mut TraversalCounts,
) -> Option<Hit> {
    let mut hit = Hit::miss(ray);
    let root = nodes.first()?;
    let inv = safe_inverse(ray.dir);
    box_entry(
        root.aabb_min,
        root.aabb_max,
        ray.origin,
        inv,
        ray.tmin,
        hit.t,
    )?;
    let mut stack = [0u32; BVH_STACK_SIZE as usize];
    let mut stack_t = [0f32; BVH_STACK_SIZE as usize];
    let mut sp = 0usize;
    let mut node = 0usize;
    counts.descents += 1;
    loop {
        let n = &nodes[node];
        if n.count > 0 {
            counts.triangles += n.count as u64;
            for i in n.left_first..n.left_first + n.count {
                if let Some((t, u, v)) = intersect_triangle(ray, &triangles[i as usize], hit.t)
                    && (t < hit.t || i < hit.triangle)
                {
                    hit = Hit {
                        t,
                        triangle: i,
                        u,
                        v,
                    };
                }
            }
        } else {
            counts.interior += 1;
            let (l, r) = (n.left_first as usize, n.left_first as usize + 1);
            let (nl, nr) = (&nodes[l], &nodes[r]);
            let tl = box_entry(nl.aabb_min, nl.aabb_max, ray.origin, inv, ray.tmin, hit.t);
            let tr = box_entry(nr.aabb_min, nr.aabb_max, ray.origin, inv, ray.tmin, hit.t);
            match (tl, tr) {
                (Some(tl), Some(tr)) => {
                    let (near, far, tfar) = if tl <= tr { (l, r, tr) } else { (r, l, tl) };
                    if sp < stack.len() {
                        stack[sp] = far as u32;
                        stack_t[sp] = tfar;
                        sp += 1;
                    }
                    node = near;
                    continue;
                }
                (Some(_), None) => {
                    node = l;
                    continue;
                }
                (None, Some(_)) => {
                    node = r;
                    continue;
                }
                (None, None) => {}
            }
        }
        // Pop the next far child that can still hold a closer hit.
        let mut next = None;
        while sp > 0 {
            sp -= 1;
            counts.pops += 1;
            if stack_t[sp] <= hit.t * BOX_TFAR_SCALE {
                next = Some(stack[sp] as usize);
                break;
            }
        }
        match next {
            Some(n) => {
                node = n;
                counts.descents += 1;
            }
            None => break,
        }
    }
    Hit::from_gpu(hit)
}

/// Any hit with `tmin <= t <= tmax` through the BVH (shadow rays). Stackless: any hit needs no
/// front-to-back order, so it follows the skip links of [`BvhNode`] (into the left child on a
/// box hit, else past the subtree), visiting the nodes of a left-first stack traversal in the
/// same order.
pub fn occluded(nodes: &[BvhNode], triangles: &[GpuTriangle], ray: &Ray) -> bool {
    if nodes.is_empty() {
        return false;
    }
    let inv = safe_inverse(ray.dir);
    let mut node = 0usize;
    loop {
        let n = &nodes[node];
        let hit = box_entry(n.aabb_min, n.aabb_max, ray.origin, inv, ray.tmin, ray.tmax);
        if hit.is_some() && n.count > 0 {
            for i in n.left_first..n.left_first + n.count {
                if intersect_triangle(ray, &triangles[i as usize], ray.tmax).is_some() {
                    return true;
                }
            }
        }
        node = match hit {
            Some(_) if n.count == 0 => n.left_first,
            _ => n.skip,
        } as usize;
        if node == 0 {
            return false;
        }
    }
}

/// Reference: test every triangle (same tie-break as [`closest_hit`]).
pub fn closest_hit_brute_force(triangles: &[GpuTriangle], ray: &Ray) -> Option<Hit> {
    let mut hit = Hit::miss(ray);
    for (i, tri) in triangles.iter().enumerate() {
        let i = i as u32;
        if let Some((t, u, v)) = intersect_triangle(ray, tri, hit.t)
            && (t < hit.t || i < hit.triangle)
        {
            hit = Hit {
                t,
                triangle: i,
                u,
                v,
            };
        }
    }
    debug_assert!(hit.triangle == HIT_MISS || hit.t <= ray.tmax);
    Hit::from_gpu(hit)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(v0: Vec3, v1: Vec3, v2: Vec3) -> GpuTriangle {
        GpuTriangle {
            v0,
            e1: v1 - v0,
            e2: v2 - v0,
        }
    }

    #[test]
    fn hits_and_barycentrics() {
        let t = tri(Vec3::ZERO, Vec3::X, Vec3::Y);
        let ray = Ray::new(Vec3::new(0.25, 0.5, 1.0), Vec3::NEG_Z, 0.0, 10.0);
        let (t_, u, v) = intersect_triangle(&ray, &t, ray.tmax).unwrap();
        assert_eq!((t_, u, v), (1.0, 0.25, 0.5));
        // Behind the origin, outside [tmin, tmax], outside the triangle.
        assert!(intersect_triangle(&Ray::new(Vec3::Z, Vec3::Z, 0.0, 10.0), &t, 10.0).is_none());
        assert!(intersect_triangle(&ray, &t, 0.5).is_none());
        let off = Ray::new(Vec3::new(0.8, 0.8, 1.0), Vec3::NEG_Z, 0.0, 10.0);
        assert!(intersect_triangle(&off, &t, 10.0).is_none());
    }

    #[test]
    fn axis_parallel_rays_hit_flat_boxes() {
        // A ray with zero direction components against a zero-thickness box.
        let inv = safe_inverse(Vec3::NEG_Y);
        assert!(inv.is_finite());
        let e = box_entry(
            Vec3::new(-1.0, -1.0, -1.0),
            Vec3::new(1.0, -1.0, 1.0),
            Vec3::new(0.3, 0.0, 0.2),
            inv,
            0.0,
            f32::MAX,
        );
        assert_eq!(e, Some(1.0));
    }
}

#[cfg(test)]
mod glsl_sync {
    use super::*;

    /// The literals in bvh.glsl must be the Rust constants.
    #[test]
    fn bvh_glsl_constants_match() {
        // Runtime variable: `cargo test` sets it to this checkout even when the binary was
        // built from another checkout sharing the target dir.
        let root = std::env::var("CARGO_MANIFEST_DIR").unwrap();
        let path = format!("{root}/../../shaders/include/bvh.glsl");
        let src = std::fs::read_to_string(path).unwrap();
        let value = |name: &str| -> f32 {
            let line = src
                .lines()
                .find(|l| l.contains(&format!("const float {name} =")))
                .unwrap();
            line.split('=')
                .nth(1)
                .unwrap()
                .trim()
                .trim_end_matches(';')
                .parse()
                .unwrap()
        };
        assert_eq!(value("BVH_TFAR_SCALE"), BOX_TFAR_SCALE);
        assert_eq!(value("BVH_MIN_DIR_COMPONENT"), MIN_DIR_COMPONENT);
    }
}
