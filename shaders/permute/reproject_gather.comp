#version 460
// Seed reprojection, step 3 of 5: a pixel whose claim won takes its source's seed; the others
// are holes. Counts per padded row the holes and the unclaimed sources (their seeds are the
// leftovers), and sums the winners' motion (clamped) for the mask to follow the image.
// CPU twin: crates/permute/src/reproject.rs reproject_seeds_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "generated/motion.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { MotionParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Src { uint src[]; };
layout(set = 0, binding = 1, scalar) readonly buffer Claim { uint claim[]; };
layout(set = 0, binding = 2, scalar) readonly buffer SeedsIn { uint seeds_in[]; };
layout(set = 0, binding = 3, scalar) writeonly buffer SeedsOut { uint seeds_out[]; };
// [2y] = holes in padded row y, [2y + 1] = unclaimed pixels in row y (zero-filled).
layout(set = 0, binding = 4, scalar) buffer Rows { uint rows[]; };
// Sum of dx, sum of dy, count over the winners (zero-filled).
layout(set = 0, binding = 5, scalar) buffer Motion { int motion[]; };

void main() {
    uint q = gl_GlobalInvocationID.x;
    if (q >= p.padded_width * p.padded_height) return;
    uint s = src[q];
    bool won = s != REPROJECT_NONE && claim[s] == q;
    uint y = q / p.padded_width;
    uint sc = won ? s : q;
    ivec2 m = ivec2(q % p.padded_width, y) - ivec2(sc % p.padded_width, sc / p.padded_width);
    m = clamp(m, ivec2(-REPROJECT_MAX_MOTION), ivec2(REPROJECT_MAX_MOTION));
    if (won) seeds_out[q] = seeds_in[s];
    else atomicAdd(rows[2u * y], 1u);
    // Motion sums: one atomic per subgroup instead of three per pixel (one address for the
    // whole screen would serialise every invocation). Integer sums: order-independent.
    ivec3 sum = subgroupAdd(won ? ivec3(m, 1) : ivec3(0));
    if (subgroupElect() && sum.z > 0) {
        atomicAdd(motion[0], sum.x);
        atomicAdd(motion[1], sum.y);
        atomicAdd(motion[2], sum.z);
    }
    if (claim[q] == REPROJECT_NONE) atomicAdd(rows[2u * y + 1u], 1u);
}
