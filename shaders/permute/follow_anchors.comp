#version 460
// Anchored masks: each pixel's anchor (a fixed-point screen position packed in its seed) moves
// with the surface it shows. A pixel whose surface the previous frame saw at the continuous
// position c (its hit point projected with the previous camera, the pixel s = floor(c) showing
// a `similar` surface) takes s's anchor plus c's offset from s's centre, so a surface keeps
// its anchor, and with it its mask values, exactly under any motion. Any other pixel (sky,
// disoccluded, off screen) keeps the anchor it had. One invocation per padded pixel; padding
// keeps its anchor. Written as the CPU twin (crates/permute/src/anchors.rs).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "generated/params.glsl"
#include "project.glsl"
#include "similar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Prev { GBufferTexel prev[]; };        // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Cur { GBufferTexel cur[]; };          // W*H
layout(set = 0, binding = 2, scalar) readonly buffer AnchorsIn { uint anchors_in[]; };     // padded
layout(set = 0, binding = 3, scalar) writeonly buffer AnchorsOut { uint anchors_out[]; };  // padded

// One coordinate's fixed-point step: the offset of c from the centre of pixel s.
uint step_of(float c, float s) {
    precise float d = (c - (s + 0.5)) * float(1u << ANCHOR_FRAC_BITS);
    return uint(int(roundEven(d)));
}

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.padded_width || q.y >= p.padded_height) return;
    uint at = q.y * p.padded_width + q.x;
    uint keep = anchors_in[at];
    bool visible = q.x < p.width && q.y < p.height;
    GBufferTexel g = cur[min(q.y, p.height - 1u) * p.width + min(q.x, p.width - 1u)];
    float z;
    vec2 c = project_previous(p, g.position, z);
    uvec2 s;
    bool inside = previous_pixel(p, c, z, s);
    bool ok = visible && g.material != 0u && inside && similar(g, prev[s.y * p.width + s.x]);
    uint from = anchors_in[s.y * p.padded_width + s.x];
    uint x = ((from & 0xffffu) + step_of(c.x, float(s.x))) & 0xffffu;
    uint y = ((from >> 16u) + step_of(c.y, float(s.y))) & 0xffffu;
    anchors_out[at] = ok ? x | (y << 16u) : keep;
}
