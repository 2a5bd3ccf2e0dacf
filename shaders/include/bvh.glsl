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
//                      out uint count, out uint skip);  // the fields of BvhNode `index`
//   void bvh_load_children(uint first, out vec3 lmin, out vec3 lmax, out uint lfirst,
//                          out uint lcount, out vec3 rmin, out vec3 rmax, out uint rfirst,
//                          out uint rcount);  // nodes `first` and `first + 1`
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
// the leaf it reached right away, then pops. Occlusion needs no stack (see bvh_occluded).
// The nodes visited and triangles tested, and their order, are exactly those of the Rust
// loops (one node per iteration there).
// Inner loops are written bottom-tested (`if (c) do { .. } while (c)`): llvmpipe runs a loop
// body once more after the last lane's last iteration when the test is at the top (the exit
// check sees the mask only at the end of the body), which cost 16% of the pass here.
//
// API:
//   bool bvh_closest_hit(Ray ray, out Hit hit)  closest t in [ray.tmin, ray.tmax]; on a miss
//                                               hit = {ray.tmax, HIT_MISS, 0, 0}, returns false
//   bool bvh_occluded(Ray ray)                  any hit with t in [ray.tmin, ray.tmax]
//   bool bvh_intersect_triangle(Ray, GpuTriangle, float tmax, out float t, out float u, out float v)
#ifndef BVH_GLSL
#define BVH_GLSL

// A statement run at the top of every loop iteration, given the loop's TRACE_LOOP_* id (the
// params header); the trace shader counts llvmpipe's loop iterations with it
// (trace_body.glsl). Empty by default.
#ifndef BVH_LOOP_TICK
#define BVH_LOOP_TICK(loop)
#endif

#ifdef BVH_FROM_BUFFERS
void bvh_load_node(uint index, out vec3 aabb_min, out vec3 aabb_max, out uint left_first,
                   out uint count, out uint skip) {
    aabb_min = bvh_nodes[index].aabb_min;
    left_first = bvh_nodes[index].left_first;
    aabb_max = bvh_nodes[index].aabb_max;
    count = bvh_nodes[index].count;
    skip = bvh_nodes[index].skip;
}

