//! `target=follow`: the sorting target (the spatio-temporal mask `sort-cycle` ranks against)
//! moves with the image instead of staying on the screen. A temporal filter that follows
//! the motion then meets each surface point at the same mask texel frame after frame, whose
//! values over the slices are temporally blue. One shift for the whole image, the image
//! motion of the scene's centre: exact for that depth, a drift of the parallax elsewhere.
use blueshift_layout::motion::MotionParams;
use blueshift_permute::project_previous;
use glam::{DVec2, Vec3};

/// The accumulated image motion of one world point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FollowShift {
    /// The point followed: the centre of the scene's bounds.
    centre: Vec3,
    /// Where the last view put it (pixels); `None` before the first view or while it was
    /// behind the camera.
    last: Option<DVec2>,
    /// The sum of its moves since the sequence began (pixels).
    shift: DVec2,
}

impl FollowShift {
    pub fn new(centre: Vec3) -> Self {
        Self {
            centre,
            last: None,
            shift: DVec2::ZERO,
        }
    }

    /// Back to the start of a sequence.
    pub fn reset(&mut self) {
        *self = Self::new(self.centre);
    }

    /// Adds the centre's move from the last view to `view` (the frame's camera, as
    /// `motion_params` gives it; `project_previous` projects with any such camera).
    pub fn update(&mut self, view: &MotionParams) {
        let (c, z) = project_previous(view, self.centre);
        let now = (z > 0.0 && c.is_finite()).then(|| c.as_dvec2());
        if let (Some(a), Some(b)) = (self.last, now) {
            self.shift += b - a;
        }
        self.last = now;
    }

    /// The mask offset (`SortParams::offset_x/y`) on a tile of `n` texels that moves the
    /// mask with the image: pixel p reads texel p - shift.
    pub fn offset(&self, n: u32) -> (u32, u32) {
        let n = i64::from(n.max(1));
        let wrap = |s: f64| (-(s.round() as i64)).rem_euclid(n) as u32;
        (wrap(self.shift.x), wrap(self.shift.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use blueshift_scene::Camera;

    /// The view of a camera at height 1 looking down -z from x, 128x96 pixels.
    fn view(x: f32, offset: (f32, f32)) -> MotionParams {
        let cam = Camera {
            position: Vec3::new(x, 1.0, 4.0),
            target: Vec3::new(x, 1.0, 0.0),
            up: Vec3::Y,
            yfov: 45f32.to_radians(),
        };
        let b = cam.basis(128.0 / 96.0);
        MotionParams {
            cam_origin: b.position,
            cam_forward: b.forward,
            cam_right: b.right,
            cam_up: b.up,
            view_offset: offset.into(),
            view_size: glam::Vec2::new(128.0, 96.0),
            ..Default::default()
        }
    }

    fn at(v: &MotionParams, p: Vec3) -> DVec2 {
        project_previous(v, p).0.as_dvec2()
    }

    #[test]
    fn the_shift_is_the_followed_point_s_motion() {
        let centre = Vec3::new(0.2, 0.7, -1.0);
        let mut f = FollowShift::new(centre);
        let views: Vec<MotionParams> = (0..5).map(|t| view(0.05 * t as f32, (0.0, 0.0))).collect();
        for v in &views {
            f.update(v);
        }
        let moved = at(&views[4], centre) - at(&views[0], centre);
        assert!((f.shift - moved).length() < 1e-4);
        // The camera moves right: the image moves left, and the mask with it.
        assert!(f.shift.x < -1.0 && f.shift.y.abs() < 1e-4);
        let n = 64;
        assert_eq!(f.offset(n), ((f.shift.x.round().abs() as u32) % n, 0));
    }

    #[test]
    fn an_image_space_pan_shifts_by_its_pixels_and_a_still_view_not_at_all() {
        let mut f = FollowShift::new(Vec3::ZERO);
        for t in 0..4 {
            f.update(&view(0.0, (t as f32, 0.0)));
        }
        assert!((f.shift - DVec2::new(-3.0, 0.0)).length() < 1e-4);
        assert_eq!(f.offset(64), (3, 0));
        let mut still = FollowShift::new(Vec3::ZERO);
        for _ in 0..4 {
            still.update(&view(0.5, (0.0, 0.0)));
        }
        assert_eq!(still.shift, DVec2::ZERO);
        assert_eq!(still.offset(64), (0, 0));
        // Behind the camera the point is not followed, and the shift stays.
        let mut behind = FollowShift::new(Vec3::new(0.0, 1.0, 9.0));
        behind.update(&view(0.0, (0.0, 0.0)));
        behind.update(&view(0.5, (0.0, 0.0)));
        assert_eq!((behind.shift, behind.last), (DVec2::ZERO, None));
        still.update(&view(0.9, (0.0, 0.0)));
        still.reset();
        assert_eq!((still.shift, still.last), (DVec2::ZERO, None));
    }
}
