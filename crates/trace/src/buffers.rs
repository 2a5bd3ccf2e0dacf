//! The scene's constants on the device (its arrays are images: [`crate::SceneImages`]).
use crate::{Result, TraceError};
use blueshift_device::{Buffer, Device};
use blueshift_scene::SceneGpu;

/// The scene's [`blueshift_scene::SceneInfo`] on the device. The passes read the arrays from
/// the scene images only; uploading them as storage buffers too held a second copy of the
/// scene on the device (140 bytes per triangle) that nothing read.
pub struct SceneBuffers {
    pub info: Buffer,
}

impl std::fmt::Debug for SceneBuffers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneBuffers")
            .field("info", &self.info.size)
            .finish_non_exhaustive()
    }
}

impl SceneBuffers {
    /// Uploads `scene`'s info, first checking every array against the device's
    /// storage-buffer range (as when they were storage buffers: the same scenes are refused).
    pub fn new(dev: &Device, scene: &SceneGpu) -> Result<Self> {
        let limit = dev.info().max_storage_buffer_range;
        scene
            .check_limits(limit)
            .map_err(|e| TraceError::Scene(e.to_string()))?;
        Ok(Self {
            info: Buffer::upload(dev, "scene.info", std::slice::from_ref(&scene.info))?,
        })
    }
}
