//! [`RenderConfig`]: what to render and how, checked against the device limits before
//! anything is allocated.
use crate::{Method, RenderError, Result, SeedMap, TRACE_LOOP_GUARD};
use blueshift_device::Device;
use blueshift_sampling::Sampler;

/// What to render and how.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderConfig {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel per frame.
    pub spp: u32,
    /// Path vertices after the camera (1 = direct light only).
    pub bounces: u32,
    pub method: Method,
    /// Sorting block edge B (2..=8) of the methods that take one (`Method::fixed_block` is
    /// `None`); `None`: [`crate::PAPER_BLOCK`]. A method with blocks of its own refuses
    /// another size.
    pub block: Option<u32>,
    /// Seeded sampler; `None` = the method's default.
    pub sampler: Option<Sampler>,
    /// Experiment: hash the frame index into fixed seeds (breaks the temporal correlation).
    pub frame_salt: bool,
    /// Seeds the initial seed map (different sequences for the same settings).
    pub sequence: u32,
    pub exposure: f32,
    /// Nominal view size mapping onto the camera's field of view; `None` = (width, height).
    /// A wider image with the nominal size of the frames renders a whole pan at once.
    pub view_size: Option<(u32, u32)>,
    /// Primary rays through pixel centres (no anti-aliasing jitter).
    pub no_jitter: bool,
    /// A frame whose trace pass ran this many loop iterations in one SIMD batch is an error
    /// (`TraceError::LoopLimit`); default [`TRACE_LOOP_GUARD`].
    pub loop_guard: u32,
    /// The seed map of frame 0 (the `hbo19` method always uses [`SeedMap::Hbo19`]).
    pub seed_map: SeedMap,
    /// Trace with the Lambert-only shader variant when the scene allows it (every material a
    /// triangle uses has metallic = specular = 0; same images, bit for bit). `false` keeps
    /// the full BRDF (tests, timing).
    pub lambert_variant: bool,
    /// Trace with the loop-counting shader (`trace/trace_loop_stats`; same images, slower):
    /// [`crate::FrameStats::loops`].
    pub loop_stats: bool,
    /// How frames accumulate when the camera moves.
    pub accumulation: Accumulation,
}

/// How the accumulation (the output the tonemap shows) takes in each frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Accumulation {
    /// The running mean since the last reset or camera move.
    #[default]
    Mean,
    /// Along the motion (the `taa` pass, [`crate::taa`]) on every frame, the operator `eval`
    /// measures: with a still camera, the EMA of weight [`crate::taa::ALPHA`].
    Taa,
    /// Along the motion while the camera moves, the running mean while it is still: a
    /// viewer's choice (what one sees while moving is what `eval` measures, and a still view
    /// converges). After motion the mean goes on as if from 1 / ALPHA - 1 frames, so its first
    /// step weighs the new frame as the TAA did.
    Follow,
}

impl RenderConfig {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            spp: 1,
            bounces: 8,
            method: Method::DEFAULT,
            block: None,
            sampler: None,
            frame_salt: false,
            sequence: 0,
            exposure: 1.0,
            view_size: None,
            no_jitter: false,
            loop_guard: TRACE_LOOP_GUARD,
            seed_map: SeedMap::Random,
            lambert_variant: true,
            loop_stats: false,
            accumulation: Accumulation::Mean,
        }
    }

    /// Whether seeds are HBO+19 tile positions: always for `hbo19`; for the permutation
    /// methods if asked (the others keep their own seeds, so baselines stay what they are).
    pub fn tile_seeds(&self) -> bool {
        self.method == Method::Hbo19 || (self.seed_map == SeedMap::Hbo19 && self.method.sorts())
    }

    /// The sorting block edge in effect.
    pub fn effective_block(&self) -> u32 {
        self.method.block(self.block)
    }

    /// The seeded sampler in effect.
    pub fn effective_sampler(&self) -> Sampler {
        self.sampler.unwrap_or(if self.tile_seeds() {
            Sampler::Hbo19
        } else {
            self.method.default_sampler()
        })
    }

    /// Checks every user-controlled value against its range and the device limits.
    pub fn validate(&self, dev: &Device) -> Result<()> {
        let max = dev.info().max_image_dimension_2d.min(16384);
        let bad = |m: String| Err(RenderError::Invalid(m));
        if self.width == 0 || self.height == 0 || self.width > max || self.height > max {
            return bad(format!(
                "resolution {}x{} is outside 1..={max} per side",
                self.width, self.height
            ));
        }
        if !(1..=4096).contains(&self.spp) {
            return bad(format!("spp {} is outside 1..=4096", self.spp));
        }
        if self.bounces > 64 {
            return bad(format!("bounces {} is over 64", self.bounces));
        }
        if let Some(block) = self.block {
            if !(2..=8).contains(&block) {
                return bad(format!("block size {block} is outside 2..=8"));
            }
            if let Some(own) = self.method.fixed_block().filter(|own| *own != block) {
                return bad(format!(
                    "block size {block}: {} sorts {own}x{own} blocks of its own (--block \
                     applies to sort-retarget and its spelled-out forms)",
                    self.method
                ));
            }
        }
        if !self.exposure.is_finite() || self.exposure <= 0.0 {
            return bad(format!(
                "exposure {} must be a positive number",
                self.exposure
            ));
        }
        let bytes = self.width as u64 * self.height as u64 * 16;
        if bytes > dev.info().max_storage_buffer_range {
            return bad(format!(
                "resolution {}x{} needs a {} MiB estimate buffer, over the device's {} MiB storage-buffer range",
                self.width,
                self.height,
                bytes >> 20,
                dev.info().max_storage_buffer_range >> 20
            ));
        }
        Ok(())
    }
}
