#version 460
// History keys: each pixel's history mean, the mean sorting key its surface showed in earlier
// frames (fetched through the reprojection's source pixel), so that the sorting pass ranks
// key - mean, an estimate of the seed's *error*, instead of the key itself: ranking values
// sorts by the image's own gradients and shadow edges as much as by error, the more so the
// lower the error (more spp). The mean a pixel ranks against averages the histories of its
// 3x3 window that show its surface and are at least min_frames long (NaN when none: the
// sorting pass falls back on the class mean). Pixels without a source (disoccluded, sky)
// restart their own history. On a sequence's first frame the means are 0: raw keys, the
// paper's ranking. CPU twin: crates/permute/src/history.rs history_key_cpu.
//
// One invocation per HISTORY_COLUMNS (4) columns of a strip of HISTORY_STRIP rows, walking
// down it with the window's three rows of six taps in registers: each tap is fetched once per
// strip and serves up to nine pixels. On llvmpipe every per-lane fetch is a loop over the
// lanes (so are subgroup shuffles, which cost as much here), and a pixel that fetched its whole
// window (9 G-buffer texels, sources and histories) cost 59 ns at 1080p.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "similar.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { HistoryParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Src { uint src[]; };           // padded
// (mean key, frames) per padded pixel: the previous frame's, and this frame's.
layout(set = 0, binding = 2, scalar) readonly buffer HistIn { vec2 hist_in[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer HistOut { vec2 hist_out[]; };
layout(set = 0, binding = 4, scalar) writeonly buffer Mean { float hist_mean[]; };  // W*H
// This frame's G-buffer, W*H.
layout(set = 0, binding = 5, scalar) readonly buffer GBuffer { GBufferTexel gbuffer[]; };

// One pixel of the window: its G-buffer texel, its previous history (0 without a source) and
// whether that history counts (on screen, with a source, at least min_frames long).
struct Tap {
    GBufferTexel g;
    vec2 h;
    bool ok;
};

Tap fetch_tap(int x, int y) {
    bool inside = x >= 0 && y >= 0 && x < int(p.width) && y < int(p.height);
    ivec2 q = clamp(ivec2(x, y), ivec2(0), ivec2(p.width - 1u, p.height - 1u));
    uint s = src[q.y * int(p.padded_width) + q.x];
    bool has = s != REPROJECT_NONE;
    Tap t;
    t.g = gbuffer[q.y * int(p.width) + q.x];
    t.h = has ? hist_in[has ? s : 0u] : vec2(0.0);
    t.ok = inside && has && !(t.h.y < float(p.min_frames));
    return t;
}

// Adds a tap that shows the centre's surface, in the twin's order (row by row, left to right).
void add_tap(GBufferTexel c, Tap t, inout float sum, inout float count) {
    bool take = t.ok && similar(c, t.g);
    precise float s = sum + t.h.x;
    precise float n = count + 1.0;
    sum = take ? s : sum;
    count = take ? n : count;
}

// The history of pixel (x, y) from its window's taps (rows top, middle, bottom; columns left,
// centre, right): written if x is on screen.
void emit(int x, int y, Tap t0, Tap t1, Tap t2, Tap m0, Tap m1, Tap m2, Tap b0, Tap b1, Tap b2) {
    // The centre's own history: a pixel without a source restarts from 0 frames.
    precise float frames = min(m1.h.y + 1.0, float(p.max_frames));
    float key = estimate[y * int(p.width) + min(x, int(p.width) - 1)].w;
    precise float mean = m1.h.x + (key - m1.h.x) * (1.0 / frames);
    precise float sum = 0.0, count = 0.0;
    add_tap(m1.g, t0, sum, count);
    add_tap(m1.g, t1, sum, count);
    add_tap(m1.g, t2, sum, count);
    add_tap(m1.g, m0, sum, count);
    add_tap(m1.g, m1, sum, count);
    add_tap(m1.g, m2, sum, count);
    add_tap(m1.g, b0, sum, count);
    add_tap(m1.g, b1, sum, count);
    add_tap(m1.g, b2, sum, count);
    precise float window = sum * (1.0 / count);
    if (x < int(p.width)) {
        hist_out[y * int(p.padded_width) + x] = vec2(mean, frames);
        hist_mean[y * int(p.width) + x] = count > 0.0 ? window : uintBitsToFloat(0x7fc00000u);
    }
}

// Taps 0..5 of a row are columns x0 - 1 .. x0 + 4; pixel x0 + k uses taps k .. k + 2.
#define EACH_TAP(F) F(0) F(1) F(2) F(3) F(4) F(5)
#define EACH_PIXEL(F) F(0) F(1) F(2) F(3)

void main() {
    int x0 = int(gl_GlobalInvocationID.x * HISTORY_COLUMNS);
    int y0 = int(gl_GlobalInvocationID.y * HISTORY_STRIP);
    if (x0 >= int(p.width) || y0 >= int(p.height)) return;
    int end = min(y0 + int(HISTORY_STRIP), int(p.height));
    if (p.has_history == 0u) {
        for (int y = y0; y < end; y++) {
            for (int x = x0; x < min(x0 + int(HISTORY_COLUMNS), int(p.width)); x++) {
                hist_out[y * int(p.padded_width) + x] = vec2(estimate[y * int(p.width) + x].w, 1.0);
                hist_mean[y * int(p.width) + x] = 0.0;
            }
        }
        return;
    }
    Tap t[6], m[6], b[6];
#define FETCH_TOP(i) t[i] = fetch_tap(x0 - 1 + i, y0 - 1); m[i] = fetch_tap(x0 - 1 + i, y0);
    EACH_TAP(FETCH_TOP)
    int y = y0;
    do {  // bottom-tested: y0 < end (see bvh.glsl on llvmpipe's loops)
#define FETCH_BOTTOM(i) b[i] = fetch_tap(x0 - 1 + i, y + 1);
        EACH_TAP(FETCH_BOTTOM)
#define EMIT(k) emit(x0 + k, y, t[k], t[k + 1], t[k + 2], m[k], m[k + 1], m[k + 2], b[k], \
                     b[k + 1], b[k + 2]);
        EACH_PIXEL(EMIT)
#define ROLL(i) t[i] = m[i]; m[i] = b[i];
        EACH_TAP(ROLL)
        y++;
    } while (y < end);
}
