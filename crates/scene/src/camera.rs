//! A plain pinhole camera. The trace crate owns the per-frame GPU parameters; this type only
//! describes where the camera is and produces the basis vectors a ray generator needs.

use crate::{Aabb, Ray};
use glam::Vec3;

/// A look-at pinhole camera. `yfov` is the full vertical field of view in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub yfov: f32,
}

/// Ray-generation basis: the direction through normalized device coordinates
/// `(x, y)` in `[-1, 1]^2` (x to the right, y up) is `forward + x * right + y * up`.
/// `right` has length `tan(yfov / 2) * aspect`, `up` has length `tan(yfov / 2)`,
/// `forward` is unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraBasis {
    pub position: Vec3,
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
}

impl Camera {
    /// A camera that sees the whole bounding sphere of `bounds` from the +z side
    /// (the glTF "front"), with a 45 degree vertical field of view.
    pub fn framing(bounds: &Aabb) -> Camera {
        let yfov = 45f32.to_radians();
        let (center, radius) = if bounds.is_empty() {
            (Vec3::ZERO, 1.0)
        } else {
            (bounds.center(), (bounds.extent().length() * 0.5).max(1e-3))
        };
        // Distance at which the bounding sphere fits the vertical field of view.
        let distance = radius / (yfov * 0.5).sin();
        Camera {
            position: center + Vec3::Z * distance,
            target: center,
            up: Vec3::Y,
            yfov,
        }
    }

    /// Basis vectors for an image of the given aspect ratio (width / height).
    /// A degenerate camera (target == position, or up parallel to the view direction) falls
    /// back to looking down -z / a perpendicular up vector instead of producing NaNs.
    pub fn basis(&self, aspect: f32) -> CameraBasis {
        let forward = (self.target - self.position)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        let mut right = forward.cross(self.up).try_normalize();
        if right.is_none() {
            right = forward
                .cross(forward.any_orthonormal_vector())
                .try_normalize();
        }
        let right = right.unwrap_or(Vec3::X);
        let up = right.cross(forward);
        let tan_half = (self.yfov * 0.5).tan();
        CameraBasis {
            position: self.position,
            forward,
            right: right * tan_half * aspect,
            up: up * tan_half,
        }
    }
}

impl CameraBasis {
    /// Unit direction through normalized device coordinates (x right, y up, both in [-1, 1]).
    pub fn direction(&self, ndc_x: f32, ndc_y: f32) -> Vec3 {
        (self.forward + ndc_x * self.right + ndc_y * self.up).normalize()
    }

    /// The ray through the centre of pixel `(px, py)` of a `width x height` image, row 0 at
    /// the top. `tmin = 0`, `tmax = f32::MAX`.
    pub fn primary_ray(&self, px: u32, py: u32, width: u32, height: u32) -> Ray {
        let x = (px as f32 + 0.5) / width as f32 * 2.0 - 1.0;
        let y = 1.0 - (py as f32 + 0.5) / height as f32 * 2.0;
        Ray::new(self.position, self.direction(x, y), 0.0, f32::MAX)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_scaled_by_fov_and_aspect() {
        let cam = Camera {
            position: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            yfov: 90f32.to_radians(),
        };
        let b = cam.basis(2.0);
        assert!((b.forward - Vec3::NEG_Z).length() < 1e-6);
        assert!((b.up - Vec3::Y).length() < 1e-6);
        assert!((b.right - Vec3::X * 2.0).length() < 1e-5);
    }

    #[test]
    fn degenerate_camera_gives_finite_basis() {
        let cam = Camera {
            position: Vec3::ZERO,
            target: Vec3::Y,
            up: Vec3::Y,
            yfov: 1.0,
        };
        let b = cam.basis(1.0);
        assert!(b.right.is_finite() && b.up.is_finite() && b.right.length() > 0.1);
    }

    #[test]
    fn framing_sees_the_bounds() {
        let bounds = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        let cam = Camera::framing(&bounds);
        let b = cam.basis(1.0);
        // Every corner projects inside the image.
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            let d = c - b.position;
            let z = d.dot(b.forward);
            let x = d.dot(b.right) / b.right.length_squared() / z;
            let y = d.dot(b.up) / b.up.length_squared() / z;
            assert!(x.abs() <= 1.0 && y.abs() <= 1.0, "corner {c} at ({x}, {y})");
        }
    }
}
