//! The CPU scene: world-space triangles, materials, textures, camera, environment.

use crate::load::{self, LoadOptions};
use crate::{Aabb, Camera, EnvMap, EnvSampling, PunctualLight, Result};
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One world-space triangle with its shading attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub positions: [Vec3; 3],
    /// Unit shading normals (the flat face normal where the file had none).
    pub normals: [Vec3; 3],
    /// TEXCOORD_0 (zero where the file had none).
    pub uvs: [Vec2; 3],
    /// Index into [`Scene::materials`].
    pub material: u32,
}

/// A glTF metallic-roughness material (factors linear; texture indices into
/// [`Scene::textures`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: Option<String>,
    pub base_color: [f32; 4],
    pub metallic: f32,
    pub roughness: f32,
    /// Emissive factor times KHR_materials_emissive_strength.
    pub emissive: Vec3,
    /// KHR_materials_specular `specularFactor`: weight of the dielectric specular layer
    /// (1 = the plain glTF dielectric, 0 = pure Lambert diffuse).
    pub specular: f32,
    /// KHR_materials_specular `specularColorFactor`: tint of the dielectric F0 (linear RGB).
    pub specular_color: Vec3,
    pub base_color_texture: Option<u32>,
    pub metallic_roughness_texture: Option<u32>,
    pub emissive_texture: Option<u32>,
    pub double_sided: bool,
}

impl Default for Material {
    /// The glTF default material (white, fully metallic, fully rough; glTF spec 3.9.6).
    fn default() -> Self {
        Material {
            name: None,
            base_color: [1.0; 4],
            metallic: 1.0,
            roughness: 1.0,
            emissive: Vec3::ZERO,
            specular: 1.0,
            specular_color: Vec3::ONE,
            base_color_texture: None,
            metallic_roughness_texture: None,
            emissive_texture: None,
            double_sided: false,
        }
    }
}

/// Texture coordinate wrap mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Wrap {
    #[default]
    Repeat,
    Clamp,
    Mirror,
}

/// A texture: an image plus sampler state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Texture {
    /// Index into [`Scene::images`].
    pub image: u32,
    pub wrap_s: Wrap,
    pub wrap_t: Wrap,
    pub nearest: bool,
}

/// A decoded image, RGBA8, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub name: Option<String>,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

/// The radiance of the environment that lights a scene with no light of its own.
pub const DEFAULT_ENVIRONMENT: Vec3 = Vec3::ONE;

/// A loaded scene. Build its GPU form with [`crate::SceneGpu::build`].
#[derive(Clone, Debug)]
pub struct Scene {
    /// The file it came from.
    pub source: PathBuf,
    pub triangles: Vec<Triangle>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Shared with the GPU form's texture atlas ([`crate::gpu::Atlas`]), not copied into it.
    pub images: Arc<[Image]>,
    /// The first perspective camera of the scene's node tree, if any.
    pub camera: Option<Camera>,
    /// Constant environment radiance (linear RGB) seen by rays that leave the scene, unless
    /// `environment_map` is set.
    pub environment: Vec3,
    /// An equirectangular map seen by rays that leave the scene (replaces `environment`).
    pub environment_map: Option<Arc<EnvMap>>,
    /// How next-event estimation samples the map.
    pub environment_sampling: EnvSampling,
    /// `KHR_lights_punctual` lights.
    pub lights: Vec<PunctualLight>,
    /// One line per kind of unsupported or skipped content (also printed once to stderr).
    pub warnings: Vec<String>,
}

impl Scene {
    /// Loads a `.gltf` (embedded or external buffers) or `.glb` file with default options.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
        load::load(path.as_ref(), &LoadOptions::default())
    }

    /// Loads with options (e.g. an environment override).
    pub fn load_with(path: impl AsRef<Path>, options: &LoadOptions) -> Result<Scene> {
        load::load(path.as_ref(), options)
    }

    /// Loads a `.gltf` (JSON) or `.glb` from memory. External buffer and image URIs are
    /// resolved against `base` (with `None` they are an error) and must stay inside it unless
    /// [`LoadOptions::allow_outside_paths`] is set; errors name the source `<memory>`.
    pub fn from_slice(bytes: &[u8], base: Option<&Path>, options: &LoadOptions) -> Result<Scene> {
        load::load_bytes(Path::new("<memory>"), bytes, base, options)
    }

    /// Bare triangles facing +Z with the default material, and nothing else: no camera, no
    /// light, a black environment. Geometry for tests and benchmarks.
    pub fn from_triangles(positions: impl IntoIterator<Item = [Vec3; 3]>) -> Scene {
        Scene {
            source: "<triangles>".into(),
            triangles: positions
                .into_iter()
                .map(|positions| Triangle {
                    positions,
                    normals: [Vec3::Z; 3],
                    uvs: [Vec2::ZERO; 3],
                    material: 0,
                })
                .collect(),
            materials: vec![Material::default()],
            textures: vec![],
            images: Arc::new([]),
            camera: None,
            environment: Vec3::ZERO,
            environment_map: None,
            environment_sampling: EnvSampling::Importance,
            lights: vec![],
            warnings: vec![],
        }
    }

    /// World-space bounds of all triangles.
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for t in &self.triangles {
            for &p in &t.positions {
                b.grow_point(p);
            }
        }
        b
    }

    /// The file's camera, or [`Camera::framing`] of the scene bounds.
    pub fn camera_or_default(&self) -> Camera {
        self.camera
            .unwrap_or_else(|| Camera::framing(&self.bounds()))
    }

    /// Whether anything emits: an emissive triangle, a punctual light, or the environment.
    pub fn has_light(&self) -> bool {
        let emissive = |m: u32| {
            self.materials
                .get(m as usize)
                .is_some_and(|m| m.emissive.max_element() > 0.0)
        };
        self.environment.max_element() > 0.0
            || self.environment_map.as_ref().is_some_and(|m| m.has_light())
            || self.lights.iter().any(|l| l.intensity.max_element() > 0.0)
            || self.triangles.iter().any(|t| emissive(t.material))
    }

    /// Multiplies the environment (constant or map) by `k`.
    pub fn scale_environment(&mut self, k: f32) {
        self.environment *= k;
        if let Some(m) = &mut self.environment_map {
            Arc::make_mut(m).scale(k);
        }
    }

    /// Sets the map's rotation about +Y (radians; no effect on a constant environment).
    pub fn rotate_environment(&mut self, radians: f32) {
        if let Some(m) = &mut self.environment_map {
            Arc::make_mut(m).rotation = radians;
        }
    }

    /// Lights a scene that has no light at all with [`DEFAULT_ENVIRONMENT`], and returns the
    /// one warning to print (a black frame with no word about why helps nobody).
    pub fn light_if_dark(&mut self) -> Option<String> {
        if self.has_light() {
            return None;
        }
        self.environment = DEFAULT_ENVIRONMENT;
        self.environment_map = None; // (an all-black map)
        Some(format!(
            "{}: nothing emits light (no emissive material, no KHR_lights_punctual light, no \
             environment): lit by a uniform white environment of radiance 1; choose lighting \
             with --environment R,G,B or --environment FILE.hdr|.exr",
            self.source.display()
        ))
    }
}
