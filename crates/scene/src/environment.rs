//! Environment maps: equirectangular HDR images (`.hdr`, `.exr`) lighting what rays leave the
//! scene towards, and the importance-sampling tables the trace shader reads.
//!
//! Orientation (+Y up): the image centre faces -Z, three quarters across faces +X, the top
//! row is straight up. Image coordinate `(u, v)` (u to the right, v down, both 0..1) is the
//! direction at azimuth `phi = 2 pi (u - 0.5)` from -Z towards +X and polar angle
//! `theta = pi v` from +Y: `(sin theta sin phi, cos theta, -sin theta cos phi)`. Seen from
//! inside, looking along -Z, the map appears unmirrored. A rotation of `a` turns the
//! map about +Y counter-clockwise seen from above: at 90 degrees the image centre faces -X.
//!
//! Sampling: texel `(i, j)` is chosen with probability proportional to its luminance times
//! `sin theta` at its row centre (a marginal CDF over rows, a conditional CDF per row, both
//! inverted by binary search so stratified inputs stay stratified), then a uniform point in
//! it; the solid-angle density is `p(i, j) W H / (2 pi^2 sin theta)`. The functions here are
//! the CPU twins of `env_*` in `shaders/include/lights.glsl` (same f32 operations).

use crate::geometry::luminance;
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};
use std::path::{Path, PathBuf};

/// Largest map side accepted (a 16k x 8k map is 2 GiB of texels on the device already).
pub const MAX_ENV_SIDE: u32 = 16384;
/// Most texels a map may have: 16384 x 8192, the largest equirectangular map (twice as wide
/// as high) within [`MAX_ENV_SIDE`].
pub const MAX_ENV_TEXELS: u64 = MAX_ENV_SIDE as u64 * (MAX_ENV_SIDE as u64 / 2);
/// How next-event estimation samples an environment map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvSampling {
    /// By luminance times solid angle, with MIS against BRDF sampling.
    #[default]
    Importance,
    /// By solid angle alone, with MIS (a reference for importance sampling).
    Uniform,
    /// Not at all: only rays that leave the scene find the map.
    Brdf,
}

impl EnvSampling {
    pub const ALL: [EnvSampling; 3] = [
        EnvSampling::Importance,
        EnvSampling::Uniform,
        EnvSampling::Brdf,
    ];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            EnvSampling::Importance => "importance",
            EnvSampling::Uniform => "uniform",
            EnvSampling::Brdf => "brdf",
        }
    }
}

/// An equirectangular environment map, intensity applied.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvMap {
    /// The file it came from (labels messages).
    pub source: PathBuf,
    pub width: u32,
    pub height: u32,
    /// Linear RGB radiance, row-major, top row (+Y) first.
    pub texels: Vec<Vec3>,
    /// Rotation about +Y, radians (see the module documentation).
    pub rotation: f32,
}

/// What went wrong reading a map (the caller names the flag or file).
#[derive(Debug, thiserror::Error)]
pub enum EnvMapError {
    #[error("{}: environment map not found", path.display())]
    NotFound { path: PathBuf },
    #[error("{}: the environment map file is empty", path.display())]
    Empty { path: PathBuf },
    #[error("{}: cannot read the environment map: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(
        "{}: environment maps must be .hdr (Radiance) or .exr (OpenEXR) files",
        path.display()
    )]
    Extension { path: PathBuf },
    #[error("{}: cannot decode the environment map: {message}", path.display())]
    Decode { path: PathBuf, message: String },
    #[error(
        "{}: environment map is {width}x{height}; it must be at least 2x1, at most \
         {MAX_ENV_SIDE} texels a side and at most {MAX_ENV_SIDE}x{} = {MAX_ENV_TEXELS} texels \
         in all",
        path.display(), MAX_ENV_SIDE / 2
    )]
    Size {
        path: PathBuf,
        width: u32,
        height: u32,
    },

    /// Within the map limits but not within the device's light image (decided from the
    /// header, before anything is decoded).
    #[error(
        "{}: environment map is {width}x{height}: with its row table it needs {texels} texels \
         of the light image, over the {room} this device holds (maxImageDimension2D = {rows} \
         rows of 4096 texels)",
        path.display()
    )]
    OverDevice {
        path: PathBuf,
        width: u32,
        height: u32,
        texels: u64,
        room: u64,
        rows: u32,
    },
}

