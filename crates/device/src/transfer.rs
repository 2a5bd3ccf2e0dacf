//! Transfer commands of the [`Recorder`]: copies, fills and image initialisation, each after a
//! barrier when it depends on an earlier command (`Recorder::access`).
use crate::commands::Recorder;
use crate::device::Device;
use crate::error::Result;
use crate::memory::{Buffer, Image, color_range};
use ash::vk;

impl Recorder {
    /// Records `f` into a recorder of its own, submits it and waits: the staging copies of
    /// set-up, resets and one-off reads.
    pub fn one_shot(
        dev: &Device,
        name: &str,
        f: impl FnOnce(&mut Recorder) -> Result<()>,
    ) -> Result<()> {
        let mut rec = Recorder::new(dev, name)?;
        rec.begin()?;
        f(&mut rec)?;
        rec.submit_and_wait()?;
        Ok(())
    }

    /// Copies `size` bytes (whole `src` when `None`) from `src` to `dst`.
    pub fn copy_buffer(&mut self, src: &Buffer, dst: &Buffer, size: Option<u64>) -> Result<()> {
        let size = size.unwrap_or(src.size.min(dst.size));
        self.copy_region(src, dst, 0, size)
    }

    /// Copies `size` bytes from the start of `src` to byte `offset` of `dst`.
    pub fn copy_region(
        &mut self,
        src: &Buffer,
        dst: &Buffer,
        offset: u64,
        size: u64,
    ) -> Result<()> {
        self.check_recording()?;
        self.access(&[handle(src.raw)], &[handle(dst.raw)]);
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: offset,
            size,
        };
        // SAFETY: recording; both buffers are TRANSFER capable.
        unsafe {
            self.dev
                .raw()
                .cmd_copy_buffer(self.cmd, src.raw, dst.raw, &[region])
        };
        Ok(())
    }

    /// Fills a whole buffer with a repeated u32.
    pub fn fill_buffer(&mut self, buf: &Buffer, value: u32) -> Result<()> {
        self.check_recording()?;
        self.access(&[], &[handle(buf.raw)]);
        // SAFETY: recording.
        unsafe {
            self.dev
                .raw()
                .cmd_fill_buffer(self.cmd, buf.raw, 0, vk::WHOLE_SIZE, value)
        };
        Ok(())
    }

    /// Moves a fresh image from UNDEFINED to GENERAL (contents discarded).
    pub fn init_image(&mut self, img: &Image) -> Result<()> {
        self.check_recording()?;
        let b = vk::ImageMemoryBarrier::default()
            .image(img.raw)
            .old_layout(vk::ImageLayout::UNDEFINED)
            .new_layout(vk::ImageLayout::GENERAL)
            .src_access_mask(vk::AccessFlags::empty())
            .dst_access_mask(vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE)
            .subresource_range(color_range());
        // SAFETY: recording.
        unsafe {
            self.dev.raw().cmd_pipeline_barrier(
                self.cmd,
                vk::PipelineStageFlags::TOP_OF_PIPE,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[b],
            );
        }
        Ok(())
    }
}

/// A Vulkan handle as the key of the barrier bookkeeping.
fn handle(h: impl vk::Handle) -> u64 {
    h.as_raw()
}

/// A tightly packed buffer <-> colour image copy of the whole `width x height` mip 0.
pub(crate) fn whole_image_copy(width: u32, height: u32) -> vk::BufferImageCopy {
    vk::BufferImageCopy::default()
        .image_subresource(vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        })
        .image_extent(vk::Extent3D {
            width,
            height,
            depth: 1,
        })
}
