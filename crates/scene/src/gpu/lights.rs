//! The lights that are not triangles, as the GPU reads them: punctual lights and the
//! environment map with its sampling tables (layout: the `texels` module).

use super::*;
use crate::scene::Scene;
use crate::{EnvSampling, LightKind};

/// An environment map as the light image holds it.
#[derive(Clone, Debug, Default)]
pub struct EnvGpu {
    pub width: u32,
    pub height: u32,
    /// Inclusive CDF over rows.
    pub marginal: Vec<f32>,
    /// `(r, g, b, conditional CDF within the row)` per texel, row-major, top row first.
    pub texels: Vec<[f32; 4]>,
}

/// Appends the punctual lights and the environment map (when it is sampled) to the light list
/// with their selection powers; returns their records, the map's tables and its light index.
pub(super) fn non_triangle_lights(
    scene: &Scene,
    radius: f32,
    lights: &mut Vec<GpuLight>,
    powers: &mut Vec<f64>,
    total: &mut f64,
) -> (Vec<LightParams>, Option<EnvGpu>, i32) {
    let mut params = Vec::new();
    let mut push = |record: LightParams, power: f64, params: &mut Vec<LightParams>| {
        if !(power > 0.0 && power.is_finite()) {
            return -1;
        }
        *total += power;
        powers.push(power);
        lights.push(GpuLight {
            triangle: LIGHT_PARAMS_BIT | params.len() as u32,
            area: 1.0,
            pdf: 0.0,
            cdf: 0.0,
        });
        params.push(record);
        lights.len() as i32 - 1
    };
    for l in &scene.lights {
        let (cos_inner, cos_outer) = l.cone_cosines();
        let kind = match l.kind {
            LightKind::Point => LIGHT_POINT,
            LightKind::Spot { .. } => LIGHT_SPOT,
            LightKind::Directional => LIGHT_DIRECTIONAL,
        };
        let record = LightParams {
            position: l.position,
            kind,
            direction: l.direction,
            cos_inner,
            intensity: l.intensity,
            cos_outer,
        };
        push(record, l.selection_power(radius), &mut params);
    }
    let Some(map) = scene.environment_map.as_deref() else {
        return (params, None, -1);
    };
    let tables = map.tables_for(scene.environment_sampling);
    let sampled = scene.environment_sampling != EnvSampling::Brdf;
    let env_light = if sampled && map.has_light() {
        let record = LightParams {
            kind: LIGHT_ENVIRONMENT,
            ..LightParams::default()
        };
        let power = std::f64::consts::PI * (radius as f64).powi(2) * map.luminance_integral();
        push(record, power, &mut params)
    } else {
        -1
    };
    let texels = map
        .texels
        .iter()
        .zip(&tables.conditional)
        .map(|(c, &p)| [c.x, c.y, c.z, p])
        .collect();
    let env = EnvGpu {
        width: map.width,
        height: map.height,
        marginal: tables.marginal,
        texels,
    };
    (params, Some(env), env_light)
}
