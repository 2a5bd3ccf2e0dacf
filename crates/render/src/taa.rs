//! Accumulation along the motion (TAA), the temporal filter a moving camera's viewer sees: the
//! CPU twin of the `taa` pass (shaders/image/taa.comp), and what `eval` measures with.
//!
//! An exponential moving average of screen pixels keeps, under motion, the per-pixel structure
//! of screen-fixed patterns (Sobol indices, mask slices) that a real temporal filter never
//! sees: a real one follows the surface. So each pixel takes the surface point it sees at its
//! centre (the G-buffer's hit point), projects it with the previous frame's camera, and fetches
//! the previous accumulation there bilinearly; each of the four taps whose pixel showed another
//! surface (`blueshift_permute::similar`, the reprojection passes' test) is dropped and the
//! surviving weights renormalised; with no tap left the history restarts from this frame. Then
//! it blends with alpha [`ALPHA`].
//!
//! The operator is linear in the images it filters and the same for every method, so applied
//! to error images it gives the filtered estimate minus the filtered reference. The taps and
//! weights depend only on the camera path ([`Reprojection`], computed once per frame), never
//! on the method being measured. With a still camera every pixel keeps its own value with
//! weight 1 and the operator is the EMA of `metrics`, bit for bit.
use blueshift_layout::motion::{GBufferTexel, TAA_ALPHA, TAA_SNAP};
use blueshift_permute::{MotionParams, project_previous, similar};
use glam::Vec2;

/// Weight of the newest frame (the EMA's).
pub const ALPHA: f32 = TAA_ALPHA;
/// Bilinear positions are rounded to 1/SNAP px (see [`TAA_SNAP`]).
pub const SNAP: f32 = TAA_SNAP;

/// One pixel's history: up to four (previous pixel, weight) taps, weights summing to 1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Taps {
    at: [u32; 4],
    w: [f32; 4],
    n: u8,
}

/// Where every pixel of a frame finds its history in the previous frame's accumulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Reprojection {
    taps: Vec<Taps>,
    /// Mean screen-space displacement (px) of the pixel-centre hit points seen by both
    /// cameras (in front of the previous one), 0 when none is.
    pub motion_px: f64,
}

impl Reprojection {
    /// A still camera: every pixel keeps its own history.
    pub fn still(pixels: usize) -> Self {
        let own = |i: usize| Taps {
            at: [i as u32, 0, 0, 0],
            w: [1.0, 0.0, 0.0, 0.0],
            n: 1,
        };
        Self {
            taps: (0..pixels).map(own).collect(),
            motion_px: 0.0,
        }
    }

    /// From this frame's and the previous frame's G-buffers (`w x h`, row-major) and the
    /// previous camera `prev` (pixels that see nothing restart).
    pub fn new(
        cur: &[GBufferTexel],
        prev: &[GBufferTexel],
        prev_cam: &MotionParams,
        w: u32,
    ) -> Self {
        let (mut moved, mut seen) = (0.0f64, 0usize);
        let sources: Vec<Option<Vec2>> = cur
            .iter()
            .enumerate()
            .map(|(i, g)| {
                if g.material == 0 {
                    return None;
                }
                let (c, z) = project_previous(prev_cam, g.position);
                if z.is_nan() || z <= 0.0 || !c.is_finite() {
                    return None;
                }
                let centre = Vec2::new((i as u32 % w) as f32, (i as u32 / w) as f32) + 0.5;
                moved += f64::from((c - centre).length());
                seen += 1;
                Some(c)
            })
            .collect();
        let mut r = Self::from_sources(cur, prev, &sources, w);
        r.motion_px = if seen == 0 { 0.0 } else { moved / seen as f64 };
        r
    }

    /// From the previous-frame position of every pixel's surface (pixel centres at `x + 0.5`;
    /// `None`: nothing to follow): bilinear taps, those on another surface or off screen
    /// dropped, the rest renormalised.
    pub fn from_sources(
        cur: &[GBufferTexel],
        prev: &[GBufferTexel],
        sources: &[Option<Vec2>],
        w: u32,
    ) -> Self {
        let h = (cur.len() / w.max(1) as usize) as i64;
        let taps = cur
            .iter()
            .zip(sources)
            .map(|(g, s)| {
                let mut t = Taps::default();
                let Some(c) = s else {
                    return t;
                };
                // Snapped to 1/SNAP px (see TAA_SNAP).
                let p = ((*c - 0.5) * SNAP).round() / SNAP;
                let (x0, y0) = (p.x.floor(), p.y.floor());
                let (fx, fy) = (p.x - x0, p.y - y0);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let corners = [
                    (x0, y0, (1.0 - fx) * (1.0 - fy)),
                    (x0 + 1, y0, fx * (1.0 - fy)),
                    (x0, y0 + 1, (1.0 - fx) * fy),
                    (x0 + 1, y0 + 1, fx * fy),
                ];
                let mut sum = 0.0f32;
                for (x, y, wt) in corners {
                    let inside = x >= 0 && y >= 0 && x < i64::from(w) && y < h;
                    if wt > 0.0 && inside {
                        let at = (y * i64::from(w) + x) as usize;
                        if similar(g, &prev[at]) {
                            t.at[t.n as usize] = at as u32;
                            t.w[t.n as usize] = wt;
                            t.n += 1;
                            sum += wt;
                        }
                    }
                }
                for wt in &mut t.w[..t.n as usize] {
                    *wt /= sum;
                }
                t
            })
            .collect();
        Self {
            taps,
            motion_px: 0.0,
        }
    }

    /// Share of pixels that kept some history.
    pub fn kept_share(&self) -> f64 {
        let kept = self.taps.iter().filter(|t| t.n > 0).count();
        kept as f64 / self.taps.len().max(1) as f64
    }

    /// Whether pixel `i` kept some history (else it restarts from this frame).
    pub fn kept(&self, i: usize) -> bool {
        self.taps.get(i).is_some_and(|t| t.n > 0)
    }

    /// One TAA step on images of `ch` interleaved channels: the previous accumulation `acc`
    /// (previous frame's pixels), this frame's image `cur`; the new accumulation.
    pub fn step(&self, acc: &[f32], cur: &[f32], ch: usize) -> Vec<f32> {
        let mut out = cur.to_vec();
        for (i, t) in self.taps.iter().enumerate() {
            let n = t.n as usize;
            if n == 0 {
                continue; // restart: this frame's value
            }
            for c in 0..ch {
                // The first product starts the sum, so one tap of weight 1 is exactly its value.
                let mut h = t.w[0] * acc[t.at[0] as usize * ch + c];
                for k in 1..n {
                    h += t.w[k] * acc[t.at[k] as usize * ch + c];
                }
                let e = cur[i * ch + c];
                out[i * ch + c] = h + ALPHA * (e - h);
            }
        }
        out
    }
}

/// The next accumulation of a stream of `ch`-channel images: `cur` itself on the first frame
/// (`acc` empty) or without history, else one TAA step.
pub fn accumulate(op: Option<&Reprojection>, acc: &[f32], cur: &[f32], ch: usize) -> Vec<f32> {
    match op {
        Some(op) if acc.len() == cur.len() => op.step(acc, cur, ch),
        _ => cur.to_vec(),
    }
}

#[cfg(test)]
#[path = "taa_tests.rs"]
mod tests;
