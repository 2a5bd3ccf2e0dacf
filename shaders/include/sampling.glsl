// Per-pixel samplers driven only by (seed, sample index, dimension).
// CPU twins: crates/sampling/src/{sobol,r2,hbo19,lib}.rs (same names, same bits).
#ifndef SAMPLING_GLSL
#define SAMPLING_GLSL
#include "rng.glsl"
#include "generated/sobol.glsl"

// Unscrambled Sobol point `index`, dimension `dim` (0 or 1), bit-reversed (the form the nested
// uniform scramble consumes). Every sampler here takes Sobol's points two dimensions at a time
// (SOBOL_GROUP_DIMS = 2, block nets and HBO+19 pairs), so only these two are computed:
// dimension 0 is the index itself; dimension 1's generator matrix is Pascal's triangle mod 2,
// i.e. the superset-XOR transform of the index bits (five butterfly steps). Loop-free and
// without table lookups (llvmpipe runs a dynamically indexed const array as a per-lane gather;
// the 64 masked XORs of dimensions 2 and 3, computed for every call whatever `dim` was, were a
// large part of the samplers' cost).
uint sobol_reversed(uint index, uint dim) {
    uint x1 = index;
    x1 ^= (x1 & 0xaaaaaaaau) >> 1u;
    x1 ^= (x1 & 0xccccccccu) >> 2u;
    x1 ^= (x1 & 0xf0f0f0f0u) >> 4u;
    x1 ^= (x1 & 0xff00ff00u) >> 8u;
    x1 ^= (x1 & 0xffff0000u) >> 16u;
    return dim == 0u ? index : x1;
}

// Unscrambled Sobol point `index`, dimension `dim` (0 or 1), MSB-aligned (CPU twin: sobol()).
uint sobol(uint index, uint dim) { return bitfieldReverse(sobol_reversed(index, dim)); }

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

// Dimensions 0 and 1 of the Sobol point at `shuffled` (an already scrambled index), each
// scrambled with its own seed from the pair's `key`: the tail every Sobol-based sampler here
// shares. Dimension 0's point is the index itself (sobol_reversed), and without the double bit
// reversal of nested_uniform_scramble(sobol(shuffled, d), ...).
uvec2 scrambled_sobol_pair(uint shuffled, uint key) {
    return uvec2(bitfieldReverse(owen_hash(shuffled, hash_combine(key, 1u))),
                 bitfieldReverse(owen_hash(sobol_reversed(shuffled, 1u), hash_combine(key, 2u))));
}

// The samplers below draw dimensions two at a time (SOBOL_GROUP_DIMS = 2): `pair` p holds
// dimensions 2p and 2p + 1, which share their scramble key and shuffled index, so the trace
// computes both at once (path.glsl vertex_bits); the one-dimension forms pick one of them.
uint pair_component(uvec2 bits, uint dim) { return (dim & 1u) == 0u ? bits.x : bits.y; }

uvec2 owen_sobol_pair(uint seed, uint index, uint pair) {
    uint group_seed = hash_combine(seed, pair);
    return scrambled_sobol_pair(nested_uniform_scramble(index, group_seed), group_seed);
}

uint owen_sobol_bits(uint seed, uint index, uint dim) {
    return pair_component(owen_sobol_pair(seed, index, dim >> 1u), dim);
}

// Seeds of one block (seed >> 6) share the scrambled (0,2)-sequence of each dimension pair;
// seed & 63 at sample `index` takes point index * 64 + (seed & 63), shuffled per pair within
// its aligned 64-point chunk, so a block's seeds hold a (0,6,2)-net at every index (CPU twin:
// sobol.rs block_net_bits).
uvec2 block_net_pair(uint seed, uint index, uint pair) {
    uint key = hash_combine(seed >> 6u, pair);
    return scrambled_sobol_pair(nested_uniform_scramble((index << 6u) | (seed & 63u), key), key);
}

uint block_net_bits(uint seed, uint index, uint dim) {
    return pair_component(block_net_pair(seed, index, dim >> 1u), dim);
}

uint r2_bits(uint seed, uint index, uint dim) {
    uint offset = hash3(seed, dim, 0x5232u);
    return offset + index * ((dim & 1u) == 0u ? R2_ALPHA_X : R2_ALPHA_Y);
}

// HBO+19 keyed Owen-Sobol (crates/sampling/src/hbo19.rs): `key` = (scramble, rank) of the
// pair; pairs past the `pairs` optimised ones are plain Owen-Sobol.
uvec2 hbo19_pair(uvec2 key, uint pairs, uint seed, uint index, uint pair) {
    if (pair >= pairs) return owen_sobol_pair(seed, index, pair);
    return scrambled_sobol_pair(nested_uniform_scramble(index ^ key.y, key.x), key.x);
}

#ifdef HBO19_KEYS
// HBO19_KEYS names the includer's uvec2 key buffer: [0] = (tile edge, pairs), then the keys
// at 1 + (tile position * pairs + pair); the seed is the tile position (KeyTable::bits). The
// tile edge is a power of two (KeyTable::new checks it).
uvec2 hbo19_lookup_pair(uint seed, uint index, uint pair) {
    uvec2 hdr = HBO19_KEYS[0];
    uint tile_pair = min(pair, hdr.y - 1u);
    uvec2 key = HBO19_KEYS[1u + (seed & (hdr.x * hdr.x - 1u)) * hdr.y + tile_pair];
    return hbo19_pair(key, hdr.y, seed, index, pair);
}

uint hbo19_lookup_bits(uint seed, uint index, uint dim) {
    return pair_component(hbo19_lookup_pair(seed, index, dim >> 1u), dim);
}
#endif

// SAMPLER_HBO19 needs a key table (hbo19_lookup_pair); without one it is plain Owen-Sobol,
// as Samples::bits without keys.
uvec2 sample_pair_bits(uint kind, uint seed, uint index, uint pair) {
    if (kind == SAMPLER_SOBOL || kind == SAMPLER_HBO19) return owen_sobol_pair(seed, index, pair);
    if (kind == SAMPLER_R2)
        return uvec2(r2_bits(seed, index, 2u * pair), r2_bits(seed, index, 2u * pair + 1u));
    if (kind == SAMPLER_BLOCKNET) return block_net_pair(seed, index, pair);
    return uvec2(hash3(seed, index, 2u * pair), hash3(seed, index, 2u * pair + 1u));
}

uint sample_bits(uint kind, uint seed, uint index, uint dim) {
    return pair_component(sample_pair_bits(kind, seed, index, dim >> 1u), dim);
}

// Dimensions d .. d + 6 (a path vertex's seven) from the four pairs that hold them, `a` being
// pair d >> 1 (of the eight dimensions, the first is unused when d is odd, the last when even).
void seven_from_pairs(uvec2 a, uvec2 b, uvec2 c, uvec2 e, uint d, out uint u[7]) {
    bool odd = (d & 1u) != 0u;
    u[0] = odd ? a.y : a.x;
    u[1] = odd ? b.x : a.y;
    u[2] = odd ? b.y : b.x;
    u[3] = odd ? c.x : b.y;
    u[4] = odd ? c.y : c.x;
    u[5] = odd ? e.x : c.y;
    u[6] = odd ? e.y : e.x;
}

float sample_1d(uint kind, uint seed, uint index, uint dim) {
    return to_unit(sample_bits(kind, seed, index, dim));
}

#endif
