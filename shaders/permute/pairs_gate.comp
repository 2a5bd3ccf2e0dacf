#version 460
// Pairs gate of sort-grid-adaptive: folds this frame's (skewed classes, classes counted), which
// the sorting pass summed, into the smoothed share of skewed classes that the next frame's
// sort reads (SortParams::pairs == SORT_PAIRS_FROM_GATE). On the GPU so that the next frame
// need not wait for this one's counts on the CPU. Fixed point, integer arithmetic only: the
// CPU twin (crates/permute/src/pairs_gate.rs PairsGate::update) agrees exactly.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "generated/params.glsl"

layout(local_size_x = 1) in;
layout(set = 0, binding = 0, scalar) readonly buffer Stats { uint sort_stats[2]; };
// (share in units of 1 / PAIRS_GATE_ONE, 1 once a frame counted); zero for a new sequence.
layout(set = 0, binding = 1, scalar) buffer Gate { uint pairs_gate[2]; };

void main() {
    uint counted = sort_stats[1];
    if (counted == 0u) return;
    uint64_t s = uint64_t(min(sort_stats[0], counted)) * uint64_t(PAIRS_GATE_ONE) /
                 uint64_t(counted);
    uint64_t share = pairs_gate[1] == 0u ? s : (3ul * uint64_t(pairs_gate[0]) + s) / 4ul;
    pairs_gate[0] = uint(share);
    pairs_gate[1] = 1u;
}
