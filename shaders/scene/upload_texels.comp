#version 460
// Copies `count` texels of a scene array (crates/scene/src/gpu/texels.rs), from texel `first`
// on, from a storage buffer (a staging chunk) into its rgba32ui scene image: texel k to
// (k % SCENE_TEXELS_WIDTH, k / SCENE_TEXELS_WIDTH).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/scene.glsl"
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint first; uint count; } pc;
layout(set = 0, binding = 0, scalar) readonly buffer Src { uvec4 src[]; };
layout(set = 0, binding = 1, rgba32ui) writeonly uniform uimage2D dst;
void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
    if (i >= pc.count) return;
    uint k = pc.first + i;
    uint w = 1u << SCENE_TEXELS_WIDTH_LOG2;
    imageStore(dst, ivec2(int(k & (w - 1u)), int(k >> SCENE_TEXELS_WIDTH_LOG2)), src[i]);
}
