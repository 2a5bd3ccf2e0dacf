// sort-cycle's shading edges (included by sort_seeds.glsl, after SX, SY, SORT_EACH): pixels
// whose running mean jumps inside their surface class, mostly at sharp shadows. There a
// seed's recorded error says little about its error at another pixel of the class (whether
// its light sample is visible changes from pixel to pixel), so the sort cannot help and the
// trace takes those pixels' light sample from the rotating mask (TRACE_FLAG_SHADE_EDGES).
// Integer arithmetic throughout, so that the CPU twin (crates/permute/src/shade.rs,
// shade_edge_marks_cpu) agrees bit for bit: the running mean in fixed point, the relative
// comparison cross-multiplied.

// The running mean in fixed point (CPU twin: shade_edge_fixed); NaN and negatives give 0.
uint shade_edge_fixed(float m) {
    return m > 0.0 ? uint(min(m, SHADE_EDGE_MAX_MEAN) * SHADE_EDGE_SCALE) : 0u;
}

#define SE_Q(s, dx, dy) clamp((s) + (dx) + (dy) * SORT_ROW, 0, SORT_SLOTS - 1)
// Slot s's neighbour (dx, dy) lies in the block, on the screen and in s's class.
#define SE_SAME(s, dx, dy) \
    (SX(s) + (dx) >= 0 && SX(s) + (dx) < SORT_ROW && SY(s) + (dy) >= 0 && \
     SY(s) + (dy) < SORT_SLOTS / SORT_ROW && valid[SE_Q(s, dx, dy)] && \
     cls[SE_Q(s, dx, dy)] == cls[s])

// Marks of the block's slots: `means` the fixed-point running means, `on` false clears all
// (llvmpipe runs both sides of a uniform branch, so the test runs either way).
// The mean blurred 3x3 (weights 1-2-1 per axis) over the slot's class, against each
// same-class 4-neighbour's: a jump above SHADE_EDGE_PER_MILLE of the larger, floored at half
// the block's mean, marks the slot; then the marks grow by one pixel within the class.
void shade_edge_marks(bool valid[SORT_SLOTS], uint cls[SORT_SLOTS], uint means[SORT_SLOTS],
                      bool on, out bool marked[SORT_SLOTS]) {
    uint total = 0u, count = 0u;
#define SE_TOTAL(s) if (valid[s]) { total += means[s]; count += 1u; }
    SORT_EACH(SE_TOTAL)
    // Blurred sums and weights (at most 16 x 2^24, 16).
    uint bsum[SORT_SLOTS], bw[SORT_SLOTS];
#define SE_TAP(s, dx, dy, w) if (SE_SAME(s, dx, dy)) { \
        sum += (w) * means[SE_Q(s, dx, dy)]; \
        wt += (w); \
    }
#define SE_BLUR(s) { \
        uint sum = 0u, wt = 0u; \
        SE_TAP(s, -1, -1, 1u) SE_TAP(s, 0, -1, 2u) SE_TAP(s, 1, -1, 1u) \
        SE_TAP(s, -1, 0, 2u) SE_TAP(s, 0, 0, 4u) SE_TAP(s, 1, 0, 2u) \
        SE_TAP(s, -1, 1, 1u) SE_TAP(s, 0, 1, 2u) SE_TAP(s, 1, 1, 1u) \
        bsum[s] = sum; \
        bw[s] = wt; \
    }
    SORT_EACH(SE_BLUR)
    // |bsum_s / bw_s - bsum_q / bw_q| > t max(bsum_s / bw_s, bsum_q / bw_q, total / (2 count)),
    // times 1000 bw_s bw_q 2 count (below 2^50).
    uint64_t scale = 2ul * uint64_t(count);
    // The test is symmetric in s and q, so each pair is tested once (to the right and down)
    // and marks both pixels.
    bool raw[SORT_SLOTS];
#define SE_CLEAR(s) raw[s] = false;
    SORT_EACH(SE_CLEAR)
#define SE_JUMP(s, dx, dy) if (valid[s] && SE_SAME(s, dx, dy)) { \
        const int q = SE_Q(s, dx, dy); \
        uint64_t a = uint64_t(bsum[s]) * uint64_t(bw[q]), b = uint64_t(bsum[q]) * uint64_t(bw[s]); \
        uint64_t d = a > b ? a - b : b - a; \
        uint64_t limit = max(max(a, b) * scale, uint64_t(total) * uint64_t(bw[s] * bw[q])); \
        if (d * scale * 1000ul > limit * uint64_t(SHADE_EDGE_PER_MILLE)) { \
            raw[s] = true; \
            raw[q] = true; \
        } \
    }
#define SE_MARK(s) SE_JUMP(s, 1, 0) SE_JUMP(s, 0, 1)
    SORT_EACH(SE_MARK)
#define SE_NEAR(s, dx, dy) if (SE_SAME(s, dx, dy)) near = near || raw[SE_Q(s, dx, dy)];
#define SE_GROW(s) { \
        bool near = raw[s]; \
        SE_NEAR(s, 1, 0) SE_NEAR(s, -1, 0) SE_NEAR(s, 0, 1) SE_NEAR(s, 0, -1) \
        marked[s] = on && valid[s] && near; \
    }
    SORT_EACH(SE_GROW)
}
