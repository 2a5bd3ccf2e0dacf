// glTF 2.0 metallic-roughness BRDF with KHR_materials_specular, as the glTF spec mixes it:
// mix(dielectric, metal, metallic), where the dielectric is
// (1 - specular * max(F_d)) * Lambert + specular * F_d * GGX (F_d: Schlick from
// F0 = min(0.04 * specular_color, 1), F90 = 1) and the metal is F_m * GGX (F0 = base colour).
// GGX uses the height-correlated Smith visibility term. specular = 1 with a white
// specular_color is the plain glTF dielectric; specular = 0 is pure Lambert. The max(F_d)
// weight keeps every channel's albedo <= 1 (energy conserved). Sampling picks a lobe
// with a probability from the Fresnel weight at the view angle; pdfs are the lobe mixture so
// MIS with light sampling is consistent. All vectors in world space, n facing wo.
// BRDF_LAMBERT 1 (before the include) compiles out the specular lobe, for scenes whose
// materials all have metallic = specular = 0: there the full BRDF is exactly Lambert (the
// specular terms are exact zeros, the lobe probability 0), so results are bit-identical.
#ifndef BRDF_GLSL
#define BRDF_GLSL

#ifndef BRDF_LAMBERT
#define BRDF_LAMBERT 0
#endif

const float PI = 3.14159265358979;
// Below this GGX becomes numerically a delta; clamping keeps pdfs finite.
const float MIN_ROUGHNESS = 0.03;

struct BrdfInput {
    vec3 base;       // linear base colour
    float metallic;
    float roughness; // perceptual; alpha = roughness^2
    float specular;       // KHR_materials_specular weight of the dielectric specular layer
    vec3 specular_color;  // its F0 tint
};

float luminance(vec3 c) { return dot(c, vec3(REC709_LUMA_R, REC709_LUMA_G, REC709_LUMA_B)); }

vec3 fresnel_schlick(vec3 f0, float cos_theta) {
    float m = 1.0 - clamp(cos_theta, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

float ggx_d(float n_h, float a2) {
    float d = n_h * n_h * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float smith_v(float n_v, float n_l, float a2) {
    float gv = n_l * sqrt(n_v * n_v * (1.0 - a2) + a2);
    float gl = n_v * sqrt(n_l * n_l * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-8);
}

float brdf_alpha2(BrdfInput m) {
    float r = max(m.roughness, MIN_ROUGHNESS);
    float a = r * r;
    return a * a;
}

vec3 dielectric_fresnel(BrdfInput m, float cos_theta) {
    return fresnel_schlick(min(vec3(0.04) * m.specular_color, vec3(1.0)), cos_theta);
}

// The specular lobe's Fresnel weight: dielectric layer and metal mixed by metallic.
vec3 brdf_fresnel(BrdfInput m, float cos_theta) {
    return mix(m.specular * dielectric_fresnel(m, cos_theta), fresnel_schlick(m.base, cos_theta),
               m.metallic);
}

// The Lambert lobe's weight: what the dielectric layer lets through, times 1 - metallic.
float brdf_diffuse_weight(BrdfInput m, float cos_theta) {
    vec3 f = dielectric_fresnel(m, cos_theta);
    return (1.0 - m.metallic) * (1.0 - m.specular * max(f.r, max(f.g, f.b)));
}

// Probability of sampling the specular lobe (0 when it is absent: pure Lambert).
float brdf_spec_prob(BrdfInput m, float n_v) {
    float spec = luminance(brdf_fresnel(m, n_v));
    float diff = luminance(m.base) * (1.0 - m.metallic);
    if (spec <= 0.0) return 0.0;
    if (diff <= 0.0) return 1.0;
    return clamp(spec / (spec + diff), 0.1, 0.9);
}

vec3 brdf_eval(BrdfInput m, vec3 n, vec3 wo, vec3 wi) {
    float n_l = dot(n, wi), n_v = dot(n, wo);
    if (n_l <= 0.0 || n_v <= 0.0) return vec3(0.0);
#if BRDF_LAMBERT
    return m.base / PI;
#else
    vec3 h = normalize(wo + wi);
    float n_h = max(dot(n, h), 0.0), v_h = max(dot(wo, h), 0.0);
    float a2 = brdf_alpha2(m);
    vec3 spec = brdf_fresnel(m, v_h) * ggx_d(n_h, a2) * smith_v(n_v, n_l, a2);
    vec3 diff = brdf_diffuse_weight(m, v_h) * m.base / PI;
    return diff + spec;
#endif
}

float brdf_pdf(BrdfInput m, vec3 n, vec3 wo, vec3 wi) {
    float n_l = dot(n, wi), n_v = dot(n, wo);
    if (n_l <= 0.0 || n_v <= 0.0) return 0.0;
#if BRDF_LAMBERT
    return n_l / PI;
#else
    vec3 h = normalize(wo + wi);
    float n_h = max(dot(n, h), 0.0), v_h = max(dot(wo, h), 1e-8);
    float ps = brdf_spec_prob(m, n_v);
    float spec_pdf = ggx_d(n_h, brdf_alpha2(m)) * n_h / (4.0 * v_h);
    return ps * spec_pdf + (1.0 - ps) * n_l / PI;
#endif
}

// Orthonormal basis around n (Duff et al. 2017).
void onb(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Samples wi from (lobe choice u_lobe, direction u); returns false if below the surface.
bool brdf_sample(BrdfInput m, vec3 n, vec3 wo, float u_lobe, vec2 u, out vec3 wi) {
    vec3 t, b;
    onb(n, t, b);
    float phi = 2.0 * PI * u.y;
    if (BRDF_LAMBERT == 0 && u_lobe < brdf_spec_prob(m, dot(n, wo))) {
        float a2 = brdf_alpha2(m);
        float cos_t = sqrt((1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x));
        float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
        vec3 h = normalize(t * (cos(phi) * sin_t) + b * (sin(phi) * sin_t) + n * cos_t);
        wi = reflect(-wo, h);
    } else {
        float r = sqrt(u.x);
        wi = normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(0.0, 1.0 - u.x)));
    }
    return dot(n, wi) > 0.0;
}

#endif
