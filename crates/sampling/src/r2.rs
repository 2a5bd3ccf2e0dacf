//! R2 (Roberts 2018): the additive recurrence with the plastic number's inverse powers, in
//! 32-bit fixed point so GPU and CPU agree exactly. Each pair of dimensions is one R2 sequence
//! with a per-seed Cranley-Patterson rotation (random offset).

use crate::rng::hash3;

/// The plastic number g, root of x^3 = x + 1.
pub const PLASTIC: f64 = 1.324_717_957_244_746;

/// 1/g and 1/g^2 as 32-bit fractions (round(2^32 / g), round(2^32 / g^2)).
pub const ALPHA: [u32; 2] = [3_242_174_889, 2_447_445_414];

/// R2 sample `dim` of point `index` with a Cranley-Patterson offset from (seed, dim).
#[inline]
pub fn r2_bits(seed: u32, index: u32, dim: u32) -> u32 {
    let offset = hash3(seed, dim, 0x5232);
    offset.wrapping_add(index.wrapping_mul(ALPHA[(dim & 1) as usize]))
}

/// R2 sample in [0, 1).
#[inline]
pub fn r2(seed: u32, index: u32, dim: u32) -> f32 {
    crate::rng::to_unit(r2_bits(seed, index, dim))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_matches_the_plastic_number() {
        assert_eq!(ALPHA[0], (4_294_967_296.0 / PLASTIC).round() as u32);
        assert_eq!(
            ALPHA[1],
            (4_294_967_296.0 / (PLASTIC * PLASTIC)).round() as u32
        );
        assert!((PLASTIC.powi(3) - PLASTIC - 1.0).abs() < 1e-12);
    }

    #[test]
    fn r2_points_are_well_spread() {
        // Low discrepancy: each of 16x16 cells gets close to n/256 of 4096 points (<= 2x off).
        let n = 4096;
        let mut cells = [0u32; 256];
        for i in 0..n {
            let (x, y) = (r2(9, i, 0), r2(9, i, 1));
            cells[(y * 16.0) as usize * 16 + (x * 16.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| (8..=32).contains(&c)), "{cells:?}");
    }
}
