// Sorting pass (Heitz & Belcour 2019): per B x B block, the seed of the k-th darkest pixel moves
// to the position of the k-th smallest mask value. Ranking is within classes (classify_pixels:
// surfaces of the block; all 0 for the paper's method): pixels and mask values both sort on
// (class, key, in-block index), so the k-th pixel and the k-th mask position share a class and
// ties are deterministic. In place: blocks are disjoint. With SORT_RETARGET the seeds go on
// to their retargeted places in a second buffer instead (the retargeting pass fused in).
// With SORT_CYCLE it runs sort-cycle's point cycle on the way in (the keys and seeds it ranks
// are those the block's seeds had one cycle ago).
// CPU twins: crates/permute/src/cycle.rs cycle_keys_cpu, then crates/permute/src/cpu.rs
// sort_seeds_cpu (which ranks by counting), then retarget_seeds_cpu.
//
// Shaped for llvmpipe: one invocation per block (8 blocks per SIMD batch, no barriers), and
// every per-pixel array is indexed only by compile-time constants, so it lives in registers
// (a dynamic index makes each access a per-lane loop through memory). The block is laid out
// in SORT_SLOTS slots, slot s = in-block pixel (s % SORT_ROW, s / SORT_ROW); slots outside the
// block or the screen are invalid and sort after every valid one. Each side is one 64-bit key
// per slot, (class : 26 bits, key : 32, slot : 6), sorted by a sorting network
// (generated/sort_network.glsl); a third network on (pixel slot of rank r : mask slot of rank r)
// turns the two orders into each slot's destination without any dynamic index.
//
// Compiled once per blueshift_layout::variants::SortVariant, which sets before the include:
//   SORT_CLASSES  1: rank within the classes of classify_pixels; 0: one class per block
//   SORT_HISTORY  1: rank key minus history mean (history_key); 0: the raw key
//   SORT_PAIRS    1: antithetic pairs where SortParams::pairs asks for them; 0: the mask only
//   SORT_SKEW     1: count skewed classes where SortParams::count_skew asks for it, and
//                 take the pairs gate's choice where SortParams::pairs says so
//   SORT_SLOTS    16: blocks up to 4x4; 64: up to 8x8
//   SORT_RETARGET 1: then retarget: mask texels carry D (pack_mask_moves), blocks cover the
//                 padded screen, whose off-screen pixels keep their place before the move
//   SORT_CYCLE    1: first the point cycle: record each pixel's (seed, key minus running
//                 mean) in the slot of this frame's phase, then rank the seeds and keys of the
//                 next phase's slot (once written) against mask slice SortParams::mask_layer;
//   SORT_SAMPLE_KEYS 1 (only with SORT_CYCLE): the seeds rank by their next light sample's
//                 position instead of those keys (SortParams::cycle_sample_keys, from which
//                 the pass picks this specialisation)
// With the first four 0 this is the paper's sorting and nothing else.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "generated/params.glsl"
#include "generated/sort_network.glsl"
#include "sort_blocks.glsl"
#if SORT_SAMPLE_KEYS
#include "sampling.glsl"

// The index of the point (x, y) (32-bit fractions) along a Hilbert curve through the
// 2^SAMPLE_KEY_BITS grid (CPU twin: blueshift_layout::params::sample_key_code). Selects, no
// branches: the loop unrolls into straight code.
uint sample_key_code(uint x, uint y) {
    const uint n = 1u << SAMPLE_KEY_BITS;
    x >>= 32u - SAMPLE_KEY_BITS;
    y >>= 32u - SAMPLE_KEY_BITS;
    uint d = 0u;
    for (uint s = n / 2u; s > 0u; s >>= 1u) {
        uint rx = (x & s) != 0u ? 1u : 0u;
        uint ry = (y & s) != 0u ? 1u : 0u;
        d += s * s * ((3u * rx) ^ ry);
        // Into the sub-square's own frame: reflected in the last quadrant, transposed.
        bool reflect = ry == 0u && rx == 1u;
        x = reflect ? n - 1u - x : x;
        y = reflect ? n - 1u - y : y;
        bool swap = ry == 0u;
        uint t = swap ? y : x;
        y = swap ? x : y;
        x = t;
    }
    return d;
}
#endif

