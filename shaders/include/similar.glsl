// Whether two G-buffer pixels show one surface (edge-aware grouping, seed reprojection). The
// float work is `precise` (no contraction into FMAs) and in the same order as the CPU twin
// (crates/permute/src/similar.rs), so both decide alike. Needs generated/motion.glsl.
#ifndef SIMILAR_GLSL
#define SIMILAR_GLSL

bool similar(GBufferTexel a, GBufferTexel b) {
    vec3 na = a.normal, nb = b.normal;
    precise vec3 d = a.position - b.position;
    precise float c = na.x * nb.x + na.y * nb.y + na.z * nb.z;
    precise float plane = nb.x * d.x + nb.y * d.y + nb.z * d.z;
    bool near = c >= SIMILAR_MIN_COS && abs(plane) <= SIMILAR_PLANE_DISTANCE * max(a.depth, b.depth);
    return a.material == b.material && (a.material == 0u || near);
}

#endif
