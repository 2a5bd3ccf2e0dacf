#version 460
// GLSL unit run of lights.glsl: per input, env_sample(u), env_texel_of and env_pdf of a given
// direction, and punctual_incident of every punctual record at a given point.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/scene.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint count; uint punctual; } pc;
layout(set = 0, binding = 0, rgba32ui) readonly uniform uimage2D scene_lights;
layout(set = 0, binding = 1, scalar) readonly buffer Info { SceneInfo scene; };
// Per input: (u.xy, 0, 0), (direction, 0), (point, 0).
layout(set = 0, binding = 2, scalar) readonly buffer In { vec4 inputs[]; };
// Per input: (sampled wi, pdf), (texel i, texel j, env_pdf, 0), then per punctual record
// (wi, dist), (irradiance, 0).
layout(set = 0, binding = 3, scalar) writeonly buffer Out { vec4 results[]; };

// The two scene_texels.glsl accessors lights.glsl needs (that file needs every scene image).
#define SCENE_TEXEL(image, k) \
    imageLoad(image, ivec2(int((k) & ((1u << SCENE_TEXELS_WIDTH_LOG2) - 1u)), int((k) >> SCENE_TEXELS_WIDTH_LOG2)))
GpuLight scene_light(uint index) {
    uvec4 a = SCENE_TEXEL(scene_lights, LIGHT_TEXELS * index);
    return GpuLight(a.x, uintBitsToFloat(a.y), uintBitsToFloat(a.z), uintBitsToFloat(a.w));
}
#define LOOP_TICK(loop)
#include "lights.glsl"

void main() {
    lights_init(scene);
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uint stride = 2u + 2u * pc.punctual;
    vec3 wi;
    float pdf;
    env_sample(inputs[3u * i].xy, true, wi, pdf);
    results[stride * i] = vec4(wi, pdf);
    vec3 d = inputs[3u * i + 1u].xyz;
    uvec2 t = env_texel_of(d);
    results[stride * i + 1u] = vec4(float(t.x), float(t.y), env_pdf(d), 0.0);
    vec3 p = inputs[3u * i + 2u].xyz;
    for (uint k = 0u; k < pc.punctual; k++) {
        vec3 w, e;
        float dist;
        punctual_incident(light_params(k), p, w, dist, e);
        results[stride * i + 2u + 2u * k] = vec4(w, dist);
        results[stride * i + 3u + 2u * k] = vec4(e, 0.0);
    }
}
