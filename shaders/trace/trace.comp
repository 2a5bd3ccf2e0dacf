#version 460
// Path-tracing pass: one invocation per pixel and one path per dispatch (the host dispatches
// spp times per frame), software BVH traversal,
// glTF BRDF, next-event estimation on emissive triangles with MIS (power heuristic) against
// BRDF sampling, constant environment, Russian roulette. All randomness comes from the pixel's
// seed in the seed buffer (see sample_dim), so moving seeds moves whole estimates.
// Output: the raw per-frame estimate (rgb, Rec.709 luminance) that the sorting pass ranks.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/scene.glsl"
#include "generated/params.glsl"
#include "sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TraceParams pc; };

layout(set = 0, binding = 0, scalar) readonly buffer Nodes { BvhNode bvh_nodes[]; };
layout(set = 0, binding = 1, scalar) readonly buffer Tris { GpuTriangle bvh_triangles[]; };
layout(set = 0, binding = 2, scalar) readonly buffer Shading { TriangleShading triangle_shading[]; };
layout(set = 0, binding = 3, scalar) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 4, scalar) readonly buffer Textures { GpuTexture textures[]; };
layout(set = 0, binding = 5, scalar) readonly buffer Texels { uint texels[]; };
layout(set = 0, binding = 6, scalar) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 7, scalar) readonly buffer Info { SceneInfo scene; };
layout(set = 0, binding = 8, scalar) readonly buffer Seeds { uint seeds[]; };
layout(set = 0, binding = 9, scalar) readonly buffer Mask { uint mask[]; };
layout(set = 0, binding = 10, scalar) buffer Estimate { vec4 estimate[]; };

#include "bvh.glsl"
#include "brdf.glsl"
#include "textures.glsl"
#include "path.glsl"

void main() {
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= pc.width || px.y >= pc.height) return;
    uint seed = seeds[px.y * pc.stride + px.x];
    if ((pc.flags & TRACE_FLAG_SALT_FRAME) != 0u) seed = hash3(seed, pc.frame, 0x5a17u);
    uint s = pc.sample_index;
    uint index = (pc.flags & TRACE_FLAG_ADVANCE_INDEX) != 0u ? pc.frame * pc.spp + s : s;
    vec3 l = trace_path(px, seed, index, s);
    // Running mean over this frame's dispatches (one per sample, see TraceParams::sample_index).
    uint o = px.y * pc.width + px.x;
    if (s > 0u) l = estimate[o].rgb + (l - estimate[o].rgb) / float(s + 1u);
    estimate[o] = vec4(l, luminance(l));
}
