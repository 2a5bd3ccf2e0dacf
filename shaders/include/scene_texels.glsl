// The scene read from rgba32ui storage images: the texel layout of
// crates/scene/src/gpu/texels.rs (the table there; keep the two in sync). On llvmpipe an image
// load is a straight-line gather, several times cheaper than a divergent storage-buffer load.
//
// Requirements of the INCLUDING shader, before `#include "scene_texels.glsl"`:
//   #include "generated/scene.glsl"
//   layout(set = S, binding = ..., rgba32ui) readonly uniform uimage2D scene_nodes;
//   ... and likewise scene_triangles, scene_shading, scene_materials, scene_lights,
//   scene_textures, scene_texels.
// Defines bvh_load_node / bvh_load_children / bvh_load_triangle for bvh.glsl, so include this
// first.
#ifndef SCENE_TEXELS_GLSL
#define SCENE_TEXELS_GLSL

ivec2 scene_texel_coord(uint k) {
    return ivec2(int(k & ((1u << SCENE_TEXELS_WIDTH_LOG2) - 1u)), int(k >> SCENE_TEXELS_WIDTH_LOG2));
}

#define SCENE_TEXEL(image, k) imageLoad(image, scene_texel_coord(k))

// The fields of a BvhNode from its two texels (count and skip share b.w).
void node_fields(uvec4 a, uvec4 b, out vec3 aabb_min, out vec3 aabb_max, out uint left_first,
                 out uint count) {
    aabb_min = uintBitsToFloat(a.xyz);
    left_first = a.w;
    aabb_max = uintBitsToFloat(b.xyz);
    count = b.w & ((1u << NODE_COUNT_BITS) - 1u);
}

// Node `index` starts at texel NODE_TEXELS * (index + 1) (one node of padding first), so the
// children of a node (an odd index and the next) are four texels of one row, like the four
// texels of a triangle: one coordinate computation per pair or triangle (texels.rs).
void bvh_load_node(uint index, out vec3 aabb_min, out vec3 aabb_max, out uint left_first,
                   out uint count, out uint skip) {
    ivec2 c = scene_texel_coord(NODE_TEXELS * (index + 1u));
    uvec4 b = imageLoad(scene_nodes, c + ivec2(1, 0));
    node_fields(imageLoad(scene_nodes, c), b, aabb_min, aabb_max, left_first, count);
    skip = b.w >> NODE_COUNT_BITS;
}

// Both children of an interior node: nodes `first` and `first + 1`.
void bvh_load_children(uint first, out vec3 lmin, out vec3 lmax, out uint lfirst,
                       out uint lcount, out vec3 rmin, out vec3 rmax, out uint rfirst,
                       out uint rcount) {
    ivec2 c = scene_texel_coord(NODE_TEXELS * (first + 1u));
    node_fields(imageLoad(scene_nodes, c), imageLoad(scene_nodes, c + ivec2(1, 0)), lmin, lmax,
                lfirst, lcount);
    node_fields(imageLoad(scene_nodes, c + ivec2(2, 0)), imageLoad(scene_nodes, c + ivec2(3, 0)),
                rmin, rmax, rfirst, rcount);
}

// A triangle with the shading fields stored next to it.
struct SceneTriangle {
    GpuTriangle tri;
    uint material;
    int light;  // index in the light texels, -1 = not emissive
};

SceneTriangle scene_triangle(uint index) {
    ivec2 q = scene_texel_coord(TRIANGLE_TEXELS * index);  // (4 texels, one row)
    uvec4 a = imageLoad(scene_triangles, q);
    uvec4 b = imageLoad(scene_triangles, q + ivec2(1, 0));
    uvec4 c = imageLoad(scene_triangles, q + ivec2(2, 0));
    SceneTriangle t;
    t.tri.v0 = uintBitsToFloat(a.xyz);
    t.tri.e1 = uintBitsToFloat(uvec3(a.w, b.xy));
    t.tri.e2 = uintBitsToFloat(uvec3(b.zw, c.x));
    t.material = c.y;
    t.light = int(c.z);
    return t;
}

GpuTriangle bvh_load_triangle(uint index) { return scene_triangle(index).tri; }

// Shading normals of a triangle; uvs only when `with_uv` (one texel more).
struct SceneShading {
    vec3 n0, n1, n2;
    vec2 uv0, uv1, uv2;
};

SceneShading scene_shading_at(uint index, bool with_uv) {
    ivec2 q = scene_texel_coord(SHADING_TEXELS * index);  // (4 texels, one row)
    uvec4 a = imageLoad(scene_shading, q);
    uvec4 b = imageLoad(scene_shading, q + ivec2(1, 0));
    uvec4 c = imageLoad(scene_shading, q + ivec2(2, 0));
    uvec4 d = with_uv ? imageLoad(scene_shading, q + ivec2(3, 0)) : uvec4(0u);
    SceneShading s;
    s.n0 = uintBitsToFloat(a.xyz);
    s.n1 = uintBitsToFloat(b.xyz);
    s.n2 = uintBitsToFloat(c.xyz);
    s.uv0 = uintBitsToFloat(uvec2(a.w, b.w));
    s.uv1 = uintBitsToFloat(uvec2(c.w, d.x));
    s.uv2 = uintBitsToFloat(d.yz);
    return s;
}

struct SceneMaterial {
    vec3 base;  // linear base colour factor
    float metallic;
    vec3 emissive;
    float roughness;
    uint flags;
    int base_color_tex, emissive_tex, mr_tex;  // -1 = none
    vec3 specular_color;  // KHR_materials_specular
    float specular;
};

SceneMaterial scene_material(uint index) {
    ivec2 q = scene_texel_coord(MATERIAL_TEXELS * index);  // (4 texels, one row)
    uvec4 a = imageLoad(scene_materials, q);
    uvec4 b = imageLoad(scene_materials, q + ivec2(1, 0));
    uvec4 c = imageLoad(scene_materials, q + ivec2(2, 0));
    uvec4 d = imageLoad(scene_materials, q + ivec2(3, 0));
    SceneMaterial m;
    m.base = uintBitsToFloat(a.xyz);
    m.metallic = uintBitsToFloat(a.w);
    m.emissive = uintBitsToFloat(b.xyz);
    m.roughness = uintBitsToFloat(b.w);
    m.flags = c.x;
    m.base_color_tex = int(c.y);
    m.emissive_tex = int(c.z);
    m.mr_tex = int(c.w);
    m.specular_color = uintBitsToFloat(d.xyz);
    m.specular = uintBitsToFloat(d.w);
    return m;
}

GpuLight scene_light(uint index) {
    uvec4 a = SCENE_TEXEL(scene_lights, LIGHT_TEXELS * index);
    return GpuLight(a.x, uintBitsToFloat(a.y), uintBitsToFloat(a.z), uintBitsToFloat(a.w));
}

GpuTexture scene_texture(int index) {
    uvec4 a = SCENE_TEXEL(scene_textures, TEXTURE_TEXELS * uint(index));
    return GpuTexture(a.x, a.y, a.z, a.w);
}

// Atlas word `i` (one RGBA8 texel packed as in GpuTexture).
uint scene_atlas_word(uint i) {
    uvec4 a = SCENE_TEXEL(scene_texels, i / ATLAS_WORDS_PER_TEXEL);
    uint c = i % ATLAS_WORDS_PER_TEXEL;
    return c == 0u ? a.x : c == 1u ? a.y : c == 2u ? a.z : a.w;
}

#endif
