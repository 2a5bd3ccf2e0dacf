//! The camera paths that depend on the scene: a strafe whose speed is given in pixels at the
//! scene's centre, and an orbit that keeps the whole scene in view. Both need the scene's
//! bounds and the view, so a parsed path is [`crate::CameraPath::fit`] to them before use.
use blueshift_scene::{Aabb, Camera};
use glam::{Quat, Vec3};

/// How far (fraction of the view height, in pixels at the scene's centre) a strafe travels
/// before it turns back, like a pan: far enough for parallax and disocclusion, short enough
/// that the view stays on the scene.
pub const STRAFE_SPAN: f32 = 0.25;

/// How far (degrees) an in-view orbit turns before it turns back: a scene open on one side
/// (the Cornell box) keeps showing its inside.
pub const ORBIT_VIEW_SPAN: f32 = 30.0;

/// What [`crate::CameraPath::fit`] derives from the scene for a strafe: world units per
/// frame along the camera's right axis, and the span (world units) it turns back after.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrafeFit {
    pub right: Vec3,
    pub step: f32,
    pub span: f32,
}

/// What [`crate::CameraPath::fit`] derives from the scene for an in-view orbit: the pivot (the
/// bounds' centre), the camera's distance from it and its direction at frame 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitFit {
    pub pivot: Vec3,
    pub distance: f32,
    pub start: Vec3,
}

/// A strafe of `px_per_frame` at the depth of the bounds' centre, for a view `view_height`
/// pixels high: a pixel there spans `2 d tan(yfov / 2) / view_height` world units.
pub fn strafe(px_per_frame: f32, bounds: &Aabb, base: &Camera, view_height: u32) -> StrafeFit {
    let b = base.basis(1.0);
    let (f, right) = (b.forward, b.right.normalize_or(Vec3::X));
    let centre = if bounds.is_empty() {
        base.target
    } else {
        bounds.center()
    };
    let depth = (centre - base.position).dot(f);
    let depth = if depth > 1e-6 { depth } else { 1.0 };
    let per_px = 2.0 * depth * (base.yfov * 0.5).tan() / view_height.max(1) as f32;
    let per_px = if per_px.is_finite() { per_px } else { 0.0 };
    StrafeFit {
        right,
        step: px_per_frame * per_px,
        // Positive, or the turn-back would divide by zero.
        span: (STRAFE_SPAN * view_height as f32 * per_px).max(f32::MIN_POSITIVE),
    }
}

/// An orbit about the bounds' centre at a distance where their bounding sphere fits the
/// narrower field of view of a `view` (w, h) frame, or the base camera's distance if larger:
/// the whole scene stays in view at every angle.
pub fn orbit(bounds: &Aabb, base: &Camera, view: (u32, u32)) -> OrbitFit {
    let (pivot, radius) = if bounds.is_empty() {
        (base.target, 1.0)
    } else {
        (bounds.center(), (bounds.extent().length() * 0.5).max(1e-3))
    };
    let aspect = view.0.max(1) as f32 / view.1.max(1) as f32;
    let half_y = base.yfov * 0.5;
    let half = half_y.min((half_y.tan() * aspect).atan());
    let away = base.position - pivot;
    OrbitFit {
        pivot,
        // A little past the sphere's fit, so no corner sits exactly on the frustum.
        distance: (radius / half.sin() * 1.01).max(away.length()),
        start: away.try_normalize().unwrap_or(Vec3::Z),
    }
}

/// The strafe's camera after moving `offset` world units along its right axis.
pub fn strafed(base: &Camera, fit: &StrafeFit, offset: f32) -> Camera {
    let d = fit.right * offset;
    Camera {
        position: base.position + d,
        target: base.target + d,
        ..*base
    }
}

/// The in-view orbit's camera at `degrees` about the base camera's up axis.
pub fn orbited(base: &Camera, fit: &OrbitFit, degrees: f32) -> Camera {
    let axis = base.up.try_normalize().unwrap_or(Vec3::Y);
    let dir = Quat::from_axis_angle(axis, degrees.to_radians()) * fit.start;
    Camera {
        position: fit.pivot + dir * fit.distance,
        target: fit.pivot,
        ..*base
    }
}
