// Sorting pass (Heitz & Belcour 2019): per B x B block, the seed of the k-th darkest pixel moves
// to the position of the k-th smallest mask value. One invocation per block ranks by counting
// over (key, in-block index), so ties are deterministic; no shared memory and no barriers
// (barriers are expensive on CPU Vulkan implementations, and a block is at most 64 pixels).
// Ranking is within classes (classify_pixels: surfaces of the block; all 0 for the paper's
// method): pixels and mask values both sort on (class, key, index), so the k-th pixel and the
// k-th mask position share a class. In place: blocks are disjoint.
// CPU twin: crates/permute/src/cpu.rs sort_seeds_cpu.
//
// Compiled once per blueshift_layout::variants::SortVariant, which sets before the include:
//   SORT_CLASSES  1: rank within the classes of classify_pixels; 0: one class per block
//   SORT_HISTORY  1: rank key minus history mean (history_key); 0: the raw key
//   SORT_PAIRS    1: antithetic pairs where SortParams::pairs asks for them; 0: the mask only
//   SORT_SKEW     1: count skewed classes where SortParams::count_skew asks for it
// With all four 0 this is the paper's sorting and nothing else.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
#include "sort_blocks.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { SortParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // rgb + sort key
layout(set = 0, binding = 1, scalar) readonly buffer Mask { uint mask[]; };          // N*N ranks
layout(set = 0, binding = 2, scalar) buffer Seeds { uint seeds[]; };                 // padded
#if SORT_CLASSES
layout(set = 0, binding = 3, scalar) readonly buffer Classes { uint classes[]; };     // W*H
#endif
#if SORT_HISTORY
// History means (history_key), NaN where a pixel has no history yet: W*H.
layout(set = 0, binding = 4, scalar) readonly buffer History { float hist_mean[]; };
#endif
#if SORT_SKEW
// (skewed classes, classes counted), summed over blocks with SortParams::count_skew
// (count_skewed_classes); zeroed by the host.
layout(set = 0, binding = 5, scalar) buffer Stats { uint sort_stats[2]; };
#endif

// Orders like the float (CPU twin: sort_key): positives over 0x80000000, negatives inverted,
// 0, -0 and NaN at 0x80000000.
uint sort_key(float v) {
    uint b = floatBitsToUint(v);
    return v > 0.0 ? 0x80000000u | b : (v < 0.0 ? ~b : 0x80000000u);
}

// (class, key, index) of b orders before that of a.
bool before(uint cb, uint kb, uint b, uint ca, uint ka, uint a) {
    return cb < ca || (cb == ca && (kb < ka || (kb == ka && b < a)));
}

#if SORT_PAIRS
// Thin classes (at most 2 columns or 2 rows of the block; with pairs == 2 every class) rank
// against antithetic pairs instead of the mask: pixels of one checkerboard colour keep their
// mask keys and take the lower half of the class's keys; each pixel of the other colour takes
// the upper half, in the reverse order of its partner's mask key (partner: the class's pixel
// to the left, else right, above, below), so neighbours hold opposite errors. Mask keys are
// u16 ranks, below 0x10000.
// Classes are in-block indices (classify_pixels' leaders, or 0), so spans index by class.
void pair_thin_classes(SortParams p, ivec2 origin, uint n, uint cell[64], uint cls[64],
                       inout uint mask_key[64]) {
    uint B = p.block;
    uint at[64];                // visible pixel at each in-block index, or 64
    uvec2 lo[64], hi[64];       // bounding box of each class in block coordinates
    for (uint k = 0u; k < 64u; ++k) {
        at[k] = 64u;
        lo[k] = uvec2(B);
        hi[k] = uvec2(0u);
    }
    for (uint a = 0u; a < n; ++a) {
        at[cell[a]] = a;
        uint c = min(cls[a], 63u);
        uvec2 d = uvec2(cell[a] % B, cell[a] / B);
        lo[c] = min(lo[c], d);
        hi[c] = max(hi[c], d);
    }
    uint key[64];
    for (uint a = 0u; a < n; ++a) {
        uint k = min(cls[a], 63u);
        bool thin = p.pairs == 2u || hi[k].x - lo[k].x < 2u || hi[k].y - lo[k].y < 2u;
        uvec2 c = uvec2(cell[a] % B, cell[a] / B);
        uint colour = (uint(origin.x + origin.y) + c.x + c.y + p.phase) & 1u;
        uint partner = a;
        ivec2 steps[4] = ivec2[4](ivec2(0, 1), ivec2(0, -1), ivec2(1, 0), ivec2(-1, 0));
        for (uint i = 0u; i < 4u; ++i) {  // the last match wins: left has priority
            ivec2 q = ivec2(c) + steps[i];
            if (q.x < 0 || q.y < 0 || q.x >= int(B) || q.y >= int(B)) continue;
            uint b = at[uint(q.y) * B + uint(q.x)];
            if (b < 64u && cls[b] == cls[a]) partner = b;
        }
        key[a] = !thin || colour == 0u ? mask_key[a] : 0x1FFFFu - mask_key[partner];
    }
    for (uint a = 0u; a < n; ++a) mask_key[a] = key[a];
}
#endif

