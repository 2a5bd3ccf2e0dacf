//! `KHR_lights_punctual`: the light a node carries, in world space.
//!
//! Read from the JSON rather than through `Node::light`, which unwraps the extension's light
//! list and index (a hostile file would make it panic).

use super::Warnings;
use crate::{LightKind, PunctualLight, SceneError};
use glam::{Mat4, Vec3};
use gltf::json::extensions::scene::khr_lights_punctual::{Light, Type};
use gltf::json::validation::Checked;
use std::path::Path;

/// The light attached to `node`, transformed by `world`, or `None` (with a warning when the
/// light exists but cannot be used). A light whose `color * intensity` overflows f32 is an
/// error: skipped or clamped, it would leave a wrong image without a word about why.
pub(crate) fn read(
    path: &Path,
    document: &gltf::Document,
    node: &gltf::Node,
    world: &Mat4,
    warnings: &mut Warnings,
) -> Result<Option<PunctualLight>, SceneError> {
    let root = document.as_json();
    let Some(index) = root
        .nodes
        .get(node.index())
        .and_then(|n| n.extensions.as_ref())
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map(|l| l.light)
    else {
        return Ok(None);
    };
    let Some(light) = root.get(index) else {
        warnings.warn("light-index", || {
            format!(
                "node {} names KHR_lights_punctual light {}, which does not exist; ignored",
                node.index(),
                index.value()
            )
        });
        return Ok(None);
    };
    // Valid factors (finite, >= 0; others are skipped with a warning below) whose product
    // is not.
    let color = Vec3::from_array(light.color);
    let valid = |x: f32| x.is_finite() && x >= 0.0;
    let valid_factors = valid(light.intensity) && color.to_array().into_iter().all(valid);
    if valid_factors && !(color * light.intensity).is_finite() {
        return Err(SceneError::Light {
            path: path.to_path_buf(),
            what: format!("KHR_lights_punctual light {}", index.value()),
            problem: format!(
                "has color {:?} times intensity {:?}, which overflows f32 (infinite radiance \
                 renders black); scale the light down",
                light.color, light.intensity
            ),
        });
    }
    Ok(convert(index.value(), light, world, warnings))
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
