//! Exact duplicate triangles: dropped at load, counted in one warning.
//!
//! A file may draw the same triangle many times (20,000 primitives sharing one POSITION
//! accessor). Every copy sits in the BVH, so a ray through the pile visits every node and tests
//! every copy: 20,000 copies cost a ray ~35,000 loop iterations, past the trace pass's loop
//! guard (llvmpipe ends loops after 65,535; `blueshift_trace::TRACE_LOOP_GUARD`).
//!
//! A copy equal bit for bit to an earlier triangle (positions in the same order, normals, UVs,
//! material) gives the same intersection and the same shading, and closest-hit ties go to one
//! copy anyway, so dropping it leaves what a ray sees unchanged. (An emissive copy also
//! doubled its triangle's power in next-event estimation while a ray hitting the pile counted
//! it once; with one copy the two agree.) Anything less than bit-equal is kept: another
//! material, another vertex order, a coordinate one ulp off, or -0.0 for 0.0.

use super::warnings::{Warnings, thousands};
use crate::scene::Triangle;
use std::collections::HashSet;
use std::hash::{Hash, Hasher};

/// The words of a triangle, as compared: every f32 by its bits.
fn words(t: &Triangle) -> [u32; 25] {
    let mut w = [0u32; 25];
    let floats = t
        .positions
        .iter()
        .chain(&t.normals)
        .flat_map(|v| v.to_array())
        .chain(t.uvs.iter().flat_map(|v| v.to_array()));
    for (slot, f) in w.iter_mut().zip(floats) {
        *slot = f.to_bits();
    }
    w[24] = t.material;
    w
}

/// A triangle compared and hashed by its bits (a float `==` would equate -0.0 and 0.0).
struct Bits<'a>(&'a Triangle);

impl PartialEq for Bits<'_> {
    fn eq(&self, other: &Self) -> bool {
        words(self.0) == words(other.0)
    }
}

impl Eq for Bits<'_> {}

impl Hash for Bits<'_> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        words(self.0).hash(state);
    }
}

/// Removes every triangle equal bit for bit to an earlier one, keeping the order of the rest
/// (a scene without duplicates is left exactly as it was), and warns with their count.
pub(super) fn drop_duplicates(triangles: &mut Vec<Triangle>, warnings: &mut Warnings) {
    let n = remove(triangles);
    if n > 0 {
        warnings.warn("duplicates", || {
            format!(
                "{} duplicate triangles dropped (each has the vertices, normals, texture \
                 coordinates and material of an earlier one; the image is the same)",
                thousands(n as u64)
            )
        });
    }
}

/// [`drop_duplicates`] without the warning; returns how many were removed. The set uses std's
/// randomly keyed SipHash: the triangles come from an untrusted file, and a fixed hash would
/// let one craft collisions that make this quadratic.
fn remove(triangles: &mut Vec<Triangle>) -> usize {
    let keep: Vec<bool> = {
        let mut seen = HashSet::with_capacity(triangles.len());
        triangles.iter().map(|t| seen.insert(Bits(t))).collect()
    };
    let before = triangles.len();
    let mut keep = keep.into_iter();
    triangles.retain(|_| keep.next().unwrap_or(true));
    before - triangles.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    fn tri(x: f32, material: u32) -> Triangle {
        Triangle {
            positions: [Vec3::new(x, 0.0, 0.0), Vec3::X, Vec3::Y],
            normals: [Vec3::Z; 3],
            uvs: [Vec2::ZERO; 3],
            material,
        }
    }

    #[test]
    fn only_bit_equal_copies_are_dropped_and_the_order_is_kept() {
        let a = tri(0.0, 0);
        let mut rotated = a;
        rotated.positions.rotate_left(1);
        let mut uv = a;
        uv.uvs[2] = Vec2::new(0.5, 0.0);
        let mut normal = a;
        normal.normals[0] = Vec3::new(0.0, 0.6, 0.8);
        let one_ulp = tri(f32::from_bits(1), 0);
        let kept = [a, tri(-0.0, 0), tri(0.0, 1), rotated, uv, normal, one_ulp];
        let mut tris = vec![
            a, kept[1], a, kept[2], kept[3], a, kept[4], kept[5], kept[6],
        ];
        tris.extend([kept[6], a, kept[2]]);
        assert_eq!(remove(&mut tris), 5);
        assert_eq!(tris, kept);
    }

    #[test]
    fn a_scene_without_duplicates_is_unchanged() {
        let tris: Vec<Triangle> = (0..100).map(|i| tri(i as f32 * 0.01, i % 3)).collect();
        let mut out = tris.clone();
        assert_eq!(remove(&mut out), 0);
        assert_eq!(out, tris);
    }
}
