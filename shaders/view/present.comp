#version 460
// Present pass: composes the renderers' outputs into the window's packed 8-bit pixels, which
// the host copies into the swapchain image (and reads back for screenshots).
// - nearest upscaling from the render size to the window size;
// - split-screen: left of split_x from source A, right from source B, a divider between;
// - error view: |accum - reference| * error_scale, sRGB-encoded (the LDR inputs already are).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/view.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { PresentParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer LdrA { uint ldr_a[]; };
layout(set = 0, binding = 1, scalar) readonly buffer LdrB { uint ldr_b[]; };
layout(set = 0, binding = 2, scalar) readonly buffer AccumA { vec4 accum_a[]; };
layout(set = 0, binding = 3, scalar) readonly buffer AccumB { vec4 accum_b[]; };
layout(set = 0, binding = 4, scalar) readonly buffer Reference { vec4 reference[]; };
layout(set = 0, binding = 5, scalar) writeonly buffer Window { uint window[]; };

vec3 linear_to_srgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    uvec2 o = gl_GlobalInvocationID.xy;
    if (o.x >= p.out_width || o.y >= p.out_height) return;
    bool split = (p.flags & PRESENT_FLAG_SPLIT) != 0u;
    uint px;
    if (split && o.x >= p.split_x - min(p.split_x, PRESENT_DIVIDER_WIDTH / 2u)
              && o.x < p.split_x + PRESENT_DIVIDER_WIDTH / 2u) {
        px = 0xff40d0ffu; // divider: warm yellow (r = 0xff, g = 0xd0, b = 0x40)
    } else {
        // Nearest source pixel (no overflow: both sizes are at most 16384).
        uint sx = min(o.x * p.src_width / p.out_width, p.src_width - 1u);
        uint sy = min(o.y * p.src_height / p.out_height, p.src_height - 1u);
        uint i = sy * p.src_width + sx;
        bool right = split && o.x >= p.split_x;
        if ((p.flags & PRESENT_FLAG_ERROR) != 0u) {
            vec3 a = right ? accum_b[i].rgb : accum_a[i].rgb;
            vec3 e = clamp(abs(a - reference[i].rgb) * p.error_scale, 0.0, 1.0);
            px = packUnorm4x8(vec4(linear_to_srgb(e), 1.0));
        } else {
            px = right ? ldr_b[i] : ldr_a[i];
        }
    }
    if ((p.flags & PRESENT_FLAG_BGRA) != 0u) {
        px = (px & 0xff00ff00u) | ((px & 0xffu) << 16) | ((px >> 16) & 0xffu);
    }
    window[o.y * p.out_width + o.x] = px;
}
