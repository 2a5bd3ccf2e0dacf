//! The viewer's GPU side: the swapchain, the renderers (the view, the right-hand view in
//! split-screen, the error view's reference) and the present pass.
//!
//! Presentation: after the renderers' frames (each its own waited-for submission), one
//! submission runs `view/present`, which composes their LDR (or, for the error view, accum)
//! buffers into a host-visible buffer of window pixels in the swapchain's byte order (nearest
//! upscaling, split-screen divider). That buffer is copied into the acquired swapchain image
//! (UNDEFINED -> TRANSFER_DST_OPTIMAL -> copy -> PRESENT_SRC), waiting for the acquire
//! semaphore and signalling the image's render-finished semaphore. A screenshot reads the same
//! buffer, so it is exactly what was presented.
use super::controls::{Change, ERROR_SCALE, REFERENCE_SPP, Settings};
use super::renderers::{make_reference, make_renderer};
use anyhow::{Context, Result};
use blueshift_device::{
    ACQUIRE_SEMAPHORES, Binding, Buffer, ComputePipeline, Device, DeviceDesc, Instance,
    MemoryLocation, Recorder, Surface, SwapImage, Swapchain, is_bgra, vk,
};
use blueshift_layout::params::{
    PRESENT_FLAG_BGRA, PRESENT_FLAG_ERROR, PRESENT_FLAG_SPLIT, PresentParams,
};
use blueshift_render::{FrameStats, MethodAssets, RenderConfig, Renderer};
use blueshift_scene::{Camera, Scene};

/// What stays fixed for the whole run.
#[derive(Debug)]
pub struct Options {
    pub scene: Scene,
    pub assets: MethodAssets,
    /// Sampler and seed map; size, quality and method are set per renderer.
    pub template: RenderConfig,
    /// Render resolution divisor (1, 2 or 4).
    pub scale: u32,
    pub vsync: bool,
    pub device_index: Option<usize>,
}

/// The outcome of one frame.
#[derive(Debug)]
pub enum Frame {
    Presented {
        /// The shown renderers' per-pass GPU times (one entry per side).
        stats: Vec<FrameStats>,
        /// GPU time of the present submission.
        present_ms: f64,
        /// GPU time of the error view's reference frame, when it ran.
        reference_ms: Option<f64>,
    },
    /// The swapchain was out of date; it is recreated before the next frame.
    Skipped,
    /// The window has zero area (minimised): nothing rendered, nothing presented.
    Paused,
}

/// Render size for a window: `scale` times smaller, at least 1x1.
pub fn render_size(window: (u32, u32), scale: u32) -> (u32, u32) {
    let s = scale.max(1);
    ((window.0 / s).max(1), (window.1 / s).max(1))
}

/// Packed window pixels (swapchain byte order) to RGBA bytes.
pub fn to_rgba(words: &[u32], bgra: bool) -> Vec<u8> {
    words
        .iter()
        .flat_map(|&w| {
            let [b0, b1, b2, b3] = w.to_le_bytes();
            if bgra {
                [b2, b1, b0, b3]
            } else {
                [b0, b1, b2, b3]
            }
        })
        .collect()
}

const PRESENT_BINDINGS: [Binding; 6] = [
    Binding::storage(0, "ldr_a"),
    Binding::storage(1, "ldr_b"),
    Binding::storage(2, "accum_a"),
    Binding::storage(3, "accum_b"),
    Binding::storage(4, "reference"),
    Binding::storage(5, "window"),
];

/// Device, swapchain, renderers and the present pass. Fields drop in order: renderers and
/// buffers first, then the swapchain (which waits for the device and owns the surface).
pub struct ViewGpu {
    a: Renderer,
    b: Option<Renderer>,
    reference: Option<Renderer>,
    /// Present submissions take turns, one per frame in flight; each turn's recorder is
    /// waited for before its acquire semaphore is used again.
    recs: [Recorder; ACQUIRE_SEMAPHORES],
    turn: usize,
    /// The latest finished frame of `a` and `b`, and the latest finished present's time.
    finished: [Option<FrameStats>; 2],
    present_ms: f64,
    present: ComputePipeline,
    window_buf: Option<Buffer>,
    /// Size of the last presented image (what `window_buf` holds).
    presented: Option<(u32, u32)>,
    swapchain: Swapchain,
    dev: Device,
    opts: Options,
    /// Window size the swapchain was last made for.
    window: (u32, u32),
    dirty: bool,
}

impl std::fmt::Debug for ViewGpu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ViewGpu")
            .field("swapchain", &self.swapchain)
            .finish_non_exhaustive()
    }
}

