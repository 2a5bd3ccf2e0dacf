//! Threshold dithering against a tiled mask (thesis section 2.2).
//!
//! The thesis rule: for a gray level `p` in [0, 1], output **black where the mask value
//! `<= p`**, white otherwise. With the mask value of a rank taken as its threshold
//! `(rank + 0.5) / n^2`, a constant `p` makes `round(p n^2)` of every `n^2` pixels black:
//! the black fraction is within `0.5 / n^2` of `p`. So `p` is the *probability of black*
//! (darkness). Images store brightness, so the CLI uses `p = 1 - value` by default
//! (`--gray-is brightness`), which keeps the picture positive; `--gray-is darkness` feeds the
//! pixel value to the rule unchanged.

use blueshift_analysis::Gray;
use blueshift_analysis::assets::Mask;

/// `true` (black) where `threshold(mask(x mod n, y mod n)) <= p(x, y)`.
pub fn dither_black(p: &Gray, mask: &Mask) -> Vec<bool> {
    let n = mask.n;
    let mut out = Vec::with_capacity(p.w * p.h);
    for y in 0..p.h {
        for x in 0..p.w {
            let t = mask.threshold(mask.ranks[(y % n) * n + x % n]);
            out.push(t <= p.at(x, y));
        }
    }
    out
}

/// Black = 0, white = 255 image of [`dither_black`].
pub fn dither_image(p: &Gray, mask: &Mask) -> image::GrayImage {
    let px: Vec<u8> = dither_black(p, mask)
        .into_iter()
        .map(|b| if b { 0 } else { 255 })
        .collect();
    image::GrayImage::from_raw(p.w as u32, p.h as u32, px)
        .unwrap_or_else(|| image::GrayImage::new(p.w as u32, p.h as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voidcluster::{VcParams, void_and_cluster};

    #[test]
    fn constant_gray_gives_its_black_fraction() {
        let n = 32;
        let mask = Mask::new(
            n,
            void_and_cluster(&VcParams::new_2d(n, 5), &mut |_| {}).unwrap(),
        )
        .unwrap();
        for i in 0..=40 {
            let g = i as f32 / 40.0;
            let img = Gray::from_fn(n, n, |_, _| g);
            let black = dither_black(&img, &mask).iter().filter(|b| **b).count();
            let frac = black as f64 / (n * n) as f64;
            assert!(
                (frac - f64::from(g)).abs() <= 1.0 / (n * n) as f64,
                "g {g}: black fraction {frac}"
            );
        }
    }
}
