#version 460
// G-buffer pass: the primary hit through each pixel centre (same camera ray as `trace` without
// jitter): world position, geometric normal facing the camera, material + 1 (0 = no hit),
// distance. Feeds edge-aware grouping and seed reprojection. Engines with their own G-buffer
// can fill the same struct instead. CPU twin: crates/trace/src/gbuffer.rs gbuffer_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/scene.glsl"
#include "generated/params.glsl"
#include "generated/motion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TraceParams pc; };

layout(set = 0, binding = 0, rgba32ui) readonly uniform uimage2D scene_nodes;
layout(set = 0, binding = 1, rgba32ui) readonly uniform uimage2D scene_triangles;
layout(set = 0, binding = 2, rgba32ui) readonly uniform uimage2D scene_shading;
layout(set = 0, binding = 3, rgba32ui) readonly uniform uimage2D scene_materials;
layout(set = 0, binding = 4, rgba32ui) readonly uniform uimage2D scene_textures;
layout(set = 0, binding = 5, rgba32ui) readonly uniform uimage2D scene_texels;
layout(set = 0, binding = 6, rgba32ui) readonly uniform uimage2D scene_lights;
layout(set = 0, binding = 7, scalar) readonly buffer Info { SceneInfo scene; };
layout(set = 0, binding = 8, scalar) writeonly buffer GBuffer { GBufferTexel gbuffer[]; };

#include "scene_texels.glsl"
#include "bvh.glsl"

void main() {
    TraceParams P = pc;
    // Keeps every scene binding, so this pass shares the path tracer's binding table.
    int keep = imageSize(scene_textures).x + imageSize(scene_texels).x + imageSize(scene_shading).x
        + imageSize(scene_materials).x + imageSize(scene_lights).x + int(scene.light_count);
    uvec2 px = gl_GlobalInvocationID.xy;
    bool inside = px.x < P.width && px.y < P.height;
    vec2 ndc = (vec2(px) + P.view_offset + vec2(0.5)) / P.view_size * 2.0 - 1.0;
    vec3 dir = normalize(P.cam_forward + ndc.x * P.cam_right - ndc.y * P.cam_up);
    Ray ray = Ray(P.cam_origin, 0.0, dir, 1e30);
    Hit hit;
    bool found = bvh_closest_hit(ray, hit);
    SceneTriangle tri = scene_triangle(found ? hit.triangle : 0u);
    vec3 ng = normalize(cross(tri.tri.e1, tri.tri.e2));
    ng = dot(ng, dir) > 0.0 ? -ng : ng;
    GBufferTexel g;
    g.position = found ? P.cam_origin + dir * hit.t : vec3(0.0);
    g.material = found ? tri.material + 1u : 0u;
    g.normal = found ? ng : vec3(0.0);
    g.depth = found ? hit.t : 0.0;
    if (inside && keep != -1) gbuffer[px.y * P.width + px.x] = g;
}
