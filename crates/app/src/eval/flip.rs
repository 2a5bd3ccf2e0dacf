//! FLIP (NVIDIA's perceptual image difference) of the accumulated image: one per-pixel error
//! map, pooled over all pixels and over the emitter-free ones.
use super::figures::tonemap;

/// Mean FLIP of one image over all pixels and over the emitter-free pixels.
#[derive(Debug, Clone, Copy, Default)]
pub struct FlipScores {
    pub all: f64,
    /// NaN when no pixel is emitter-free.
    pub clean: f64,
}

/// Per-pixel LDR FLIP error of `test` against `reference` (both linear RGB, shown as the
/// report's images are: clamped at 1 and sRGB-encoded), row-major.
pub fn flip_map(test: &[[f32; 4]], reference: &[[f32; 4]], w: u32, h: u32) -> Vec<f32> {
    let r = nv_flip::FlipImageRgb8::with_data(w, h, &tonemap(reference));
    let t = nv_flip::FlipImageRgb8::with_data(w, h, &tonemap(test));
    nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE).to_vec()
}

/// Mean of `map` over the pixels where `mask` is true (in f64; nv_flip's own pool has no
/// mask). NaN for an empty mask.
pub fn masked_mean(map: &[f32], mask: &[bool]) -> f64 {
    let (sum, n) = map
        .iter()
        .zip(mask)
        .filter(|&(_, &on)| on)
        .fold((0.0f64, 0usize), |(s, n), (&v, _)| {
            (s + f64::from(v), n + 1)
        });
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// FLIP of `test` against `reference`, pooled over all pixels and over `clean`. The map is
/// computed once: FLIP filters the whole image, so an emitter's error still reaches the
/// emitter-free pixels next to it through FLIP's own spatial filters.
pub fn scores(
    test: &[[f32; 4]],
    reference: &[[f32; 4]],
    w: u32,
    h: u32,
    clean: &[bool],
) -> FlipScores {
    let map = flip_map(test, reference, w, h);
    FlipScores {
        all: masked_mean(&map, &vec![true; map.len()]),
        clean: masked_mean(&map, clean),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> Vec<[f32; 4]> {
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let v = f(x, y);
                [v, 0.5 * v, 0.25 + 0.5 * v, 1.0]
            })
            .collect()
    }

    #[test]
    fn pooling_over_all_pixels_is_the_plain_mean() {
        let (w, h) = (48, 40);
        let reference = image(w, h, |x, y| ((x * 7 + y * 3) % 11) as f32 / 11.0);
        let test = image(w, h, |x, y| ((x * 5 + y * 13) % 17) as f32 / 17.0);
        let map = flip_map(&test, &reference, w, h);
        // nv_flip's own pooling of the same map, computed independently of ours.
        let err = nv_flip::FlipImageFloat::with_data(w, h, &map);
        let want = f64::from(nv_flip::FlipPool::from_image(&err).mean());
        assert!(want > 0.01, "the images differ: {want}");
        let s = scores(&test, &reference, w, h, &vec![true; (w * h) as usize]);
        assert!((s.all - want).abs() <= 1e-5 * want, "{} vs {want}", s.all);
        assert_eq!(s.all, s.clean);
    }

    #[test]
    fn pooling_over_a_mask_averages_only_its_pixels() {
        let map = [0.5, 2.0, 0.25, 4.0];
        assert_eq!(masked_mean(&map, &[false, true, false, true]), 3.0);
        assert_eq!(masked_mean(&map, &[true, false, true, false]), 0.375);
        assert!(masked_mean(&map, &[false; 4]).is_nan());
    }
}
