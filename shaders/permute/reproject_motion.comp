#version 460
// Seed reprojection, step 1 of 5: for each pixel q of this frame, the pixel of the previous
// frame that showed the same surface (its hit point projected with the previous camera, and
// `similar` there), or REPROJECT_NONE (sky, off screen, disoccluded). One invocation per padded
// pixel; padding pixels have no source. CPU twin: crates/permute/src/reproject.rs
// reproject_motion_cpu (the projection in project.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "project.glsl"
#include "similar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Prev { GBufferTexel prev[]; };  // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Cur { GBufferTexel cur[]; };    // W*H
layout(set = 0, binding = 2, scalar) writeonly buffer Src { uint src[]; };           // padded

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.padded_width || q.y >= p.padded_height) return;
    bool visible = q.x < p.width && q.y < p.height;
    GBufferTexel g = cur[min(q.y, p.height - 1u) * p.width + min(q.x, p.width - 1u)];
    float z;
    vec2 c = project_previous(p, g.position, z);
    uvec2 s;
    bool inside = previous_pixel(p, c, z, s);
    bool same = similar(g, prev[s.y * p.width + s.x]);
    bool ok = visible && g.material != 0u && inside && same;
    src[q.y * p.padded_width + q.x] = ok ? s.y * p.padded_width + s.x : REPROJECT_NONE;
}
