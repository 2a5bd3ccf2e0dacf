//! The frame loop a host application drives frame by frame: the method decoded into a
//! [`recipe`] of passes per view state (`trace -> sort_seeds (retargeting on the way out) -> accumulate ->
//! tonemap` for the paper), one submission per frame with GPU timestamps per pass, up to
//! [`FRAMES_IN_FLIGHT`] frames in flight. The seed buffer is a permutation at every moment.
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
//! let dev = blueshift_device::headless(false, None)?;
//! let scene = blueshift_scene::Scene::load("assets/scenes/cornell-box.gltf")?;
//! let assets = MethodAssets::load(&default_assets_dir())?;
//! let cfg = RenderConfig { method: Method::SORT_RETARGET, ..RenderConfig::new(256, 256) };
//! let mut r = Renderer::new(&dev, &scene, &assets, cfg)?;
//! for _ in 0..16 { r.render_frame()?; }
//! let image = r.read_ldr()?;
//! # Ok(()) }
//! ```
mod camera_path;
mod config;
mod cycle;
mod error;
mod follow;
mod frame;
mod image;
mod method;
mod method_spec;
mod motion;
mod passes;
mod permutation;
mod readback;
mod recipe;
mod resources;
mod seeds;
mod slots;
mod stats;
pub mod taa;
mod taa_pass;
mod trace_params;

pub use blueshift_assets::{MethodAssets, default_assets_dir};
pub use blueshift_permute::{PAIRS_MAX_SKEWED_SHARE, PairsGate, SKEWED_SHARE_ALPHA};
pub use blueshift_trace::{
    GBufferPass, LLVMPIPE_LOOP_LIMIT, SceneBuffers, SceneImages, TRACE_LOOP_GUARD, TraceError,
    TraceVariant, gbuffer_cpu,
};
pub use camera_path::{CameraPath, Keyframe};
pub use config::{Accumulation, RenderConfig};
pub use error::{RenderError, Result};
pub use method::{
    GRID_BLOCK, Grouping, Key, MaskDims, Method, Motion, PAPER_BLOCK, Pairs, Permutation, Points,
    Target, Transport, Without,
};
pub use motion::motion_params;
pub use readback::HistoryState;
pub use seeds::{SeedMap, block_seeds, initial_seeds, tile_seeds};
pub use slots::{Completed, FRAMES_IN_FLIGHT, FrameOutput};
pub use stats::{FrameStats, LoopCount, LoopStats};
pub use trace_params::r2_offset;

use blueshift_device::{Buffer, Device, MemoryLocation, Recorder};
use blueshift_layout::params::TRACE_STATUS_WORDS;
pub use blueshift_layout::params::TraceLoop;
use blueshift_permute::{PermutePasses, Screen};
use blueshift_scene::{Camera, Scene, SceneGpu};
use blueshift_trace::TracePass;
use image::ImagePasses;
use recipe::Recipes;
use resources::{FrameResources, Masks, Pipelines};
use seeds::{key_words, seeds_of};
use slots::FrameSlot;

/// Timing labels of every pass a permutation or anchored-mask method adds to the path tracer,
/// in frame order: their sum against `trace` is the method's overhead.
pub const PERMUTE_PASSES: [&str; 8] = [
    "gbuffer",
    "reproject_motion",
    "reproject_seeds",
    "follow_anchors",
    "history_key",
    "classify_pixels",
    "sort_seeds",
    "pairs_gate",
];

/// The renderer: scene on the device, seed buffers, images, passes, frame slots.
pub struct Renderer {
    dev: Device,
    cfg: RenderConfig,
    /// What every frame does in each view state, decoded from `cfg` whenever it changes.
    recipes: Recipes,
    screen: Screen,
    /// The pipelines of the passes.
    passes: Pipelines,
    /// The buffers the passes read and write.
    res: FrameResources,
    slots: [FrameSlot; FRAMES_IN_FLIGHT],
    /// The slot the next frame records into.
    slot: usize,
    initial_seeds: Vec<u32>,
    /// Path vertices per trace dispatch (adapted to the counted loop iterations).
    dispatch_vertices: u32,
    /// Samples per dispatch of the trace pass last recorded.
    per_dispatch: u32,
    assets: MethodAssets,
    camera: Camera,
    view_offset: (f32, f32),
    /// The camera or view window changed since the last frame was recorded.
    view_changed: bool,
    frame: u64,
    accumulated: u32,
    /// `sort-grid-adaptive`'s choice of pairs from the counts so far in this sequence.
    pairs_gate: PairsGate,
    /// G-buffers, surface classes and reprojection state, made when a recipe first needs them.
    surfaces: Option<motion::Surfaces>,
    /// `sort-cycle`'s per-phase history, made when a recipe first needs it.
    cycle: Option<cycle::CycleHistory>,
    /// The `taa` pass and its state, made when the accumulation first follows the motion.
    taa: Option<taa_pass::TaaPass>,
    /// The image motion a moving sorting target follows (`target=follow`).
    follow: follow::FollowShift,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("cfg", &self.cfg)
            .field("frame", &self.frame)
            .finish()
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        // The frames in flight use the buffers dropped after this.
        for s in &mut self.slots {
            if s.rec.is_pending() {
                let _ = s.rec.wait();
            }
        }
    }
}

