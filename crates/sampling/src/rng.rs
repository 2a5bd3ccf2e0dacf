//! Integer hashes used for white-noise sampling and seed initialisation.

/// PCG-based 32-bit hash ("pcg" in Jarzynski & Olano 2020, "Hash Functions for GPU
/// Rendering"): one LCG step followed by PCG's RXS-M-XS output permutation. A bijection on u32
/// with good avalanche, so distinct inputs never collide.
#[inline]
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Chris Wellons' "lowbias32" (xorshift-multiply, two rounds): a cheap bijection on u32 for
/// hashing small indices where PCG's LCG step is not wanted.
#[inline]
pub fn lowbias32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// Hash of three words, each folded in with a full `pcg_hash` round.
#[inline]
pub fn hash3(a: u32, b: u32, c: u32) -> u32 {
    pcg_hash(a ^ pcg_hash(b ^ pcg_hash(c)))
}

/// Maps the top 24 bits of `h` to [0, 1): exact in f32, never returns 1.0.
#[inline]
pub fn to_unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// White-noise sample for (seed, sample index, dimension).
#[inline]
pub fn white(seed: u32, index: u32, dim: u32) -> f32 {
    to_unit(hash3(seed, index, dim))
}

/// The decorrelated initial seed of pixel (x, y) for a sequence salt.
#[inline]
pub fn pixel_seed(x: u32, y: u32, salt: u32) -> u32 {
    hash3(x, y, salt ^ 0x9e37_79b9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg_hash_is_a_bijection_on_a_window() {
        // A bijection on u32 maps 2^20 distinct inputs to 2^20 distinct outputs.
        let mut v: Vec<u32> = (0..1u32 << 20).map(pcg_hash).collect();
        v.sort_unstable();
        v.dedup();
        assert_eq!(v.len(), 1 << 20);
    }

    #[test]
    fn lowbias32_is_a_bijection_on_a_window() {
        let mut v: Vec<u32> = (0..1u32 << 20).map(|i| lowbias32(i << 12)).collect();
        v.sort_unstable();
        v.dedup();
        assert_eq!(v.len(), 1 << 20);
    }

    #[test]
    fn white_is_uniform() {
        // Mean and variance of U[0,1) within 5 standard errors over 2^18 samples.
        let n = 1 << 18;
        let xs: Vec<f64> = (0..n).map(|i| white(12345, i, 3) as f64).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        let se = (1.0 / 12.0f64 / n as f64).sqrt();
        assert!((mean - 0.5).abs() < 5.0 * se, "mean {mean}");
        assert!((var - 1.0 / 12.0).abs() < 0.002, "var {var}");
        assert!(xs.iter().all(|&x| (0.0..1.0).contains(&x)));
    }

    /// Dimensions of one sample are uncorrelated (within 5 standard errors of zero over 2^16
    /// samples), and swapping a pixel's coordinates gives another seed.
    #[test]
    fn dimensions_are_uncorrelated_and_pixels_distinct() {
        let n = 1 << 16;
        let corr = |a: u32, b: u32| {
            let c: f64 = (0..n)
                .map(|i| (white(99, i, a) as f64 - 0.5) * (white(99, i, b) as f64 - 0.5))
                .sum();
            // Pearson correlation: the covariance over the uniform variance 1/12.
            c / n as f64 * 12.0
        };
        let se = 1.0 / (n as f64).sqrt();
        for (a, b) in [(0, 1), (1, 2), (2, 3), (0, 7)] {
            let r = corr(a, b);
            assert!(r.abs() < 5.0 * se, "dims {a}, {b}: correlation {r}");
        }
        let swapped = (0..64u32)
            .flat_map(|x| (0..64u32).map(move |y| (x, y)))
            .filter(|(x, y)| x != y && pixel_seed(*x, *y, 0) == pixel_seed(*y, *x, 0))
            .count();
        assert_eq!(swapped, 0);
    }
}