#if SORT_SLOTS == 16
#define SORT_ROW 4
#define SORT_NETWORK SORT_NETWORK_16
#define SORT_EACH SORT_EACH_16
#else
#define SORT_ROW 8
#define SORT_NETWORK SORT_NETWORK_64
#define SORT_EACH SORT_EACH_64
#endif
// Compile-time in-block coordinates of slot s.
#define SX(s) ((s) % SORT_ROW)
#define SY(s) ((s) / SORT_ROW)

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { SortParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // rgb + sort key
layout(set = 0, binding = 1, scalar) readonly buffer Mask { uint mask[]; };          // N*N ranks
#if SORT_RETARGET
layout(set = 0, binding = 2, scalar) readonly buffer Seeds { uint seeds[]; };        // padded
layout(set = 0, binding = 6, scalar) writeonly buffer SeedsOut { uint seeds_out[]; };
#else
layout(set = 0, binding = 2, scalar) buffer Seeds { uint seeds[]; };                 // padded
#endif
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
#if SORT_PAIRS
// The pairs gate (pairs_gate.comp) as the frames before left it: (share, counted at all).
layout(set = 0, binding = 10, scalar) readonly buffer Gate { uint pairs_gate[2]; };
#endif
#endif
#if SORT_CYCLE
// (seed, key bits) per phase slot and visible pixel: CYCLE_FRAMES * width * height.
layout(set = 0, binding = 7, scalar) buffer CycleHistory { uvec2 cycle_history[]; };
// The running mean of the earlier frames (accumulate), vec4 per visible pixel.
layout(set = 0, binding = 8, scalar) readonly buffer Accum { vec4 accum[]; };
#endif

// Orders like the float (CPU twin: sort_key): positives over 0x80000000, negatives inverted,
// 0, -0 and NaN at 0x80000000. Never above 0xFF800000 (+inf).
uint sort_key(float v) {
    uint b = floatBitsToUint(v);
    return v > 0.0 ? 0x80000000u | b : (v < 0.0 ? ~b : 0x80000000u);
}

// The 64-bit sort key of slot s: (class, key, slot); invalid slots above every valid one
// (class bits and key bits all set, which no valid slot has: keys stay below 0xFFFFFFFF).
// Classes must be below 2^26 (classify_pixels writes in-block indices).
uint64_t slot_key(bool valid, uint cls, uint key, uint s) {
    uint64_t k = (uint64_t(cls) << 38) | (uint64_t(key) << 6);
    return (valid ? k : ~uint64_t(0) << 6) | uint64_t(s);
}

#if SORT_RETARGET
// The mask side when retargeting: (class : 25, mask key : 17, slot : 6, D : 16). D rides
// below the slot, which is unique, so the order is slot_key's; classes below 2^25 here.
uint64_t mask_slot_key(bool valid, uint cls, uint key, uint s, uint d) {
    uint64_t k = (uint64_t(cls) << 39) | (uint64_t(key) << 22);
    return (valid ? k : ~uint64_t(0) << 22) | (uint64_t(s) << 16) | uint64_t(d);
}
#endif

#if SORT_PAIRS
// Thin classes (at most 2 columns or 2 rows of the block; with pairs == 2 every class) rank
// against antithetic pairs instead of the mask: pixels of one checkerboard colour keep their
// mask keys and take the lower half of the class's keys; each pixel of the other colour takes
// the upper half, in the reverse order of its partner's mask key (partner: the class's pixel
// to the left, else right, above, below), so neighbours hold opposite errors. Mask keys are
// u16 ranks, below 0x10000.
void pair_thin_classes(ivec2 origin, bool valid[SORT_SLOTS], uint cls[SORT_SLOTS], uint pairs,
                       inout uint mkey[SORT_SLOTS]) {
    uint B = p.block;
    uvec2 lo[64], hi[64];  // bounding box of each class (classes from 63 up merged)
    for (uint k = 0u; k < 64u; ++k) {
        lo[k] = uvec2(B);
        hi[k] = uvec2(0u);
    }
#define BOX(s) if (valid[s]) { \
        uint c = min(cls[s], 63u); \
        lo[c] = min(lo[c], uvec2(SX(s), SY(s))); \
        hi[c] = max(hi[c], uvec2(SX(s), SY(s))); \
    }
    SORT_EACH(BOX)
    // The neighbour (dx, dy) of slot s, if in the slot grid (a constant condition), visible
    // and of the same class; checked below, above, right, left: the last match wins.
#define PARTNER(s, dx, dy) \
    if (SX(s) + dx >= 0 && SX(s) + dx < SORT_ROW && SY(s) + dy >= 0 && SY(s) + dy < SORT_ROW) { \
        const int q = clamp(s + dx + dy * SORT_ROW, 0, SORT_SLOTS - 1); \
        if (valid[q] && cls[q] == cls[s]) partner = mkey[q]; \
    }
    uint key[SORT_SLOTS];
#define PAIR_KEY(s) { \
        uint c = min(cls[s], 63u); \
        bool thin = pairs == 2u || hi[c].x - lo[c].x < 2u || hi[c].y - lo[c].y < 2u; \
        uint colour = (uint(origin.x + origin.y) + SX(s) + SY(s) + p.phase) & 1u; \
        uint partner = mkey[s]; \
        PARTNER(s, 0, 1) PARTNER(s, 0, -1) PARTNER(s, 1, 0) PARTNER(s, -1, 0) \
        key[s] = !thin || colour == 0u ? mkey[s] : 0x1FFFFu - partner; \
    }
    SORT_EACH(PAIR_KEY)
    mkey = key;
}
#endif

