#version 460
// TAA, the accumulation along the motion: each pixel's surface point (this frame's G-buffer)
// projected with the previous camera fetches the previous accumulation bilinearly; a tap whose
// pixel showed another surface is dropped and the others renormalised; with no tap left (sky,
// behind the previous camera, off screen, disoccluded) the history restarts from this frame.
// Then an EMA step of weight TAA_ALPHA. The float work is `precise` and in the CPU twin's order
// (crates/render/src/taa.rs), so both pick the same taps.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "project.glsl"
#include "similar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TaaParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Cur { GBufferTexel cur[]; };    // this frame
layout(set = 0, binding = 1, scalar) readonly buffer Prev { GBufferTexel prev[]; };  // previous
layout(set = 0, binding = 2, scalar) readonly buffer History { vec4 history[]; };    // previous accum
layout(set = 0, binding = 3, scalar) readonly buffer Estimate { vec4 estimate[]; };
layout(set = 0, binding = 4, scalar) writeonly buffer Accum { vec4 accum[]; };

// Rust's f32::round (halves away from zero), exactly: x - trunc(x) has no rounding error.
float round_away(float x) {
    float t = trunc(x);
    precise float f = x - t;
    return abs(f) >= 0.5 ? t + sign(x) : t;
}

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    uint w = p.camera.width, h = p.camera.height;
    if (q.x >= w || q.y >= h) return;
    uint i = q.y * w + q.x;
    vec4 e = estimate[i];
    if (p.still != 0u) {
        vec4 own = history[i];
        precise vec4 o = own + TAA_ALPHA * (e - own);
        accum[i] = o;
        return;
    }
    GBufferTexel g = cur[i];
    float z;
    vec2 c = project_previous(p.camera, g.position, z);
    bool seen = g.material != 0u && z > 0.0 && !any(isnan(c)) && !any(isinf(c));
    precise vec2 scaled = (c - 0.5) * TAA_SNAP;
    precise vec2 s = vec2(round_away(scaled.x), round_away(scaled.y)) / TAA_SNAP;
    vec2 o = floor(s);
    precise vec2 f = s - o;
    precise float wts[4] = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y),
                                    (1.0 - f.x) * f.y, f.x * f.y);
    uint at[4];
    float kept[4];
    uint n = 0u;
    precise float sum = 0.0;
    for (uint k = 0u; seen && k < 4u; k++) {
        vec2 t = o + vec2(float(k & 1u), float(k >> 1u));
        bool inside = t.x >= 0.0 && t.y >= 0.0 && t.x < float(w) && t.y < float(h);
        if (wts[k] > 0.0 && inside) {
            uint a = uint(t.y) * w + uint(t.x);
            if (similar(g, prev[a])) {
                at[n] = a;
                kept[n] = wts[k];
                n++;
                sum += wts[k];
            }
        }
    }
    if (n == 0u) {
        accum[i] = e;  // restart: this frame's value
        return;
    }
    // The first product starts the sum, so one tap of weight 1 is exactly its value.
    precise float w0 = kept[0] / sum;
    precise vec4 hist = w0 * history[at[0]];
    for (uint k = 1u; k < n; k++) {
        precise float wk = kept[k] / sum;
        hist += wk * history[at[k]];
    }
    precise vec4 outv = hist + TAA_ALPHA * (e - hist);
    accum[i] = outv;
}
