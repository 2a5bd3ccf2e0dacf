//! `KHR_lights_punctual`: the light a node carries, in world space.
//!
//! Read from the JSON rather than through `Node::light`, which unwraps the extension's light
//! list and index (a hostile file would make it panic).

use super::Warnings;
use crate::{LightKind, PunctualLight};
use glam::{Mat4, Vec3};
use gltf::json::extensions::scene::khr_lights_punctual::{Light, Type};
use gltf::json::validation::Checked;

/// The light attached to `node`, transformed by `world`, or `None` (with a warning when the
/// light exists but cannot be used).
pub(crate) fn read(
    document: &gltf::Document,
    node: &gltf::Node,
    world: &Mat4,
    warnings: &mut Warnings,
) -> Option<PunctualLight> {
    let root = document.as_json();
    let index = root
        .nodes
        .get(node.index())?
        .extensions
        .as_ref()?
        .khr_lights_punctual
        .as_ref()?
        .light;
    let Some(light) = root.get(index) else {
        warnings.warn("light-index", || {
            format!(
                "node {} names KHR_lights_punctual light {}, which does not exist; ignored",
                node.index(),
                index.value()
            )
        });
        return None;
    };
    convert(index.value(), light, world, warnings)
}

fn convert(
    index: usize,
    light: &Light,
    world: &Mat4,
    warnings: &mut Warnings,
) -> Option<PunctualLight> {
    // One line per kind of problem (`kind`), however many lights have it.
    let skip = |kind: &str, why: String, warnings: &mut Warnings| {
        warnings.warn_item(
            kind,
            "KHR_lights_punctual lights skipped",
            || format!("light {index} {why}"),
            |item| format!("KHR_lights_punctual {item}; the light is skipped"),
        );
        None
    };
    let color = Vec3::from_array(light.color);
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return skip(
            "light-intensity",
            format!(
                "has intensity {}, which must be a finite number >= 0",
                light.intensity
            ),
            warnings,
        );
    }
    if !(color.is_finite() && color.min_element() >= 0.0) {
        return skip(
            "light-color",
            format!("has color {:?}, which must be finite and >= 0", light.color),
            warnings,
        );
    }
    let kind = match (&light.type_, &light.spot) {
        (Checked::Valid(Type::Point), _) => LightKind::Point,
        (Checked::Valid(Type::Directional), _) => LightKind::Directional,
        (Checked::Valid(Type::Spot), Some(s)) => {
            let (inner, outer) = (s.inner_cone_angle, s.outer_cone_angle);
            let half_pi = std::f32::consts::FRAC_PI_2;
            if !(inner >= 0.0 && inner < outer && outer <= half_pi) {
                return skip(
                    "light-cone",
                    format!(
                        "has cone angles inner {inner}, outer {outer}; they must satisfy \
                     0 <= inner < outer <= pi/2"
                    ),
                    warnings,
                );
            }
            LightKind::Spot { inner, outer }
        }
        (Checked::Valid(Type::Spot), None) => {
            return skip("light-spot", "is a spot without `spot`".into(), warnings);
        }
        (Checked::Invalid, _) => {
            return skip("light-type", "has an unknown type".into(), warnings);
        }
    };
    if light.range.is_some() {
        warnings.warn("light-range", || {
            "KHR_lights_punctual `range` is ignored: lights follow the inverse-square law to \
             any distance"
                .into()
        });
    }
    let position = world.transform_point3(Vec3::ZERO);
    let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
    if !position.is_finite() || direction == Vec3::ZERO {
        return skip(
            "light-transform",
            "sits on a node with a degenerate transform".into(),
            warnings,
        );
    }
    Some(PunctualLight {
        kind,
        position,
        direction,
        intensity: color * light.intensity,
    })
}
