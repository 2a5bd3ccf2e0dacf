#version 460
// Seed reprojection, step 5 of 5: the k-th hole takes the seed of the k-th unclaimed pixel
// (fresh seeds for disoccluded pixels, from the ones that no longer map anywhere). After this
// the output is again a permutation of the input.
// CPU twin: crates/permute/src/reproject.rs reproject_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Holes { uint holes[]; };          // NONE-filled
layout(set = 0, binding = 1, scalar) readonly buffer Leftovers { uint leftovers[]; };
layout(set = 0, binding = 2, scalar) readonly buffer SeedsIn { uint seeds_in[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer SeedsOut { uint seeds_out[]; };

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= p.padded_width * p.padded_height) return;
    uint h = holes[k];
    uint n = p.padded_width * p.padded_height;
    // Entries past the lists' end are NONE in `holes` and undefined in `leftovers`: clamped so
    // that even a masked-off lane never reads out of bounds.
    if (h != REPROJECT_NONE) seeds_out[min(h, n - 1u)] = seeds_in[min(leftovers[k], n - 1u)];
}
