//! Which pixels a metric covers: edge and smooth pixels (by reference gradient) and
//! emitter-free pixels (away from visible lights). All masks come from the reference alone, so
//! every method of a configuration is measured on the same pixels.
use blueshift_analysis::Gray;

/// Relative reference gradient above which a pixel is an edge pixel (before a 1-px dilation).
pub const EDGE_THRESHOLD: f32 = 0.1;

/// Reference luminance at or above which a pixel is an emitter pixel: the linear value the
/// display shows as white. Both tonemaps of the project (shaders/image/tonemap.comp, and
/// `figures::tonemap`, which the report's images and FLIP use) multiply by the exposure (1: eval
/// never changes it) and clamp every channel at 1.0 before the sRGB curve. Rec.709 luminance
/// weights sum to 1, so a pixel at luminance 1.0 or above has at least one clipped channel:
/// the screen shows it (near) white whatever its error.
pub const DISPLAY_WHITE: f32 = 1.0;

/// How far (pixels, square neighbourhood) the emitter set grows before its complement is
/// taken as emitter-free. 4 = the radius `ceil(4 sigma)` of the P1 blur kernel: the blurred
/// error of an emitter-free pixel then contains no emitter pixel's error, so RMSE and P1 on
/// emitter-free pixels do not see the emitters at all. P2's kernel reaches 8 px and still
/// picks up a tail of them.
pub const EMITTER_DILATION: usize = 4;

/// Blur sigmas (px) of P4 and P8: the error at a spatial denoiser's scale, which keeps only low
/// frequencies.
pub const WIDE_SIGMAS: [f64; 2] = [4.0, 8.0];

/// The emitter set grows by this many sigmas for the wide blurs. Their kernels reach 4 sigma,
/// but the Gaussian's tail beyond 3 sigma carries 0.3% of its weight: enough to keep an
/// aliased light edge's error (about 100x the rest) from dominating, without the 4-sigma ring
/// that leaves few pixels at sigma 8 on a 128-px frame.
pub const WIDE_DILATION_SIGMAS: f64 = 3.0;

/// Per-pixel masks of one reference image (row-major, `w * h` entries each).
#[derive(Debug, Clone)]
pub struct Masks {
    /// Pixels at a reference edge; the smooth pixels are the rest.
    pub edge: Vec<bool>,
    /// Emitter-free pixels: not within [`EMITTER_DILATION`] px of a pixel whose reference
    /// luminance is at or above [`DISPLAY_WHITE`]. With anti-aliasing jitter, the edge of a
    /// visible light carries an aliasing error about 100x the light-transport error, which no
    /// seed permutation can move; these pixels leave it out.
    pub clean: Vec<bool>,
    /// For each of [`WIDE_SIGMAS`]: not within [`WIDE_DILATION_SIGMAS`] sigma of an emitter
    /// pixel (the emitter-free pixels of P4 and P8).
    pub far: [Vec<bool>; WIDE_SIGMAS.len()],
}

impl Masks {
    pub fn from_reference(r: &Gray) -> Self {
        let emitter: Vec<bool> = r.data.iter().map(|&v| v >= DISPLAY_WHITE).collect();
        let free = |radius: usize| -> Vec<bool> {
            dilate_square(&emitter, r.w, r.h, radius)
                .into_iter()
                .map(|e| !e)
                .collect()
        };
        Self {
            edge: edge_mask(r),
            clean: free(EMITTER_DILATION),
            far: WIDE_SIGMAS.map(|s| free((WIDE_DILATION_SIGMAS * s).ceil() as usize)),
        }
    }
}

/// Edge pixels: max forward difference of the reference luminance, relative to the image mean
/// luminance, above [`EDGE_THRESHOLD`], dilated by one pixel (4-neighbourhood).
fn edge_mask(r: &Gray) -> Vec<bool> {
    let (w, h) = (r.w, r.h);
    let scale = (r.mean() as f32).max(1e-6);
    let mut raw = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let v = r.at(x, y);
            let dx = if x + 1 < w {
                (r.at(x + 1, y) - v).abs()
            } else {
                0.0
            };
            let dy = if y + 1 < h {
                (r.at(x, y + 1) - v).abs()
            } else {
                0.0
            };
            raw[y * w + x] = dx.max(dy) / scale > EDGE_THRESHOLD;
        }
    }
    let mut edge = raw.clone();
    for y in 0..h {
        for x in 0..w {
            if raw[y * w + x] {
                for (nx, ny) in [
                    (x.wrapping_sub(1), y),
                    (x + 1, y),
                    (x, y.wrapping_sub(1)),
                    (x, y + 1),
                ] {
                    if nx < w && ny < h {
                        edge[ny * w + nx] = true;
                    }
                }
            }
        }
    }
    edge
}

/// `set` grown by `r` px in a square (Chebyshev distance): a pixel is set when any pixel within
/// `r` in x and in y is. Separable, like the blur whose support it matches: rows, then columns.
fn dilate_square(set: &[bool], w: usize, h: usize, r: usize) -> Vec<bool> {
    let mut rows = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let (lo, hi) = (x.saturating_sub(r), (x + r).min(w - 1));
            rows[y * w + x] = set[y * w + lo..=y * w + hi].iter().any(|&b| b);
        }
    }
    let mut out = vec![false; w * h];
    for y in 0..h {
        let (lo, hi) = (y.saturating_sub(r), (y + r).min(h - 1));
        for x in 0..w {
            out[y * w + x] = (lo..=hi).any(|yy| rows[yy * w + x]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_mark_a_step_edge_and_its_neighbours() {
        let r = Gray::from_fn(8, 8, |x, _| 0.1 + if x < 4 { 0.1 } else { 0.2 });
        let m = Masks::from_reference(&r);
        for y in 0..8 {
            for x in 0..8 {
                assert_eq!(m.edge[y * 8 + x], (2..=4).contains(&x), "({x},{y})");
            }
        }
        assert!(m.clean.iter().all(|&c| c), "no pixel reaches display white");
    }

    #[test]
    fn emitter_mask_is_a_bright_square_and_its_four_pixel_ring() {
        // A light of 4x5 px two pixels from the left border (its ring is clipped there), one
        // of its pixels exactly at display white, on a background below it; one isolated pixel
        // just below display white must not count.
        let (w, h) = (32, 24);
        let light = |x: usize, y: usize| (2..6).contains(&x) && (9..14).contains(&y);
        let r = Gray::from_fn(w, h, |x, y| {
            if (x, y) == (5, 13) {
                1.0
            } else if light(x, y) {
                7.5
            } else if (x, y) == (25, 4) {
                0.999
            } else {
                0.3
            }
        });
        let m = Masks::from_reference(&r);
        let lights: Vec<(i64, i64)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| light(x, y))
            .map(|(x, y)| (x as i64, y as i64))
            .collect();
        let mut emitters = 0;
        for y in 0..h {
            for x in 0..w {
                let near = lights.iter().any(|&(lx, ly)| {
                    (lx - x as i64).abs().max((ly - y as i64).abs()) <= EMITTER_DILATION as i64
                });
                emitters += usize::from(near);
                assert_eq!(m.clean[y * w + x], !near, "({x},{y})");
            }
        }
        // Columns 0..=9 (clipped at x = 0), rows 5..=17.
        assert_eq!(emitters, 10 * 13);
    }
}
