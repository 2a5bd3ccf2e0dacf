//! `--environment` and friends: how a scene is lit beyond its own emitters and lights.
use anyhow::{Context, Result, bail};
use blueshift_scene::{EnvMap, EnvSampling, EnvironmentSource, Scene};
use glam::Vec3;
use std::path::Path;
use std::sync::Arc;

#[derive(clap::Args, Debug, Clone)]
pub struct LightArgs {
    /// Environment light: `R,G,B` (constant linear radiance) or an equirectangular `.hdr` /
    /// `.exr` map (centre facing -Z, +Y up). Default: the scene's own; a scene with no light
    /// at all gets a uniform white environment (radiance 1) and a warning. A black one given
    /// here (`0,0,0`) stays black.
    #[arg(long, value_name = "R,G,B|FILE")]
    pub environment: Option<String>,
    /// Turn the map about +Y by DEG degrees (counter-clockwise seen from above: at 90 the
    /// image centre faces -X).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub environment_rotation: f32,
    /// Multiply the environment (given, the scene's own, or the default) by X.
    #[arg(
        long,
        value_name = "X",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub environment_intensity: f32,
    /// How next-event estimation samples the map: importance (by luminance, with MIS),
    /// uniform (by solid angle, with MIS) or brdf (not at all: only rays that leave the scene
    /// find it). The last two are for comparisons.
    #[arg(long, default_value = EnvSampling::default().name(),
          value_parser = crate::args::env_sampling_parser())]
    pub environment_sampling: EnvSampling,
}

impl Default for LightArgs {
    fn default() -> Self {
        LightArgs {
            environment: None,
            environment_rotation: 0.0,
            environment_intensity: 1.0,
            environment_sampling: EnvSampling::default(),
        }
    }
}

impl LightArgs {
    /// The environment the flags name, with the map's warning (bad texels), if any.
    /// A map `device` cannot hold is refused from its header, before it is decoded.
    pub fn source(
        &self,
        device: &blueshift_scene::DeviceLimits,
    ) -> Result<(Option<EnvironmentSource>, Option<String>)> {
        let Some(spec) = &self.environment else {
            return Ok((None, None));
        };
        if let Some(rgb) = parse_rgb(spec)? {
            return Ok((Some(EnvironmentSource::Constant(rgb)), None));
        }
        let (map, warning) = EnvMap::load_for(Path::new(spec), device).context("--environment")?;
        Ok((Some(EnvironmentSource::Map(Arc::new(map))), warning))
    }

    /// Checks the numbers, then applies the default environment (returning its warning),
    /// intensity, rotation and sampling to a loaded scene. The default (white) lights only a
    /// scene without light and without `--environment`: a black environment given is kept,
    /// and if then nothing emits, the warning says so.
    pub fn apply(&self, scene: &mut Scene) -> Result<Option<String>> {
        let k = self.environment_intensity;
        if !(k.is_finite() && k >= 0.0) {
            bail!("--environment-intensity must be a finite number >= 0, got {k}");
        }
        let r = self.environment_rotation;
        if !r.is_finite() {
            bail!("--environment-rotation must be a finite number of degrees, got {r}");
        }
        let default_light = match self.environment {
            None => scene.light_if_dark(),
            Some(_) => None,
        };
        scene.scale_environment(k);
        // Radiance past f32's range is infinite, and an infinite light renders black.
        let map_finite = scene
            .environment_map
            .as_ref()
            .is_none_or(|m| m.texels.iter().all(|t| t.is_finite()));
        if !scene.environment.is_finite() || !map_finite {
            let what = match self.environment.as_deref() {
                Some(spec) => format!("--environment {spec}"),
                None => "the scene's environment".to_string(),
            };
            bail!(
                "{what} times --environment-intensity {k} overflows f32 (infinite radiance \
                 renders black); scale the environment down"
            );
        }
        scene.rotate_environment(r.to_radians());
        scene.environment_sampling = self.environment_sampling;
        if scene.has_light() {
            return Ok(default_light);
        }
        // Nothing emits because the flags said so: a black frame, and why.
        let why = if k == 0.0 {
            "--environment-intensity 0 turns the environment off".to_string()
        } else {
            let spec = self.environment.as_deref().unwrap_or_default();
            format!("--environment {spec} is black")
        };
        Ok(Some(format!(
            "{}: nothing emits light (no emissive material, no KHR_lights_punctual light, and \
             {why}): the frames will be black",
            scene.source.display()
        )))
    }
}

/// `R,G,B` as a colour; `None` for a file name (no comma, or a map's extension).
fn parse_rgb(spec: &str) -> Result<Option<Vec3>> {
    let lower = spec.to_ascii_lowercase();
    if !spec.contains(',') || lower.ends_with(".hdr") || lower.ends_with(".exr") {
        return Ok(None);
    }
    let values: Vec<f32> = spec
        .split(',')
        .filter_map(|p| p.trim().parse().ok())
        .collect();
    let n = spec.split(',').count();
    if n != 3 || values.len() != 3 || values.iter().any(|v| !v.is_finite() || *v < 0.0) {
        bail!(
            "--environment {spec}: a constant environment is R,G,B: three finite numbers >= 0 \
             (linear radiance)"
        );
    }
    Ok(Some(Vec3::new(values[0], values[1], values[2])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgb_is_parsed_and_bad_numbers_are_named() {
        assert_eq!(
            parse_rgb("1,0.5,2").unwrap(),
            Some(Vec3::new(1.0, 0.5, 2.0))
        );
        assert_eq!(parse_rgb("sky.hdr").unwrap(), None);
        assert_eq!(parse_rgb("maps/a,b.hdr").unwrap(), None);
        for bad in ["1,2", "1,-2,3", "1,nan,3", "1,inf,2", "1,2,3,4"] {
            let e = parse_rgb(bad).unwrap_err().to_string();
            assert!(e.contains("R,G,B"), "{bad}: {e}");
        }
    }
}
