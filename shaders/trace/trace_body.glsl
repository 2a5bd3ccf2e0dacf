// Path-tracing pass: one invocation per pixel running TraceParams::sample_count paths per
// dispatch (the host splits a frame's samples into dispatches sized against llvmpipe's loop
// limit, counted below; see passes.rs), software BVH traversal over the scene images, glTF BRDF, next-event
// estimation on emissive triangles with MIS (power heuristic) against BRDF sampling, constant
// environment, Russian roulette. All randomness comes from the pixel's seed in the seed buffer
// (see sample_dim), so moving seeds moves whole estimates.
// Output: the raw per-frame estimate (rgb, Rec.709 luminance) that the sorting pass ranks.
//
// Included by the pipeline variants trace/trace.comp (everything chosen at run time) and
// trace/variants/*.comp, which fix before the include:
//   TRACE_SAMPLER_KIND  SAMPLER_WHITE / SAMPLER_SOBOL / SAMPLER_R2, or P.sampler_kind (the
//                       TraceParams field: chosen at run time)
//   TRACE_MASK          1: blue-noise mask modes (TraceParams::mask_mode) supported; 0: mask off
//   TRACE_TEXTURES      1: material textures and uvs; 0: texture indices ignored (no textures)
//   TRACE_LAMBERT       1: every material the triangles use has metallic = specular = 0, so
//                       the BRDF is Lambert alone (BRDF_LAMBERT, brdf.glsl); 0: full glTF
//   TRACE_HBO19         1: samples from hbo19_lookup_bits with the key table at binding 12
//                       (optional, default 0: sample_bits(TRACE_SAMPLER_KIND, ...))
//   TRACE_LOOP_STATS    1: count every loop's iterations per batch and per lane
//                       (trace/trace_loop_stats.comp; optional, default 0)
// The variants differ only in dead code: llvmpipe runs both sides of every branch, so
// branches that a method or scene never takes are compiled out (crates/render picks the
// variant; see passes.rs).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "generated/scene.glsl"
#include "generated/params.glsl"
// HBO+19 keys (hbo19_lookup_bits; one element (1, 1) when the method has none).
layout(set = 0, binding = 12, scalar) readonly buffer Hbo19Keys { uvec2 hbo19_keys[]; };
#define HBO19_KEYS hbo19_keys
#include "sampling.glsl"
#ifndef TRACE_HBO19
#define TRACE_HBO19 0
#endif
#if TRACE_HBO19
#define TRACE_SAMPLE_BITS(seed, index, dim) hbo19_lookup_bits(seed, index, dim)
#else
#define TRACE_SAMPLE_BITS(seed, index, dim) sample_bits(TRACE_SAMPLER_KIND, seed, index, dim)
#endif

layout(local_size_x = TRACE_GROUP_X, local_size_y = TRACE_GROUP_Y) in;
layout(push_constant, scalar) uniform Push { TraceParams pc; };

// The scene (texel layout: crates/scene/src/gpu/texels.rs, scene_texels.glsl).
layout(set = 0, binding = 0, rgba32ui) readonly uniform uimage2D scene_nodes;
layout(set = 0, binding = 1, rgba32ui) readonly uniform uimage2D scene_triangles;
layout(set = 0, binding = 2, rgba32ui) readonly uniform uimage2D scene_shading;
layout(set = 0, binding = 3, rgba32ui) readonly uniform uimage2D scene_materials;
layout(set = 0, binding = 4, rgba32ui) readonly uniform uimage2D scene_textures;
layout(set = 0, binding = 5, rgba32ui) readonly uniform uimage2D scene_texels;
layout(set = 0, binding = 6, rgba32ui) readonly uniform uimage2D scene_lights;
layout(set = 0, binding = 7, scalar) readonly buffer Info { SceneInfo scene; };
layout(set = 0, binding = 8, scalar) readonly buffer Seeds { uint seeds[]; };
layout(set = 0, binding = 9, scalar) readonly buffer Mask { uint mask[]; };
layout(set = 0, binding = 10, scalar) buffer Estimate { vec4 estimate[]; };
// [0]: the most loop iterations any SIMD batch ran in this frame (atomicMax; the host zeroes
// it before the pass and turns values near llvmpipe's limit into an error); from
// TRACE_STATUS_LOOPS on, the loop statistics (TRACE_LOOP_STATS).
layout(set = 0, binding = 11, scalar) buffer Status { uint trace_status[]; };

