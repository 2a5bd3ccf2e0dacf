#version 460
// GLSL unit run: sample_bits for every sampler, and hbo19 with a key table, on
// (seed, index, dim) triples from a buffer; and the seven block-net dimensions from `dim` on
// as the trace draws a path vertex's (seven_from_pairs).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint count; } pc;
layout(set = 0, binding = 0, scalar) readonly buffer In { uvec3 inputs[]; };
// Twelve words per input: white, sobol, r2, hbo19 with keys, blocknet; blocknet dimensions
// dim .. dim + 6 from pairs.
layout(set = 0, binding = 1, scalar) writeonly buffer Out { uint results[]; };
layout(set = 0, binding = 2, scalar) readonly buffer Keys { uvec2 keys[]; };
#define HBO19_KEYS keys
#include "sampling.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uvec3 q = inputs[i];
    uint o = 12u * i;
    results[o] = sample_bits(SAMPLER_WHITE, q.x, q.y, q.z);
    results[o + 1u] = sample_bits(SAMPLER_SOBOL, q.x, q.y, q.z);
    results[o + 2u] = sample_bits(SAMPLER_R2, q.x, q.y, q.z);
    results[o + 3u] = hbo19_lookup_bits(q.x, q.y, q.z);
    results[o + 4u] = sample_bits(SAMPLER_BLOCKNET, q.x, q.y, q.z);
    uint p = q.z >> 1u;
    uint u[7];
    seven_from_pairs(block_net_pair(q.x, q.y, p), block_net_pair(q.x, q.y, p + 1u),
                     block_net_pair(q.x, q.y, p + 2u), block_net_pair(q.x, q.y, p + 3u), q.z, u);
    for (uint k = 0u; k < 7u; k++) results[o + 5u + k] = u[k];
}
