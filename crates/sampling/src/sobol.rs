//! Owen-scrambled Sobol after Burley 2020 ("Practical Hash-based Owen Scrambling"): the sample
//! index is shuffled by a nested uniform scramble, the Sobol point is computed from direction
//! numbers, and each coordinate is Owen-scrambled with its own seed. The sequence is padded by
//! pairs: each pair of dimensions (2k, 2k+1) takes Sobol dimensions 0 and 1 with a fresh seed
//! (hash of seed and pair) and its own index shuffle, as pbrt-v4's padded Sobol sampler does.
//! Pairs rather than Burley's groups of four because Sobol dimensions 2-3 are no (0,2)-sequence,
//! and the path tracer draws its samples in pairs (lens, light, BSDF): with groups of four, every
//! second pair (the light sample among them) lost the (0,2)-net property.
//!
//! The hash inside the scramble is Vegdahl's revised Laine-Karras-style permutation
//! ("Building a Better LK Hash", 2021, second version of the constants), not Burley's original
//! LK constants: Vegdahl measured clearly better avalanche between bits, which matters here
//! because every pixel gets its own seed and correlated scrambles would show up as structure
//! across pixels. Both are valid nested scrambles (each bit of the reversed value is changed
//! only depending on lower reversed bits), so the (0,m,2)-net property survives (see tests).

use crate::rng::pcg_hash;

/// Dimensions per padded Sobol group (then the seed and the index shuffle are re-hashed).
pub const GROUP_DIMS: u32 = 2;

/// Joe & Kuo (new-joe-kuo-6.21201) parameters for dimensions 2..4: (degree s, a, m_1..m_s).
const JOE_KUO: [(u32, u32, [u32; 3]); 3] =
    [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])];

/// The 32 MSB-aligned direction numbers of each of the first four Sobol dimensions.
pub fn direction_numbers() -> [[u32; 32]; 4] {
    let mut v = [[0u32; 32]; 4];
    for (i, d) in v[0].iter_mut().enumerate() {
        *d = 1u32 << (31 - i);
    }
    for (dim, &(s, a, m)) in JOE_KUO.iter().enumerate() {
        let s = s as usize;
        let out = &mut v[dim + 1];
        for k in 0..s {
            out[k] = m[k] << (31 - k);
        }
        for k in s..32 {
            let mut x = out[k - s] ^ (out[k - s] >> s);
            for j in 1..s {
                if (a >> (s - 1 - j)) & 1 == 1 {
                    x ^= out[k - j];
                }
            }
            out[k] = x;
        }
    }
    v
}

/// Unscrambled Sobol coordinate `dim` (0..4) of point `index`, as a 32-bit fraction.
pub fn sobol(index: u32, dim: u32, dirs: &[[u32; 32]; 4]) -> u32 {
    let mut x = 0u32;
    let mut i = index;
    let mut bit = 0;
    while i != 0 {
        if i & 1 == 1 {
            x ^= dirs[dim as usize][bit];
        }
        i >>= 1;
        bit += 1;
    }
    x
}

/// Vegdahl's revised LK-style hash on bit-reversed values (see module docs).
#[inline]
pub fn owen_hash(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3d20_adea);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6c56);
    x ^= x.wrapping_mul(0x53a2_2864);
    x
}

/// Nested uniform (Owen) scramble of a 32-bit fraction.
#[inline]
pub fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    owen_hash(x.reverse_bits(), seed).reverse_bits()
}

/// Combines a seed with a small integer (boost-style mixing, then one PCG round).
#[inline]
pub fn hash_combine(seed: u32, v: u32) -> u32 {
    pcg_hash(
        seed ^ (v
            .wrapping_add(0x9e37_79b9)
            .wrapping_add(seed << 6)
            .wrapping_add(seed >> 2)),
    )
}

/// Owen-scrambled, shuffled Sobol sample as a 32-bit fraction.
pub fn owen_sobol_bits(seed: u32, index: u32, dim: u32, dirs: &[[u32; 32]; 4]) -> u32 {
    let group_seed = hash_combine(seed, dim / GROUP_DIMS);
    let d = dim % GROUP_DIMS;
    let shuffled = nested_uniform_scramble(index, group_seed);
    nested_uniform_scramble(sobol(shuffled, d, dirs), hash_combine(group_seed, d + 1))
}

/// Seed bits that number a seed within its block for [`block_net_bits`]: 64 seeds per block.
pub const BLOCK_NET_LOCAL_BITS: u32 = 6;

