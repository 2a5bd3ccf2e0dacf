//! Twin of `count_skewed_classes` in sort_seeds.glsl: how many classes of a block have keys
//! skewed enough (sample skewness |g| > SKEW_LIMIT) that antithetic pairs would not cancel
//! them.
use blueshift_layout::params::{SKEW_LIMIT, SKEW_MIN_PIXELS};

/// (skewed, counted) over the classes of one block with at least SKEW_MIN_PIXELS pixels.
/// `classes` and `keys` are the block's visible pixels in order; `count` the pixels per class
/// (min(class, 63), as the shader keys them). Same float operations in the same order as the
/// shader, so the counts match exactly.
pub(crate) fn count_skewed_classes(classes: &[u32], keys: &[f32], count: &[f32; 64]) -> [u32; 2] {
    let (mut mean, mut dmax, mut m2, mut m3) = ([0f32; 64], [0f32; 64], [0f32; 64], [0f32; 64]);
    for (&c, &k) in classes.iter().zip(keys) {
        mean[c.min(63) as usize] += k;
    }
    for c in 0..64 {
        mean[c] = if count[c] > 0.0 {
            mean[c] * (1.0 / count[c])
        } else {
            0.0
        };
    }
    for (&c, &k) in classes.iter().zip(keys) {
        let c = c.min(63) as usize;
        dmax[c] = dmax[c].max((k - mean[c]).abs());
    }
    for (&c, &k) in classes.iter().zip(keys) {
        let c = c.min(63) as usize;
        let d = if dmax[c] > 0.0 {
            (k - mean[c]) * (1.0 / dmax[c])
        } else {
            0.0
        };
        let d2 = d * d;
        m2[c] += d2;
        m3[c] += d2 * d;
    }
    let mut r = [0, 0];
    for c in (0..64).filter(|&c| count[c] >= SKEW_MIN_PIXELS as f32) {
        // |g| > L  <=>  (m3 / n)^2 > L^2 (m2 / n)^3  <=>  m3^2 * n > L^2 * m2^3
        let rhs = SKEW_LIMIT * SKEW_LIMIT * m2[c] * m2[c] * m2[c];
        r[0] += u32::from(m3[c] * m3[c] * count[c] > rhs);
        r[1] += 1;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heavy_tail_is_skewed_and_a_symmetric_spread_is_not() {
        let mut count = [0f32; 64];
        count[0] = 16.0;
        count[5] = 16.0;
        count[9] = 2.0; // too small to count
        let classes: Vec<u32> = (0..34).map(|i| [0, 5, 9][(i / 16).min(2)]).collect();
        let keys: Vec<f32> = (0..34)
            .map(|i| match i {
                0..16 => i as f32 - 7.5, // symmetric: g = 0
                16 => 100.0,             // one firefly among zeros
                17..32 => 0.0,
                _ => 1000.0 * i as f32,
            })
            .collect();
        assert_eq!(count_skewed_classes(&classes, &keys, &count), [1, 2]);
    }
}
