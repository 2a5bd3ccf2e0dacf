//! `blueshift eval`: renders a camera path with several methods, renders references, and
//! writes a report (report.md, report.json, PNG figures) with the metrics of docs/results.md.
mod figures;
mod flip;
mod front;
mod masks;
mod metrics;
mod ratios;
mod reference;
mod report;
mod report_taa;
mod timing;
mod track;

use crate::GpuOpts;
use crate::args::{SceneArgs, comparison_parser};
use crate::output::Staged;
use anyhow::{Context, Result, bail};
use blueshift_analysis::{Gray, luminance};
use blueshift_render::{CameraPath, Method, RenderConfig, Renderer, SeedMap, taa};
use blueshift_scene::SceneGpu;
use indicatif::{ProgressBar, ProgressStyle};
use masks::Masks;
use metrics::{RunAccumulator, RunMetrics};
use reference::{RefJob, references};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The largest `--first-sequence` (any u32 would do; larger is a typo).
const MAX_FIRST_SEQUENCE: u32 = 1 << 20;

/// `eval`'s flags: each item of a list is parsed as the single value of `render`'s flag.
#[derive(clap::Args, Debug)]
pub struct EvalArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Comma-separated methods (presets, comparison baselines or spelled-out
    /// `PRESET:field=value` forms); `white` is always added (ratios are against it).
    #[arg(
        long,
        value_delimiter = ',',
        value_parser = comparison_parser(),
        default_value = "sort-cycle,white,sobol,hbo19,stbn,fast,sort-retarget,sort-grid-adaptive"
    )]
    pub methods: Vec<Method>,
    /// Comma-separated samples per pixel per frame.
    #[arg(long, value_delimiter = ',', default_value = "1",
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub spp: Vec<u32>,
    /// Comma-separated camera paths: static, pan:PX, orbit:DEG, swing:DEG, strafe:PX,
    /// orbit-view:DEG, or keyframe files.
    #[arg(long, value_delimiter = ',', default_value = "static", value_parser = CameraPath::parse)]
    pub camera: Vec<CameraPath>,
    /// Comma-separated bounce counts (1 = direct light only).
    #[arg(long, value_delimiter = ',', default_value = "1,8",
          value_parser = clap::value_parser!(u32).range(0..=64))]
    pub bounces: Vec<u32>,
    #[arg(long, default_value_t = 32)]
    pub frames: u32,
    #[arg(long, default_value_t = 128)]
    pub width: u32,
    #[arg(long, default_value_t = 128)]
    pub height: u32,
    /// Reference samples per pixel (>= 1024).
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Independent sequences (initial seed maps) per configuration; metrics are averaged.
    #[arg(long, default_value_t = 1)]
    pub sequences: u32,
    /// The first sequence's number: tune a method's constants on sequences the reported
    /// tables do not use (e.g. 100 and up; the tables use 0..).
    #[arg(long, default_value_t = 0)]
    pub first_sequence: u32,
    /// Reference cache (default: ~/.cache/blueshift/references).
    #[arg(long)]
    pub cache: Option<PathBuf>,
    #[arg(long, default_value = "out/eval")]
    pub out: PathBuf,
    /// Also write every raw frame and its reference as EXR under OUT/frames/ (for checking the
    /// report's numbers independently).
    #[arg(long)]
    pub save_frames: bool,
    /// Primary rays through pixel centres (the paper's setting) instead of jittered inside the
    /// pixel. Jitter is on by default because real-time renderers (and `render`/`view`) use
    /// it; the aliasing it brings to the edges of visible lights, which no seed permutation
    /// can move, is what the emitter-free metrics leave out.
    #[arg(long)]
    pub no_jitter: bool,
}

/// One configuration: everything but the method.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    pub camera: CameraPath,
    pub bounces: u32,
    pub spp: u32,
}

impl Config {
    pub fn label(&self) -> String {
        format!("{} b{} spp{}", self.camera.label(), self.bounces, self.spp)
    }
    pub fn slug(&self) -> String {
        format!(
            "{}_b{}_spp{}",
            self.camera.label().replace([':', '.', '/'], "-"),
            self.bounces,
            self.spp
        )
    }
}