/// The largest environment map file read: a 16384 x 8192 map of 32-bit float RGBA.
const MAX_MAP_FILE_BYTES: u64 = MAX_ENV_TEXELS * 16;

impl EnvMap {
    /// Reads an equirectangular `.hdr` or `.exr` file (a regular file: a FIFO or device is
    /// refused before it is opened). Texels that are NaN, infinite or
    /// negative become 0, reported in the returned warning (one line).
    pub fn load(path: &Path) -> Result<(EnvMap, Option<String>), EnvMapError> {
        Self::load_within(path, None)
    }

    /// [`EnvMap::load`], refusing from the header a map that `device` cannot hold in its light
    /// image (so a map that will be refused is not decoded first: a 16384 x 8192 map is
    /// 1.5 GiB of texels). [`crate::Scene::check_limits`] checks it exactly with the scene.
    pub fn load_for(
        path: &Path,
        device: &crate::DeviceLimits,
    ) -> Result<(EnvMap, Option<String>), EnvMapError> {
        Self::load_within(path, Some(device))
    }

    fn load_within(
        path: &Path,
        device: Option<&crate::DeviceLimits>,
    ) -> Result<(EnvMap, Option<String>), EnvMapError> {
        let bytes = crate::read_regular(path, MAX_MAP_FILE_BYTES).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => EnvMapError::NotFound {
                path: path.to_path_buf(),
            },
            _ => EnvMapError::Io {
                path: path.to_path_buf(),
                source: e,
            },
        })?;
        Self::from_bytes_within(path, &bytes, device)
    }

    /// Decodes a map from memory; `path` gives the format (by extension) and labels errors.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<(EnvMap, Option<String>), EnvMapError> {
        Self::from_bytes_within(path, bytes, None)
    }

    /// [`EnvMap::from_bytes`] with the device check of [`EnvMap::load_for`].
    pub fn from_bytes_within(
        path: &Path,
        bytes: &[u8],
        device: Option<&crate::DeviceLimits>,
    ) -> Result<(EnvMap, Option<String>), EnvMapError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let format = match ext.as_deref() {
            Some("hdr") => image::ImageFormat::Hdr,
            Some("exr") => image::ImageFormat::OpenExr,
            _ => {
                return Err(EnvMapError::Extension {
                    path: path.to_path_buf(),
                });
            }
        };
        if bytes.is_empty() {
            return Err(EnvMapError::Empty {
                path: path.to_path_buf(),
            });
        }
        let (width, height, mut texels) = decode::texels(path, bytes, format, device)?;
        // (RGBE cannot hold these; EXR can.)
        let mut bad = 0usize;
        for c in &mut texels {
            if !(c.is_finite() && c.min_element() >= 0.0) {
                bad += 1;
                *c = Vec3::ZERO;
            }
        }
        let warning = (bad > 0).then(|| {
            format!(
                "{}: {bad} environment map texels are NaN, infinite or negative; they are \
                 treated as black",
                path.display()
            )
        });
        let map = EnvMap {
            source: path.to_path_buf(),
            width,
            height,
            texels,
            rotation: 0.0,
        };
        Ok((map, warning))
    }

    /// A map of one constant radiance (tests and furnaces).
    pub fn constant(width: u32, height: u32, radiance: Vec3) -> EnvMap {
        EnvMap {
            source: PathBuf::from("<constant>"),
            width,
            height,
            texels: vec![radiance; (width * height) as usize],
            rotation: 0.0,
        }
    }

    /// Whether any texel emits.
    pub fn has_light(&self) -> bool {
        self.texels.iter().any(|&c| luminance(c) > 0.0)
    }

    /// Multiplies every texel by `k`.
    pub fn scale(&mut self, k: f32) {
        for t in &mut self.texels {
            *t *= k;
        }
    }

    /// `(cos, sin)` of the rotation, as the shader receives them.
    pub fn rotation_cs(&self) -> Vec2 {
        Vec2::new(self.rotation.cos(), self.rotation.sin())
    }

    /// Radiance towards world direction `d` (unit length): the texel under it, no filtering
    /// (so the sampled density is exactly proportional to what is seen).
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        let (i, j) = env_texel_of(d, self.rotation_cs(), self.width, self.height);
        self.texels[(j * self.width + i) as usize]
    }

    /// Integral of luminance over the sphere (W/m^2/sr x sr), for light selection.
    pub fn luminance_integral(&self) -> f64 {
        let (w, h) = (self.width as usize, self.height as usize);
        let texel_area = 2.0 * std::f64::consts::PI * std::f64::consts::PI / (w * h) as f64;
        (0..h)
            .map(|j| {
                let s = (std::f64::consts::PI * (j as f64 + 0.5) / h as f64).sin();
                let row: f64 = self.texels[j * w..(j + 1) * w]
                    .iter()
                    .map(|&c| luminance(c) as f64)
                    .sum();
                row * s * texel_area
            })
            .sum()
    }

    /// The importance-sampling tables.
    pub fn tables(&self) -> EnvTables {
        EnvTables::new(self, false)
    }

    /// The tables for `sampling`: by luminance, or (`EnvSampling::Uniform`) by solid angle
    /// alone, nearly uniform over the sphere (exactly so per row).
    pub fn tables_for(&self, sampling: EnvSampling) -> EnvTables {
        EnvTables::new(self, sampling == EnvSampling::Uniform)
    }
}

