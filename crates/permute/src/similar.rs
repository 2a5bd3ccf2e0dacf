//! CPU twin of shaders/include/similar.glsl: whether two G-buffer pixels show one surface.
//! Same operations in the same order as the `precise` GLSL (no fused multiply-adds), so GPU and
//! CPU decide alike bit for bit.
use blueshift_layout::motion::{GBufferTexel, SIMILAR_MIN_COS, SIMILAR_PLANE_DISTANCE};
use glam::Vec3;

#[inline]
pub(crate) fn dot3(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// Same material, and for hits: normals within acos(SIMILAR_MIN_COS), and a within
/// SIMILAR_PLANE_DISTANCE x the larger depth of b's tangent plane.
pub fn similar(a: &GBufferTexel, b: &GBufferTexel) -> bool {
    let d = a.position - b.position;
    let c = dot3(a.normal, b.normal);
    let plane = dot3(b.normal, d);
    let near = c >= SIMILAR_MIN_COS && plane.abs() <= SIMILAR_PLANE_DISTANCE * a.depth.max(b.depth);
    a.material == b.material && (a.material == 0 || near)
}
