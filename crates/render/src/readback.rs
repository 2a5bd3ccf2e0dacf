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
        &self.res.ldr
    }
    /// The device buffer of the running mean (`[f32; 4]` per pixel, row-major).
    pub fn accum_buffer(&self) -> &Buffer {
        &self.res.accum
    }

    /// The raw estimate of the last frame: (r, g, b, luminance) per pixel, row-major.
    pub fn read_estimate(&self) -> Result<Vec<[f32; 4]>> {
        Ok(self.res.estimate.read::<[f32; 4]>()?[..self.pixels()].to_vec())
    }
    /// `PRIMARY_*` bits of each pixel's latest primary hit (kept only by methods that take
    /// the jitter from the seed on textured surfaces; zero otherwise).
    pub fn read_primary_flags(&self) -> Result<Vec<u32>> {
        Ok(self.res.primary_flags.read::<u32>()?[..self.pixels()].to_vec())
    }
    /// Overwrites the `PRIMARY_*` bits the next frame's trace pass reads (for tests: which
    /// pixels take their jitter from the seed).
    pub fn write_primary_flags(&mut self, flags: &[u32]) -> Result<()> {
        if flags.len() != self.pixels() {
            return Err(crate::RenderError::Invalid(format!(
                "{} primary flags for {} pixels",
                flags.len(),
                self.pixels()
            )));
        }
        self.finish_frames()?;
        Ok(self.res.primary_flags.write(0, flags)?)
    }
    /// The running mean since the last reset or camera move.
    pub fn read_accum(&self) -> Result<Vec<[f32; 4]>> {
        Ok(self.res.accum.read::<[f32; 4]>()?[..self.pixels()].to_vec())
    }
    /// The tonemapped accumulation as RGBA8 bytes.
    pub fn read_ldr(&self) -> Result<Vec<u8>> {
        let words = self.res.ldr.read::<u32>()?;
        Ok(bytemuck::cast_slice(&words[..self.pixels()]).to_vec())
    }
    /// The G-buffer of the last frame, if the method uses one (edge-aware or reprojecting).
    pub fn read_gbuffer(&self) -> Result<Option<Vec<GBufferTexel>>> {
        match &self.surfaces {
            Some(m) => Ok(Some(m.current_gbuffer().read()?[..self.pixels()].to_vec())),
            None => Ok(None),
        }
    }
    /// The surface classes the last sort read (edge-aware methods), per pixel.
    pub fn read_classes(&self) -> Result<Option<Vec<u32>>> {
        match &self.surfaces {
            Some(m) => Ok(Some(m.classes.read()?[..self.pixels()].to_vec())),
            None => Ok(None),
        }
    }
    /// The mean motion (pixels) the last reprojection measured; (0, 0) without one.
    pub fn last_motion(&self) -> (i32, i32) {
        self.surfaces.as_ref().map_or((0, 0), |m| m.last_motion)
    }
    /// The current (padded) seed buffer.
    pub fn read_seeds(&self) -> Result<Vec<u32>> {
        Ok(self.res.seeds[self.res.current].read::<u32>()?[..self.screen.seed_count()].to_vec())
    }
    pub fn initial_seeds(&self) -> &[u32] {
        &self.initial_seeds
    }
    /// Every buffer the method carries from frame to frame besides the seeds, as floats over
    /// the visible pixels: the running mean (`sort-cycle`'s point cycle ranks against it),
    /// `sort-cycle`'s per-phase keys and the history keys' means and frame counts. All must
    /// stay finite over any run; only [`HistoryState::nan_is_none`] buffers use NaN, as "no
    /// history". The buffers a method has not made yet are left out.
    pub fn read_history_state(&self) -> Result<Vec<HistoryState>> {
        let (w, h, stride) = (
            self.cfg.width as usize,
            self.cfg.height as usize,
            self.screen.stride() as usize,
        );
        let visible = |at: &dyn Fn(usize) -> f32| -> Vec<f32> {
            (0..h)
                .flat_map(|y| (0..w).map(move |x| y * stride + x))
                .map(at)
                .collect()
        };
        let mut out = vec![HistoryState::of(
            "frame.accum",
            self.read_accum()?.iter().flatten().copied().collect(),
        )];
        if let Some(c) = &self.cycle {
            // (seed, key bits) per phase slot and visible pixel; unwritten slots are zeroed.
            let slots = c.history.read::<[u32; 2]>()?;
            let keys = slots.iter().map(|&[_, k]| f32::from_bits(k)).collect();
            out.push(HistoryState::of("cycle.history keys", keys));
        }
        if let Some(hk) = self.surfaces.as_ref().and_then(|s| s.history_keys()) {
            // (mean, frames) per padded pixel: the padding is never written, so left out.
            let hist = hk.current().read::<[f32; 2]>()?;
            out.push(HistoryState::of(
                "history means",
                visible(&|i: usize| hist[i][0]),
            ));
            out.push(HistoryState::of(
                "history frames",
                visible(&|i: usize| hist[i][1]),
            ));
            let mean = hk.mean.read::<f32>()?;
            out.push(HistoryState {
                nan_is_none: true,
                ..HistoryState::of("history.mean", mean[..w * h].to_vec())
            });
        }
        Ok(out)
    }
    pub fn screen(&self) -> Screen {
        self.screen
    }
    pub(crate) fn pixels(&self) -> usize {
        self.cfg.width as usize * self.cfg.height as usize
    }
}

/// One buffer of [`Renderer::read_history_state`].
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryState {
    pub name: &'static str,
    pub values: Vec<f32>,
    /// NaN marks a pixel without history here (the means the sort ranks against).
    pub nan_is_none: bool,
}

impl HistoryState {
    fn of(name: &'static str, values: Vec<f32>) -> Self {
        Self {
            name,
            values,
            nan_is_none: false,
        }
    }

    /// How many values are not finite (NaN counts only where it does not mean "none").
    pub fn bad_values(&self) -> usize {
        self.values
            .iter()
            .filter(|v| v.is_infinite() || (v.is_nan() && !self.nan_is_none))
            .count()
    }
}