/// Block-net sample as a 32-bit fraction: the seeds of one block (equal `seed >> 6`) share one
/// Owen-scrambled Sobol (0,2)-sequence per pair of dimensions, and seed `seed & 63` at sample
/// `index` takes point `index * 64 + (seed & 63)` of it, shuffled per pair by a nested
/// uniform scramble of the point number (which maps each aligned 64-point chunk onto a whole
/// chunk, and decorrelates the pairs). So whatever pixel each seed sits on, the block's seeds
/// at any one index together hold a (0,6,2)-net in every pair (the light sample's included),
/// which keeps the block's mean error small in every frame; the permutation passes only
/// arrange it (`sort-cycle`). Pairs, as in [`owen_sobol_bits`].
pub fn block_net_bits(seed: u32, index: u32, dim: u32, dirs: &[[u32; 32]; 4]) -> u32 {
    let key = hash_combine(seed >> BLOCK_NET_LOCAL_BITS, dim / 2);
    let local = seed & ((1 << BLOCK_NET_LOCAL_BITS) - 1);
    let point = nested_uniform_scramble((index << BLOCK_NET_LOCAL_BITS) | local, key);
    let d = dim % 2;
    nested_uniform_scramble(sobol(point, d, dirs), hash_combine(key, d + 1))
}

/// Every elementary interval of area 2^-m holds exactly one of the first 2^m points.
#[cfg(test)]
pub(crate) fn is_0m2_net(points: &[(u32, u32)], m: u32) -> bool {
    (0..=m).all(|k| {
        let (bx, by) = (k, m - k);
        let mut seen = vec![false; 1 << m];
        points.iter().all(|&(x, y)| {
            // u64 so that a shift by 32 (zero bits on an axis) is defined and gives 0.
            let cell = ((x as u64 >> (32 - bx)) << by | (y as u64 >> (32 - by))) as usize;
            !std::mem::replace(&mut seen[cell], true)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At any index, the 64 seeds of a block hold a (0,6,2)-net in every pair of dimensions,
    /// and one seed's points over 16 consecutive indices are distinct.
    #[test]
    fn block_net_seeds_of_a_block_form_a_net_at_every_index() {
        let dirs = direction_numbers();
        for block in [0u32, 7, 0x3ff_ffff] {
            for index in [0u32, 1, 5, 15, 1000] {
                for pair in 0..5 {
                    let pts: Vec<_> = (0..64)
                        .map(|l| {
                            let seed = block << 6 | l;
                            let dim = pair * 2;
                            (
                                block_net_bits(seed, index, dim, &dirs),
                                block_net_bits(seed, index, dim + 1, &dirs),
                            )
                        })
                        .collect();
                    assert!(
                        is_0m2_net(&pts, 6),
                        "block {block} index {index} pair {pair}"
                    );
                }
            }
        }
        let mut xs: Vec<u32> = (0..16)
            .map(|i| block_net_bits(3 << 6 | 9, i, 0, &dirs))
            .collect();
        xs.sort_unstable();
        xs.dedup();
        assert_eq!(xs.len(), 16);
    }

    #[test]
    fn sobol_dims_0_1_are_0m2_nets_unscrambled() {
        let dirs = direction_numbers();
        for m in 1..=12 {
            let pts: Vec<_> = (0..1u32 << m)
                .map(|i| (sobol(i, 0, &dirs), sobol(i, 1, &dirs)))
                .collect();
            assert!(is_0m2_net(&pts, m), "m = {m}");
        }
    }

    #[test]
    fn every_owen_scrambled_pair_is_a_0m2_net() {
        // Every pair the path tracer draws (lens, light, BSDF at each vertex), not only the
        // first of each group: the light sample sits on dimensions 2-3.
        let dirs = direction_numbers();
        for seed in [0u32, 1, 0xdead_beef, 12345] {
            for pair in 0..8 {
                for m in 1..=12 {
                    let d = 2 * pair;
                    let pts: Vec<_> = (0..1u32 << m)
                        .map(|i| {
                            (
                                owen_sobol_bits(seed, i, d, &dirs),
                                owen_sobol_bits(seed, i, d + 1, &dirs),
                            )
                        })
                        .collect();
                    assert!(is_0m2_net(&pts, m), "seed {seed} pair {pair} m {m}");
                }
            }
        }
    }

    #[test]
    fn every_dimension_is_stratified_in_1d() {
        let dirs = direction_numbers();
        for dim in 0..8 {
            let m = 10;
            let mut seen = vec![false; 1 << m];
            for i in 0..1u32 << m {
                let cell = (owen_sobol_bits(77, i, dim, &dirs) >> (32 - m)) as usize;
                assert!(!std::mem::replace(&mut seen[cell], true), "dim {dim}");
            }
        }
    }

    #[test]
    fn scrambling_changes_points_and_is_deterministic() {
        let dirs = direction_numbers();
        let a: Vec<_> = (0..16).map(|i| owen_sobol_bits(1, i, 0, &dirs)).collect();
        let b: Vec<_> = (0..16).map(|i| owen_sobol_bits(2, i, 0, &dirs)).collect();
        let a2: Vec<_> = (0..16).map(|i| owen_sobol_bits(1, i, 0, &dirs)).collect();
        assert_ne!(a, b);
        assert_eq!(a, a2);
    }
}
