#version 460
// Accumulation pass: running mean of the raw estimates (count = frames already accumulated).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { ImageParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };
layout(set = 0, binding = 1, scalar) buffer Accum { vec4 accum[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.width * p.height) return;
    vec4 e = estimate[i];
    accum[i] = p.count == 0u ? e : accum[i] + (e - accum[i]) / float(p.count + 1u);
}
