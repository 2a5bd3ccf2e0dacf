//! The lights that are not triangles, as the GPU reads them: punctual lights and the
//! environment map with its sampling tables (layout: the `texels` module).

use super::*;
use crate::environment::cdf_iter;
use crate::scene::Scene;
use crate::{EnvMap, EnvSampling, LightKind};
use std::sync::Arc;

/// An environment map as the light image holds it: `height` marginal texels, then
/// `(r, g, b, conditional CDF)` per map texel, written from the map itself a range at a time
/// ([`Self::write`]) so the host never holds the map twice.
#[derive(Clone, Debug)]
pub struct EnvGpu {
    pub width: u32,
    pub height: u32,
    /// Inclusive CDF over rows.
    pub marginal: Vec<f32>,
    map: Arc<EnvMap>,
    /// Conditional CDFs by solid angle alone (`EnvSampling::Uniform`).
    uniform: bool,
}

impl EnvGpu {
    fn new(map: Arc<EnvMap>, sampling: EnvSampling) -> EnvGpu {
        let uniform = sampling == EnvSampling::Uniform;
        EnvGpu {
            width: map.width,
            height: map.height,
            marginal: map.marginal(uniform),
            map,
            uniform,
        }
    }

    /// Texels of the map's region of the light image.
    pub fn texel_count(&self) -> usize {
        self.marginal.len() + self.map.texels.len()
    }

    /// Writes texels `first ..` of the region into `out`, up to its end: each row's CDF is
    /// computed once per call that reaches it.
    pub fn write(&self, first: usize, out: &mut [Texel]) {
        let f = f32::to_bits;
        let h = self.marginal.len();
        let mut k = first;
        let end = self.texel_count().min(first.saturating_add(out.len()));
        while k < end.min(h) {
            out[k - first] = [f(self.marginal[k]), 0, 0, 0];
            k += 1;
        }
        let w = self.width as usize;
        let mut weights = Vec::with_capacity(w);
        while k < end {
            let (j, i0) = ((k - h) / w, (k - h) % w);
            self.map.row_weights(j, self.uniform, &mut weights);
            let row = &self.map.texels[j * w..(j + 1) * w];
            let n = (w - i0).min(end - k);
            let texels = row.iter().zip(cdf_iter(&weights)).skip(i0).take(n);
            for (t, (c, p)) in out[k - first..].iter_mut().zip(texels) {
                *t = [f(c.x), f(c.y), f(c.z), f(p)];
            }
            k += n;
        }
    }
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
    let Some(map) = scene.environment_map.as_ref() else {
        return (params, None, -1);
    };
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
    let env = EnvGpu::new(map.clone(), scene.environment_sampling);
    (params, Some(env), env_light)
}
