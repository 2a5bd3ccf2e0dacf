// The path integrator of the trace shaders (trace/trace_body.glsl declares its resources and
// the TRACE_* specialisation macros; needs scene_texels.glsl, bvh.glsl, brdf.glsl,
// textures.glsl, sampling.glsl, and lights.glsl with TRACE_LIGHTS).
//
// llvmpipe executes both sides of every `if` under a lane mask; only loops exit early. So
// per-method and per-scene choices (sampler, blue-noise mask, textures) are compile-time
// macros of separate pipeline variants rather than branches, and data every lane needs is
// loaded once at the top of main, outside control flow (where a uniform load is one scalar
// load instead of a loop over the lanes).
#ifndef PATH_GLSL
#define PATH_GLSL

const float GOLDEN = 0.61803398875;

// Per-dispatch constants, set at the top of main.
TraceParams P;
uint g_light_count;
vec3 g_environment;
// Base colour at the latest primary hit (main sets 1, which a pixel whose rays miss keeps):
// the divisor of the demodulated sorting key (TRACE_FLAG_DEMODULATE).
vec3 g_albedo0;
// Where this pixel reads the mask: the pixel itself, or with TRACE_FLAG_MASK_ANCHORED its
// seed's anchor (set by main).
uvec2 g_mask_px;
#if TRACE_MASK
// g_textured0: this frame's primary hit is textured (recorded for the next frame's
// TRACE_FLAG_SEED_JITTER_ON_TEXTURES).
bool g_textured0;
#endif

#if TRACE_MASK
// The mask's share of the first MASK_DIMS sample dimensions (the camera jitter and the first
// vertex), fixed for the whole dispatch: bit `dim` of g_mask_from says that this pixel takes
// dimension `dim` from the mask, g_mask_rank its value before the per-sample golden-ratio
// step, g_mask_turn its rotation (MASK_MODE_ROTATE). mask_init reads them once in main:
// llvmpipe runs every branch, so a read in sample_dim cost a gather and its address
// arithmetic for each of the 9 dimensions at every path vertex of every sample.
uint g_mask_from;
float g_mask_rank[MASK_DIMS];
float g_mask_turn[MASK_DIMS];

// Whether a pixel takes mask dimension `dim` (the first MASK_DIMS dimensions, or those the
// flags' dimension bits select; the jitter's two not with `seed_jitter`), and its value,
// read at g_mask_px, each dimension at its own fixed offset so the dimensions decorrelate.
// The mask's side is a power of two (blueshift_assets checks every mask it loads): the wrap
// is a bit mask and the rank's scale exact as a product.
#define MASK_INIT(dim)                                                                         \
    {                                                                                          \
        bool take = (dim_set == 0u || ((dim_set >> dim) & 1u) != 0u) &&                        \
                    !(dim < 2u && seed_jitter);                                                \
        if (P.mask_mode != MASK_MODE_NONE && take) g_mask_from |= 1u << dim;                  \
        uvec2 q = (g_mask_px + uvec2(P.mask_offset_x, P.mask_offset_y) +                       \
                   dim * uvec2(MASK_DIM_OFFSET_X, MASK_DIM_OFFSET_Y)) & (n - 1u);              \
        g_mask_rank[dim] = (float(mask[(layer * n + q.y) * n + q.x]) + 0.5) * scale;           \
        /* Rotated in 32-bit fixed point: mask_step R2 steps, exact for any count, or for the  \
           jitter with TRACE_FLAG_SOBOL_JITTER point mask_step of a Sobol sequence. */         \
        bool sobol_walk = dim < 2u && sobol_jitter;                                            \
        g_mask_turn[dim] = to_unit(sobol_walk ? sobol(P.mask_step, dim)                        \
                                              : P.mask_step * ((dim & 1u) == 0u ? R2_ALPHA_X : R2_ALPHA_Y)); \
    }