/// One run's results.
pub struct Run {
    pub config: Config,
    pub method: Method,
    pub metrics: RunMetrics,
    /// P1 (all / smooth / edge / emitter-free pixels) of each sequence, for the spread of the
    /// ratios across sequences.
    pub p1_per_sequence: Vec<metrics::Split>,
    /// The same for the EMA and for the TAA (accumulated along the motion).
    pub ema_p1_per_sequence: Vec<metrics::Split>,
    pub taa_p1_per_sequence: Vec<metrics::Split>,
    /// FLIP of the accumulated image at the last frame, over all pixels (averaged over
    /// sequences).
    pub flip: f64,
    /// The same FLIP map averaged over the emitter-free pixels only.
    pub flip_clean: f64,
    /// FLIP of the estimate's TAA against the reference's TAA (the same operator on both) at
    /// the last frame: all pixels, emitter-free pixels.
    pub taa_flip: f64,
    pub taa_flip_clean: f64,
    /// Share of emitter-free pixels in the last frame's reference.
    pub clean_fraction: f64,
    pub pass_ms: BTreeMap<String, f64>,
    pub seconds: f64,
    pub last_frame: Vec<[f32; 4]>,
    pub last_error: Option<Gray>,
}

pub fn run(gpu: &GpuOpts, args: &EvalArgs) -> Result<()> {
    let start = Instant::now();
    let mut methods = args.methods.clone();
    if !methods.contains(&Method::White) {
        methods.insert(0, Method::White);
    }
    let (spps, cameras, bounces) = (&args.spp, &args.camera, &args.bounces);
    if !(2..=100_000).contains(&args.frames) {
        bail!("--frames {} is outside 2..=100000", args.frames);
    }
    if !(1..=64).contains(&args.sequences) {
        bail!("--sequences {} is outside 1..=64", args.sequences);
    }
    if args.first_sequence > MAX_FIRST_SEQUENCE {
        bail!(
            "--first-sequence {} is above {MAX_FIRST_SEQUENCE}",
            args.first_sequence
        );
    }
    // The device first: the scene is loaded within what it can hold, and every array is
    // checked against its limits before the BVH is built.
    let dev = gpu.device()?;
    let scene = args.scene.load_scene(dev.info())?;
    scene.check_limits(&blueshift_render::scene_limits(dev.info()))?;
    let (base, bounds) = (scene.camera_or_default(), scene.bounds());
    let cameras: Vec<CameraPath> = cameras
        .iter()
        .map(|c| c.clone().fit(&bounds, &base, (args.width, args.height)))
        .collect();
    let path = args.scene.scene_path();
    let scene_bytes =
        std::fs::read(&path).with_context(|| format!("reading scene {}", path.display()))?;
    let assets = args.scene.load_assets()?;
    let seed_map = args.scene.initial_seeds;
    let cache = args.cache.clone().unwrap_or_else(|| {
        std::env::var_os("HOME")
            .map_or(PathBuf::from(".cache"), PathBuf::from)
            .join(".cache/blueshift/references")
    });
    RenderConfig {
        method: Method::SORT_RETARGET, // a method that takes the block size
        block: args.scene.block,
        ..RenderConfig::new(args.width, args.height)
    }
    .validate(&dev)?;
    // The report, figures and saved frames appear in the output directory only if the whole
    // run succeeds: a failed run leaves it as it was (or absent).
    let out = Staged::new(&args.out)?;
    let scene_gpu = SceneGpu::build(&scene);

    let mut runs = Vec::new();
    let mut configs = Vec::new();
    for camera in cameras {
        // The measuring filter depends on the camera path alone: traced once per path.
        let motions = track::motions(
            &scene_gpu,
            &camera,
            &scene,
            args.frames,
            (args.width, args.height),
        );
        for &b in bounces {
            let job = RefJob {
                dev: &dev,
                scene: &scene,
                scene_bytes: &scene_bytes,
                assets: &assets,
                width: args.width,
                height: args.height,
                bounces: b,
                spp: args.reference_spp,
                frames: args.frames,
                path: &camera,
                cache: &cache,
                no_jitter: args.no_jitter,
            };
            let refs = references(&job)?;
            // The reference's TAA at the last frame, shared by every method and sequence.
            let taa_ref = (0..args.frames).fold(Vec::new(), |acc, t| {
                let px = refs.frame(t, args.width, args.height).px;
                taa::accumulate(
                    motions[t as usize].as_ref(),
                    &acc,
                    bytemuck::cast_slice(&px),
                    4,
                )
            });
            for &spp in spps {
                let config = Config {
                    camera: camera.clone(),
                    bounces: b,
                    spp,
                };
                let bar =
                    ProgressBar::new((methods.len() as u32 * args.frames * args.sequences) as u64);
                bar.set_style(
                    ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} frames eta {eta}")
                        .unwrap_or_else(|_| ProgressStyle::default_bar()),
                );
                bar.set_message(config.label());
                let ctx = RunContext {
                    dev: &dev,
                    scene: &scene,
                    motions: &motions,
                    taa_ref: &taa_ref,
                    assets: &assets,
                    args,
                    refs: &refs,
                    bar: &bar,
                    out: out.path(),
                };
                let first = runs.len();
                for &m in &methods {
                    runs.push(run_method(&ctx, &config, m, seed_map)?);
                }
                bar.set_message(format!("{} timing", config.label()));
                let times = timing::measure(&ctx, &config, &methods, seed_map)?;
                for (run, pass_ms) in runs[first..].iter_mut().zip(times) {
                    run.pass_ms = pass_ms;
                }
                bar.finish_and_clear();
                configs.push(config);
            }
        }
    }
    crate::check_validation(&dev)?;
    let elapsed = start.elapsed().as_secs_f64();
    report::write(out.path(), args, &dev, &configs, &runs, elapsed)?;
    out.commit()?;
    println!(
        "wrote {} ({} runs, {:.0} s)",
        args.out.join("report.md").display(),
        runs.len(),
        elapsed
    );
    Ok(())
}

