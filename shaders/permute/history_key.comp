#version 460
// History keys: each pixel's history mean, the mean sorting key its surface showed in earlier
// frames (fetched through the reprojection's source pixel), so that the sorting pass ranks
// key - mean, an estimate of the seed's *error*, instead of the key itself: ranking values
// sorts by the image's own gradients and shadow edges as much as by error, the more so the
// lower the error (more spp). Pixels without a source (disoccluded, sky) restart their history;
// histories shorter than min_frames give NaN (the sorting pass falls back on the class mean).
// On a sequence's first frame the means are 0: raw keys, the paper's ranking.
// One invocation per visible pixel. CPU twin: crates/permute/src/history.rs history_key_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { HistoryParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Src { uint src[]; };           // padded
// (mean key, frames) per padded pixel: the previous frame's, and this frame's.
layout(set = 0, binding = 2, scalar) readonly buffer HistIn { vec2 hist_in[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer HistOut { vec2 hist_out[]; };
layout(set = 0, binding = 4, scalar) writeonly buffer Mean { float hist_mean[]; };  // W*H

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.width || q.y >= p.height) return;
    uint at = q.y * p.width + q.x;
    uint here = q.y * p.padded_width + q.x;
    float key = estimate[at].w;
    uint s = p.has_history != 0u ? src[here] : REPROJECT_NONE;
    if (s == REPROJECT_NONE) {
        hist_out[here] = vec2(key, 1.0);
        hist_mean[at] = p.has_history != 0u ? uintBitsToFloat(0x7fc00000u) : 0.0;
        return;
    }
    vec2 h = hist_in[s];
    precise float frames = min(h.y + 1.0, float(p.max_frames));
    precise float mean = h.x + (key - h.x) * (1.0 / frames);
    hist_out[here] = vec2(mean, frames);
    hist_mean[at] = h.y >= float(p.min_frames) ? h.x : uintBitsToFloat(0x7fc00000u);
}
