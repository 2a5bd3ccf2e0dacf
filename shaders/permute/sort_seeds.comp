#version 460
// Sorting pass (Heitz & Belcour 2019): per B x B block, the seed of the k-th darkest pixel moves
// to the position of the k-th smallest mask value. One workgroup per block, ranks by counting
// in shared memory with (key, in-block index) so ties are deterministic. In place: blocks are
// disjoint. CPU twin: crates/permute/src/cpu.rs sort_seeds_cpu.
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
    uint i = gl_LocalInvocationIndex;
    uint B = p.block;
    uint tx = i % 8u, ty = i / 8u;
    uint k = ty * B + tx;  // in-block index (row-major), the tie-breaker
    uvec2 px = gl_WorkGroupID.xy * B + uvec2(tx, ty);
    bool mine = tx < B && ty < B && px.x < p.width && px.y < p.height;
    if (tx < B && ty < B) {
        valid[k] = mine;
        if (mine) {
            lum_key[k] = sort_key(estimate[px.y * p.width + px.x].w);
            uvec2 m = (px + uvec2(p.offset_x, p.offset_y)) % p.mask_size;
            mask_key[k] = mask[m.y * p.mask_size + m.x];
            seed[k] = seeds[px.y * p.stride + px.x];
        }
    }
    barrier();
    uint lum_rank = 0u, mask_rank = 0u;
    if (mine) {
        for (uint j = 0u; j < B * B; ++j) {
            if (!valid[j]) continue;
            if (lum_key[j] < lum_key[k] || (lum_key[j] == lum_key[k] && j < k)) lum_rank++;
            if (mask_key[j] < mask_key[k] || (mask_key[j] == mask_key[k] && j < k)) mask_rank++;
        }
        pos_of_mask_rank[mask_rank] = k;
    }
    barrier();
    if (mine) {
        uint dst = pos_of_mask_rank[lum_rank];
        uvec2 d = gl_WorkGroupID.xy * B + uvec2(dst % B, dst / B);
        seeds[d.y * p.stride + d.x] = seed[k];
    }
}
