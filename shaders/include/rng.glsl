// Integer hashes for white-noise sampling and seeds. CPU twin: crates/sampling/src/rng.rs.
#ifndef RNG_GLSL
#define RNG_GLSL

// PCG-based hash (Jarzynski & Olano 2020): LCG step + RXS-M-XS output permutation.
uint pcg_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint hash3(uint a, uint b, uint c) {
    return pcg_hash(a ^ pcg_hash(b ^ pcg_hash(c)));
}

// Top 24 bits to [0, 1), exact in float.
float to_unit(uint h) {
    return float(h >> 8u) * (1.0 / 16777216.0);
}

float white(uint seed, uint index, uint dim) {
    return to_unit(hash3(seed, index, dim));
}

uint pixel_seed(uint x, uint y, uint salt) {
    return hash3(x, y, salt ^ 0x9e3779b9u);
}

#endif
