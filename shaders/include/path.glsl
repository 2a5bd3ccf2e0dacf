// The path integrator of trace/trace.comp (needs its buffers, bvh.glsl, brdf.glsl,
// textures.glsl and sampling.glsl).
#ifndef PATH_GLSL
#define PATH_GLSL

const float GOLDEN = 0.61803398875;

// Sample dimension `dim` of sample `index` for this pixel: from the mask in the mask modes
// (first MASK_DIMS dimensions, each read at its own fixed offset so dimensions decorrelate,
// rotated by the golden ratio per sample for spp > 1), else from the seeded sampler.
float sample_dim(uvec2 px, uint seed, uint index, uint s, uint dim) {
    if (pc.mask_mode != MASK_MODE_NONE && dim < MASK_DIMS) {
        uint n = pc.mask_size;
        uvec2 q = (px + uvec2(pc.mask_offset_x, pc.mask_offset_y) + dim * uvec2(37u, 71u)) % n;
        uint layer = pc.mask_mode == MASK_MODE_SPATIOTEMPORAL ? pc.frame % pc.mask_frames : 0u;
        uint rank = mask[(layer * n + q.y) * n + q.x];
        return fract((float(rank) + 0.5) / float(n * n) + float(s) * GOLDEN);
    }
    return sample_1d(pc.sampler_kind, seed, index, dim);
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
    GpuTriangle tri = bvh_triangles[hit.triangle];
    TriangleShading sh = triangle_shading[hit.triangle];
    float w = 1.0 - hit.u - hit.v;
    s.p = ray.origin + ray.dir * hit.t;
    vec3 n = normalize(w * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
    vec3 ng = normalize(cross(tri.e1, tri.e2));
    if (dot(ng, n) < 0.0) ng = -ng;  // geometric normal on the side of the file's normals
    s.front = dot(ng, ray.dir) < 0.0;
    if (!s.front) { ng = -ng; n = -n; }
    if (dot(n, ray.dir) > 0.0) n = ng;  // shading normal behind the ray: fall back
    s.n = n;
    s.ng = ng;
    s.uv = w * sh.uv0 + hit.u * sh.uv1 + hit.v * sh.uv2;
    s.material = sh.material;
    s.light = sh.light;
    return s;
}

BrdfInput material_at(uint index, vec2 uv) {
    GpuMaterial m = materials[index];
    BrdfInput b;
    b.base = vec3(m.base_color[0], m.base_color[1], m.base_color[2]);
    b.metallic = m.metallic;
    b.roughness = m.roughness;
    if (m.base_color_tex >= 0) b.base *= srgb_to_linear(texture_raw(m.base_color_tex, uv).rgb);
    if (m.mr_tex >= 0) {
        vec4 t = texture_raw(m.mr_tex, uv);
        b.roughness *= t.g;
        b.metallic *= t.b;
    }
    return b;
}

vec3 emission_at(uint material, vec2 uv, bool front) {
    GpuMaterial m = materials[material];
    if (!front && (m.flags & MATERIAL_DOUBLE_SIDED) == 0u) return vec3(0.0);
    vec3 e = m.emissive;
    if (m.emissive_tex >= 0) e *= srgb_to_linear(texture_raw(m.emissive_tex, uv).rgb);
    return e;
}

vec3 offset_origin(vec3 p, vec3 ng) {
    return p + ng * (1e-4 * (1.0 + max(max(abs(p.x), abs(p.y)), abs(p.z))));
}

// Solid-angle pdf of light sampling towards a point on light `li` at distance d.
float light_pdf(int li, float d, float cos_l) {
    GpuLight l = lights[li];
    return l.pdf / l.area * d * d / max(cos_l, 1e-8);
}

// Next-event estimation: one point on one emissive triangle, MIS-weighted.
vec3 sample_light(Surface s, BrdfInput m, vec3 wo, vec3 u) {
    if (scene.light_count == 0u) return vec3(0.0);
    uint lo = 0u, hi = scene.light_count - 1u;
    while (lo < hi) {  // first light with u.z < cdf
        uint mid = (lo + hi) / 2u;
        if (u.z < lights[mid].cdf) hi = mid; else lo = mid + 1u;
    }
    GpuLight l = lights[lo];
    GpuTriangle tri = bvh_triangles[l.triangle];
    TriangleShading sh = triangle_shading[l.triangle];
    float su = sqrt(u.x);
    float b1 = 1.0 - su, b2 = u.y * su;
    vec3 q = tri.v0 + b1 * tri.e1 + b2 * tri.e2;
    vec3 to = q - s.p;
    float d = length(to);
    if (d <= 0.0) return vec3(0.0);
    vec3 wi = to / d;
    vec3 nl = normalize(cross(tri.e1, tri.e2));
    if (dot(nl, sh.n0) < 0.0) nl = -nl;
    float cos_l = dot(nl, -wi);
    bool front = cos_l > 0.0;
    vec2 uv = (1.0 - b1 - b2) * sh.uv0 + b1 * sh.uv1 + b2 * sh.uv2;
    vec3 le = emission_at(sh.material, uv, front);
    cos_l = abs(cos_l);
    if (dot(s.n, wi) <= 0.0 || dot(s.ng, wi) <= 0.0 || all(equal(le, vec3(0.0)))) return vec3(0.0);
    Ray shadow = Ray(offset_origin(s.p, s.ng), 0.0, wi, d * (1.0 - 1e-4));
    if (bvh_occluded(shadow)) return vec3(0.0);
    float pl = light_pdf(int(lo), d, cos_l);
    float pb = brdf_pdf(m, s.n, wo, wi);
    return le * brdf_eval(m, s.n, wo, wi) * dot(s.n, wi) / pl * power_heuristic(pl, pb);
}

vec3 trace_path(uvec2 px, uint seed, uint index, uint s) {
    vec2 jitter = vec2(0.5);
    if ((pc.flags & TRACE_FLAG_NO_JITTER) == 0u) {
        jitter = vec2(sample_dim(px, seed, index, s, 0u), sample_dim(px, seed, index, s, 1u));
    }
    vec2 ndc = (vec2(px) + pc.view_offset + jitter) / pc.view_size * 2.0 - 1.0;
    vec3 dir = normalize(pc.cam_forward + ndc.x * pc.cam_right - ndc.y * pc.cam_up);
    Ray ray = Ray(pc.cam_origin, 0.0, dir, 1e30);
    vec3 l = vec3(0.0), throughput = vec3(1.0);
    float prev_pdf = 0.0;  // BRDF pdf of the last bounce (0: camera ray, no MIS)
    for (uint b = 0u; b < pc.max_bounces + 1u; ++b) {
        Hit hit;
        if (!bvh_closest_hit(ray, hit)) {
            l += throughput * scene.environment;
            break;
        }
        Surface srf = surface_at(ray, hit);
        vec3 le = emission_at(srf.material, srf.uv, srf.front);
        if (any(greaterThan(le, vec3(0.0)))) {
            float w = 1.0;
            if (prev_pdf > 0.0 && srf.light >= 0) {
                w = power_heuristic(prev_pdf, light_pdf(srf.light, hit.t, abs(dot(srf.ng, ray.dir))));
            }
            l += throughput * le * w;
        }
        if (b == pc.max_bounces) break;
        uint d = 2u + b * DIMS_PER_BOUNCE;
        BrdfInput m = material_at(srf.material, srf.uv);
        vec3 wo = -ray.dir;
        vec3 ul = vec3(sample_dim(px, seed, index, s, d), sample_dim(px, seed, index, s, d + 1u),
                       sample_dim(px, seed, index, s, d + 2u));
        l += throughput * sample_light(srf, m, wo, ul);
        vec3 wi;
        float u_lobe = sample_dim(px, seed, index, s, d + 3u);
        vec2 ub = vec2(sample_dim(px, seed, index, s, d + 4u), sample_dim(px, seed, index, s, d + 5u));
        if (!brdf_sample(m, srf.n, wo, u_lobe, ub, wi) || dot(srf.ng, wi) <= 0.0) break;
        float pdf = brdf_pdf(m, srf.n, wo, wi);
        if (pdf <= 0.0) break;
        throughput *= brdf_eval(m, srf.n, wo, wi) * dot(srf.n, wi) / pdf;
        prev_pdf = pdf;
        if (b >= 3u) {  // Russian roulette after a few bounces
            float q = clamp(max(throughput.r, max(throughput.g, throughput.b)), 0.05, 1.0);
            if (sample_dim(px, seed, index, s, d + 6u) >= q) break;
            throughput /= q;
        }
        ray = Ray(offset_origin(srf.p, srf.ng), 0.0, wi, 1e30);
    }
    return any(isnan(l)) || any(isinf(l)) ? vec3(0.0) : l;
}

#endif
