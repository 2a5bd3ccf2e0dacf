//! Punctual lights (glTF `KHR_lights_punctual`): points, spots and directional lights, which
//! only next-event estimation can reach (no ray ever hits them).
//!
//! Units follow the extension and are used as linear radiometric values: point and spot
//! intensity `I` (candela) is radiant intensity, so a surface at distance `d` facing the light
//! receives irradiance `I / d^2`; directional intensity `E` (lux) is the irradiance on a surface
//! facing the light. `color * intensity` is stored. Spots fall off between the inner and the
//! outer cone with the extension's recommended curve (`t^2`, `t` linear in the cosine) and are
//! zero outside the outer cone. `range` is not used (the inverse-square law holds to infinity).

use glam::Vec3;

/// What kind of punctual light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    Point,
    /// Cone half-angles in radians, `0 <= inner < outer <= pi/2`.
    Spot {
        inner: f32,
        outer: f32,
    },
    Directional,
}

/// One punctual light in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PunctualLight {
    pub kind: LightKind,
    /// Where it is (unused by directional lights).
    pub position: Vec3,
    /// Unit direction the light shines along (spot and directional; glTF's local -Z).
    pub direction: Vec3,
    /// `color * intensity`: radiant intensity (point, spot) or irradiance (directional).
    pub intensity: Vec3,
}

impl PunctualLight {
    /// `(cos inner, cos outer)` of a spot; `(-2, -3)` for other kinds (every direction is
    /// then inside the cone, with no falloff).
    pub fn cone_cosines(&self) -> (f32, f32) {
        match self.kind {
            LightKind::Spot { inner, outer } => (inner.cos(), outer.cos()),
            _ => (-2.0, -3.0),
        }
    }

    /// Power used to choose among lights (luminance of the emitted flux; for a directional
    /// light, what crosses a disc of the scene's bounding radius `radius`).
    pub fn selection_power(&self, radius: f32) -> f64 {
        let lum = crate::geometry::luminance(self.intensity) as f64;
        let pi = std::f64::consts::PI;
        match self.kind {
            LightKind::Point => 4.0 * pi * lum,
            LightKind::Spot { .. } => {
                let (ci, co) = self.cone_cosines();
                2.0 * pi * (1.0 - 0.5 * (ci as f64 + co as f64)) * lum
            }
            LightKind::Directional => pi * (radius as f64).powi(2) * lum,
        }
    }

    /// Light arriving at `p` (CPU twin of `punctual_incident` in lights.glsl), ignoring
    /// occlusion: `(direction towards the light, distance, irradiance on a surface facing it)`.
    pub fn incident(&self, p: Vec3) -> (Vec3, f32, Vec3) {
        if self.kind == LightKind::Directional {
            return (-self.direction, f32::INFINITY, self.intensity);
        }
        let to = self.position - p;
        let d2 = to.dot(to);
        let d = d2.sqrt();
        let wi = to / d;
        let (ci, co) = self.cone_cosines();
        let cd = self.direction.dot(-wi);
        let t = ((cd - co) / (ci - co).max(1e-4)).clamp(0.0, 1.0);
        (wi, d, self.intensity * (t * t / d2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_follows_the_inverse_square_law() {
        let l = PunctualLight {
            kind: LightKind::Point,
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Vec3::splat(8.0),
        };
        let (wi, d, e) = l.incident(Vec3::ZERO);
        assert_eq!((wi, d), (Vec3::Y, 2.0));
        assert_eq!(e, Vec3::splat(2.0));
    }

    #[test]
    fn spot_is_full_inside_the_inner_cone_and_zero_outside_the_outer() {
        let l = PunctualLight {
            kind: LightKind::Spot {
                inner: 0.2,
                outer: 0.4,
            },
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Vec3::ONE,
        };
        let at = |angle: f32| l.incident(Vec3::new(angle.tan(), 0.0, 0.0)).2.x;
        assert!((at(0.1) * 0.1f32.tan().hypot(1.0).powi(2) - 1.0).abs() < 1e-5);
        assert_eq!(at(0.41), 0.0);
        assert!(at(0.3) > 0.0 && at(0.3) < at(0.19));
    }
}
