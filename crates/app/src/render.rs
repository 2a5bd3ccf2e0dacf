//! `blueshift render`: headless frames of a scene to PNG (tonemapped) and EXR (linear raw).
use crate::GpuOpts;
use crate::lighting::LightArgs;
use crate::output::{exr_rgb32f, png_rgba8, prepare_dir, write_atomic};
use anyhow::{Context, Result, bail};
use blueshift_render::{
    CameraPath, Method, MethodAssets, RenderConfig, Renderer, SeedMap, default_assets_dir,
};
use blueshift_sampling::Sampler;
use blueshift_scene::Scene;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    /// glTF/GLB file, or a bundled preset: cornell-box, textured, edges.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    #[arg(long, default_value_t = 256)]
    pub width: u32,
    #[arg(long, default_value_t = 256)]
    pub height: u32,
    /// Samples per pixel per frame.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Path vertices after the camera (1 = direct light only).
    #[arg(long, default_value_t = 8)]
    pub bounces: u32,
    /// Sorting block edge (2..=8).
    #[arg(long, default_value_t = 4)]
    pub block: u32,
    /// Seeded sampler (white, sobol, r2, hbo19); default depends on the method.
    #[arg(long)]
    pub sampler: Option<String>,
    /// Frame-0 seed map of sort / sort-retarget: random, or hbo19 (HBO+19 tile positions with
    /// the hbo19 sampler, so that they start from blue noise).
    #[arg(long, default_value = "random")]
    pub initial_seeds: String,
    /// Directory with masks and retarget tables.
    #[arg(long)]
    pub assets: Option<PathBuf>,
    #[command(flatten)]
    pub lights: LightArgs,
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[arg(long, default_value_t = 16)]
    pub frames: u32,
    /// A preset (white, sobol, hbo19, mask-r2, stbn, sort, sort-retarget, sort-grid-history,
    /// sort-grid-adaptive) or a spelled-out permutation, e.g. `sort:transport=grid,key=demod`.
    #[arg(long, default_value = "sort-cycle")]
    pub method: String,
    /// static, pan:PX (image-space pan, px/frame), orbit:DEG (deg/frame), swing:DEG (an orbit
    /// turning back after 12 degrees), or a keyframe JSON file.
    #[arg(long, default_value = "static")]
    pub camera_path: String,
    /// Experiment: hash the frame into fixed seeds (breaks temporal correlation).
    #[arg(long)]
    pub frame_salt: bool,
    /// Write every frame (default: only the last).
    #[arg(long)]
    pub all_frames: bool,
    #[arg(long, default_value = "out/render")]
    pub out: PathBuf,
}

/// Resolves a preset name to the bundled file, else treats it as a path.
pub fn scene_path(spec: &str) -> PathBuf {
    let preset = default_assets_dir()
        .join("scenes")
        .join(format!("{spec}.gltf"));
    if !spec.contains('/') && !spec.contains('.') && preset.exists() {
        preset
    } else {
        PathBuf::from(spec)
    }
}

/// Loads a scene lit as `lights` says, printing its warnings (one line each).
pub fn load_scene(spec: &str, lights: &LightArgs) -> Result<Scene> {
    let path = scene_path(spec);
    let (environment, map_warning) = lights.source()?;
    let opts = blueshift_scene::LoadOptions {
        environment,
        quiet: true,
    };
    let looks_like_preset = !spec.contains(['/', '.']);
    let mut scene = match Scene::load_with(&path, &opts) {
        Err(blueshift_scene::SceneError::NotFound { .. }) if looks_like_preset => bail!(
            "scene '{spec}' is neither a file nor a preset (presets: cornell-box, textured, edges)"
        ),
        // The scene error names the file.
        r => r?,
    };
    let dark = lights.apply(&mut scene)?;
    for w in scene.warnings.iter().chain(&map_warning).chain(&dark) {
        eprintln!("warning: {w}");
    }
    Ok(scene)
}

/// A preset name or a spelled-out permutation method (`sort:field=value,...`).
pub fn parse_method(name: &str) -> Result<Method> {
    name.parse().map_err(anyhow::Error::msg)
}

pub fn config(a: &SceneArgs, method: &str) -> Result<RenderConfig> {
    let method = parse_method(method)?;
    let sampler =
        match &a.sampler {
            None => None,
            Some(s) => Some(Sampler::from_name(s).with_context(|| {
                format!("unknown sampler '{s}' (known: white, sobol, r2, hbo19)")
            })?),
        };
    Ok(RenderConfig {
        spp: a.spp,
        bounces: a.bounces,
        block: a.block,
        method,
        sampler,
        seed_map: a
            .initial_seeds
            .parse::<SeedMap>()
            .map_err(|e| anyhow::anyhow!("--initial-seeds: {e}"))?,
        ..RenderConfig::new(a.width, a.height)
    })
}

pub fn load_assets(a: &SceneArgs) -> Result<MethodAssets> {
    let dir = a.assets.clone().unwrap_or_else(default_assets_dir);
    Ok(MethodAssets::load(&dir)?)
}

pub fn run(gpu: &GpuOpts, args: &RenderArgs) -> Result<()> {
    if args.frames == 0 || args.frames > 100_000 {
        bail!("--frames {} is outside 1..=100000", args.frames);
    }
    let mut cfg = config(&args.scene, &args.method)?;
    cfg.frame_salt = args.frame_salt;
    let path = CameraPath::parse(&args.camera_path).map_err(anyhow::Error::msg)?;
    let (view, base_offset) = path.view_window(args.frames, cfg.width, cfg.height);
    cfg.view_size = Some(view);
    let scene = load_scene(&args.scene.scene, &args.scene.lights)?;
    let assets = load_assets(&args.scene)?;
    let dev = gpu.device()?;
    let mut r = Renderer::new(&dev, &scene, &assets, cfg.clone())?;
    // Only now that every input is known to be good: a failed run leaves no output directory.
    let _out = prepare_dir(&args.out)?;
    let base = scene.camera_or_default();
    let path = path.fit(&scene.bounds(), &base, view);
    let bar = ProgressBar::new(args.frames as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} frames, {msg} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    for f in 0..args.frames {
        r.set_camera(path.camera(&base, f));
        let o = path.view_offset(f);
        r.set_view_offset((base_offset.0 + o.0, base_offset.1 + o.1));
        let stats = r.render_frame()?;
        bar.set_message(format!("trace {:.1} ms", stats.ms("trace")));
        bar.inc(1);
        if args.all_frames || f + 1 == args.frames {
            write_frame(&r, &args.out, f)?;
        }
    }
    bar.finish();
    crate::check_validation(&dev)?;
    println!(
        "wrote {} to {}",
        if args.all_frames {
            "all frames"
        } else {
            "the last frame"
        },
        args.out.display()
    );
    Ok(())
}

fn write_frame(r: &Renderer, dir: &Path, f: u32) -> Result<()> {
    let (w, h) = (r.config().width, r.config().height);
    write_atomic(
        &dir.join(format!("frame_{f:05}.png")),
        &png_rgba8(w, h, &r.read_ldr()?)?,
    )?;
    write_atomic(
        &dir.join(format!("frame_{f:05}.exr")),
        &exr_rgb32f(w, h, &r.read_estimate()?)?,
    )?;
    Ok(())
}