impl ViewGpu {
    /// Creates the device for `surface`, the swapchain and the renderers for `settings`.
    pub fn new(
        instance: &Instance,
        surface: Surface,
        window: (u32, u32),
        opts: Options,
        settings: &Settings,
    ) -> Result<Self> {
        let dev = Device::new(
            instance,
            &DeviceDesc {
                device_index: opts.device_index,
                surface: Some(&surface),
            },
        )?;
        let swapchain = Swapchain::new(&dev, surface, window, opts.vsync)?;
        let spirv = blueshift_shaders::require("view/present").map_err(anyhow::Error::msg)?;
        let present = ComputePipeline::new(
            &dev,
            "view/present",
            &spirv,
            &PRESENT_BINDINGS,
            size_of::<PresentParams>() as u32,
        )?;
        let size = match swapchain.extent() {
            (0, _) | (_, 0) => render_size(window, opts.scale),
            e => render_size(e, opts.scale),
        };
        let a = make_renderer(&dev, &opts, size, settings, settings.methods[0])?;
        let mut gpu = Self {
            a,
            b: None,
            reference: None,
            recs: [
                Recorder::new(&dev, "view.0")?,
                Recorder::new(&dev, "view.1")?,
            ],
            turn: 0,
            finished: [None, None],
            present_ms: 0.0,
            present,
            window_buf: None,
            presented: None,
            swapchain,
            dev,
            opts,
            window,
            dirty: false,
        };
        gpu.rebuild(settings, size)?;
        Ok(gpu)
    }

    pub fn device(&self) -> &Device {
        &self.dev
    }
    pub fn swapchain(&self) -> &Swapchain {
        &self.swapchain
    }
    /// Render size of the views.
    pub fn render_size(&self) -> (u32, u32) {
        (self.a.config().width, self.a.config().height)
    }

    /// (Re)creates every renderer the settings need at render size `size`.
    /// Waits for the present submissions in flight (before a renderer they read is dropped).
    fn finish_presents(&mut self) -> Result<()> {
        for r in &mut self.recs {
            if r.is_pending() {
                self.present_ms = r.wait()?.iter().map(|t| t.ms).sum();
            }
        }
        self.finished = [None, None];
        Ok(())
    }

    fn rebuild(&mut self, s: &Settings, size: (u32, u32)) -> Result<()> {
        self.finish_presents()?;
        // Free the old ones first: at most one set of frame buffers exists at a time.
        self.b = None;
        self.reference = None;
        if self.render_size() != size {
            self.a = make_renderer(&self.dev, &self.opts, size, s, s.methods[0])?;
        }
        if s.split {
            self.b = Some(make_renderer(&self.dev, &self.opts, size, s, s.methods[1])?);
            self.a.reset()?;
        }
        if s.error {
            self.reference = Some(make_reference(&self.dev, &self.opts, size, s)?);
        }
        Ok(())
    }

    /// Acts on a changed setting.
    pub fn apply(&mut self, change: Change, s: &Settings) -> Result<()> {
        let size = self.render_size();
        if change != Change::Nothing {
            self.finish_presents()?;
        }
        match change {
            Change::Nothing | Change::Side | Change::Accumulation | Change::Quit => {}
            Change::Method => {
                // In split-screen both restart, so both sides show the same frame index.
                self.a.set_method(s.methods[0])?;
                self.a
                    .set_quality(s.spp, s.bounces, s.block_for(s.methods[0]))?;
                if let Some(b) = &mut self.b {
                    b.set_method(s.methods[1])?;
                    b.set_quality(s.spp, s.bounces, s.block_for(s.methods[1]))?;
                }
            }
            Change::Quality => {
                for r in [Some(&mut self.a), self.b.as_mut()].into_iter().flatten() {
                    let block = s.block_for(r.config().method);
                    r.set_quality(s.spp, s.bounces, block)?;
                }
                if let Some(r) = &mut self.reference {
                    let block = s.block_for(r.config().method);
                    r.set_quality(s.spp.max(REFERENCE_SPP), s.bounces, block)?;
                }
            }
            Change::Reset => {
                for r in [Some(&mut self.a), self.b.as_mut(), self.reference.as_mut()]
                    .into_iter()
                    .flatten()
                {
                    r.reset()?;
                }
            }
            Change::Split => {
                self.b = None;
                if s.split {
                    self.b = Some(make_renderer(&self.dev, &self.opts, size, s, s.methods[1])?);
                    self.a.reset()?;
                }
            }
            Change::Error => {
                self.reference = None;
                if s.error {
                    self.reference = Some(make_reference(&self.dev, &self.opts, size, s)?);
                }
            }
        }
        Ok(())
    }

    /// Renders and presents one frame for a window of `window` pixels.
    pub fn frame(&mut self, s: &Settings, camera: Camera, window: (u32, u32)) -> Result<Frame> {
        if window.0 == 0 || window.1 == 0 {
            return Ok(Frame::Paused);
        }
        if self.dirty || window != self.window || self.swapchain.is_paused() {
            self.swapchain.recreate(window)?;
            self.window = window;
            self.dirty = false;
            if self.swapchain.is_paused() {
                return Ok(Frame::Paused);
            }
            let size = render_size(self.swapchain.extent(), self.opts.scale);
            if size != self.render_size() {
                self.rebuild(s, size)?;
            }
        }
        // This turn's recorder, and with it the acquire semaphore its submission waited on.
        if self.recs[self.turn].is_pending() {
            self.present_ms = self.recs[self.turn].wait()?.iter().map(|t| t.ms).sum();
        }
        let Some(img) = self.swapchain.acquire()? else {
            self.dirty = true;
            return Ok(Frame::Skipped);
        };
        // Frames stay in flight: the stats are those of the latest finished frames.
        let renderers = [Some(&mut self.a), self.b.as_mut()];
        for (r, last) in renderers.into_iter().zip(&mut self.finished) {
            let Some(r) = r else { continue };
            if !s.accumulate {
                r.restart_accumulation();
            }
            r.set_camera(camera);
            if let Some(c) = r.submit_frame()?.pop() {
                *last = Some(c.stats);
            }
        }
        let mut reference_ms = None;
        if let Some(r) = &mut self.reference {
            r.set_camera(camera);
            if let Some(c) = r.submit_frame()?.pop() {
                reference_ms = Some(c.stats.passes.iter().map(|p| p.ms).sum());
            }
        }
        self.compose(s, &img)?;
        if !self.swapchain.present(&img)? {
            self.dirty = true;
        }
        Ok(Frame::Presented {
            stats: self.finished.iter().flatten().cloned().collect(),
            present_ms: self.present_ms,
            reference_ms,
        })
    }

