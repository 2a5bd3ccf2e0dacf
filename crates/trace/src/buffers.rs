//! Scene upload: one named storage buffer per scene array.
use crate::{Result, TraceError};
use blueshift_device::{Buffer, Device};
use blueshift_scene::SceneGpu;

/// The scene on the device.
pub struct SceneBuffers {
    pub nodes: Buffer,
    pub triangles: Buffer,
    pub shading: Buffer,
    pub materials: Buffer,
    pub textures: Buffer,
    pub texels: Buffer,
    pub lights: Buffer,
    pub info: Buffer,
}

impl std::fmt::Debug for SceneBuffers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneBuffers")
            .field("nodes", &self.nodes.size)
            .finish_non_exhaustive()
    }
}

impl SceneBuffers {
    /// Uploads `scene`, first checking every array against the device's storage-buffer range.
    pub fn new(dev: &Device, scene: &SceneGpu) -> Result<Self> {
        let limit = dev.info().max_storage_buffer_range;
        scene
            .check_limits(limit)
            .map_err(|e| TraceError::Scene(e.to_string()))?;
        Ok(Self {
            nodes: Buffer::upload(dev, "scene.bvh_nodes", &scene.nodes)?,
            triangles: Buffer::upload(dev, "scene.bvh_triangles", &scene.triangles)?,
            shading: Buffer::upload(dev, "scene.triangle_shading", &scene.shading)?,
            materials: Buffer::upload(dev, "scene.materials", &scene.materials)?,
            textures: Buffer::upload(dev, "scene.textures", &scene.textures)?,
            texels: Buffer::upload(dev, "scene.texels", &scene.texels)?,
            lights: Buffer::upload(dev, "scene.lights", &scene.lights)?,
            info: Buffer::upload(dev, "scene.info", std::slice::from_ref(&scene.info))?,
        })
    }
}
