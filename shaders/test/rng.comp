#version 460
// GLSL unit run: evaluates the rng.glsl functions on a range of inputs for the CPU-twin test.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "rng.glsl"

layout(local_size_x = 64) in;

layout(push_constant, scalar) uniform Push {
    uint base;
    uint count;
} pc;

// Per input i: pcg_hash(i), hash3(i, i*3, 7), bits of white(i, 5, i & 15), pixel_seed(i, ~i, 1).
layout(set = 0, binding = 0, scalar) writeonly buffer Out { uvec4 results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uint v = pc.base + i;
    results[i] = uvec4(pcg_hash(v), hash3(v, v * 3u, 7u), floatBitsToUint(white(v, 5u, v & 15u)),
                       pixel_seed(v, ~v, 1u));
}
