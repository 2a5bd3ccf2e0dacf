#version 460
// GLSL unit run: sample_bits for every sampler, and hbo19 with a key table, on
// (seed, index, dim) triples from a buffer.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint count; } pc;
layout(set = 0, binding = 0, scalar) readonly buffer In { uvec3 inputs[]; };
// Five words per input: white, sobol, r2, hbo19 with keys, blocknet.
layout(set = 0, binding = 1, scalar) writeonly buffer Out { uint results[]; };
layout(set = 0, binding = 2, scalar) readonly buffer Keys { uvec2 keys[]; };
#define HBO19_KEYS keys
#include "sampling.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uvec3 q = inputs[i];
    results[5u * i] = sample_bits(SAMPLER_WHITE, q.x, q.y, q.z);
    results[5u * i + 1u] = sample_bits(SAMPLER_SOBOL, q.x, q.y, q.z);
    results[5u * i + 2u] = sample_bits(SAMPLER_R2, q.x, q.y, q.z);
    results[5u * i + 3u] = hbo19_lookup_bits(q.x, q.y, q.z);
    results[5u * i + 4u] = sample_bits(SAMPLER_BLOCKNET, q.x, q.y, q.z);
}
