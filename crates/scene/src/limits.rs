//! What a device can hold of a scene, checked from the loaded scene before its BVH is built.
//!
//! The scene's arrays are read from images of `SCENE_TEXELS_WIDTH` texels a row
//! (`crate::gpu::texels`), so what really bounds them is `maxImageDimension2D` rows and the
//! memory budget. They are also held to `maxStorageBufferRange`, as when they were storage
//! buffers: a scene that fits a device's buffers fits any renderer of the same layout. The
//! environment map is the exception: it was always sampled from the light image, and an
//! 8192 x 4096 map (512 MiB of texels) is an ordinary one, far over lavapipe's 128 MiB range.

use crate::gpu::{self, SCENE_TEXELS_WIDTH};
use crate::scene::Scene;
use crate::{Result, SceneError};

/// The limits of the device a scene is rendered on that bound what it can hold (the fields of
/// `blueshift_device::DeviceInfo` of the same names). The loader's budget follows from them
/// ([`crate::LoadBudget::for_device`]), so a file the device cannot hold is refused from its
/// counts, before it is expanded, rather than after seconds of loading and a BVH build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DeviceLimits {
    /// Each scene array but the environment map is held to it.
    pub max_storage_buffer_range: u64,
    /// Rows of each scene image.
    pub max_image_dimension_2d: u32,
    /// Bytes the device may allocate in all.
    pub memory_budget: u64,
}

impl DeviceLimits {
    /// lavapipe's (Mesa 22.3, 64-bit host with 2 GiB or more): what CI renders on.
    pub const LAVAPIPE: DeviceLimits = DeviceLimits {
        max_storage_buffer_range: 128 << 20,
        max_image_dimension_2d: 16384,
        memory_budget: 2 << 30,
    };
}

impl Scene {
    /// Checks that this scene fits `device` before anything is built for it: each array
    /// against `maxStorageBufferRange` (the BVH node array by its worst case, 2n - 1 nodes;
    /// [`crate::SceneGpu::check_limits`] checks the exact sizes after the build), each scene
    /// image against `maxImageDimension2D` rows, and all of them against the memory budget.
    pub fn check_limits(&self, device: &DeviceLimits) -> Result<()> {
        let n = self.triangles.len() as u64;
        let emissive = self
            .triangles
            .iter()
            .filter(|t| {
                self.materials
                    .get(t.material as usize)
                    .is_some_and(|m| m.emissive.max_element() > 0.0)
            })
            .count() as u64;
        let lights = emissive + self.lights.len() as u64;
        let texels: u64 = self
            .images
            .iter()
            .map(|i| i.width as u64 * i.height as u64)
            .sum();
        let (materials, textures) = (self.materials.len() as u64, self.textures.len() as u64);
        let size = |count: u64, bytes: usize| count.saturating_mul(bytes as u64);
        let arrays = [
            (
                "BVH node",
                size((2 * n).saturating_sub(1), size_of::<gpu::BvhNode>()),
            ),
            ("BVH triangle", size(n, size_of::<gpu::GpuTriangle>())),
            (
                "triangle shading",
                size(n, size_of::<gpu::TriangleShading>()),
            ),
            ("material", size(materials, size_of::<gpu::GpuMaterial>())),
            (
                "texture table",
                size(textures, size_of::<gpu::GpuTexture>()),
            ),
            ("texel", texels.saturating_mul(4)),
            ("light", size(lights + 1, size_of::<gpu::GpuLight>())),
        ];
        check_sizes(&arrays, device.max_storage_buffer_range)?;

        // Texels of each scene image (`SceneGpu::texel_sources`), nodes at their worst case.
        let environment = self
            .environment_map
            .as_ref()
            .map_or(0, |m| m.texels.len() as u64 + m.height as u64);
        let params = self.lights.len().max(1) as u64;
        let images = [
            ("BVH node", gpu::NODE_TEXELS as u64 * 2 * n),
            ("triangle", gpu::TRIANGLE_TEXELS as u64 * n),
            ("triangle shading", gpu::SHADING_TEXELS as u64 * n),
            ("material", gpu::MATERIAL_TEXELS as u64 * materials),
            ("texture table", textures),
            ("texel", texels.div_ceil(gpu::ATLAS_WORDS_PER_TEXEL as u64)),
            (
                "light (lights and environment map)",
                lights + gpu::LIGHT_PARAMS_TEXELS as u64 * params + environment,
            ),
        ];
        let width = SCENE_TEXELS_WIDTH as u64;
        let mut bytes = 0u64;
        for (image, texels) in images {
            let rows = texels.max(1).div_ceil(width);
            if rows > device.max_image_dimension_2d as u64 {
                return Err(SceneError::ImageOverLimit {
                    image,
                    rows,
                    limit: device.max_image_dimension_2d,
                });
            }
            bytes = bytes.saturating_add(rows * width * 16);
        }
        if bytes > device.memory_budget {
            return Err(SceneError::MemoryOverLimit {
                mib: bytes >> 20,
                budget_mib: device.memory_budget >> 20,
            });
        }
        Ok(())
    }
}

/// The first array over the storage-buffer range, as an error.
pub(crate) fn check_sizes(sizes: &[(&'static str, u64)], limit: u64) -> Result<()> {
    match sizes.iter().find(|(_, size)| *size > limit) {
        Some(&(buffer, size)) => Err(SceneError::over_limit(buffer, size, limit)),
        None => Ok(()),
    }
}