// llvmpipe's loop limiter: one counter per SIMD batch (subgroup), shared by all loops, that
// ends every loop silently after 65535 iterations of the batch (an iteration in which any
// lane is active). Each lane counts its own loop iterations and the batch's lanes agree on
// their maximum once per path vertex (trace_paths), which undercounts the batch only where
// lanes run different numbers of inner-loop iterations within one vertex (measured: the
// batch's true count, from a subgroupElect() tick per iteration, was 1.26x..1.46x this on
// the bundled scenes; that exact tick cost about 10% of the pass's CPU time, this about 2-3%).
// Hence the renderer's guard sits well below the limit (TRACE_LOOP_GUARD).
uint g_loop_ticks;
#ifndef TRACE_LOOP_STATS
#define TRACE_LOOP_STATS 0
#endif
#if TRACE_LOOP_STATS
// Loop statistics (trace/trace_loop_stats.comp; TraceLoop in Rust): per loop, the iterations
// this lane ran and those its batch ran (one elected lane counts each iteration of the batch),
// added to trace_status at the end of main. The counting itself costs time: timings come from
// the other variants.
uint g_lane_iterations[TRACE_LOOP_COUNT];
uint g_batch_iterations[TRACE_LOOP_COUNT];
#define LOOP_TICK(loop) \
    g_loop_ticks++; \
    g_lane_iterations[loop]++; \
    if (subgroupElect()) g_batch_iterations[loop]++
#else
#define LOOP_TICK(loop) g_loop_ticks++
#endif
#define LOOP_SYNC g_loop_ticks = subgroupMax(g_loop_ticks)
#define BVH_LOOP_TICK(loop) LOOP_TICK(loop)

#include "scene_texels.glsl"
#include "bvh.glsl"
#ifndef TRACE_LAMBERT
#define TRACE_LAMBERT 0
#endif
#define BRDF_LAMBERT TRACE_LAMBERT
#include "brdf.glsl"
#include "textures.glsl"
#include "path.glsl"

#if TRACE_LOOP_STATS
// Adds the batch's `value` (the same in every lane) to the 64-bit count at trace_status[word]
// (low word first): a wrapping add carries into the high word.
void status_add64(uint word, uint value) {
    if (subgroupElect()) {
        uint old = atomicAdd(trace_status[word], value);
        if (old + value < old) atomicAdd(trace_status[word + 1u], 1u);
    }
}
#endif

void main() {
    // Uniform data first, outside control flow (no early return: it would put the rest of
    // the shader under a lane mask).
    P = pc;
    g_loop_ticks = 0u;
#if TRACE_LOOP_STATS
    for (uint k = 0u; k < TRACE_LOOP_COUNT; k++) {
        g_lane_iterations[k] = 0u;
        g_batch_iterations[k] = 0u;
    }
#endif
    g_light_count = scene.light_count;
    g_environment = scene.environment;
    g_albedo0 = vec3(1.0);
    // Keeps every binding in every variant, so all variants share one binding table.
    int keep = imageSize(scene_textures).x + imageSize(scene_texels).x + mask.length() +
               hbo19_keys.length();
    // Each 8 consecutive invocations (one SIMD batch of llvmpipe's 256-bit vectors) take a
    // 4x2 block of the group's pixels rather than 8 pixels of a row: closer rays diverge less
    // in the traversal loops (measured 1.7% faster on the Cornell box). Needs TRACE_GROUP_X
    // a multiple of 4 and TRACE_GROUP_Y of 2 (the group's pixels are permuted, none lost).
    uint li = gl_LocalInvocationIndex, batch = li / 8u, lane = li % 8u;
    uint blocks_x = TRACE_GROUP_X / 4u;
    uvec2 px = gl_WorkGroupID.xy * uvec2(TRACE_GROUP_X, TRACE_GROUP_Y) +
               uvec2((batch % blocks_x) * 4u + lane % 4u, (batch / blocks_x) * 2u + lane / 4u);
    bool inside = px.x < P.width && px.y < P.height;
    px = min(px, uvec2(P.width, P.height) - 1u);
    uint seed = seeds[px.y * P.stride + px.x];
    seed = (P.flags & TRACE_FLAG_SALT_FRAME) != 0u ? hash3(seed, P.frame, 0x5a17u) : seed;
    uint s0 = P.sample_index, count = P.sample_count;
    vec3 l = trace_paths(px, seed, s0, count) / float(count);
    // Running mean over this frame's dispatches (see TraceParams::sample_index).
    uint o = px.y * P.width + px.x;
    vec3 prev = estimate[o].rgb;
    l = s0 > 0u ? prev + (l - prev) * (float(count) / float(s0 + count)) : l;
    // The sorting key: luminance, or with TRACE_FLAG_DEMODULATE the luminance of the lighting
    // (estimate over the primary hit's base colour; a heuristic that only steers the sort).
    vec3 albedo = (P.flags & TRACE_FLAG_DEMODULATE) != 0u
        ? max(g_albedo0, vec3(DEMODULATE_MIN_ALBEDO)) : vec3(1.0);
    if (inside && keep != -1) estimate[o] = vec4(l, luminance(l / albedo));
    uint ticks = subgroupMax(g_loop_ticks);
    if (subgroupElect()) atomicMax(trace_status[0], ticks);
#if TRACE_LOOP_STATS
    for (uint k = 0u; k < TRACE_LOOP_COUNT; k++) {
        status_add64(TRACE_STATUS_LOOPS + 4u * k, subgroupAdd(g_lane_iterations[k]));
        status_add64(TRACE_STATUS_LOOPS + 4u * k + 2u, subgroupAdd(g_batch_iterations[k]));
    }
#endif
}
