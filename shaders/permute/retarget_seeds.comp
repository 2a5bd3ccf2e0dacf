#version 460
// Retargeting pass: the seed at padded pixel x moves to x + D((x + o) mod N), toroidally on the
// padded screen, so seeds sorted for mask t land where they suit mask t+1 (= mask t shifted by
// the table's integer shift). A bijection because the padded screen tiles the mask exactly.
// CPU twin: crates/permute/src/cpu.rs retarget_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { RetargetParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Table { ivec2 table[]; };  // D per mask texel
layout(set = 0, binding = 1, scalar) readonly buffer SeedsIn { uint seeds_in[]; };
layout(set = 0, binding = 2, scalar) writeonly buffer SeedsOut { uint seeds_out[]; };

void main() {
    uvec2 x = gl_GlobalInvocationID.xy;
    if (x.x >= p.padded_width || x.y >= p.padded_height) return;
    // (x + o) mod N without a modulo per pixel (llvmpipe scalarises a vector modulo by a
    // run-time value): one for the workgroup's corner, the same in every lane, then the lane's
    // offset (< 8) wrapped by subtraction, enough times for any N >= 1.
    uint N = p.mask_size;
    uvec2 u = (gl_WorkGroupID.xy * 8u + uvec2(p.offset_x, p.offset_y)) % N + gl_LocalInvocationID.xy;
    for (uint i = 0u; i < 7u; ++i) u = mix(u, u - N, greaterThanEqual(u, uvec2(N)));
    ivec2 d = table[u.y * N + u.x];
    // Displacements are within the retarget radius (|d| < N <= size), so x + d + size lies in
    // [0, 3 size): two conditional subtractions wrap it.
    uvec2 size = uvec2(p.padded_width, p.padded_height);
    uvec2 t = uvec2(ivec2(x) + d + ivec2(size));
    t = mix(t, t - size, greaterThanEqual(t, size));
    t = mix(t, t - size, greaterThanEqual(t, size));
    seeds_out[t.y * p.padded_width + t.x] = seeds_in[x.y * p.padded_width + x.x];
}
