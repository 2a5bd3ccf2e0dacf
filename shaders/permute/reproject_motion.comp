#version 460
// Seed reprojection, step 1 of 5: for each pixel q of this frame, the pixel of the previous
// frame that showed the same surface (its hit point projected with the previous camera, and
// `similar` there), or REPROJECT_NONE (sky, off screen, disoccluded). One invocation per padded
// pixel; padding pixels have no source. The projection is `precise` and written as in the CPU
// twin (crates/permute/src/reproject.rs reproject_motion_cpu).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/motion.glsl"
#include "similar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Prev { GBufferTexel prev[]; };  // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Cur { GBufferTexel cur[]; };    // W*H
layout(set = 0, binding = 2, scalar) writeonly buffer Src { uint src[]; };           // padded

float dot3(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.padded_width || q.y >= p.padded_height) return;
    bool visible = q.x < p.width && q.y < p.height;
    GBufferTexel g = cur[min(q.y, p.height - 1u) * p.width + min(q.x, p.width - 1u)];
    precise vec3 d = g.position - p.cam_origin;
    precise float z = dot3(d, p.cam_forward);
    precise float nx = dot3(d, p.cam_right) / (dot3(p.cam_right, p.cam_right) * z);
    precise float ny = -dot3(d, p.cam_up) / (dot3(p.cam_up, p.cam_up) * z);
    precise vec2 c = (vec2(nx, ny) + 1.0) * 0.5 * p.view_size - p.view_offset;
    precise vec2 biased = c + REPROJECT_TIE_BIAS;  // consistent side at pixel borders
    vec2 f = floor(biased);
    bool inside = z > 0.0 && f.x >= 0.0 && f.y >= 0.0 && f.x < float(p.width) && f.y < float(p.height);
    uvec2 s = inside ? uvec2(f) : uvec2(0u);  // (f may be NaN or huge when not inside)
    bool same = similar(g, prev[s.y * p.width + s.x]);
    bool ok = visible && g.material != 0u && inside && same;
    src[q.y * p.padded_width + q.x] = ok ? s.y * p.padded_width + s.x : REPROJECT_NONE;
}
