//! Recorder commands for presentation: layout transitions of raw images (swapchain images are
//! not [`crate::Image`]s) and copies of packed pixels from a buffer into them.
use crate::commands::Recorder;
use crate::error::Result;
use crate::memory::{Buffer, color_range};
use ash::vk;

impl Recorder {
    /// Moves a swapchain image between layouts. From `UNDEFINED` (contents discarded) the
    /// barrier starts at TRANSFER, the stage a submission waits for the acquire semaphore at;
    /// `TRANSFER_DST_OPTIMAL -> PRESENT_SRC_KHR` makes a copy visible to the presentation
    /// engine. Other layouts get full barriers.
    pub fn transition_image(
        &mut self,
        image: vk::Image,
        old: vk::ImageLayout,
        new: vk::ImageLayout,
    ) -> Result<()> {
        self.check_recording()?;
        let transfer = (
            vk::PipelineStageFlags::TRANSFER,
            vk::AccessFlags::TRANSFER_WRITE,
        );
        let (src_stage, src_access) = match old {
            vk::ImageLayout::UNDEFINED => {
                (vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::empty())
            }
            vk::ImageLayout::TRANSFER_DST_OPTIMAL => transfer,
            _ => (
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::AccessFlags::MEMORY_WRITE,
            ),
        };
        let (dst_stage, dst_access) = match new {
            vk::ImageLayout::PRESENT_SRC_KHR => (
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                vk::AccessFlags::empty(),
            ),
            vk::ImageLayout::TRANSFER_DST_OPTIMAL => transfer,
            _ => (
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE,
            ),
        };
        let b = vk::ImageMemoryBarrier::default()
            .image(image)
            .old_layout(old)
            .new_layout(new)
            .src_access_mask(src_access)
            .dst_access_mask(dst_access)
            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .subresource_range(color_range());
        // SAFETY: recording; the image belongs to this device.
        unsafe {
            self.dev.raw().cmd_pipeline_barrier(
                self.cmd,
                src_stage,
                dst_stage,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[b],
            );
        }
        Ok(())
    }

    /// Copies tightly packed 4-byte texels from `src` into `image` (in TRANSFER_DST_OPTIMAL) of
    /// `width x height`, after a barrier if `src` was just written.
    pub fn copy_buffer_to_image(
        &mut self,
        src: &Buffer,
        image: vk::Image,
        width: u32,
        height: u32,
    ) -> Result<()> {
        self.check_recording()?;
        let needed = width as u64 * height as u64 * 4;
        if src.size < needed {
            return Err(crate::DeviceError::Usage(format!(
                "copy of {width}x{height} texels from '{}' ({} bytes, {needed} needed)",
                src.name, src.size
            )));
        }
        let region = crate::transfer::whole_image_copy(width, height);
        self.access(&[vk::Handle::as_raw(src.raw)], &[vk::Handle::as_raw(image)]);
        // SAFETY: recording; the buffer is TRANSFER_SRC, the image in TRANSFER_DST_OPTIMAL.
        unsafe {
            self.dev.raw().cmd_copy_buffer_to_image(
                self.cmd,
                src.raw,
                image,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            );
        }
        Ok(())
    }
}
