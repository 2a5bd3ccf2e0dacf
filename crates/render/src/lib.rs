//! The frame loop a host application drives frame by frame:
//! `trace -> sort_seeds (retargeting on the way out) -> accumulate -> tonemap`, one submission per frame,
//! with GPU timestamps per pass. The seed buffer is a permutation at every moment.
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
mod image;
mod method;
mod method_spec;
mod motion;
mod pairs_gate;
mod readback;
mod seeds;
mod stats;
mod trace_params;

pub use blueshift_assets::{MethodAssets, default_assets_dir};
pub use blueshift_trace::{
    GBufferPass, LLVMPIPE_LOOP_LIMIT, SceneBuffers, SceneImages, TRACE_LOOP_GUARD, TraceError,
    TraceVariant, gbuffer_cpu,
};
pub use camera_path::{CameraPath, Keyframe};
pub use config::RenderConfig;
pub use error::{RenderError, Result};
pub use method::{
    GRID_BLOCK, Grouping, Key, Method, Motion, Pairs, Permutation, Points, Transport,
};
pub use motion::motion_params;
pub use pairs_gate::{PAIRS_MAX_SKEWED_SHARE, PairsGate, SKEWED_SHARE_ALPHA};
pub use seeds::{SeedMap, block_seeds, initial_seeds, tile_seeds};
pub use stats::{FrameStats, LoopCount, LoopStats};
pub use trace_params::r2_offset;

use blueshift_device::{Buffer, Device, MemoryLocation, Recorder};
pub use blueshift_layout::params::TraceLoop;
use blueshift_layout::params::{ImageParams, TRACE_STATUS_WORDS};
use blueshift_permute::{
    PermutePasses, Screen, SortInput, SortParams, grid_offset, mask_offset, pair_phase,
};
use blueshift_scene::{Camera, Scene, SceneGpu};
use blueshift_trace::TracePass;
use image::ImagePasses;
use seeds::{key_words, seeds_of};

/// Timing labels of every pass a permutation method adds to the path tracer, in frame order:
/// their sum against `trace` is the method's overhead.
pub const PERMUTE_PASSES: [&str; 6] = [
    "gbuffer",
    "reproject_motion",
    "reproject_seeds",
    "history_key",
    "classify_pixels",
    "sort_seeds",
];

/// The renderer: scene on the device, seed buffers, images, passes.
pub struct Renderer {
    dev: Device,
    cfg: RenderConfig,
    screen: Screen,
    scene: SceneBuffers,
    images: SceneImages,
    trace: TracePass,
    image: ImagePasses,
    permute: PermutePasses,
    rec: Recorder,
    seeds: [Buffer; 2],
    current: usize,
    initial_seeds: Vec<u32>,
    estimate: Buffer,
    trace_status: Buffer,
    /// Path vertices per trace dispatch (adapted to the counted loop iterations).
    dispatch_vertices: u32,
    accum: Buffer,
    ldr: Buffer,
    mask: Buffer,
    /// The HBO+19 key table for the current spp (GPU layout of `KeyTable::gpu_words`).
    keys: Buffer,
    keys_spp: Option<u32>,
    stbn: Buffer,
    /// The FAST mask, when the asset exists.
    fast: Option<Buffer>,
    /// The mask packed with the retarget table (`pack_mask_moves`), for sorting that retargets.
    mask_moves: Buffer,
    assets: MethodAssets,
    camera: Camera,
    view_offset: (f32, f32),
    frame: u64,
    accumulated: u32,
    /// (skewed classes, classes counted) of the last sorting pass (`SortInput::stats`).
    sort_stats: Buffer,
    /// `sort-grid-adaptive`'s choice of pairs from the counts so far in this sequence.
    pairs_gate: PairsGate,
    /// G-buffers and reprojection state, created when a method first needs them.
    motion: Option<motion::MotionState>,
    /// `sort-cycle`'s history and sorting inputs, created when a method first needs them.
    cycle: Option<cycle::CycleState>,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("cfg", &self.cfg)
            .field("frame", &self.frame)
            .finish()
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
        let gpu_scene = SceneGpu::build(scene);
        let scene_buffers = SceneBuffers::new(dev, &gpu_scene)?;
        let mut scene_images = SceneImages::new(dev, &gpu_scene)?;
        scene_images.lambert &= cfg.lambert_variant;
        let screen = Screen::new(cfg.width, cfg.height, assets.n)?;
        let initial = seeds_of(&cfg, &screen, assets)?;
        let (words, keys_spp) = key_words(&cfg, assets)?;
        let pixels = cfg.width as u64 * cfg.height as u64;
        let host = MemoryLocation::GpuToCpu;
        let seeds = [
            Buffer::from_slice(dev, "frame.seeds.a", &initial)?,
            Buffer::from_slice(dev, "frame.seeds.b", &initial)?,
        ];
        let r = Self {
            dev: dev.clone(),
            screen,
            scene: scene_buffers,
            images: scene_images,
            trace: TracePass::new(dev),
            image: ImagePasses::new(dev)?,
            permute: PermutePasses::new(dev)?,
            rec: Recorder::new(dev, "frame")?,
            seeds,
            current: 0,
            initial_seeds: initial,
            estimate: Buffer::new(dev, "frame.estimate", pixels * 16, host)?,
            trace_status: Buffer::new(
                dev,
                "frame.trace_status",
                4 * TRACE_STATUS_WORDS as u64,
                host,
            )?,
            dispatch_vertices: blueshift_trace::TRACE_FIRST_DISPATCH_VERTICES,
            accum: Buffer::new(dev, "frame.accum", pixels * 16, host)?,
            ldr: Buffer::new(dev, "frame.ldr", pixels * 4, host)?,
            mask: Buffer::from_slice(dev, "assets.mask", &assets.mask)?,
            keys: Buffer::from_slice(dev, "assets.hbo19_keys", &words)?,
            keys_spp,
            stbn: Buffer::from_slice(dev, "assets.stbn", &assets.stbn)?,
            fast: if assets.fast.is_empty() {
                None
            } else {
                Some(Buffer::from_slice(dev, "assets.fast", &assets.fast)?)
            },
            mask_moves: Buffer::from_slice(
                dev,
                "assets.mask_moves",
                &blueshift_permute::pack_mask_moves(&assets.mask, &assets.table)?,
            )?,
            assets: assets.clone(),
            camera: scene.camera_or_default(),
            view_offset: (0.0, 0.0),
            frame: 0,
            accumulated: 0,
            sort_stats: Buffer::new(dev, "frame.sort_stats", 8, host)?,
            pairs_gate: PairsGate::default(),
            motion: None,
            cycle: None,
            cfg,
        };
        Ok(r)
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
    /// `sort-grid-adaptive`'s smoothed share of skewed classes and its choice of pairs.
    pub fn pairs_gate(&self) -> PairsGate {
        self.pairs_gate
    }
    pub fn device(&self) -> &Device {
        &self.dev
    }

