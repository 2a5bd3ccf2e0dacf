// BVH traversal: closest hit and occlusion over the scene BVH built by blueshift-scene.
// GPU twin of crates/scene/src/intersect.rs: same traversal order, same slab test, same
// Möller–Trumbore operation order (`precise` forbids fused multiply-adds, which Rust does not
// use either), ties broken by the smaller triangle index. Keep the two in sync.
//
// Requirements of the INCLUDING shader, before `#include "bvh.glsl"`:
//   #extension GL_EXT_scalar_block_layout : require
//   #include "generated/scene.glsl"             // BvhNode, GpuTriangle, Ray, Hit, BVH_STACK_SIZE
// and the two fetch functions (where the data lives is the includer's choice):
//   void bvh_load_node(uint index, out vec3 aabb_min, out vec3 aabb_max, out uint left_first,
//                      out uint count);         // the fields of BvhNode `index`
//   GpuTriangle bvh_load_triangle(uint index);  // triangle `index` of the BVH leaf order
// scene_texels.glsl defines them over the scene images (the trace shader); defining
// BVH_FROM_BUFFERS before the include defines them over
//   layout(scalar, set = S, binding = B) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
//   layout(scalar, set = S, binding = C) readonly buffer BvhTriangles { GpuTriangle bvh_triangles[]; };
// (the test shader).
//
// Shaped for llvmpipe, where every `if` runs both sides under a lane mask and only loops exit
// early (cost = instructions on all paths, times loop iterations of the slowest of the 8
// lanes): the current node's fields stay in registers (an interior node costs one fetch of
// its two children, which carries their fields; a leaf one fetch per triangle), and each
// iteration of the traversal loop descends through interior nodes in an inner loop, tests
// the leaf it reached right away, then pops. The nodes visited and triangles tested, and
// their order, are exactly those of the Rust loop (one node per iteration there).
//
// API:
//   bool bvh_closest_hit(Ray ray, out Hit hit)  closest t in [ray.tmin, ray.tmax]; on a miss
//                                               hit = {ray.tmax, HIT_MISS, 0, 0}, returns false
//   bool bvh_occluded(Ray ray)                  any hit with t in [ray.tmin, ray.tmax]
//   bool bvh_intersect_triangle(Ray, GpuTriangle, float tmax, out float t, out float u, out float v)
#ifndef BVH_GLSL
#define BVH_GLSL

// A statement run at the top of every loop iteration; the trace shader counts llvmpipe's
// loop iterations with it (trace_body.glsl). Empty by default.
#ifndef BVH_LOOP_TICK
#define BVH_LOOP_TICK
#endif

#ifdef BVH_FROM_BUFFERS
void bvh_load_node(uint index, out vec3 aabb_min, out vec3 aabb_max, out uint left_first,
                   out uint count) {
    aabb_min = bvh_nodes[index].aabb_min;
    left_first = bvh_nodes[index].left_first;
    aabb_max = bvh_nodes[index].aabb_max;
    count = bvh_nodes[index].count;
}

GpuTriangle bvh_load_triangle(uint index) { return bvh_triangles[index]; }
#endif

// Box exit distances, and the closest t they are compared with, are scaled by this so
// rounding never culls a box holding a triangle at (or within rounding of) the closest hit
// (Rust: BOX_TFAR_SCALE). Direction components below 1e-30 are replaced by +-1e-30 before
// inverting (Rust: MIN_DIR_COMPONENT).
const float BVH_TFAR_SCALE = 1.000002;
const float BVH_MIN_DIR_COMPONENT = 1e-30;

// Stack entries pack a node's (left_first, count): count < 8 (MAX_LEAF_SIZE is 4) and
// left_first < 2^29 (the scene images hold fewer texels).
const uint BVH_COUNT_BITS = 3u;

float bvh_safe_component(float x) {
    if (abs(x) < BVH_MIN_DIR_COMPONENT) {
        return x >= 0.0 ? BVH_MIN_DIR_COMPONENT : -BVH_MIN_DIR_COMPONENT;
    }
    return x;
}

vec3 bvh_safe_inverse(vec3 d) {
    precise vec3 inv = vec3(1.0 / bvh_safe_component(d.x), 1.0 / bvh_safe_component(d.y),
                            1.0 / bvh_safe_component(d.z));
    return inv;
}

// Slab test: true if the box overlaps [tmin, tmax]; tnear = entry distance.
bool bvh_box_entry(vec3 bmin, vec3 bmax, vec3 origin, vec3 inv, float tmin, float tmax,
                   out float tnear) {
    precise vec3 t0 = (bmin - origin) * inv;
    precise vec3 t1 = (bmax - origin) * inv;
    vec3 lo = min(t0, t1);
    vec3 hi = max(t0, t1);
    tnear = max(max(max(lo.x, lo.y), lo.z), tmin);
    precise float tfar = min(min(min(hi.x, hi.y), hi.z) * BVH_TFAR_SCALE, tmax * BVH_TFAR_SCALE);
    return tnear <= tfar;
}

vec3 bvh_cross(vec3 a, vec3 b) {
    precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    return c;
}

float bvh_dot(vec3 a, vec3 b) {
    precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
    return d;
}

// Möller–Trumbore; edges count as inside.
bool bvh_intersect_triangle(Ray ray, GpuTriangle tri, float tmax, out float t, out float u,
                            out float v) {
    t = 0.0;
    u = 0.0;
    v = 0.0;
    vec3 pvec = bvh_cross(ray.dir, tri.e2);
    float det = bvh_dot(tri.e1, pvec);
    if (det == 0.0) {
        return false;
    }
    precise float inv_det = 1.0 / det;
    precise vec3 tvec = ray.origin - tri.v0;
    u = bvh_dot(tvec, pvec) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) {
        return false;
    }
    vec3 qvec = bvh_cross(tvec, tri.e1);
    v = bvh_dot(ray.dir, qvec) * inv_det;
    precise float uv_sum = u + v;
    if (!(v >= 0.0 && uv_sum <= 1.0)) {
        return false;
    }
    t = bvh_dot(tri.e2, qvec) * inv_det;
    return t >= ray.tmin && t <= tmax;
}

