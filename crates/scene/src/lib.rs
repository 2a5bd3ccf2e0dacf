//! Scenes for Blueshift: glTF 2.0 loading, a binned-SAH BVH, and the flattened GPU layout the
//! path-tracing compute shader reads. Pure CPU; nothing here needs a Vulkan device.
//!
//! Pipeline: [`Scene::load`] (glTF/GLB -> world-space triangles, materials, textures, camera)
//! -> [`SceneGpu::build`] (BVH build, triangles reordered into BVH leaf order, light CDF,
//! texture atlas) -> upload [`SceneGpu::buffers`]. The CPU intersector on [`SceneGpu`]
//! ([`SceneGpu::closest_hit`], [`SceneGpu::occluded`], [`SceneGpu::trace_rays`]) is the twin
//! of `shaders/include/bvh.glsl`: same traversal, same Möller–Trumbore operation order.
//!
//! ```no_run
//! # fn main() -> Result<(), blueshift_scene::SceneError> {
//! use blueshift_scene::{Scene, SceneGpu, Ray};
//! let scene = Scene::load("assets/scenes/cornell-box.gltf")?;
//! scene.check_limits(&blueshift_scene::DeviceLimits::LAVAPIPE)?;
//! let gpu = SceneGpu::build(&scene);
//! let camera = scene.camera_or_default();
//! let ray = camera.basis(1.0).primary_ray(128, 128, 256, 256);
//! let hit = gpu.closest_hit(&ray);
//! # let _ = (hit, Ray::default()); Ok(()) }
//! ```

pub mod bvh;
mod camera;
mod environment;
mod error;
mod geometry;
pub mod gpu;
mod intersect;
mod lights;
mod limits;
mod load;
pub mod presets;
mod scene;

pub use blueshift_assets::files::{open_regular, read_regular};
pub use bvh::Bvh;
pub use camera::{Camera, CameraBasis};
pub use environment::{
    EnvMap, EnvMapError, EnvSampling, EnvTables, MAX_ENV_SIDE, MAX_ENV_TEXELS, env_density,
    env_direction, env_texel_of, env_uv,
};
pub use error::SceneError;
pub use geometry::Aabb;
pub use gpu::{
    BvhNode, GpuLight, GpuMaterial, GpuTexture, GpuTriangle, Hit, LIGHT_QUAD_SHIFT,
    LIGHT_TRIANGLE_MASK, QuadFrame, Ray, SceneGpu, SceneInfo, TriangleShading,
};
pub use intersect::{
    TraversalCounts, closest_hit, closest_hit_brute_force, closest_hit_counted, intersect_triangle,
    occluded,
};
pub use lights::{LightKind, PunctualLight};
pub use limits::DeviceLimits;
pub use load::{EnvironmentSource, LoadBudget, LoadOptions, MAX_COORDINATE};
pub use scene::{DEFAULT_ENVIRONMENT, Image, Material, Scene, Texture, Triangle, Wrap};

/// Result alias for this crate.
pub type Result<T, E = SceneError> = std::result::Result<T, E>;

/// The generated GLSL header with every shared scene struct and constant, meant for
/// `shaders/include/generated/scene.glsl`.
pub fn glsl_header() -> String {
    gpu::header().render("scene")
}