/// What `info`'s device can hold of a scene: what the loader's budget
/// ([`blueshift_scene::LoadBudget::for_device`]) and [`Scene::check_limits`] are held to.
pub fn scene_limits(info: &blueshift_device::DeviceInfo) -> blueshift_scene::DeviceLimits {
    blueshift_scene::DeviceLimits {
        max_storage_buffer_range: info.max_storage_buffer_range,
        max_image_dimension_2d: info.max_image_dimension_2d,
        memory_budget: info.memory_budget,
    }
}

impl Renderer {
    pub fn new(
        dev: &Device,
        scene: &Scene,
        assets: &MethodAssets,
        cfg: RenderConfig,
    ) -> Result<Self> {
        cfg.validate(dev)?;
        // Every scene buffer against the device's limit before the BVH is built: building a
        // scene that will not fit costs seconds and gigabytes for nothing (the node buffer is
        // bounded by its worst case here and checked exactly once built).
        scene
            .check_limits(&scene_limits(dev.info()))
            .map_err(|e| blueshift_trace::TraceError::Scene(e.to_string()))?;
        let gpu_scene = SceneGpu::build(scene);
        let scene_buffers = SceneBuffers::new(dev, &gpu_scene)?;
        let mut scene_images = SceneImages::new(dev, &gpu_scene)?;
        scene_images.lambert &= cfg.lambert_variant;
        let screen = Screen::new(cfg.width, cfg.height, assets.n)?;
        let initial = seeds_of(&cfg, &screen, assets)?;
        let (words, keys_spp) = key_words(&cfg, assets)?;
        let pixels = cfg.width as u64 * cfg.height as u64;
        let local = |name: &str, bytes: u64| Buffer::new(dev, name, bytes, MemoryLocation::GpuOnly);
        let primary_flags = local("frame.primary_flags", pixels * 4)?;
        zero(dev, &primary_flags)?;
        let pairs_gate = local("frame.pairs_gate", 8)?;
        zero(dev, &pairs_gate)?;
        let seeds = [
            Buffer::upload(dev, "frame.seeds.a", &initial)?,
            Buffer::upload(dev, "frame.seeds.b", &initial)?,
        ];
        let renderer = Self {
            dev: dev.clone(),
            recipes: Recipes::new(&cfg, scene_images.textured),
            screen,
            passes: Pipelines {
                trace: TracePass::new(dev),
                image: ImagePasses::new(dev)?,
                permute: PermutePasses::new(dev)?,
            },
            res: FrameResources {
                scene: scene_buffers,
                images: scene_images,
                seeds,
                current: 0,
                estimate: local("frame.estimate", pixels * 16)?,
                primary_flags,
                trace_status: local("frame.trace_status", 4 * TRACE_STATUS_WORDS as u64)?,
                accum: local("frame.accum", pixels * 16)?,
                ldr: local("frame.ldr", pixels * 4)?,
                masks: Masks::new(dev, assets, &words, keys_spp)?,
                sort_stats: local("frame.sort_stats", 8)?,
                pairs_gate,
            },
            slots: [FrameSlot::new(dev, 0)?, FrameSlot::new(dev, 1)?],
            slot: 0,
            initial_seeds: initial,
            dispatch_vertices: blueshift_trace::TRACE_FIRST_DISPATCH_VERTICES,
            per_dispatch: 0,
            assets: assets.clone(),
            camera: scene.camera_or_default(),
            view_offset: (0.0, 0.0),
            view_changed: false,
            frame: 0,
            accumulated: 0,
            pairs_gate: PairsGate::default(),
            surfaces: None,
            cycle: None,
            taa: None,
            follow: follow::FollowShift::new(scene.bounds().center()),
            cfg,
        };
        renderer.res.masks.check(&renderer.recipes)?;
        Ok(renderer)
    }

