#version 460
// Point-cycle pass of sort-cycle, between the trace and the sorting pass. Each seed revisits
// the same CYCLE_FRAMES points (its sample index is the frame's phase), and seeds never leave
// their sorting block, so the estimate a seed gave at phase j, CYCLE_FRAMES frames ago and a
// few pixels away, predicts the estimate it will give at phase j again. Per pixel this pass
//   1. records (seed, key) of the frame just traced in the slot of its phase, the key minus the
//      pixel's running mean once there is one (the seed's error, which carries over to the
//      other pixels of its block better than the image value does);
//   2. loads the next phase's slot: the seeds of the block with the keys they had at that
//      phase, which the sorting pass ranks against the next frame's mask slice (once a whole
//      cycle has run; before that it passes this frame's seeds and keys through);
//   3. copies that mask slice out of the spatio-temporal volume (invocations i < N*N).
// One invocation per (x, y) < (max(width, N), max(height, N)), a workgroup per 64 pixels of a
// row: no invocation divides (llvmpipe scalarises a vector division by a run-time value), and
// a workgroup touches one run of each buffer (8x8 tiles measured twice as slow).
// CPU twin: crates/permute/src/cycle.rs cycle_keys_cpu.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "generated/params.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { CycleParams p; };
layout(set = 0, binding = 0, scalar) readonly buffer Estimate { vec4 estimate[]; };  // rgb + key
layout(set = 0, binding = 1, scalar) buffer Seeds { uint seeds[]; };                 // padded
// (seed, key bits) per phase slot and visible pixel: CYCLE_FRAMES * width * height.
layout(set = 0, binding = 2, scalar) buffer CycleHistory { uvec2 cycle_history[]; };
layout(set = 0, binding = 3, scalar) readonly buffer Volume { uint volume[]; };      // N*N*T ranks
layout(set = 0, binding = 4, scalar) writeonly buffer CycleEstimate { vec4 cycle_estimate[]; };
layout(set = 0, binding = 5, scalar) writeonly buffer CycleMask { uint cycle_mask[]; };  // N*N
// The running mean of the earlier frames (accumulate), vec4 per visible pixel.
layout(set = 0, binding = 6, scalar) readonly buffer Accum { vec4 accum[]; };

void main() {
    uvec2 q = gl_GlobalInvocationID.xy;
    uint N = p.mask_size;
    if (q.x < N && q.y < N) cycle_mask[q.y * N + q.x] = volume[(p.mask_layer * N + q.y) * N + q.x];
    if (q.x >= p.width || q.y >= p.height) return;
    uint pixels = p.width * p.height;
    uint i = q.y * p.width + q.x;
    uint s = q.y * p.stride + q.x;
    float key = estimate[i].w;
    if (p.mean_count > 0u) key -= accum[i].w;
    uint seed = seeds[s];
    cycle_history[p.phase * pixels + i] = uvec2(seed, floatBitsToUint(key));
    if (p.next_valid != 0u) {
        uvec2 h = cycle_history[p.next_phase * pixels + i];
        seeds[s] = h.x;
        key = uintBitsToFloat(h.y);
    }
    cycle_estimate[i] = vec4(0.0, 0.0, 0.0, key);
}
