// Texture sampling from the packed RGBA8 atlas in the scene texels (no sampler arrays on
// lavapipe). Requires scene_texels.glsl (scene_texture, scene_atlas_word).
#ifndef TEXTURES_GLSL
#define TEXTURES_GLSL

int wrap_coord(int i, int n, uint mode) {
    if (mode == TEXTURE_WRAP_CLAMP) return clamp(i, 0, n - 1);
    if (mode == TEXTURE_WRAP_MIRROR) {
        int p = ((i % (2 * n)) + 2 * n) % (2 * n);
        return p < n ? p : 2 * n - 1 - p;
    }
    return ((i % n) + n) % n;
}

vec4 texel(GpuTexture t, int x, int y) {
    uint sx = wrap_coord(x, int(t.width), (t.flags >> TEXTURE_WRAP_S_SHIFT) & 3u);
    uint sy = wrap_coord(y, int(t.height), (t.flags >> TEXTURE_WRAP_T_SHIFT) & 3u);
    return unpackUnorm4x8(scene_atlas_word(t.offset + sy * t.width + sx));
}

// Bilinear (or nearest) lookup at glTF uv; raw texel values (no colour-space conversion).
vec4 texture_raw(int index, vec2 uv) {
    GpuTexture t = scene_texture(index);
    vec2 p = uv * vec2(t.width, t.height) - 0.5;
    // Nearest = the bilinear code at the rounded texel with weight 0 (one code path: on
    // llvmpipe both sides of an `if` run anyway).
    bool nearest = (t.flags & TEXTURE_FILTER_NEAREST) != 0u;
    vec2 f = nearest ? vec2(0.0) : p - floor(p);
    p = nearest ? p + 0.5 : p;
    int x = int(floor(p.x)), y = int(floor(p.y));
    return mix(mix(texel(t, x, y), texel(t, x + 1, y), f.x),
               mix(texel(t, x, y + 1), texel(t, x + 1, y + 1), f.x), f.y);
}

vec3 srgb_to_linear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

#endif
