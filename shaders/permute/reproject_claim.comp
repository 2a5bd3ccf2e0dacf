#version 460
// Seed reprojection, step 2 of 5: each source pixel is claimed by the lowest-index pixel that
// wants its seed (atomicMin: the result does not depend on execution order).
// CPU twin: crates/permute/src/reproject.rs reproject_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Src { uint src[]; };  // padded
layout(set = 0, binding = 1, scalar) buffer Claim { uint claim[]; };       // padded, NONE-filled

void main() {
    uint q = gl_GlobalInvocationID.x;
    if (q >= p.padded_width * p.padded_height) return;
    uint s = src[q];
    if (s != REPROJECT_NONE) atomicMin(claim[s], q);
}