// Sets g_mask_*, after main has set g_mask_px. The pixel's flags (main sets them from its
// previous primary hit): `seed_jitter` (TRACE_FLAG_SEED_JITTER_ON_TEXTURES on a textured
// one) takes the jitter from the seed; `sobol_jitter` (TRACE_FLAG_SOBOL_JITTER on an
// untextured one) walks Sobol's points instead of R2's for it.
void mask_init(bool seed_jitter, bool sobol_jitter) {
    uint dim_set = P.flags >> TRACE_FLAG_MASK_DIMS_SHIFT;
    uint n = P.mask_size;
    uint layer = P.mask_mode == MASK_MODE_SPATIOTEMPORAL ? P.mask_step : 0u;
    float scale = 1.0 / float(n * n);
    g_mask_from = 0u;
    MASK_INIT(0u) MASK_INIT(1u) MASK_INIT(2u) MASK_INIT(3u) MASK_INIT(4u)
    MASK_INIT(5u) MASK_INIT(6u) MASK_INIT(7u) MASK_INIT(8u)
}
#undef MASK_INIT
#endif

// Sample dimension `dim` (< MASK_DIMS, a constant at every call) of sample `s` at path vertex
// `vertex` (the jitter's two: 0) for this pixel, given the seeded sampler's `bits` for it:
// at vertex 0 from the mask where mask_init said so (rotated by the golden ratio per sample for
// spp > 1), else the sampler's.
float sample_dim(uint bits, uint s, uint dim, uint vertex) {
    float x = to_unit(bits);
#if TRACE_MASK
    if (vertex == 0u && ((g_mask_from >> dim) & 1u) != 0u) {
        x = fract(g_mask_rank[dim] + float(s) * GOLDEN);
        if (P.mask_mode == MASK_MODE_ROTATE) x = fract(x + g_mask_turn[dim]);
    }
#endif
    return x;
}

// The seeded sampler's bits of the 7 dimensions of one path vertex, d .. d + 6 (d = 2 + 7b:
// odd at odd vertices), from the four pairs that hold them.
void vertex_bits(uint seed, uint index, uint d, out uint u[7]) {
    uint p = d >> 1u;
    seven_from_pairs(TRACE_SAMPLE_PAIR(seed, index, p), TRACE_SAMPLE_PAIR(seed, index, p + 1u),
                     TRACE_SAMPLE_PAIR(seed, index, p + 2u), TRACE_SAMPLE_PAIR(seed, index, p + 3u),
                     d, u);
}

float power_heuristic(float a, float b) {
    float a2 = a * a;
    return a2 / max(a2 + b * b, 1e-30);
}

struct Surface {
    vec3 p;
    vec3 n;      // shading normal, facing the incoming ray
    vec3 ng;     // geometric normal, facing the incoming ray
    bool front;  // ray arrived on the side the file's normals point to
    vec2 uv;
    uint material;
    int light;
};

