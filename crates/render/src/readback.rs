//! Reading the renderer's buffers back: for tests, reports, screenshots and engines that want
//! the raw data.
use crate::{Renderer, Result};
use blueshift_device::Buffer;
use blueshift_layout::motion::GBufferTexel;
use blueshift_permute::Screen;

impl Renderer {
    /// The device buffer of the tonemapped output (packed RGBA8 per pixel, row-major), for
    /// passes that read it after [`Self::render_frame`] returned.
    pub fn ldr_buffer(&self) -> &Buffer {
        &self.ldr
    }
    /// The device buffer of the running mean (`[f32; 4]` per pixel, row-major).
    pub fn accum_buffer(&self) -> &Buffer {
        &self.accum
    }

    /// The raw estimate of the last frame: (r, g, b, luminance) per pixel, row-major.
    pub fn read_estimate(&self) -> Result<Vec<[f32; 4]>> {
        Ok(self.estimate.read::<[f32; 4]>()?[..self.pixels()].to_vec())
    }
    /// The running mean since the last reset or camera move.
    pub fn read_accum(&self) -> Result<Vec<[f32; 4]>> {
        Ok(self.accum.read::<[f32; 4]>()?[..self.pixels()].to_vec())
    }
    /// The tonemapped accumulation as RGBA8 bytes.
    pub fn read_ldr(&self) -> Result<Vec<u8>> {
        let words = self.ldr.read::<u32>()?;
        Ok(bytemuck::cast_slice(&words[..self.pixels()]).to_vec())
    }
    /// The G-buffer of the last frame, if the method uses one (edge-aware or reprojecting).
    pub fn read_gbuffer(&self) -> Result<Option<Vec<GBufferTexel>>> {
        match &self.surfaces {
            Some(m) => Ok(Some(m.current_gbuffer().read()?[..self.pixels()].to_vec())),
            None => Ok(None),
        }
    }
    /// The mean motion (pixels) the last reprojection measured; (0, 0) without one.
    pub fn last_motion(&self) -> (i32, i32) {
        self.surfaces.as_ref().map_or((0, 0), |m| m.last_motion)
    }
    /// The current (padded) seed buffer.
    pub fn read_seeds(&self) -> Result<Vec<u32>> {
        Ok(self.seeds[self.current].read::<u32>()?[..self.screen.seed_count()].to_vec())
    }
    pub fn initial_seeds(&self) -> &[u32] {
        &self.initial_seeds
    }
    pub fn screen(&self) -> Screen {
        self.screen
    }
    fn pixels(&self) -> usize {
        self.cfg.width as usize * self.cfg.height as usize
    }
}