/// Inclusive CDFs for importance sampling (last entry of each exactly 1).
#[derive(Clone, Debug, PartialEq)]
pub struct EnvTables {
    pub width: u32,
    pub height: u32,
    /// Over rows, `height` entries.
    pub marginal: Vec<f32>,
    /// Per row over its texels, `width * height` entries.
    pub conditional: Vec<f32>,
}

/// Inclusive running sums of `w` over their total as f32, the last exactly 1; a zero total
/// gives the uniform CDF (such a row is never chosen: its marginal weight is 0).
fn cdf(w: &[f64]) -> Vec<f32> {
    cdf_iter(w).collect()
}

/// [`cdf`] one entry at a time (the GPU upload writes rows without collecting them).
pub(crate) fn cdf_iter(w: &[f64]) -> impl Iterator<Item = f32> + '_ {
    let total: f64 = w.iter().sum();
    let n = w.len();
    let mut run = 0f64;
    w.iter().enumerate().map(move |(k, &x)| {
        run += x;
        if k + 1 == n {
            1.0
        } else if total > 0.0 {
            (run / total) as f32
        } else {
            (k + 1) as f32 / n as f32
        }
    })
}

impl EnvMap {
    /// The sampling weights of row `j` into `out`: luminance (1 if `uniform`) times
    /// `sin theta` at the row centre. Their sum is the row's marginal weight.
    pub(crate) fn row_weights(&self, j: usize, uniform: bool, out: &mut Vec<f64>) {
        let (w, h) = (self.width as usize, self.height as usize);
        let s = (std::f64::consts::PI * (j as f64 + 0.5) / h as f64).sin();
        out.clear();
        out.extend(
            self.texels[j * w..(j + 1) * w]
                .iter()
                .map(|&c| if uniform { 1.0 } else { luminance(c) as f64 } * s),
        );
    }

    /// The marginal CDF over rows (`EnvTables::marginal` without the conditional table).
    pub(crate) fn marginal(&self, uniform: bool) -> Vec<f32> {
        let mut weights = Vec::with_capacity(self.width as usize);
        let rows: Vec<f64> = (0..self.height as usize)
            .map(|j| {
                self.row_weights(j, uniform, &mut weights);
                weights.iter().sum()
            })
            .collect();
        cdf(&rows)
    }
}

impl EnvTables {
    fn new(map: &EnvMap, uniform: bool) -> EnvTables {
        let (w, h) = (map.width as usize, map.height as usize);
        let mut weights = Vec::with_capacity(w);
        let mut conditional = Vec::with_capacity(w * h);
        for j in 0..h {
            map.row_weights(j, uniform, &mut weights);
            conditional.extend(cdf_iter(&weights));
        }
        EnvTables {
            width: map.width,
            height: map.height,
            marginal: map.marginal(uniform),
            conditional,
        }
    }

