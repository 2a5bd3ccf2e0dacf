// Per-pixel samplers driven only by (seed, sample index, dimension).
// CPU twins: crates/sampling/src/{sobol,r2,lib}.rs (same names, same bits).
#ifndef SAMPLING_GLSL
#define SAMPLING_GLSL
#include "rng.glsl"
#include "generated/sobol.glsl"

uint sobol(uint index, uint dim) {
    uint x = 0u;
    for (uint bit = 0u; index != 0u; index >>= 1u, ++bit) {
        if ((index & 1u) != 0u) x ^= SOBOL_DIRECTIONS[dim * 32u + bit];
    }
    return x;
}

// Vegdahl's revised LK-style hash on bit-reversed values (see sobol.rs for why this one).
uint owen_hash(uint x, uint seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

uint nested_uniform_scramble(uint x, uint seed) {
    return bitfieldReverse(owen_hash(bitfieldReverse(x), seed));
}

uint hash_combine(uint seed, uint v) {
    return pcg_hash(seed ^ (v + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

uint owen_sobol_bits(uint seed, uint index, uint dim) {
    uint group_seed = hash_combine(seed, dim / SOBOL_GROUP_DIMS);
    uint d = dim % SOBOL_GROUP_DIMS;
    uint shuffled = nested_uniform_scramble(index, group_seed);
    return nested_uniform_scramble(sobol(shuffled, d), hash_combine(group_seed, d + 1u));
}

uint r2_bits(uint seed, uint index, uint dim) {
    uint offset = hash3(seed, dim, 0x5232u);
    return offset + index * ((dim & 1u) == 0u ? R2_ALPHA_X : R2_ALPHA_Y);
}

uint sample_bits(uint kind, uint seed, uint index, uint dim) {
    if (kind == SAMPLER_SOBOL) return owen_sobol_bits(seed, index, dim);
    if (kind == SAMPLER_R2) return r2_bits(seed, index, dim);
    return hash3(seed, index, dim);
}

float sample_1d(uint kind, uint seed, uint index, uint dim) {
    return to_unit(sample_bits(kind, seed, index, dim));
}

#endif