/// What every run of one configuration shares.
struct RunContext<'a> {
    dev: &'a blueshift_device::Device,
    scene: &'a blueshift_scene::Scene,
    /// The TAA's reprojection into each frame (`track::motions`).
    motions: &'a [Option<taa::Reprojection>],
    /// The reference accumulated along the motion, at the last frame.
    taa_ref: &'a [f32],
    assets: &'a blueshift_render::MethodAssets,
    args: &'a EvalArgs,
    refs: &'a reference::References,
    bar: &'a ProgressBar,
    /// Where the run's files go until it has succeeded ([`Staged::path`]).
    out: &'a Path,
}

fn run_method(ctx: &RunContext, config: &Config, method: Method, seed_map: SeedMap) -> Result<Run> {
    let RunContext {
        args, refs, bar, ..
    } = *ctx;
    let t0 = Instant::now();
    let (w, h) = (args.width, args.height);
    let window = (args.frames / 2) as usize;
    let mut merged: Option<RunMetrics> = None;
    let (mut p1_per_sequence, mut ema_p1_per_sequence, mut taa_p1_per_sequence) =
        (Vec::new(), Vec::new(), Vec::new());
    let (mut last_frame, mut last_error) = (Vec::new(), None);
    let (mut flip, mut flip_clean, mut clean_fraction) = (0.0, 0.0, 0.0);
    let (mut taa_flip, mut taa_flip_clean) = (0.0, 0.0);
    for k in 0..args.sequences {
        let mut r = PathRenderer::new(ctx, config, method, args.first_sequence + k, seed_map)?;
        let mut acc = RunAccumulator::new(window)?;
        // The estimate's TAA (rgb + the estimate's fourth channel).
        let mut taa_est: Vec<f32> = Vec::new();
        for t in 0..args.frames {
            let motion = &ctx.motions[t as usize];
            let rf = refs.frame(t, w, h);
            let reference_y = rf.luminance();
            r.render(t)?;
            let est = r.renderer.read_estimate()?;
            if args.save_frames && k == 0 {
                save_frame(ctx.out, args, config, method, t, &est, &rf.px)?;
            }
            // Luminance from rgb: the estimate's fourth channel is the sorting key, which
            // demodulating methods change.
            let e: Vec<f32> = est
                .iter()
                .zip(&reference_y)
                .map(|(a, b)| luminance([a[0], a[1], a[2]]) - b)
                .collect();
            let reference_y = Gray::new(w as usize, h as usize, reference_y)?;
            let masks = Masks::from_reference(&reference_y);
            acc.add_frame(
                t as usize,
                Gray::new(w as usize, h as usize, e)?,
                &masks,
                motion.as_ref(),
            )?;
            taa_est = taa::accumulate(motion.as_ref(), &taa_est, bytemuck::cast_slice(&est), 4);
            if t + 1 == args.frames {
                last_frame = est;
                let n = args.sequences as f64;
                let f = flip::scores(&r.renderer.read_accum()?, &rf.px, w, h, &masks.clean);
                flip += f.all / n;
                flip_clean += f.clean / n;
                let (te, tr) = (
                    bytemuck::cast_slice(&taa_est),
                    bytemuck::cast_slice(ctx.taa_ref),
                );
                let f = flip::scores(te, tr, w, h, &masks.clean);
                taa_flip += f.all / n;
                taa_flip_clean += f.clean / n;
                clean_fraction = masks.clean.iter().filter(|&&c| c).count() as f64
                    / masks.clean.len().max(1) as f64;
            }
            bar.inc(1);
        }
        last_error = acc.last_error.clone();
        let m = acc.finish()?;
        p1_per_sequence.push(m.raw.p1);
        ema_p1_per_sequence.push(m.ema.p1);
        taa_p1_per_sequence.push(m.taa.p1);
        merged = Some(match merged {
            None => m,
            Some(prev) => metrics::average(prev, m, k as f64),
        });
    }
    Ok(Run {
        config: config.clone(),
        method,
        metrics: merged.context("no sequence ran")?,
        p1_per_sequence,
        ema_p1_per_sequence,
        taa_p1_per_sequence,
        flip,
        flip_clean,
        taa_flip,
        taa_flip_clean,
        clean_fraction,
        // Filled in by the interleaved timing phase (`timing::measure`).
        pass_ms: BTreeMap::new(),
        seconds: t0.elapsed().as_secs_f64(),
        last_frame,
        last_error,
    })
}