    pub fn config(&self) -> &RenderConfig {
        &self.cfg
    }
    pub fn frame(&self) -> u64 {
        self.frame
    }
    pub fn camera(&self) -> Camera {
        self.camera
    }
    /// `sort-grid-adaptive`'s smoothed share of skewed classes and its choice of pairs, as the
    /// last frame finished left them on the GPU.
    pub fn pairs_gate(&self) -> PairsGate {
        self.pairs_gate
    }
    pub fn device(&self) -> &Device {
        &self.dev
    }

    /// Moves the camera; the running mean restarts, an accumulation along the motion follows
    /// it (seeds keep their permutation state).
    pub fn set_camera(&mut self, camera: Camera) {
        if camera != self.camera {
            self.camera = camera;
            self.view_moved();
        }
    }

    /// Shifts the view window by `offset` pixels (image-space pan), as [`Self::set_camera`].
    pub fn set_view_offset(&mut self, offset: (f32, f32)) {
        if offset != self.view_offset {
            self.view_offset = offset;
            self.view_moved();
        }
    }

    /// Whether the next frame sees the scene from another view than the frame before it
    /// (its recipe depends on it); a first frame has no view before it.
    pub fn moving(&self) -> bool {
        self.view_changed && self.frame > 0
    }

    fn view_moved(&mut self) {
        self.view_changed = true;
        if self.cfg.accumulation == Accumulation::Mean {
            self.accumulated = 0;
        }
    }

    /// Restarts the sequence: initial seeds, frame 0, empty accumulation (after the frames
    /// in flight, whose results are dropped).
    pub fn reset(&mut self) -> Result<()> {
        self.finish_frames()?;
        for s in &mut self.res.seeds {
            s.write(0, &self.initial_seeds)?;
        }
        zero(&self.dev, &self.res.primary_flags)?;
        zero(&self.dev, &self.res.pairs_gate)?;
        self.res.current = 0;
        self.frame = 0;
        self.accumulated = 0;
        self.pairs_gate = PairsGate::default();
        if let Some(m) = &mut self.surfaces {
            m.reset();
        }
        if let Some(t) = &mut self.taa {
            t.reset();
        }
        self.follow.reset();
        Ok(())
    }

    /// Switches method (and resets the sequence, whose seed map may change with it). The
    /// block size asked for stays where the new method takes one.
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        let cfg = RenderConfig {
            method,
            block: self.cfg.block.filter(|_| method.fixed_block().is_none()),
            ..self.cfg.clone()
        };
        let recipes = Recipes::new(&cfg, self.res.images.textured);
        self.res.masks.check(&recipes)?;
        self.initial_seeds = seeds_of(&cfg, &self.screen, &self.assets)?;
        self.recipes = recipes;
        self.cfg = cfg;
        self.reset()
    }

    /// Changes spp, bounces or block size without resetting seeds (accumulation restarts).
    pub fn set_quality(&mut self, spp: u32, bounces: u32, block: Option<u32>) -> Result<()> {
        let cfg = RenderConfig {
            spp,
            bounces,
            block,
            ..self.cfg.clone()
        };
        cfg.validate(&self.dev)?;
        let recipes = Recipes::new(&cfg, self.res.images.textured);
        self.res.masks.check(&recipes)?;
        self.finish_frames()?;
        let (words, keys_spp) = key_words(&cfg, &self.assets)?;
        if keys_spp != self.res.masks.keys_spp {
            // Tables of one asset set share tile and pairs: same size, seeds stay valid.
            self.res.masks.keys = Buffer::upload(&self.dev, "assets.hbo19_keys", &words)?;
            self.res.masks.keys_spp = keys_spp;
        }
        self.recipes = recipes;
        self.cfg = cfg;
        self.accumulated = 0;
        Ok(())
    }

    /// Renders one frame and waits for it: its per-pass GPU times.
    pub fn render_frame(&mut self) -> Result<FrameStats> {
        self.submit_frame()?;
        let done = self.finish_frames()?.pop();
        Ok(done
            .ok_or_else(|| RenderError::Invalid("no frame in flight".into()))?
            .stats)
    }

    /// Starts the running mean afresh with the next frame (seeds and frame index are kept):
    /// with this before every frame, the output shows single frames.
    pub fn restart_accumulation(&mut self) {
        self.accumulated = 0;
    }
}

/// Fills `buffer` with zeros on the GPU (no host copy), waiting for it.
fn zero(dev: &Device, buffer: &Buffer) -> Result<()> {
    Ok(Recorder::one_shot(dev, "frame.zero", |rec| {
        rec.fill_buffer(buffer, 0)
    })?)
}
