// Traces a batch of rays through the scene BVH: closest hit and occlusion per ray.
// GPU side of the CPU-vs-GPU BVH test; the CPU reference is SceneGpu::trace_rays_raw and
// SceneGpu::occluded_rays (crates/scene).
//
// Bindings (set 0): 0 bvh_nodes (BvhNode[]), 1 bvh_triangles (GpuTriangle[]), 2 rays (Ray[]),
// 3 hits (Hit[], out), 4 occluded (uint[], out: 1 = occluded). Push constant: ray_count.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require

#include "generated/scene.glsl"

layout(local_size_x = 64) in;

layout(scalar, set = 0, binding = 0) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(scalar, set = 0, binding = 1) readonly buffer BvhTriangles { GpuTriangle bvh_triangles[]; };
layout(scalar, set = 0, binding = 2) readonly buffer Rays { Ray rays[]; };
layout(scalar, set = 0, binding = 3) writeonly buffer Hits { Hit hits[]; };
layout(scalar, set = 0, binding = 4) writeonly buffer Occluded { uint occluded[]; };

layout(push_constant) uniform Push {
    uint ray_count;
} pc;

#define BVH_FROM_BUFFERS
#include "bvh.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.ray_count) {
        return;
    }
    Ray ray = rays[i];
    Hit hit;
    bvh_closest_hit(ray, hit);
    hits[i] = hit;
    occluded[i] = bvh_occluded(ray) ? 1u : 0u;
}