/// A renderer of one method and sequence that follows the configuration's camera path.
struct PathRenderer {
    renderer: Renderer,
    camera: CameraPath,
    base: blueshift_scene::Camera,
    base_offset: (f32, f32),
}

impl PathRenderer {
    fn new(
        ctx: &RunContext,
        config: &Config,
        method: Method,
        sequence: u32,
        seed_map: SeedMap,
    ) -> Result<Self> {
        let (w, h) = (ctx.args.width, ctx.args.height);
        let (view, base_offset) = config.camera.view_window(ctx.args.frames, w, h);
        let cfg = RenderConfig {
            spp: config.spp,
            bounces: config.bounces,
            // `--block` sizes the methods that take one; the others sort their own.
            block: ctx
                .args
                .scene
                .block
                .filter(|_| method.fixed_block().is_none()),
            method,
            sampler: ctx.args.scene.sampler,
            sequence,
            no_jitter: ctx.args.no_jitter,
            view_size: Some(view),
            seed_map,
            ..RenderConfig::new(w, h)
        };
        Ok(Self {
            renderer: Renderer::new(ctx.dev, ctx.scene, ctx.assets, cfg)?,
            camera: config.camera.clone(),
            base: ctx.scene.camera_or_default(),
            base_offset,
        })
    }

    /// Renders frame `t` of the path (the frames in order, from 0).
    fn render(&mut self, t: u32) -> Result<blueshift_render::FrameStats> {
        self.renderer.set_camera(self.camera.camera(&self.base, t));
        let o = self.camera.view_offset(t);
        self.renderer
            .set_view_offset((self.base_offset.0 + o.0, self.base_offset.1 + o.1));
        Ok(self.renderer.render_frame()?)
    }
}

/// Writes frame `t` of a run and its reference as linear EXR under `out/frames/`.
fn save_frame(
    out: &Path,
    args: &EvalArgs,
    c: &Config,
    m: Method,
    t: u32,
    est: &[[f32; 4]],
    reference: &[[f32; 4]],
) -> Result<()> {
    use crate::output::{exr_rgb32f, write_atomic};
    let dir = out
        .join("frames")
        .join(format!("{}_{}", c.slug(), m.name()));
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    write_atomic(
        &dir.join(format!("frame_{t:05}.exr")),
        &exr_rgb32f(args.width, args.height, est)?,
    )?;
    write_atomic(
        &dir.join(format!("reference_{t:05}.exr")),
        &exr_rgb32f(args.width, args.height, reference)?,
    )?;
    Ok(())
}
