#version 460
// Oracle keys (`sort-grid-oracle`): each pixel's sorting key becomes its exact luminance error
// against this frame's reference, the quantity the metrics measure. Only an evaluation has the
// reference, so this is a ceiling, not a renderer: it shows how much of the gap to the best
// ranking an estimated key (history keys) leaves, and how much is lost because a seed's error
// does not carry over to the next frame. One invocation per visible pixel. CPU twin:
// crates/permute/src/oracle.rs oracle_key_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
#include "generated/motion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { OracleParams p; };
layout(set = 0, binding = 0, scalar) buffer Estimate { vec4 estimate[]; };                // W*H
layout(set = 0, binding = 1, scalar) readonly buffer Reference { float reference[]; };  // W*H

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    if (q.x >= p.width || q.y >= p.height) return;
    uint at = q.y * p.width + q.x;
    vec3 c = estimate[at].rgb;
    // Rec.709 luminance, summed left to right as in the twin (no contraction into FMAs).
    precise float y = REC709_LUMA_R * c.r + REC709_LUMA_G * c.g + REC709_LUMA_B * c.b;
    precise float error = y - reference[at];
    estimate[at].w = error;
}