#if SORT_SKEW
// (skewed, counted): classes of at least SKEW_MIN_PIXELS pixels in the block, and those among
// them whose keys have a sample skewness |g| above SKEW_LIMIT. Keys are scaled by the largest
// deviation from the class mean first, so that the third powers cannot overflow.
// CPU twin: crates/permute/src/skew.rs count_skewed_classes.
uvec2 count_skewed_classes(uint n, uint cls[64], float count[64], float key[64]) {
    float mean[64], dmax[64], m2[64], m3[64];
    for (uint c = 0u; c < 64u; ++c) {
        mean[c] = 0.0;
        dmax[c] = 0.0;
        m2[c] = 0.0;
        m3[c] = 0.0;
    }
    for (uint a = 0u; a < n; ++a) mean[min(cls[a], 63u)] += key[a];
    for (uint c = 0u; c < 64u; ++c) mean[c] = count[c] > 0.0 ? mean[c] * (1.0 / count[c]) : 0.0;
    for (uint a = 0u; a < n; ++a) {
        uint c = min(cls[a], 63u);
        dmax[c] = max(dmax[c], abs(key[a] - mean[c]));
    }
    for (uint a = 0u; a < n; ++a) {
        uint c = min(cls[a], 63u);
        precise float d = dmax[c] > 0.0 ? (key[a] - mean[c]) * (1.0 / dmax[c]) : 0.0;
        precise float d2 = d * d;
        m2[c] += d2;
        m3[c] += d2 * d;
    }
    uvec2 r = uvec2(0u);
    for (uint c = 0u; c < 64u; ++c) {
        if (count[c] < float(SKEW_MIN_PIXELS)) continue;
        // |g| > L  <=>  (m3 / n)^2 > L^2 (m2 / n)^3  <=>  m3^2 * n > L^2 * m2^3
        precise float lhs = m3[c] * m3[c] * count[c];
        precise float rhs = SKEW_LIMIT * SKEW_LIMIT * m2[c] * m2[c] * m2[c];
        r += uvec2(lhs > rhs ? 1u : 0u, 1u);
    }
    return r;
}
#endif

void main() {
    uint B = p.block;
    uint block = gl_GlobalInvocationID.x;
    if (block >= sort_block_count(p)) return;
    ivec2 origin = sort_block_origin(p, block);
    // Visible pixels of the block in row-major order: (x, y) packed as y * B + x.
    uint cell[64], lum_key[64], mask_key[64], seed[64], cls[64];
    float val[64];
#if SORT_HISTORY
    float hm[64];
#endif
#if SORT_HISTORY || SORT_SKEW
    float csum[64], ccount[64];  // per-class sums and counts, for pixels without history
    for (uint k = 0u; k < 64u; ++k) {
        csum[k] = 0.0;
        ccount[k] = 0.0;
    }
#endif
    uint n = 0u;
    for (uint k = 0u; k < B * B; ++k) {
        uvec2 px;
        if (!sort_block_pixel(p, origin, k, px)) continue;
        cell[n] = k;
        val[n] = estimate[px.y * p.width + px.x].w;
#if SORT_HISTORY
        hm[n] = hist_mean[px.y * p.width + px.x];
#endif
        uvec2 m = (px + uvec2(p.offset_x, p.offset_y)) % p.mask_size;
        mask_key[n] = mask[m.y * p.mask_size + m.x];
        seed[n] = seeds[px.y * p.stride + px.x];
#if SORT_CLASSES
        cls[n] = classes[px.y * p.width + px.x];
#else
        cls[n] = 0u;
#endif
#if SORT_HISTORY || SORT_SKEW
        csum[min(cls[n], 63u)] += val[n];
        ccount[min(cls[n], 63u)] += 1.0;
#endif
        n++;
    }
    float key[64];
    for (uint a = 0u; a < n; ++a) {
#if SORT_HISTORY
        uint c = min(cls[a], 63u);
        float ref = isnan(hm[a]) ? csum[c] * (1.0 / ccount[c]) : hm[a];
        key[a] = val[a] - ref;
#else
        key[a] = val[a];
#endif
        lum_key[a] = sort_key(key[a]);
    }
#if SORT_SKEW
    if (p.count_skew != 0u) {
        uvec2 skew = count_skewed_classes(n, cls, ccount, key);
        if (skew.y > 0u) {
            atomicAdd(sort_stats[0], skew.x);
            atomicAdd(sort_stats[1], skew.y);
        }
    }
#endif
#if SORT_PAIRS
    if (p.pairs != 0u) pair_thin_classes(p, origin, n, cell, cls, mask_key);
#endif
    // pos_of_mask_rank[r] = the visible pixel holding the r-th smallest mask value.
    uint pos_of_mask_rank[64];
    for (uint a = 0u; a < n; ++a) {
        uint r = 0u;
        for (uint b = 0u; b < n; ++b) r += uint(before(cls[b], mask_key[b], b, cls[a], mask_key[a], a));
        pos_of_mask_rank[r] = a;
    }
    for (uint a = 0u; a < n; ++a) {
        uint r = 0u;
        for (uint b = 0u; b < n; ++b) r += uint(before(cls[b], lum_key[b], b, cls[a], lum_key[a], a));
        uint k = cell[pos_of_mask_rank[r]];
        uvec2 d;
        sort_block_pixel(p, origin, k, d);
        seeds[d.y * p.stride + d.x] = seed[a];
    }
}