    /// Moves the camera; the accumulation restarts (seeds keep their permutation state).
    pub fn set_camera(&mut self, camera: Camera) {
        if camera != self.camera {
            self.camera = camera;
            self.accumulated = 0;
        }
    }

    /// Shifts the view window by `offset` pixels (image-space pan); restarts accumulation.
    pub fn set_view_offset(&mut self, offset: (f32, f32)) {
        if offset != self.view_offset {
            self.view_offset = offset;
            self.accumulated = 0;
        }
    }

    /// Restarts the sequence: initial seeds, frame 0, empty accumulation.
    pub fn reset(&mut self) -> Result<()> {
        for s in &mut self.seeds {
            s.write(0, &self.initial_seeds)?;
        }
        self.current = 0;
        self.frame = 0;
        self.accumulated = 0;
        self.pairs_gate = PairsGate::default();
        if let Some(m) = &mut self.motion {
            m.reset();
        }
        Ok(())
    }

    /// Switches method (and resets the sequence, whose seed map may change with it).
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        let cfg = RenderConfig {
            method,
            ..self.cfg.clone()
        };
        self.initial_seeds = seeds_of(&cfg, &self.screen, &self.assets)?;
        self.cfg = cfg;
        self.reset()
    }

    /// Changes spp, bounces or block size without resetting seeds (accumulation restarts).
    pub fn set_quality(&mut self, spp: u32, bounces: u32, block: u32) -> Result<()> {
        let cfg = RenderConfig {
            spp,
            bounces,
            block,
            ..self.cfg.clone()
        };
        cfg.validate(&self.dev)?;
        let (words, keys_spp) = key_words(&cfg, &self.assets)?;
        if keys_spp != self.keys_spp {
            // Tables of one asset set share tile and pairs: same size, seeds stay valid.
            self.keys = Buffer::from_slice(&self.dev, "assets.hbo19_keys", &words)?;
            self.keys_spp = keys_spp;
        }
        self.cfg = cfg;
        self.accumulated = 0;
        Ok(())
    }

    /// Renders one frame: all passes in one submission; returns per-pass GPU times.
    pub fn render_frame(&mut self) -> Result<FrameStats> {
        let tp = self.trace_params();
        let m = self.cfg.method;
        let (off, mut passes) = self.prepare_frame(&tp)?;
        let img = ImageParams {
            width: self.cfg.width,
            height: self.cfg.height,
            count: self.accumulated,
            exposure: self.cfg.exposure,
        };
        let (cur, next) = (self.current, 1 - self.current);
        let mask = match m {
            Method::Stbn => &self.stbn,
            Method::Fast => self.fast.as_ref().ok_or_else(trace_params::no_fast)?,
            _ => &self.mask,
        };
        let new_cycle = m.cycles_points() && self.cycle.is_none();
        if new_cycle {
            let state = cycle::CycleState::new(&self.dev, &self.screen)?;
            self.cycle = Some(state);
        }
        self.rec.begin()?;
        self.rec.fill_buffer(&self.trace_status, 0)?;
        if let Some(c) = self.cycle.as_ref().filter(|_| new_cycle) {
            // Touches the whole history now (its contents are never read before written):
            // on a CPU device the first touch of each page costs a fault, which would
            // otherwise slow the sorting pass over the whole first cycle.
            self.rec.fill_buffer(&c.history, 0)?;
        }
        self.rec.begin_pass("trace")?;
        let per_dispatch = self.trace.trace(
            &mut self.rec,
            &tp,
            &self.scene,
            &self.images,
            &self.seeds[cur],
            mask,
            &self.keys,
            &self.estimate,
            &self.trace_status,
            self.dispatch_vertices,
            self.cfg.loop_stats,
        )?;
        if m.sorts() {
            let block = m.block(self.cfg.block);
            let sp = if m.shifts_grid() {
                // Sorted for the frame they will be rendered in: the next mask, the next grid.
                let (shift, n) = (self.assets.shift, self.assets.n);
                let next = mask_offset(self.frame + 1, shift, n);
                let grid = grid_offset(self.frame + 1, block);
                SortParams {
                    pairs: m.pairs(&self.pairs_gate),
                    phase: pair_phase(self.frame + 1, m.hashes_pair_phase()),
                    count_skew: u32::from(m.adapts_pairs()),
                    ..self.screen.sort_params_on_grid(block, next, grid)?
                }
            } else if m.cycles_points() {
                // Fixed blocks against the next spatio-temporal slice, the point cycle first.
                let (n, t) = (self.assets.stbn_n, self.assets.stbn_frames);
                let cp = self.screen.cycle_params(self.frame, n, t, self.accumulated);
                let sp = SortParams {
                    mask_size: n,
                    ..self.screen.sort_params(block, (0, 0))?
                };
                blueshift_permute::with_cycle(sp, &cp)
            } else {
                self.screen.sort_params(block, off)?
            };
            self.record_history_keys()?;
            self.record_classes(&tp, &sp)?;
            if sp.count_skew != 0 {
                self.rec.fill_buffer(&self.sort_stats, 0)?;
            }
            let cycle = self.cycle.as_ref().filter(|_| m.cycles_points());
            let mask = if cycle.is_some() {
                &self.stbn
            } else if m.retargets() {
                &self.mask_moves
            } else {
                &self.mask
            };
            self.rec.begin_pass("sort_seeds")?;
            let motion = self.motion.as_ref();
            let input = SortInput {
                estimate: &self.estimate,
                mask,
                classes: motion.filter(|_| m.edge_aware()).map(|st| &st.classes),
                history: motion
                    .and_then(|st| st.history_mean())
                    .filter(|_| m.history_keys()),
                pairs: m.permutation().is_some_and(|p| p.pairs != Pairs::Off),
                stats: m.adapts_pairs().then_some(&self.sort_stats),
                retarget: m.retargets().then_some(&self.seeds[next]),
                cycle: cycle.map(|c| blueshift_permute::CycleInput {
                    history: &c.history,
                    accum: &self.accum,
                }),
            };
            self.permute
                .sort_seeds(&mut self.rec, &sp, &input, &self.seeds[cur])?;
        }
        self.rec.begin_pass("accumulate")?;
        self.image
            .accumulate(&mut self.rec, &img, &self.estimate, &self.accum)?;
        self.rec.begin_pass("tonemap")?;
        self.image
            .tonemap(&mut self.rec, &img, &self.accum, &self.ldr)?;
        passes.extend(self.rec.submit_and_wait()?);
        if m.retargets() {
            self.current = next;
        }
        if m.adapts_pairs() {
            let s = self.sort_stats.read::<u32>()?;
            self.pairs_gate.update([s[0], s[1]]);
        }
        let status = self.trace_status.read::<u32>()?;
        let stats = FrameStats {
            frame: self.frame,
            passes,
            trace_loop_iterations: status[0],
            loops: self
                .cfg
                .loop_stats
                .then(|| LoopStats::from_status(&status))
                .flatten(),
        };
        self.frame += 1;
        self.accumulated = self.accumulated.saturating_add(1);
        self.dispatch_vertices = blueshift_trace::next_dispatch_vertices(
            per_dispatch,
            self.cfg.bounces,
            stats.trace_loop_iterations,
        );
        blueshift_trace::check_loop_guard(stats.trace_loop_iterations, self.cfg.loop_guard)?;
        Ok(stats)
    }

    /// Starts the running mean afresh with the next frame (seeds and frame index are kept):
    /// with this before every frame, the output shows single frames.
    pub fn restart_accumulation(&mut self) {
        self.accumulated = 0;
    }
}