bool bvh_closest_hit(Ray ray, out Hit hit) {
    hit.t = ray.tmax;
    hit.triangle = HIT_MISS;
    hit.u = 0.0;
    hit.v = 0.0;
    vec3 inv = bvh_safe_inverse(ray.dir);
    vec3 bmin, bmax;
    uint first, count;  // the current node
    bvh_load_node(0u, bmin, bmax, first, count);
    float t_root;
    if (!bvh_box_entry(bmin, bmax, ray.origin, inv, ray.tmin, hit.t, t_root)) {
        return false;
    }
    uint stack[BVH_STACK_SIZE];
    float stack_t[BVH_STACK_SIZE];
    uint sp = 0u;
    while (true) {
        BVH_LOOP_TICK;
        // An interior node: step to the nearer child hit (pushing the farther one).
        bool pop = false;
        while (count == 0u && !pop) {
            BVH_LOOP_TICK;
            vec3 lmin, lmax, rmin, rmax;
            uint lfirst, lcount, rfirst, rcount;
            bvh_load_node(first, lmin, lmax, lfirst, lcount);
            bvh_load_node(first + 1u, rmin, rmax, rfirst, rcount);
            float tl, tr;
            bool hl = bvh_box_entry(lmin, lmax, ray.origin, inv, ray.tmin, hit.t, tl);
            bool hr = bvh_box_entry(rmin, rmax, ray.origin, inv, ray.tmin, hit.t, tr);
            if (hl && hr) {
                bool left_near = tl <= tr;
                if (sp < BVH_STACK_SIZE) {
                    stack[sp] = left_near ? (rfirst << BVH_COUNT_BITS) | rcount
                                          : (lfirst << BVH_COUNT_BITS) | lcount;
                    stack_t[sp] = left_near ? tr : tl;
                    sp++;
                }
                first = left_near ? lfirst : rfirst;
                count = left_near ? lcount : rcount;
            } else if (hl || hr) {
                first = hl ? lfirst : rfirst;
                count = hl ? lcount : rcount;
            } else {
                pop = true;
            }
        }
        // A leaf (possibly the child just reached, in the same iteration): its triangles.
        if (count > 0u && !pop) {
            for (uint i = first; i < first + count; ++i) {
                BVH_LOOP_TICK;
                float t, u, v;
                if (bvh_intersect_triangle(ray, bvh_load_triangle(i), hit.t, t, u, v) &&
                    (t < hit.t || i < hit.triangle)) {
                    hit.t = t;
                    hit.triangle = i;
                    hit.u = u;
                    hit.v = v;
                }
            }
            pop = true;
        }
        if (pop) {
            // Pop the next far child that can still hold a closer hit.
            bool found = false;
            while (sp > 0u) {
                BVH_LOOP_TICK;
                sp--;
                if (stack_t[sp] <= hit.t * BVH_TFAR_SCALE) {
                    first = stack[sp] >> BVH_COUNT_BITS;
                    count = stack[sp] & ((1u << BVH_COUNT_BITS) - 1u);
                    found = true;
                    break;
                }
            }
            if (!found) {
                break;
            }
        }
    }
    return hit.triangle != HIT_MISS;
}

bool bvh_occluded(Ray ray) {
    vec3 inv = bvh_safe_inverse(ray.dir);
    vec3 bmin, bmax;
    uint first, count;
    bvh_load_node(0u, bmin, bmax, first, count);
    float t_root;
    if (!bvh_box_entry(bmin, bmax, ray.origin, inv, ray.tmin, ray.tmax, t_root)) {
        return false;
    }
    uint stack[BVH_STACK_SIZE];
    uint sp = 0u;
    bool occluded = false;
    while (true) {
        BVH_LOOP_TICK;
        bool pop = false;
        while (count == 0u && !pop) {
            BVH_LOOP_TICK;
            vec3 lmin, lmax, rmin, rmax;
            uint lfirst, lcount, rfirst, rcount;
            bvh_load_node(first, lmin, lmax, lfirst, lcount);
            bvh_load_node(first + 1u, rmin, rmax, rfirst, rcount);
            float tl, tr;
            bool hl = bvh_box_entry(lmin, lmax, ray.origin, inv, ray.tmin, ray.tmax, tl);
            bool hr = bvh_box_entry(rmin, rmax, ray.origin, inv, ray.tmin, ray.tmax, tr);
            if (hl && hr && sp < BVH_STACK_SIZE) {
                stack[sp] = (rfirst << BVH_COUNT_BITS) | rcount;
                sp++;
            }
            first = hl ? lfirst : rfirst;
            count = hl ? lcount : rcount;
            pop = !hl && !hr;
        }
        if (count > 0u && !pop) {
            for (uint i = first; i < first + count; ++i) {
                BVH_LOOP_TICK;
                float t, u, v;
                if (bvh_intersect_triangle(ray, bvh_load_triangle(i), ray.tmax, t, u, v)) {
                    occluded = true;
                }
            }
            pop = true;
        }
        if (occluded) {
            break;
        }
        if (pop) {
            if (sp == 0u) {
                break;
            }
            sp--;
            first = stack[sp] >> BVH_COUNT_BITS;
            count = stack[sp] & ((1u << BVH_COUNT_BITS) - 1u);
        }
    }
    return occluded;
}

#endif