#if SORT_SKEW
// (skewed, counted): classes of at least SKEW_MIN_PIXELS pixels in the block, and those among
// them whose keys have a sample skewness |g| above SKEW_LIMIT. Keys are scaled by the largest
// deviation from the class mean first, so that the third powers cannot overflow. Sums run in
// slot order, which is the twin's row-major order.
// CPU twin: crates/permute/src/skew.rs count_skewed_classes.
uvec2 count_skewed_classes(bool valid[SORT_SLOTS], uint cls[SORT_SLOTS], float count[64],
                           float key[SORT_SLOTS]) {
    float mean[64], dmax[64], m2[64], m3[64];
    for (uint c = 0u; c < 64u; ++c) {
        mean[c] = 0.0;
        dmax[c] = 0.0;
        m2[c] = 0.0;
        m3[c] = 0.0;
    }
#define SK_SUM(s) if (valid[s]) mean[min(cls[s], 63u)] += key[s];
    SORT_EACH(SK_SUM)
    for (uint c = 0u; c < 64u; ++c) mean[c] = count[c] > 0.0 ? mean[c] * (1.0 / count[c]) : 0.0;
#define SK_MAX(s) if (valid[s]) { \
        uint c = min(cls[s], 63u); \
        dmax[c] = max(dmax[c], abs(key[s] - mean[c])); \
    }
    SORT_EACH(SK_MAX)
#define SK_MOMENTS(s) if (valid[s]) { \
        uint c = min(cls[s], 63u); \
        precise float d = dmax[c] > 0.0 ? (key[s] - mean[c]) * (1.0 / dmax[c]) : 0.0; \
        precise float d2 = d * d; \
        m2[c] += d2; \
        m3[c] += d2 * d; \
    }
    SORT_EACH(SK_MOMENTS)
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
#if SORT_RETARGET
    uvec2 area = uvec2(p.stride, p.padded_height);
#else
    uvec2 area = uvec2(p.width, p.height);
#endif
    if (block >= sort_block_count(p, area)) return;
    ivec2 origin = sort_block_origin(p, area, block);
    // Mask coordinates of the block's columns and rows, (origin + d + offset) mod N, stepped
    // from one modulo per block (a vector modulo by a run-time value is scalarised).
    // origin >= -7, so adding 8N keeps the dividend non-negative.
    uint N = p.mask_size;
    uint mbase = p.mask_layer * N * N;  // the mask slice (0 but for spatio-temporal masks)
    ivec2 o = origin + ivec2(p.offset_x, p.offset_y) + 8 * int(N);
    uint mcol[SORT_ROW], mrow[SORT_ROW];
    mcol[0] = uint(o.x) % N;
    mrow[0] = uint(o.y) % N;
#define STEP(d) \
    mcol[d] = mcol[d - 1] + 1u == N ? 0u : mcol[d - 1] + 1u; \
    mrow[d] = mrow[d - 1] + 1u == N ? 0u : mrow[d - 1] + 1u;
    STEP(1) STEP(2) STEP(3)
#if SORT_ROW == 8
    STEP(4) STEP(5) STEP(6) STEP(7)
