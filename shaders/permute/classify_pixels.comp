#version 460
// Edge-aware grouping: per B x B block, pixels are split into surfaces by leader clustering in
// row-major order (a pixel joins the first earlier leader it is `similar` to, else leads a new
// class), and the class is written per pixel as its leader's in-block index. The sorting pass
// then ranks pixels and mask values only within a class, so a pixel across an edge never
// trades seeds with the block's other surface. One invocation per block, like sort_seeds.
// CPU twin: crates/permute/src/edges.rs classify_pixels_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
#include "sort_blocks.glsl"
#include "generated/motion.glsl"
#include "similar.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { SortParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer GBuffer { GBufferTexel gbuffer[]; };  // W*H
layout(set = 0, binding = 1, scalar) writeonly buffer Classes { uint classes[]; };        // W*H

void main() {
    uint B = p.block;
    uint block = gl_GlobalInvocationID.x;
    if (block >= sort_block_count(p)) return;
    ivec2 origin = sort_block_origin(p, block);
    // The block's texels are loaded once (storage-buffer loads in the inner loop would repeat
    // each load up to B*B times; on lavapipe a divergent load is itself a loop over lanes).
    uint at[64], leader[64];
    GBufferTexel g[64];
    uint n = 0u;
    for (uint k = 0u; k < B * B; ++k) {
        uvec2 px;
        if (!sort_block_pixel(p, origin, k, px)) continue;
        at[n] = px.y * p.width + px.x;
        g[n] = gbuffer[at[n]];
        n++;
    }
    for (uint a = 0u; a < n; ++a) {
        uint cls = a;
        for (uint b = 0u; b < a; ++b) {
            bool join = cls == a && leader[b] == b && similar(g[a], g[b]);
            cls = join ? b : cls;
        }
        leader[a] = cls;
        classes[at[a]] = cls;
    }
}
