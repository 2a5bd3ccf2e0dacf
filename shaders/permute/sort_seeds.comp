#version 460
// Sorting pass (Heitz & Belcour 2019): per B x B block, the seed of the k-th darkest pixel moves
// to the position of the k-th smallest mask value. A workgroup of 64 invocations sorts
// floor(64 / B^2) blocks (16 of 2x2, 7 of 3x3, 4 of 4x4, ...; one of 5x5..8x8), ranking by
// counting in shared memory with (key, in-block index) so ties are deterministic. In place:
// blocks are disjoint. CPU twin: crates/permute/src/cpu.rs sort_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { SortParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // rgb + luminance
layout(set = 0, binding = 1, scalar) readonly buffer Mask { uint mask[]; };          // N*N ranks
layout(set = 0, binding = 2, scalar) buffer Seeds { uint seeds[]; };                 // padded

shared uint lum_key[64];
shared uint mask_key[64];
shared bool valid[64];
shared uint seed[64];
shared uint pos_of_mask_rank[64];

uint sort_key(float l) { return l > 0.0 ? floatBitsToUint(l) : 0u; }

void main() {
    uint B = p.block, n = B * B;
    uint per_group = 64u / n;
    uint i = gl_LocalInvocationIndex;
    uint j = i / n;                  // block within the workgroup
    uint k = i % n;                  // in-block index (row-major), the tie-breaker
    uint base = j * n;               // this block's slice of the shared arrays
    uint blocks_x = (p.width + B - 1u) / B;
    uint blocks = blocks_x * ((p.height + B - 1u) / B);
    uint block = gl_WorkGroupID.x * per_group + j;
    bool in_block = j < per_group && block < blocks;
    uvec2 px = uvec2(block % blocks_x, block / blocks_x) * B + uvec2(k % B, k / B);
    bool mine = in_block && px.x < p.width && px.y < p.height;
    if (in_block) {
        valid[i] = mine;
        if (mine) {
            lum_key[i] = sort_key(estimate[px.y * p.width + px.x].w);
            uvec2 m = (px + uvec2(p.offset_x, p.offset_y)) % p.mask_size;
            mask_key[i] = mask[m.y * p.mask_size + m.x];
            seed[i] = seeds[px.y * p.stride + px.x];
        }
    }
    barrier();
    uint lum_rank = 0u, mask_rank = 0u;
    if (mine) {
        for (uint q = 0u; q < n; ++q) {
            uint o = base + q;
            if (!valid[o]) continue;
            if (lum_key[o] < lum_key[i] || (lum_key[o] == lum_key[i] && q < k)) lum_rank++;
            if (mask_key[o] < mask_key[i] || (mask_key[o] == mask_key[i] && q < k)) mask_rank++;
        }
        pos_of_mask_rank[base + mask_rank] = k;
    }
    barrier();
    if (mine) {
        uint dst = pos_of_mask_rank[base + lum_rank];
        uvec2 d = uvec2(block % blocks_x, block / blocks_x) * B + uvec2(dst % B, dst / B);
        seeds[d.y * p.stride + d.x] = seed[i];
    }
}
