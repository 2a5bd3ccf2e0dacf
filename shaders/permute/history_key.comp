#version 460
// History keys: each pixel's history mean, the mean sorting key its surface showed in earlier
// frames (fetched through the reprojection's source pixel), so that the sorting pass ranks
// key - mean, an estimate of the seed's *error*, instead of the key itself: ranking values
// sorts by the image's own gradients and shadow edges as much as by error, the more so the
// lower the error (more spp). The mean a pixel ranks against averages the histories of its
// (2r+1)^2 window that show its surface and are at least min_frames long (NaN when none: the
// sorting pass falls back on the class mean). Pixels without a source (disoccluded, sky)
// restart their own history. On a sequence's first frame the means are 0: raw keys, the
// paper's ranking. One invocation per visible pixel. CPU twin: crates/permute/src/history.rs
// history_key_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "similar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { HistoryParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Src { uint src[]; };           // padded
// (mean key, frames) per padded pixel: the previous frame's, and this frame's.
layout(set = 0, binding = 2, scalar) readonly buffer HistIn { vec2 hist_in[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer HistOut { vec2 hist_out[]; };
layout(set = 0, binding = 4, scalar) writeonly buffer Mean { float hist_mean[]; };  // W*H
// This frame's G-buffer, W*H.
layout(set = 0, binding = 5, scalar) readonly buffer GBuffer { GBufferTexel gbuffer[]; };

// Mean of the previous histories of q's window that show q's surface and are long enough;
// summed row by row as in the twin.
float window_mean(ivec2 q) {
    GBufferTexel c = gbuffer[q.y * int(p.width) + q.x];
    int r = int(p.radius);
    float sum = 0.0, count = 0.0;
    for (int y = q.y - r; y <= q.y + r; y++) {
        for (int x = q.x - r; x <= q.x + r; x++) {
            if (x < 0 || y < 0 || x >= int(p.width) || y >= int(p.height)) continue;
            uint s = src[y * int(p.padded_width) + x];
            if (s == REPROJECT_NONE) continue;
            vec2 h = hist_in[s];
            if (h.y < float(p.min_frames) || !similar(c, gbuffer[y * int(p.width) + x])) continue;
            sum += h.x;
            count += 1.0;
        }
    }
    return count > 0.0 ? sum * (1.0 / count) : uintBitsToFloat(0x7fc00000u);
}

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.width || q.y >= p.height) return;
    uint at = q.y * p.width + q.x;
    uint here = q.y * p.padded_width + q.x;
    float key = estimate[at].w;
    if (p.has_history == 0u) {
        hist_out[here] = vec2(key, 1.0);
        hist_mean[at] = 0.0;
        return;
    }
    uint s = src[here];
    vec2 h = s != REPROJECT_NONE ? hist_in[s] : vec2(0.0);
    precise float frames = min(h.y + 1.0, float(p.max_frames));
    precise float mean = h.x + (key - h.x) * (1.0 / frames);
    hist_out[here] = vec2(mean, frames);
    hist_mean[at] = window_mean(ivec2(q));
}