#endif

    bool valid[SORT_SLOTS];
    uint seed[SORT_SLOTS], cls[SORT_SLOTS], mkey[SORT_SLOTS];
#if SORT_RETARGET
    bool moves[SORT_SLOTS];  // on the padded screen: the seed moves (off screen: in place first)
    uint mdisp[SORT_SLOTS];  // D of the slot's mask texel, two signed bytes
#endif
    float val[SORT_SLOTS];
#if SORT_HISTORY
    float hm[SORT_SLOTS];
#endif
    // Loads of slot s; invalid slots read a clamped texel and are masked out later.
#define LOAD(s) { \
        ivec2 q = origin + ivec2(SX(s), SY(s)); \
        valid[s] = SX(s) < B && SY(s) < B && q.x >= 0 && q.y >= 0 && q.x < int(p.width) && \
                   q.y < int(p.height); \
        uvec2 px = uvec2(clamp(q, ivec2(0), ivec2(p.width - 1u, p.height - 1u))); \
        uint at = px.y * p.width + px.x; \
        val[s] = estimate[at].w; \
        LOAD_MASK_SEED(s, q, px, mask[mbase + mrow[SY(s)] * N + mcol[SX(s)]]) \
        LOAD_CYCLE(s, at) \
        LOAD_CLASS(s, at) \
        LOAD_HISTORY(s, at) \
    }
#if SORT_RETARGET
#define LOAD_MASK_SEED(s, q, px, texel) { \
        moves[s] = SX(s) < B && SY(s) < B && q.x >= 0 && q.y >= 0 && q.x < int(p.stride) && \
                   q.y < int(p.padded_height); \
        uint m = texel; \
        mkey[s] = m & 0xFFFFu; \
        mdisp[s] = m >> 16; \
        uvec2 pp = uvec2(clamp(q, ivec2(0), ivec2(p.stride - 1u, p.padded_height - 1u))); \
        seed[s] = seeds[pp.y * p.stride + pp.x]; \
    }
#else
#define LOAD_MASK_SEED(s, q, px, texel) \
        mkey[s] = texel; \
        seed[s] = seeds[px.y * p.stride + px.x];
#endif
#if SORT_CYCLE
    uint pixels = p.width * p.height;
#if SORT_SAMPLE_KEYS
    // The block net's point the seed takes at the next phase, in the first vertex's light
    // sample dimensions, as its index along the Hilbert curve.
#define SAMPLE_KEY(s) { \
        uvec2 key_bits = block_net_pair(seed[s], p.cycle_next_phase, SAMPLE_KEY_DIM >> 1u); \
        val[s] = float(sample_key_code(key_bits.x, key_bits.y)); }
#else
#define SAMPLE_KEY(s)
#endif
#define LOAD_CYCLE(s, at) { \
        float k = p.cycle_mean_count > 0u ? val[s] - accum[at].w : val[s]; \
        uvec2 rec = uvec2(seed[s], floatBitsToUint(k)); \
        if (valid[s]) cycle_history[p.cycle_phase * pixels + at] = rec; \
        if (p.cycle_next_valid != 0u) { \
            uvec2 h = cycle_history[p.cycle_next_phase * pixels + at]; \
            seed[s] = h.x; \
            k = uintBitsToFloat(h.y); \
        } \
        val[s] = k; \
        SAMPLE_KEY(s) \
    }
#else
#define LOAD_CYCLE(s, at)
#endif
#if SORT_CLASSES
#define LOAD_CLASS(s, at) cls[s] = classes[at];
#else
#define LOAD_CLASS(s, at) cls[s] = 0u;
#endif
#if SORT_HISTORY
#define LOAD_HISTORY(s, at) hm[s] = hist_mean[at];
#else
#define LOAD_HISTORY(s, at)
#endif
    SORT_EACH(LOAD)

    float key[SORT_SLOTS];
#if SORT_HISTORY || SORT_SKEW
    // Per-class sums and counts in row-major order (classes from 63 up merged), for pixels
    // without history and for the skew counts.
    float csum[64], ccount[64];
    for (uint k = 0u; k < 64u; ++k) {
        csum[k] = 0.0;
        ccount[k] = 0.0;
    }
#define SUM(s) if (valid[s]) { \
        uint c = min(cls[s], 63u); \
        csum[c] += val[s]; \
        ccount[c] += 1.0; \
    }
    SORT_EACH(SUM)