    /// Probability of texel `(i, j)` (CPU twin of `env_probability` in `lights.glsl`).
    pub fn probability(&self, i: u32, j: u32) -> f32 {
        let row = &self.conditional[(j * self.width) as usize..((j + 1) * self.width) as usize];
        let pc = row[i as usize] - if i > 0 { row[i as usize - 1] } else { 0.0 };
        let m = &self.marginal;
        let pm = m[j as usize] - if j > 0 { m[j as usize - 1] } else { 0.0 };
        pm * pc
    }

    /// Samples a world direction from `u` in [0,1)^2: `(direction, solid-angle pdf)` (CPU twin
    /// of `env_sample`). `u.y` picks the row, `u.x` the texel in it.
    pub fn sample(&self, u: Vec2, rotation: Vec2) -> (Vec3, f32) {
        let (j, fv) = invert(&self.marginal, u.y);
        let row = &self.conditional[(j * self.width) as usize..((j + 1) * self.width) as usize];
        let (i, fu) = invert(row, u.x);
        let uv = Vec2::new(
            (i as f32 + fu) / self.width as f32,
            (j as f32 + fv) / self.height as f32,
        );
        let d = env_direction(uv, rotation);
        let p = self.probability(i, j);
        (d, env_density(p, d, self.width, self.height))
    }

    /// Solid-angle pdf of sampling direction `d` (CPU twin of `env_pdf`).
    pub fn pdf(&self, d: Vec3, rotation: Vec2) -> f32 {
        let (i, j) = env_texel_of(d, rotation, self.width, self.height);
        env_density(self.probability(i, j), d, self.width, self.height)
    }
}

/// The first entry with `x < cdf[k]` (binary search as the shader's) and where `x` falls
/// within it, in [0, 1].
fn invert(cdf: &[f32], x: f32) -> (u32, f32) {
    let (mut lo, mut hi) = (0usize, cdf.len() - 1);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if x < cdf[mid] {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    let c0 = if lo > 0 { cdf[lo - 1] } else { 0.0 };
    let f = ((x - c0) / (cdf[lo] - c0).max(1e-30)).clamp(0.0, 1.0);
    (lo as u32, f.min(1.0 - f32::EPSILON / 2.0))
}

/// Solid-angle density of a direction `d` inside a texel of probability `p`.
pub fn env_density(p: f32, d: Vec3, width: u32, height: u32) -> f32 {
    let sin_theta = (1.0 - d.y * d.y).max(0.0).sqrt();
    p * (width * height) as f32 / (2.0 * PI * PI * sin_theta.max(1e-6))
}

/// World direction of map coordinate `uv` under rotation `(cos, sin)`.
pub fn env_direction(uv: Vec2, rotation: Vec2) -> Vec3 {
    let phi = (uv.x - 0.5) * TAU;
    let theta = uv.y * PI;
    let st = theta.sin();
    let m = Vec3::new(st * phi.sin(), theta.cos(), -st * phi.cos());
    let (c, s) = (rotation.x, rotation.y);
    Vec3::new(m.x * c + m.z * s, m.y, -m.x * s + m.z * c)
}

/// Map coordinate `uv` of world direction `d` (inverse of [`env_direction`]).
pub fn env_uv(d: Vec3, rotation: Vec2) -> Vec2 {
    let (c, s) = (rotation.x, rotation.y);
    let mx = d.x * c - d.z * s;
    let mz = d.x * s + d.z * c;
    let u = 0.5 + mx.atan2(-mz) / TAU;
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u, v)
}

/// The texel `(i, j)` under direction `d`.
pub fn env_texel_of(d: Vec3, rotation: Vec2, width: u32, height: u32) -> (u32, u32) {
    let uv = env_uv(d, rotation);
    let i = ((uv.x * width as f32) as i64).clamp(0, width as i64 - 1) as u32;
    let j = ((uv.y * height as f32) as i64).clamp(0, height as i64 - 1) as u32;
    (i, j)
}

#[path = "environment_decode.rs"]
mod decode;
#[path = "environment_exr.rs"]
mod exr;
#[path = "environment_hdr.rs"]
mod hdr;
#[cfg(test)]
#[path = "environment_tests.rs"]
mod tests;
