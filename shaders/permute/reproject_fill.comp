#version 460
// Seed reprojection, step 4 of 5: lists the holes and the unclaimed pixels in scan order
// (one invocation per padded row, starting at the sum of the earlier rows' counts). Both lists
// have the same length, so matching them k to k is a bijection. Loops stay far below
// llvmpipe's 65535 iterations per invocation (rows + width <= 2 * 16384).
// CPU twin: crates/permute/src/reproject.rs reproject_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Src { uint src[]; };
layout(set = 0, binding = 1, scalar) readonly buffer Claim { uint claim[]; };
layout(set = 0, binding = 2, scalar) readonly buffer Rows { uint rows[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer Holes { uint holes[]; };
layout(set = 0, binding = 4, scalar) writeonly buffer Leftovers { uint leftovers[]; };

void main() {
    uint y = gl_GlobalInvocationID.x;
    if (y >= p.padded_height) return;
    uint h = 0u, l = 0u;
    for (uint r = 0u; r < y; ++r) {
        h += rows[2u * r];
        l += rows[2u * r + 1u];
    }
    for (uint x = 0u; x < p.padded_width; ++x) {
        uint q = y * p.padded_width + x;
        uint s = src[q];
        bool won = s != REPROJECT_NONE && claim[s] == q;
        if (!won) holes[h++] = q;
        if (claim[q] == REPROJECT_NONE) leftovers[l++] = q;
    }
}