void bvh_load_children(uint first, out vec3 lmin, out vec3 lmax, out uint lfirst,
                       out uint lcount, out vec3 rmin, out vec3 rmax, out uint rfirst,
                       out uint rcount) {
    uint skip;
    bvh_load_node(first, lmin, lmax, lfirst, lcount, skip);
    bvh_load_node(first + 1u, rmin, rmax, rfirst, rcount, skip);
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

// min / max without NaN handling (one instruction on x86; the slab test's values are never
// NaN: inv is finite and nonzero, box corners are finite or the empty box's infinities).
float bvh_fmin(float a, float b) { return a < b ? a : b; }
float bvh_fmax(float a, float b) { return a > b ? a : b; }

// Slab test: true if the box overlaps [tmin, tmax]; tnear = entry distance.
bool bvh_box_entry(vec3 bmin, vec3 bmax, vec3 origin, vec3 inv, float tmin, float tmax,
                   out float tnear) {
    precise vec3 t0 = (bmin - origin) * inv;
    precise vec3 t1 = (bmax - origin) * inv;
    bvec3 lt = lessThan(t0, t1);
    vec3 lo = mix(t1, t0, lt);
    vec3 hi = mix(t0, t1, lt);
    tnear = bvh_fmax(bvh_fmax(bvh_fmax(lo.x, lo.y), lo.z), tmin);
    precise float far = bvh_fmin(bvh_fmin(hi.x, hi.y), hi.z) * BVH_TFAR_SCALE;
    precise float tmax_s = tmax * BVH_TFAR_SCALE;
    float tfar = bvh_fmin(far, tmax_s);
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

// Möller–Trumbore; edges count as inside. Straight-line: a zero determinant makes u infinite
// or NaN, which fails the u test like the early exit of the Rust twin (t, u, v are only
// meaningful when this returns true).
bool bvh_intersect_triangle(Ray ray, GpuTriangle tri, float tmax, out float t, out float u,
                            out float v) {
    vec3 pvec = bvh_cross(ray.dir, tri.e2);
    float det = bvh_dot(tri.e1, pvec);
    precise float inv_det = 1.0 / det;
    precise vec3 tvec = ray.origin - tri.v0;
    u = bvh_dot(tvec, pvec) * inv_det;
    vec3 qvec = bvh_cross(tvec, tri.e1);
    v = bvh_dot(ray.dir, qvec) * inv_det;
    precise float uv_sum = u + v;
    t = bvh_dot(tri.e2, qvec) * inv_det;
    return u >= 0.0 && u <= 1.0 && v >= 0.0 && uv_sum <= 1.0 && t >= ray.tmin && t <= tmax;
}

bool bvh_closest_hit(Ray ray, out Hit hit) {
    hit.t = ray.tmax;
    hit.triangle = HIT_MISS;
    hit.u = 0.0;
    hit.v = 0.0;
    vec3 inv = bvh_safe_inverse(ray.dir);
    vec3 bmin, bmax;
    uint first, count, skip;  // the current node
    bvh_load_node(0u, bmin, bmax, first, count, skip);
    float t_root;
    if (!bvh_box_entry(bmin, bmax, ray.origin, inv, ray.tmin, hit.t, t_root)) {
        return false;
    }
    uint stack[BVH_STACK_SIZE];
    float stack_t[BVH_STACK_SIZE];
    uint sp = 0u;
    while (true) {
        BVH_LOOP_TICK(TRACE_LOOP_CLOSEST_HIT);
        // An interior node: step to the nearer child hit (pushing the farther one).
        bool pop = false;
        if (count == 0u) {
            do {
                BVH_LOOP_TICK(TRACE_LOOP_CLOSEST_DESCEND);
                vec3 lmin, lmax, rmin, rmax;
                uint lfirst, lcount, rfirst, rcount;
                bvh_load_children(first, lmin, lmax, lfirst, lcount, rmin, rmax, rfirst,
                                  rcount);
                float tl, tr;
                bool hl = bvh_box_entry(lmin, lmax, ray.origin, inv, ray.tmin, hit.t, tl);
                bool hr = bvh_box_entry(rmin, rmax, ray.origin, inv, ray.tmin, hit.t, tr);
                // Branch-free selects (llvmpipe runs every branch anyway): go to the left
                // child if it is hit and nearer than the right one or the only one hit.
                bool go_left = hl && (!hr || tl <= tr);
                if (hl && hr && sp < BVH_STACK_SIZE) {
                    stack[sp] = go_left ? (rfirst << BVH_COUNT_BITS) | rcount
                                        : (lfirst << BVH_COUNT_BITS) | lcount;
                    stack_t[sp] = go_left ? tr : tl;
                    sp++;
                }
                pop = !hl && !hr;
                first = pop ? first : go_left ? lfirst : rfirst;
                count = pop ? count : go_left ? lcount : rcount;
            } while (count == 0u && !pop);
        }
        // A leaf (possibly the child just reached, in the same iteration): its triangles.
        if (count > 0u && !pop) {
            uint i = first, end = first + count;
            do {
                BVH_LOOP_TICK(TRACE_LOOP_CLOSEST_LEAF);
                float t, u, v;
                if (bvh_intersect_triangle(ray, bvh_load_triangle(i), hit.t, t, u, v) &&
                    (t < hit.t || i < hit.triangle)) {
                    hit.t = t;
                    hit.triangle = i;
                    hit.u = u;
                    hit.v = v;
                }
                i++;
            } while (i < end);
            pop = true;
        }
        if (pop) {
            // Pop the next far child that can still hold a closer hit.
            bool found = false;
            if (sp > 0u) {
                do {
                    BVH_LOOP_TICK(TRACE_LOOP_CLOSEST_POP);
                    sp--;
                    if (stack_t[sp] <= hit.t * BVH_TFAR_SCALE) {
                        first = stack[sp] >> BVH_COUNT_BITS;
                        count = stack[sp] & ((1u << BVH_COUNT_BITS) - 1u);
                        found = true;
                    }
                } while (!found && sp > 0u);
            }
            if (!found) {
                break;
            }
        }
    }
    return hit.triangle != HIT_MISS;
}

// Stackless: any hit needs no front-to-back order, so the traversal follows the skip links
// (BvhNode::skip: into the left child on a box hit, else past the subtree; node 0 = done).
// A node costs a fetch of its own two texels and one slab test and nothing is pushed (the
// stack's per-lane stores were a fifth of an interior step of the closest hit; measured 26%
// more samples per CPU second on the Cornell box than the stack traversal). The inner
// loop walks to the next leaf whose box is hit. Only loop-carried values
// (read before they are written in the body) leave the loop: llvmpipe does not keep a lane's
// own last values of the others for use after the loop. So the leaf's fields are kept by
// selects (5% faster than fetching the leaf again).
bool bvh_occluded(Ray ray) {
    vec3 inv = bvh_safe_inverse(ray.dir);
    uint node = 0u, leaf_first = 0u, leaf_count = 0u, leaf_skip = 0u;
    bool occluded = false;
    do {
        BVH_LOOP_TICK(TRACE_LOOP_OCCLUSION);
        leaf_count = 0u;  // no leaf reached yet
        bool walk = true;
        do {
            BVH_LOOP_TICK(TRACE_LOOP_OCCLUSION_WALK);
            vec3 bmin, bmax;
            uint first, count, skip;
            bvh_load_node(node, bmin, bmax, first, count, skip);
            float tnear;
            bool hit = bvh_box_entry(bmin, bmax, ray.origin, inv, ray.tmin, ray.tmax, tnear);
            bool leaf = hit && count > 0u;
            leaf_first = leaf ? first : leaf_first;
            leaf_count = leaf ? count : leaf_count;
            leaf_skip = leaf ? skip : leaf_skip;
            node = hit ? first : skip;
            walk = !leaf && node != 0u;
        } while (walk);
        if (leaf_count > 0u) {
            uint i = leaf_first, end = leaf_first + leaf_count;
            do {
                BVH_LOOP_TICK(TRACE_LOOP_OCCLUSION_LEAF);
                float t, u, v;
                if (bvh_intersect_triangle(ray, bvh_load_triangle(i), ray.tmax, t, u, v)) {
                    occluded = true;
                }
                i++;
            } while (i < end);
            node = leaf_skip;
        }
    } while (node != 0u && !occluded);
    return occluded;
}

#endif
