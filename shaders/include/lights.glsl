// Lights that are not triangles: KHR_lights_punctual lights and the environment map with its
// sampling tables, read from the light image after the GpuLight records (layout:
// crates/scene/src/gpu/texels.rs). CPU twins with the same f32 operations:
// crates/scene/src/lights.rs (punctual_incident = PunctualLight::incident) and
// crates/scene/src/environment.rs (env_* = the functions of the same names); sin, cos, atan
// and acos differ from Rust's by a few ulp.
// Needs scene_texels.glsl, the scene_lights image and LOOP_TICK.
#ifndef LIGHTS_GLSL
#define LIGHTS_GLSL

const float LIGHTS_PI = 3.14159265358979;
const float LIGHTS_TAU = 6.28318530717959;

uint g_params_offset;
uint g_env_offset;   // marginal CDF of the map, then its texels
uvec2 g_env_size;    // (0, 0) without a map: misses see g_environment
vec2 g_env_rotation; // (cos, sin) about +Y
float g_env_select;  // probability that sample_light picks the map (0: it never does)

// Scene-wide light constants (call at the top of main, outside control flow).
void lights_init(SceneInfo info) {
    g_params_offset = info.light_params_offset;
    g_env_offset = info.env_offset;
    g_env_size = uvec2(info.env_width, info.env_height);
    g_env_rotation = info.env_rotation;
    GpuLight env = scene_light(uint(max(info.env_light, 0)));
    g_env_select = info.env_light >= 0 ? env.pdf : 0.0;
}

LightParams light_params(uint k) {
    uint t = g_params_offset + LIGHT_PARAMS_TEXELS * k;
    uvec4 a = SCENE_TEXEL(scene_lights, t);
    uvec4 b = SCENE_TEXEL(scene_lights, t + 1u);
    uvec4 c = SCENE_TEXEL(scene_lights, t + 2u);
    return LightParams(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), uintBitsToFloat(b.w),
                       uintBitsToFloat(c.xyz), uintBitsToFloat(c.w));
}

// Light from a point, spot or directional light at p, occlusion aside: the direction towards
// it, the distance (1e30: infinitely far) and the irradiance on a surface facing it.
void punctual_incident(LightParams l, vec3 p, out vec3 wi, out float dist, out vec3 e) {
    vec3 to = l.position - p;
    float d2 = dot(to, to);
    float d = sqrt(d2);
    wi = to / d;
    float cd = dot(l.direction, -wi);
    float t = clamp((cd - l.cos_outer) / max(l.cos_inner - l.cos_outer, 1e-4), 0.0, 1.0);
    e = l.intensity * (t * t / d2);
    dist = d;
    bool directional = l.kind == LIGHT_DIRECTIONAL;
    wi = directional ? -l.direction : wi;
    dist = directional ? 1e30 : dist;
    e = directional ? l.intensity : e;
}

// World direction of map coordinate uv (orientation: environment.rs).
vec3 env_direction(vec2 uv) {
    float phi = (uv.x - 0.5) * LIGHTS_TAU;
    float theta = uv.y * LIGHTS_PI;
    float st = sin(theta);
    vec3 m = vec3(st * sin(phi), cos(theta), -st * cos(phi));
    float c = g_env_rotation.x, s = g_env_rotation.y;
    return vec3(m.x * c + m.z * s, m.y, -m.x * s + m.z * c);
}

// The texel under direction d.
uvec2 env_texel_of(vec3 d) {
    float c = g_env_rotation.x, s = g_env_rotation.y;
    float mx = d.x * c - d.z * s;
    float mz = d.x * s + d.z * c;
    vec2 uv = vec2(0.5 + atan(mx, -mz) / LIGHTS_TAU, acos(clamp(d.y, -1.0, 1.0)) / LIGHTS_PI);
    ivec2 size = ivec2(max(g_env_size, uvec2(1u)));
    return uvec2(clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1));
}

uint env_row(uint j) { return g_env_offset + g_env_size.y + j * g_env_size.x; }

vec3 env_radiance(uvec2 t) {
    return uintBitsToFloat(SCENE_TEXEL(scene_lights, env_row(t.y) + t.x).xyz);
}

float env_marginal(uint j) { return uintBitsToFloat(SCENE_TEXEL(scene_lights, g_env_offset + j).x); }
float env_conditional(uint j, uint i) {
    return uintBitsToFloat(SCENE_TEXEL(scene_lights, env_row(j) + i).w);
}

// Probability of choosing texel t.
float env_probability(uvec2 t) {
    float pc = env_conditional(t.y, t.x) - (t.x > 0u ? env_conditional(t.y, max(t.x, 1u) - 1u) : 0.0);
    float pm = env_marginal(t.y) - (t.y > 0u ? env_marginal(max(t.y, 1u) - 1u) : 0.0);
    return pm * pc;
}

// Solid-angle density of direction d inside a texel of probability p.
float env_density(float p, vec3 d) {
    float sin_theta = sqrt(max(1.0 - d.y * d.y, 0.0));
    return p * float(g_env_size.x * g_env_size.y) / (2.0 * LIGHTS_PI * LIGHTS_PI * max(sin_theta, 1e-6));
}

// First entry with x < cdf in [0, n) (row j of the conditional CDFs, or the marginal when
// j == ~0u) and where x falls in it. Lanes with !enabled skip the search (and return 0).
uint env_invert(uint j, uint n, float x, bool enabled, out float f) {
    uint lo = 0u, hi = enabled ? n - 1u : 0u;
    if (lo < hi) {
        do {  // bottom-tested, as sample_light's
            LOOP_TICK(TRACE_LOOP_LIGHT_CHOICE);
            uint mid = (lo + hi) / 2u;
            float c = j == ~0u ? env_marginal(mid) : env_conditional(j, mid);
            if (x < c) hi = mid; else lo = mid + 1u;
        } while (lo < hi);
    }
    float c1 = j == ~0u ? env_marginal(lo) : env_conditional(j, lo);
    float c0 = lo > 0u ? (j == ~0u ? env_marginal(max(lo, 1u) - 1u) : env_conditional(j, max(lo, 1u) - 1u)) : 0.0;
    f = min(clamp((x - c0) / max(c1 - c0, 1e-30), 0.0, 1.0), 0.99999994);
    return lo;
}

// A direction towards the map drawn by importance (u.y the row, u.x the texel) and its
// solid-angle density.
void env_sample(vec2 u, bool enabled, out vec3 wi, out float pdf) {
    float fv, fu;
    uint j = env_invert(~0u, g_env_size.y, u.y, enabled, fv);
    uint i = env_invert(j, g_env_size.x, u.x, enabled, fu);
    vec2 uv = vec2((float(i) + fu) / float(g_env_size.x), (float(j) + fv) / float(g_env_size.y));
    wi = env_direction(uv);
    pdf = env_density(env_probability(uvec2(i, j)), wi);
}

// Solid-angle density with which env_sample draws d.
float env_pdf(vec3 d) { return env_density(env_probability(env_texel_of(d)), d); }

#endif