#endif
#if SORT_HISTORY
#define KEY(s) { \
        uint c = min(cls[s], 63u); \
        float ref = isnan(hm[s]) ? csum[c] * (1.0 / ccount[c]) : hm[s]; \
        key[s] = val[s] - ref; \
    }
#else
#define KEY(s) key[s] = val[s];
#endif
    SORT_EACH(KEY)
#if SORT_SKEW
    if (p.count_skew != 0u) {
        uvec2 skew = count_skewed_classes(valid, cls, ccount, key);
        if (skew.y > 0u) {
            atomicAdd(sort_stats[0], skew.x);
            atomicAdd(sort_stats[1], skew.y);
        }
    }
#endif
#if SORT_PAIRS
    uint pairs = p.pairs;
#if SORT_SKEW
    // sort-grid-adaptive: every class while the smoothed share of skewed classes is low.
    if (pairs == SORT_PAIRS_FROM_GATE) {
        pairs = pairs_gate[1] != 0u && pairs_gate[0] >= PAIRS_GATE_LIMIT ? 0u : 2u;
    }
#endif
    if (pairs != 0u) pair_thin_classes(origin, valid, cls, pairs, mkey);
#endif

    uint64_t lk[SORT_SLOTS], mk[SORT_SLOTS];
#define KEYS(s) \
    lk[s] = slot_key(valid[s], cls[s], sort_key(key[s]), s); \
    MASK_KEY(s)
#if SORT_RETARGET
#define MASK_KEY(s) mk[s] = mask_slot_key(valid[s], cls[s], mkey[s], s, mdisp[s]);
#else
#define MASK_KEY(s) mk[s] = slot_key(valid[s], cls[s], mkey[s], s);
#endif
    SORT_EACH(KEYS)
#define CE_L(i, j) { uint64_t t = min(lk[i], lk[j]); lk[j] = max(lk[i], lk[j]); lk[i] = t; }
#define CE_M(i, j) { uint64_t t = min(mk[i], mk[j]); mk[j] = max(mk[i], mk[j]); mk[i] = t; }
    SORT_NETWORK(CE_L)
    SORT_NETWORK(CE_M)
    // Rank r pairs the pixel slot lk[r] with the mask slot mk[r] (valid with valid: both sides
    // have the same number of valid slots first, and the invalid ones pair in slot order, so
    // they stay in place). Sorted by pixel slot, entry s holds slot s's destination.
    uint dest[SORT_SLOTS];
#if SORT_RETARGET
    // (pixel slot : 6, D : 16, mask slot : 6)
#define PAIR(s) dest[s] = (uint(lk[s] & 63ul) << 22) | (uint(mk[s] & 0xFFFFul) << 6) | \
                          uint((mk[s] >> 16) & 63ul);
#else
#define PAIR(s) dest[s] = (uint(lk[s] & 63ul) << 6) | uint(mk[s] & 63ul);
#endif
    SORT_EACH(PAIR)
#define CE_D(i, j) { uint t = min(dest[i], dest[j]); dest[j] = max(dest[i], dest[j]); dest[i] = t; }
    SORT_NETWORK(CE_D)
#if SORT_RETARGET
    // Then the retargeting move t + D, toroidally on the padded screen: |D| < N <= its size, so
    // t + D + size lies in [0, 3 size) and two conditional subtractions wrap it.
    ivec2 size = ivec2(p.stride, p.padded_height);
#define STORE(s) if (moves[s]) { \
        uint d = dest[s] & 63u; \
        ivec2 disp = ivec2(int(dest[s] << 18) >> 24, int(dest[s] << 10) >> 24); \
        ivec2 t = origin + ivec2(d % SORT_ROW, d / SORT_ROW) + disp + size; \
        t = mix(t, t - size, greaterThanEqual(t, size)); \
        t = mix(t, t - size, greaterThanEqual(t, size)); \
        seeds_out[t.y * p.stride + t.x] = seed[s]; \
    }
#else
#define STORE(s) if (valid[s]) { \
        uint d = dest[s] & 63u; \
        uvec2 t = uvec2(origin + ivec2(d % SORT_ROW, d / SORT_ROW)); \
        seeds[t.y * p.stride + t.x] = seed[s]; \
    }
#endif
    SORT_EACH(STORE)
}
