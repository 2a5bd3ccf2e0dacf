// GENERATED from Rust by blueshift-layout. Do not edit: regenerate with
// `cargo run -p blueshift-headers -- --write`.
#ifndef GENERATED_SCENE_GLSL
#define GENERATED_SCENE_GLSL

const uint BVH_STACK_SIZE = 64u;
const uint HIT_MISS = 4294967295u;
const uint MATERIAL_DOUBLE_SIDED = 1u;
const uint TEXTURE_WRAP_S_SHIFT = 0u;
const uint TEXTURE_WRAP_T_SHIFT = 2u;
const uint TEXTURE_WRAP_REPEAT = 0u;
const uint TEXTURE_WRAP_CLAMP = 1u;
const uint TEXTURE_WRAP_MIRROR = 2u;
const uint TEXTURE_FILTER_NEAREST = 16u;
const uint LIGHT_PARAMS_BIT = 2147483648u;
const uint LIGHT_QUAD_SHIFT = 25u;
const uint LIGHT_TRIANGLE_MASK = 33554431u;
const uint LIGHT_POINT = 1u;
const uint LIGHT_SPOT = 2u;
const uint LIGHT_DIRECTIONAL = 3u;
const uint LIGHT_ENVIRONMENT = 4u;
const uint SCENE_TEXELS_WIDTH_LOG2 = 12u;
const uint NODE_TEXELS = 2u;
const uint NODE_COUNT_BITS = 3u;
const uint TRIANGLE_TEXELS = 4u;
const uint SHADING_TEXELS = 4u;
const uint MATERIAL_TEXELS = 4u;
const uint LIGHT_TEXELS = 1u;
const uint TEXTURE_TEXELS = 1u;
const uint LIGHT_PARAMS_TEXELS = 3u;
const uint ATLAS_WORDS_PER_TEXEL = 4u;
struct BvhNode {
    vec3 aabb_min; // offset 0, size 12
    uint left_first; // offset 12, size 4
    vec3 aabb_max; // offset 16, size 12
    uint count; // offset 28, size 4
    uint skip; // offset 32, size 4
};
const uint BVH_NODE_SIZE = 36;

struct GpuTriangle {
    vec3 v0; // offset 0, size 12
    vec3 e1; // offset 12, size 12
    vec3 e2; // offset 24, size 12
};
const uint GPU_TRIANGLE_SIZE = 36;

struct TriangleShading {
    vec3 n0; // offset 0, size 12
    vec3 n1; // offset 12, size 12
    vec3 n2; // offset 24, size 12
    vec2 uv0; // offset 36, size 8
    vec2 uv1; // offset 44, size 8
    vec2 uv2; // offset 52, size 8
    uint material; // offset 60, size 4
    int light; // offset 64, size 4
};
const uint TRIANGLE_SHADING_SIZE = 68;

struct GpuMaterial {
    float base_color[4]; // offset 0, size 16
    vec3 emissive; // offset 16, size 12
    float metallic; // offset 28, size 4
    float roughness; // offset 32, size 4
    int base_color_tex; // offset 36, size 4
    int emissive_tex; // offset 40, size 4
    int mr_tex; // offset 44, size 4
    uint flags; // offset 48, size 4
    vec3 specular_color; // offset 52, size 12
    float specular; // offset 64, size 4
};
const uint GPU_MATERIAL_SIZE = 68;

struct GpuTexture {
    uint offset; // offset 0, size 4
    uint width; // offset 4, size 4
    uint height; // offset 8, size 4
    uint flags; // offset 12, size 4
};
const uint GPU_TEXTURE_SIZE = 16;

struct GpuLight {
    uint triangle; // offset 0, size 4
    float area; // offset 4, size 4
    float pdf; // offset 8, size 4
    float cdf; // offset 12, size 4
};
const uint GPU_LIGHT_SIZE = 16;

struct LightParams {
    vec3 position; // offset 0, size 12
    uint kind; // offset 12, size 4
    vec3 direction; // offset 16, size 12
    float cos_inner; // offset 28, size 4
    vec3 intensity; // offset 32, size 12
    float cos_outer; // offset 44, size 4
};
const uint LIGHT_PARAMS_SIZE = 48;

struct SceneInfo {
    uint triangle_count; // offset 0, size 4
    uint node_count; // offset 4, size 4
    uint material_count; // offset 8, size 4
    uint texture_count; // offset 12, size 4
    uint light_count; // offset 16, size 4
    uint texel_count; // offset 20, size 4
    float total_light_power; // offset 24, size 4
    vec3 environment; // offset 28, size 12
    vec3 bounds_min; // offset 40, size 12
    vec3 bounds_max; // offset 52, size 12
    uint light_params_offset; // offset 64, size 4
    uint env_offset; // offset 68, size 4
    uint env_width; // offset 72, size 4
    uint env_height; // offset 76, size 4
    int env_light; // offset 80, size 4
    vec2 env_rotation; // offset 84, size 8
};
const uint SCENE_INFO_SIZE = 92;

struct Ray {
    vec3 origin; // offset 0, size 12
    float tmin; // offset 12, size 4
    vec3 dir; // offset 16, size 12
    float tmax; // offset 28, size 4
};
const uint RAY_SIZE = 32;

struct Hit {
    float t; // offset 0, size 4
    uint triangle; // offset 4, size 4
    float u; // offset 8, size 4
    float v; // offset 12, size 4
};
const uint HIT_SIZE = 16;

#endif
