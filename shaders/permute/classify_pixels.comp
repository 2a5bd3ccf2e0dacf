#version 460
// Edge-aware grouping: per B x B block, pixels are split into surfaces by leader clustering in
// row-major order (a pixel joins the first earlier leader it is `similar` to, else leads a new
// class), and the class is written per pixel as its leader's in-block index. The sorting pass
// then ranks pixels and mask values only within a class, so a pixel across an edge never
// trades seeds with the block's other surface. One invocation per block, like sort_seeds, and
// like it over 64 slots (slot s = in-block pixel (s % 8, s / 8)) indexed only by compile-time
// constants, so the block's texels stay in registers on llvmpipe. Clustered in rounds, one per
// class: the first unassigned pixel leads, and every unassigned pixel similar to it joins (it
// is similar to no earlier leader, or an earlier round would have taken it), which is the
// row-major clustering above.
// CPU twin: crates/permute/src/edges.rs classify_pixels_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
#include "generated/sort_network.glsl"
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
    uvec2 area = uvec2(p.width, p.height);
    if (block >= sort_block_count(p, area)) return;
    ivec2 origin = sort_block_origin(p, area, block);
    bool valid[64], done[64];
    uint at[64], idx[64], cls[64];
    GBufferTexel g[64];
    uint n = 0u;  // visible pixels before the slot: the in-block index the classes name
#define LOAD(s) { \
        ivec2 q = origin + ivec2((s) % 8, (s) / 8); \
        valid[s] = (s) % 8 < B && (s) / 8 < B && q.x >= 0 && q.y >= 0 && q.x < int(p.width) && \
                   q.y < int(p.height); \
        uvec2 px = uvec2(clamp(q, ivec2(0), ivec2(p.width - 1u, p.height - 1u))); \
        at[s] = px.y * p.width + px.x; \
        g[s] = gbuffer[at[s]]; \
        idx[s] = n; \
        n += valid[s] ? 1u : 0u; \
        done[s] = !valid[s]; \
        cls[s] = 0u; \
    }
    SORT_EACH_64(LOAD)
    // Every value the loop sets is read in it first (llvmpipe's rule for values that leave a
    // loop; docs/architecture.md).
    bool pending = n > 0u;
    while (pending) {
        bool found = false;
        GBufferTexel lead = g[0];
        uint lead_idx = 0u;
#define LEAD(s) if (!found && !done[s]) { \
            found = true; \
            lead = g[s]; \
            lead_idx = idx[s]; \
            done[s] = true; \
            cls[s] = idx[s]; \
        }
        SORT_EACH_64(LEAD)
        pending = false;
#define JOIN(s) if (!done[s]) { \
            if (similar(g[s], lead)) { \
                done[s] = true; \
                cls[s] = lead_idx; \
            } \
            pending = pending || !done[s]; \
        }
        SORT_EACH_64(JOIN)
    }
#define STORE(s) if (valid[s]) classes[at[s]] = cls[s];
    SORT_EACH_64(STORE)
}
