#version 460
// Tonemap pass: exposure, clamp, sRGB encode to packed RGBA8 (r | g<<8 | b<<16 | 255<<24).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { ImageParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Source { vec4 source[]; };
layout(set = 0, binding = 1, scalar) writeonly buffer Ldr { uint ldr[]; };
vec3 linear_to_srgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.width * p.height) return;
    vec3 c = linear_to_srgb(clamp(source[i].rgb * p.exposure, 0.0, 1.0));
    ldr[i] = packUnorm4x8(vec4(c, 1.0));
}