    /// Records and submits the present pass for `img` (not waited for: the turn's recorder
    /// is, before its next use).
    fn compose(&mut self, s: &Settings, img: &SwapImage) -> Result<()> {
        let (w, h) = self.swapchain.extent();
        let bytes = w as u64 * h as u64 * 4;
        if self.window_buf.as_ref().is_none_or(|b| b.size != bytes) {
            self.finish_presents()?;
            self.window_buf = None;
            self.window_buf = Some(Buffer::new(
                &self.dev,
                "view.window",
                bytes,
                MemoryLocation::GpuOnly,
            )?);
        }
        let out = self.window_buf.as_ref().context("window buffer")?;
        let a = &self.a;
        let b = self.b.as_ref().filter(|_| s.split);
        let reference = self.reference.as_ref().filter(|_| s.error);
        let mut flags = 0;
        if b.is_some() {
            flags |= PRESENT_FLAG_SPLIT;
        }
        if reference.is_some() {
            flags |= PRESENT_FLAG_ERROR;
        }
        if is_bgra(self.swapchain.format()) {
            flags |= PRESENT_FLAG_BGRA;
        }
        let b = b.unwrap_or(a);
        let p = PresentParams {
            out_width: w,
            out_height: h,
            src_width: a.config().width,
            src_height: a.config().height,
            split_x: w / 2,
            flags,
            error_scale: ERROR_SCALE,
        };
        let reference = reference.unwrap_or(a).accum_buffer();
        let rec = &mut self.recs[self.turn];
        rec.begin()?;
        rec.begin_pass("present")?;
        rec.dispatch(
            &self.present,
            &[
                ("ldr_a", a.ldr_buffer().into()),
                ("ldr_b", b.ldr_buffer().into()),
                ("accum_a", a.accum_buffer().into()),
                ("accum_b", b.accum_buffer().into()),
                ("reference", reference.into()),
                ("window", out.into()),
            ],
            bytemuck::bytes_of(&p),
            [w.div_ceil(8), h.div_ceil(8), 1],
        )?;
        let (undefined, dst) = (
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        );
        rec.transition_image(img.image, undefined, dst)?;
        rec.copy_buffer_to_image(out, img.image, w, h)?;
        rec.transition_image(img.image, dst, vk::ImageLayout::PRESENT_SRC_KHR)?;
        rec.submit_with(
            &[(img.acquired, vk::PipelineStageFlags::TRANSFER)],
            &[img.rendered],
        )?;
        self.turn = (self.turn + 1) % ACQUIRE_SEMAPHORES;
        self.presented = Some((w, h));
        Ok(())
    }

    /// The last presented image as RGBA bytes: (width, height, pixels).
    pub fn read_presented(&self) -> Result<(u32, u32, Vec<u8>)> {
        let (w, h) = self.presented.context("no frame presented yet")?;
        let buf = self.window_buf.as_ref().context("no frame presented yet")?;
        let words = buf.read::<u32>()?;
        let n = w as usize * h as usize;
        let words = words
            .get(..n)
            .context("window buffer smaller than the image")?;
        Ok((w, h, to_rgba(words, is_bgra(self.swapchain.format()))))
    }
}

impl Drop for ViewGpu {
    fn drop(&mut self) {
        // The present submissions in flight read the renderers' buffers, dropped after this.
        let _ = self.finish_presents();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_size_divides_and_never_vanishes() {
        assert_eq!(render_size((640, 480), 2), (320, 240));
        assert_eq!(render_size((641, 3), 4), (160, 1));
        assert_eq!(render_size((5, 5), 1), (5, 5));
    }

    #[test]
    fn bgra_words_become_rgba_bytes() {
        // RGBA (1, 2, 3, 255) packed by the tonemap as r | g << 8 | b << 16 | a << 24.
        let rgba = u32::from_le_bytes([1, 2, 3, 255]);
        assert_eq!(to_rgba(&[rgba], false), vec![1, 2, 3, 255]);
        let bgra = u32::from_le_bytes([3, 2, 1, 255]);
        assert_eq!(to_rgba(&[bgra], true), vec![1, 2, 3, 255]);
    }
}