Surface surface_at(Ray ray, Hit hit) {
    Surface s;
    SceneTriangle tri = scene_triangle(hit.triangle);
    SceneShading sh = scene_shading_at(hit.triangle, TRACE_TEXTURES != 0);
    float w = 1.0 - hit.u - hit.v;
    s.p = ray.origin + ray.dir * hit.t;
    vec3 n = normalize(w * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
    vec3 ng = normalize(cross(tri.tri.e1, tri.tri.e2));
    if (dot(ng, n) < 0.0) ng = -ng;  // geometric normal on the side of the file's normals
    s.front = dot(ng, ray.dir) < 0.0;
    if (!s.front) { ng = -ng; n = -n; }
    if (dot(n, ray.dir) > 0.0) n = ng;  // shading normal behind the ray: fall back
    s.n = n;
    s.ng = ng;
#if TRACE_TEXTURES
    s.uv = w * sh.uv0 + hit.u * sh.uv1 + hit.v * sh.uv2;
#else
    s.uv = vec2(0.0);
#endif
    s.material = tri.material;
    s.light = tri.light;
    return s;
}

BrdfInput material_at(SceneMaterial m, vec2 uv) {
    BrdfInput b;
    b.base = m.base;
    b.metallic = m.metallic;
    b.roughness = m.roughness;
    b.specular = m.specular;
    b.specular_color = m.specular_color;
#if TRACE_TEXTURES
    if (m.base_color_tex >= 0) b.base *= srgb_to_linear(texture_raw(m.base_color_tex, uv).rgb);
    if (m.mr_tex >= 0) {
        vec4 t = texture_raw(m.mr_tex, uv);
        b.roughness *= t.g;
        b.metallic *= t.b;
    }
#endif
    return b;
}

vec3 emission_at(SceneMaterial m, vec2 uv, bool front) {
    if (!front && (m.flags & MATERIAL_DOUBLE_SIDED) == 0u) return vec3(0.0);
    vec3 e = m.emissive;
#if TRACE_TEXTURES
    if (m.emissive_tex >= 0) e *= srgb_to_linear(texture_raw(m.emissive_tex, uv).rgb);
#endif
    return e;
}

vec3 offset_origin(vec3 p, vec3 ng) {
    return p + ng * (1e-4 * (1.0 + max(max(abs(p.x), abs(p.y)), abs(p.z))));
}

// Solid-angle pdf of light sampling towards a point on light `l` at distance d.
float light_pdf(GpuLight l, float d, float cos_l) {
    return l.pdf / l.area * d * d / max(cos_l, 1e-8);
}

// The light that x (in [0,1)) picks from the power CDF, and x rescaled into its interval.
// Direct light is then a function of the one dimension pair (x, the next dimension), so a
// pair-wise stratified or blue sampler (Sobol, hbo19 keys) stratifies it as a whole.
uint choose_light(float x, out GpuLight l, out float rescaled) {
    uint lo = 0u, hi = g_light_count - 1u;
    if (lo < hi) {
        do {  // first light with x < cdf (bottom-tested: see trace_paths)
            LOOP_TICK(TRACE_LOOP_LIGHT_CHOICE);
            uint mid = (lo + hi) / 2u;
            if (x < scene_light(mid).cdf) hi = mid; else lo = mid + 1u;
        } while (lo < hi);
    }
    l = scene_light(lo);
    float c0 = lo > 0u ? scene_light(max(lo, 1u) - 1u).cdf : 0.0;  // (both sides run)
    rescaled = clamp((x - c0) / max(l.cdf - c0, 1e-30), 0.0, 1.0);
    return lo;
}

// A point q on triangle light l from (ux, uy) as seen from p: direction wi, distance d,
// |cosine| at the light and the radiance it emits towards p. A parallelogram light (two
// triangles, crates/scene/src/gpu/quads.rs, whose QuadFrame::frame is the twin of the frame
// here) maps (ux, uy) affinely onto the whole quad, q = o + ux s + uy t; a triangle radially
// from its first vertex.
void triangle_light_point(GpuLight l, float ux, float uy, vec3 p, out vec3 q, out vec3 wi,
                          out float d, out float cos_l, out vec3 le) {
    uint index = l.triangle & LIGHT_TRIANGLE_MASK;
    uint code = (l.triangle >> LIGHT_QUAD_SHIFT) & 63u;
    SceneTriangle tri = scene_triangle(index);
    SceneShading sh = scene_shading_at(index, TRACE_TEXTURES != 0);
    float su = sqrt(ux);
    float b1 = 1.0 - su, b2 = uy * su;
    vec3 a0 = tri.tri.v0, a1 = tri.tri.v0 + tri.tri.e1, a2 = tri.tri.v0 + tri.tri.e2;
    uint k = (code >> 1u) & 3u;
    vec3 c = k == 0u ? a0 : (k == 1u ? a1 : a2);
    vec3 big_s = (k == 0u ? a1 : (k == 1u ? a2 : a0)) - c;
    vec3 big_t = (k == 0u ? a2 : (k == 1u ? a0 : a1)) - c;
    bool qi = (code & 8u) != 0u, qj = (code & 16u) != 0u;
    vec3 o = c + (qi ? big_s : vec3(0.0)) + (qj ? big_t : vec3(0.0));
    vec3 qs = qi ? -big_s : big_s, qt = qj ? -big_t : big_t;
    bool swap = (code & 32u) != 0u;
    vec3 side_u = swap ? qt : qs, side_v = swap ? qs : qt;
    q = (code & 1u) != 0u ? o + ux * side_u + uy * side_v
                          : tri.tri.v0 + b1 * tri.tri.e1 + b2 * tri.tri.e2;
    vec3 to = q - p;
    d = length(to);
    wi = to / d;
    vec3 nl = normalize(cross(tri.tri.e1, tri.tri.e2));
    if (dot(nl, sh.n0) < 0.0) nl = -nl;
    cos_l = dot(nl, -wi);
    bool front = cos_l > 0.0;
#if TRACE_TEXTURES
    vec2 uv = (1.0 - b1 - b2) * sh.uv0 + b1 * sh.uv1 + b2 * sh.uv2;
#else
    vec2 uv = vec2(0.0);
#endif
    le = emission_at(scene_material(tri.material), uv, front);
    cos_l = abs(cos_l);
}

// The shadow ray from s towards q (the ray ends just short of q itself: running it along wi
// for d * (1 - 1e-4) from the offset origin carried its end through the light whenever the
// offset had a component towards the light, and floors under the Cornell box's light lost
// about half their direct light), or along wi to infinity.
Ray shadow_ray(Surface s, vec3 q, vec3 wi, bool infinite) {
    vec3 o = offset_origin(s.p, s.ng);
    vec3 oq = q - o;
    float dq = length(oq);
    return infinite ? Ray(o, 0.0, wi, 1e30) : Ray(o, 0.0, oq / dq, dq * (1.0 - 1e-4));
}

#if !TRACE_LIGHTS
// Next-event estimation: one point on one emissive triangle, MIS-weighted. (u.z is left
// unused so the dimension layout stays the same.)
vec3 sample_light(Surface s, BrdfInput m, vec3 wo, vec3 u) {
    if (g_light_count == 0u) return vec3(0.0);
    GpuLight l;
    float ux;
    choose_light(u.x, l, ux);
    vec3 q, wi, le;
    float d, cos_l;
    triangle_light_point(l, ux, u.y, s.p, q, wi, d, cos_l, le);
    if (d <= 0.0) return vec3(0.0);
    if (dot(s.n, wi) <= 0.0 || dot(s.ng, wi) <= 0.0 || all(equal(le, vec3(0.0)))) return vec3(0.0);
    if (bvh_occluded(shadow_ray(s, q, wi, false))) return vec3(0.0);
    float pl = light_pdf(l, d, cos_l);
    float pb = brdf_pdf(m, s.n, wo, wi);
    return le * brdf_eval(m, s.n, wo, wi) * dot(s.n, wi) / pl * power_heuristic(pl, pb);
}

vec3 environment_seen(vec3 dir, float prev_pdf) { return g_environment; }
#else
// Next-event estimation towards one light of any kind: a point on an emissive triangle, a
// punctual light, or a direction drawn from the environment map; MIS-weighted against BRDF
// sampling where BRDF sampling can find the light too (triangles, the map). Every lane runs
// every kind (llvmpipe runs both sides of a branch); the map's searches skip other lanes.
vec3 sample_light(Surface s, BrdfInput m, vec3 wo, vec3 u) {
    if (g_light_count == 0u) return vec3(0.0);
    GpuLight l;
    float ux;
    choose_light(u.x, l, ux);
    bool tri = (l.triangle & LIGHT_PARAMS_BIT) == 0u;
    GpuLight lt = l;
    lt.triangle = tri ? l.triangle : 0u;
    vec3 q, wi, le;
    float d, cos_l;
    triangle_light_point(lt, ux, u.y, s.p, q, wi, d, cos_l, le);
    float pl = light_pdf(l, d, cos_l);  // solid angle, selection included; 0: a delta light
    bool infinite = false;
    LightParams lp = light_params(tri ? 0u : l.triangle & ~LIGHT_PARAMS_BIT);
    bool env = !tri && lp.kind == LIGHT_ENVIRONMENT;
    vec3 ewi;
    float epdf;
    env_sample(vec2(ux, u.y), env, ewi, epdf);
    vec3 pwi, pe;
    float pd;
    punctual_incident(lp, s.p, pwi, pd, pe);
    if (env) {
        wi = ewi;
        le = env_radiance(env_texel_of(ewi));
        pl = l.pdf * epdf;
        infinite = true;
        d = 1.0;
    } else if (!tri) {
        wi = pwi;
        le = pe;
        pl = 0.0;
        q = lp.position;
        infinite = pd >= 1e30;
        d = pd;
    }
    if (!(d > 0.0) || (env && !(pl > 0.0))) return vec3(0.0);
    if (dot(s.n, wi) <= 0.0 || dot(s.ng, wi) <= 0.0 || all(equal(le, vec3(0.0)))) return vec3(0.0);
    if (bvh_occluded(shadow_ray(s, q, wi, infinite))) return vec3(0.0);
    float pb = brdf_pdf(m, s.n, wo, wi);
    float w = pl > 0.0 ? power_heuristic(pl, pb) : 1.0;
    return le * brdf_eval(m, s.n, wo, wi) * dot(s.n, wi) / (pl > 0.0 ? pl : l.pdf) * w;
}

// What a ray that leaves the scene along dir brings back: the map (MIS-weighted against
// sample_light when the map is a light and the ray came from BRDF sampling) or the constant.
vec3 environment_seen(vec3 dir, float prev_pdf) {
    uvec2 t = env_texel_of(dir);
    vec3 le = env_radiance(t);
    float w = g_env_select > 0.0 && prev_pdf > 0.0
        ? power_heuristic(prev_pdf, g_env_select * env_density(env_probability(t), dir)) : 1.0;
    return g_env_size.x == 0u ? g_environment : le * w;
}
#endif

// The state of one path between vertices.
struct PathState {
    Ray ray;
    vec3 l;
    vec3 throughput;
    float prev_pdf;  // BRDF pdf of the last bounce (0: camera ray, no MIS)
    uint b;          // vertex index (0 = the camera ray's hit)
};

// The camera ray of sample `s` (sample index `index`) through pixel px.
PathState path_start(uvec2 px, uint seed, uint index, uint s) {
    uvec2 j = TRACE_SAMPLE_PAIR(seed, index, 0u);
    vec2 jitter = (P.flags & TRACE_FLAG_NO_JITTER) == 0u
        ? vec2(sample_dim(j.x, s, 0u, 0u), sample_dim(j.y, s, 1u, 0u))
        : vec2(0.5);
    vec2 ndc = (vec2(px) + P.view_offset + jitter) / P.view_size * 2.0 - 1.0;
    vec3 dir = normalize(P.cam_forward + ndc.x * P.cam_right - ndc.y * P.cam_up);
    PathState st;
    st.ray = Ray(P.cam_origin, 0.0, dir, 1e30);
    st.l = vec3(0.0);
    st.throughput = vec3(1.0);
    st.prev_pdf = 0.0;
    st.b = 0u;
    return st;
}

// Extends the path by one vertex; true when the path is complete (st.l is its estimate).
bool path_step(uint seed, uint index, uint s, inout PathState st) {
    Hit hit;
    if (!bvh_closest_hit(st.ray, hit)) {
        st.l += st.throughput * environment_seen(st.ray.dir, st.prev_pdf);
        return true;
    }
    Surface srf = surface_at(st.ray, hit);
    SceneMaterial mat = scene_material(srf.material);
    vec3 le = emission_at(mat, srf.uv, srf.front);
    if (any(greaterThan(le, vec3(0.0)))) {
        float w = 1.0;
        if (st.prev_pdf > 0.0 && srf.light >= 0) {
            GpuLight hl = scene_light(uint(srf.light));
            w = power_heuristic(st.prev_pdf, light_pdf(hl, hit.t, abs(dot(srf.ng, st.ray.dir))));
        }
        st.l += st.throughput * le * w;
    }
    BrdfInput m = material_at(mat, srf.uv);
    if (st.b == 0u) g_albedo0 = m.base;
#if TRACE_MASK
    if (st.b == 0u)
        g_textured0 = g_textured0 || (TRACE_TEXTURES != 0 &&
                                      max(mat.base_color_tex, max(mat.emissive_tex, mat.mr_tex)) >= 0);
#endif
    if (st.b == P.max_bounces) return true;
    uint d = 2u + st.b * DIMS_PER_BOUNCE;
    vec3 wo = -st.ray.dir;
    uint u[7];
    vertex_bits(seed, index, d, u);
    // (The mask's dimensions are those of vertex 0: 2 + k for the vertex's k-th.)
    uint b = st.b;
    vec3 ul = vec3(sample_dim(u[0], s, 2u, b), sample_dim(u[1], s, 3u, b), sample_dim(u[2], s, 4u, b));
    st.l += st.throughput * sample_light(srf, m, wo, ul);
    vec3 wi;
    float u_lobe = sample_dim(u[3], s, 5u, b);
    vec2 ub = vec2(sample_dim(u[4], s, 6u, b), sample_dim(u[5], s, 7u, b));
    if (!brdf_sample(m, srf.n, wo, u_lobe, ub, wi) || dot(srf.ng, wi) <= 0.0) return true;
    float pdf = brdf_pdf(m, srf.n, wo, wi);
    if (pdf <= 0.0) return true;
    st.throughput *= brdf_eval(m, srf.n, wo, wi) * dot(srf.n, wi) / pdf;
    st.prev_pdf = pdf;
    if (st.b >= 3u) {  // Russian roulette after a few bounces
        float q = clamp(max(st.throughput.r, max(st.throughput.g, st.throughput.b)), 0.05, 1.0);
        if (sample_dim(u[6], s, 8u, b) >= q) return true;
        st.throughput /= q;
    }
    st.ray = Ray(offset_origin(srf.p, srf.ng), 0.0, wi, 1e30);
    st.b++;
    return false;
}

uint sample_index_of(uint s) {
    return (P.flags & TRACE_FLAG_ADVANCE_INDEX) != 0u ? P.frame * P.spp + s : s;
}

// Sum of the estimates of samples s0 .. s0 + count. One loop over path vertices: a lane whose
// path ends starts its next sample at once, so the 8 lanes of a SIMD batch stay busy (a loop
// per path would run every lane as long as the longest of the 8 paths). Bottom-tested, like
// the loops of bvh.glsl (a top-tested loop runs one extra, fully masked, path step);
// TraceParams::sample_count is never 0.
vec3 trace_paths(uvec2 px, uint seed, uint s0, uint count) {
    uint s = s0;
    PathState st = path_start(px, seed, sample_index_of(s), s);
    vec3 sum = vec3(0.0);
    // (Written without a `break` after the step: llvmpipe 22.3 computed wrong paths for the
    // form `if (path_step(..)) { ..; if (done) break; st = path_start(..); }`.)
    do {
        LOOP_TICK(TRACE_LOOP_PATH_VERTEX);
        if (path_step(seed, sample_index_of(s), s, st)) {
            vec3 l = st.l;
            sum += any(isnan(l)) || any(isinf(l)) ? vec3(0.0) : l;
            s++;
            st = path_start(px, seed, sample_index_of(s), s);
        }
        LOOP_SYNC;
    } while (s < s0 + count);
    return sum;
}

#endif
