//! How fast the image moves from one view to the next, for the rule that keeps the
//! spatio-temporal volume while the view moves slowly ([`crate::recipe::ViewState::Slow`]).
//!
//! The default renders no G-buffer while the view moves, so the estimate comes from the scene
//! itself: points spread over its surfaces by area, projected with both views. The image
//! motion is their mean move, over the points both views see in front of them and the newer
//! view has in its window, each weighted by the pixels its neighbourhood covers there (1 /
//! depth squared): an estimate of the mean motion of the pixels' hit points that ignores
//! occlusion (`eval`'s *motion* row measures the real one). A strafe moves the points by their
//! parallax, an image-space pan all of them by its pixels, and an orbit about the scene's
//! centre every point but the centre, which is why the one point `follow.rs` follows would
//! not do.
use blueshift_layout::motion::MotionParams;
use blueshift_permute::project_previous;
use glam::{Vec2, Vec3};

/// Below this image motion (pixels per frame) a moving view counts as slow: between the
/// tuning strafes of 1 px/frame, where the volume's TAA leads the 2D mask's by 0.1, and
/// 2.5 px/frame, where the 2D mask leads on both axes (docs/experiments.md).
pub const SLOW_VIEW_PX: f32 = 1.5;

/// Points spread over the scene: enough that a view of part of it keeps a few hundred.
const POINTS: usize = 4096;

/// The points whose image motion stands for the image's.
#[derive(Debug, Clone)]
pub(crate) struct ViewSpeed {
    points: Vec<Vec3>,
}

impl ViewSpeed {
    /// [`POINTS`] points over `triangles` (vertex positions), each triangle getting its share
    /// by area: point k at the area fraction (k + 1/2) / POINTS, placed inside its triangle by
    /// the R2 sequence (deterministic, so a scene always gets the same points).
    pub fn new(triangles: impl Iterator<Item = [Vec3; 3]>) -> Self {
        let tris: Vec<([Vec3; 3], f64)> = triangles
            .map(|t| (t, f64::from((t[1] - t[0]).cross(t[2] - t[0]).length())))
            .filter(|(_, a)| a.is_finite() && *a > 0.0)
            .collect();
        let total: f64 = tris.iter().map(|(_, a)| a).sum();
        let mut points = Vec::with_capacity(POINTS);
        let (mut at, mut below) = (0, 0.0);
        for k in 0..POINTS {
            if tris.is_empty() {
                break;
            }
            let target = (k as f64 + 0.5) / POINTS as f64 * total;
            while at + 1 < tris.len() && below + tris[at].1 <= target {
                below += tris[at].1;
                at += 1;
            }
            let g = blueshift_sampling::r2::PLASTIC;
            let (u, v) = (
                (0.5 + k as f64 / g).fract(),
                (0.5 + k as f64 / (g * g)).fract(),
            );
            let (u, v) = if u + v > 1.0 {
                (1.0 - u, 1.0 - v)
            } else {
                (u, v)
            };
            let [a, b, c] = tris[at].0;
            points.push(a + (b - a) * u as f32 + (c - a) * v as f32);
        }
        Self { points }
    }

    /// The image motion (pixels) from view `before` to view `now`; `None` when no point is in
    /// front of both and inside `now`'s window (the view then counts as moving fast).
    pub fn pixels(&self, before: &MotionParams, now: &MotionParams) -> Option<f32> {
        let size = now.view_size;
        let (mut sum, mut weight) = (0.0f64, 0.0f64);
        for &p in &self.points {
            let (a, za) = project_previous(before, p);
            let (b, zb) = project_previous(now, p);
            let inside = b.cmpge(Vec2::ZERO).all() && b.cmplt(size).all();
            let d = (b - a).length();
            if za > 0.0 && zb > 0.0 && inside && d.is_finite() {
                let w = 1.0 / f64::from(zb * zb);
                sum += w * f64::from(d);
                weight += w;
            }
        }
        (weight > 0.0).then(|| (sum / weight) as f32)
    }

    /// Whether the view moves slowly from `before` to `now` (below [`SLOW_VIEW_PX`]).
    pub fn slow(&self, before: &MotionParams, now: &MotionParams) -> bool {
        self.pixels(before, now).is_some_and(|px| px < SLOW_VIEW_PX)
    }
}

/// The view of `cam` in a 128x96 window shifted by `offset` pixels: the tests' views.
#[cfg(test)]
pub(crate) fn test_view(cam: &blueshift_scene::Camera, offset: (f32, f32)) -> MotionParams {
    let b = cam.basis(128.0 / 96.0);
    MotionParams {
        cam_origin: b.position,
        cam_forward: b.forward,
        cam_right: b.right,
        cam_up: b.up,
        view_offset: offset.into(),
        view_size: Vec2::new(128.0, 96.0),
        ..Default::default()
    }
}

#[cfg(test)]
#[path = "speed_tests.rs"]
mod tests;
