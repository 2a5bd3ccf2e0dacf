//! `target=follow`: the sorting target (the spatio-temporal mask `sort-cycle` ranks against)
//! moves with the image instead of staying on the screen. A temporal filter that follows
//! the motion then meets each surface point at the same mask texel frame after frame, whose
//! values over the slices are temporally blue. One shift for the whole image, the image
//! motion of the scene's centre: exact for that depth, a drift of the parallax elsewhere.
use blueshift_scene::Camera;
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

/// One view: camera, view window size (pixels) and image-space offset.
#[derive(Debug, Clone, Copy)]
pub(crate) struct View {
    pub camera: Camera,
    pub size: (u32, u32),
    pub offset: (f32, f32),
}

impl View {
    /// The pixel coordinates (x right, y down; pixel centres at +0.5) where the primary rays
    /// of this view meet `p`, the inverse of the trace pass's ray generation; `None` when `p`
    /// is not in front of the camera.
    pub fn project(&self, p: Vec3) -> Option<DVec2> {
        let (w, h) = (self.size.0 as f32, self.size.1 as f32);
        let b = self.camera.basis(w / h);
        let d = p - b.position;
        let z = d.dot(b.forward);
        if z.is_nan() || z <= 1e-6 {
            return None;
        }
        let ndc_x = d.dot(b.right) / (b.right.length_squared() * z);
        let ndc_y = -d.dot(b.up) / (b.up.length_squared() * z);
        let x = f64::from((ndc_x + 1.0) * 0.5 * w - self.offset.0);
        let y = f64::from((ndc_y + 1.0) * 0.5 * h - self.offset.1);
        (x.is_finite() && y.is_finite()).then_some(DVec2::new(x, y))
    }
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

    /// Adds the centre's move from the last view to `view`.
    pub fn update(&mut self, view: &View) {
        let now = view.project(self.centre);
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

    fn camera(x: f32) -> Camera {
        Camera {
            position: Vec3::new(x, 1.0, 4.0),
            target: Vec3::new(x, 1.0, 0.0),
            up: Vec3::Y,
            yfov: 45f32.to_radians(),
        }
    }

    fn view(x: f32, offset: (f32, f32)) -> View {
        View {
            camera: camera(x),
            size: (128, 96),
            offset,
        }
    }

    #[test]
    fn projection_inverts_the_primary_rays() {
        // The ray through pixel (x, y) as trace_paths builds it, then back to its pixel.
        let v = view(0.3, (2.0, -1.0));
        let b = v.camera.basis(128.0 / 96.0);
        for (x, y) in [(0.5f32, 0.5f32), (64.0, 48.0), (100.25, 10.75)] {
            let ndc_x = (x + v.offset.0) / 128.0 * 2.0 - 1.0;
            let ndc_y = (y + v.offset.1) / 96.0 * 2.0 - 1.0;
            let dir = (b.forward + ndc_x * b.right - ndc_y * b.up).normalize();
            let p = v.project(b.position + dir * 3.7).expect("in front");
            assert!((p.x - f64::from(x)).abs() < 1e-3 && (p.y - f64::from(y)).abs() < 1e-3);
        }
        assert!(v.project(b.position - b.forward).is_none());
    }

    #[test]
    fn the_shift_is_the_followed_point_s_motion() {
        let centre = Vec3::new(0.2, 0.7, -1.0);
        let mut f = FollowShift::new(centre);
        let views: Vec<View> = (0..5).map(|t| view(0.05 * t as f32, (0.0, 0.0))).collect();
        for v in &views {
            f.update(v);
        }
        let moved = views[4].project(centre).unwrap() - views[0].project(centre).unwrap();
        assert!((f.shift - moved).length() < 1e-9);
        // The camera moves right: the image moves left, and the mask with it.
        assert!(f.shift.x < -1.0 && f.shift.y.abs() < 1e-6);
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
        still.update(&view(0.9, (0.0, 0.0)));
        still.reset();
        assert_eq!((still.shift, still.last), (DVec2::ZERO, None));
    }
}
