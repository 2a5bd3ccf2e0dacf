//! `blueshift view`: the desktop demo. A window (winit, X11) shows the path tracer live with a
//! fly camera; keys switch methods and settings, split-screen compares two methods on the same
//! frame, the error view shows |error| against a progressively accumulated Sobol reference.
//! `--frames N --screenshot FILE` makes a scripted run.
mod controls;
mod gpu;
mod input;
mod window;

use crate::GpuOpts;
use crate::render::{SceneArgs, config, load_assets, load_scene};
use anyhow::{Context, Result, bail};
use controls::Settings;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// glTF/GLB file, or a bundled preset: cornell-box, textured, edges.
    #[arg(long, default_value = "cornell-box")]
    pub scene: String,
    #[command(flatten)]
    pub lights: crate::lighting::LightArgs,
    /// Window width in pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Window height in pixels.
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Render resolution divisor (1, 2 or 4); the image is upscaled (nearest) to the window.
    #[arg(long, default_value_t = 2)]
    pub scale: u32,
    /// Method of the view (the left side in split-screen).
    #[arg(long, default_value = "sort-cycle")]
    pub method: String,
    /// Method of the right side in split-screen.
    #[arg(long, default_value = "white")]
    pub method_b: String,
    /// Frame-0 seed map: random, or hbo19 (sort / sort-retarget start from HBO+19 blue noise).
    #[arg(long, default_value = "random")]
    pub initial_seeds: String,
    /// Start in split-screen (key S).
    #[arg(long)]
    pub split: bool,
    /// Start in the error view (key E).
    #[arg(long)]
    pub error_view: bool,
    /// Show single frames instead of the running mean (key A).
    #[arg(long)]
    pub no_accumulation: bool,
    /// Samples per pixel per frame (keys + and -).
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Path vertices after the camera (keys [ and ]).
    #[arg(long, default_value_t = 4)]
    pub bounces: u32,
    /// Sorting block edge, 2..=8 (keys B and Shift+B).
    #[arg(long, default_value_t = 4)]
    pub block: u32,
    /// Directory with masks and retarget tables.
    #[arg(long)]
    pub assets: Option<PathBuf>,
    /// FIFO presentation (default: MAILBOX where offered).
    #[arg(long)]
    pub vsync: bool,
    /// Scripted run: exit after this many presented frames.
    #[arg(long)]
    pub frames: Option<u32>,
    /// Scripted run: write the last presented image to this PNG.
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Testing: request a new window size after frame FRAME (`--resize-at 3 128x96`).
    #[arg(long, hide = true, num_args = 2, value_names = ["FRAME", "WxH"])]
    pub resize_at: Option<Vec<String>>,
}

/// Parses `WxH` with both sides in 1..=16384.
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .with_context(|| format!("size '{s}' is not WIDTHxHEIGHT"))?;
    let side = |v: &str| -> Result<u32> {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16384).contains(n))
            .with_context(|| format!("size '{s}': '{v}' is not a number in 1..=16384"))
    };
    Ok((side(w)?, side(h)?))
}

fn script(args: &ViewArgs) -> Result<window::Script> {
    if let Some(n) = args.frames
        && !(1..=1_000_000).contains(&n)
    {
        bail!("--frames {n} is outside 1..=1000000");
    }
    let resize_at = match args.resize_at.as_deref() {
        None => None,
        Some([frame, size]) => {
            let f = frame
                .parse::<u32>()
                .with_context(|| format!("--resize-at: '{frame}' is not a frame number"))?;
            Some((f, parse_size(size)?))
        }
        Some(other) => bail!("--resize-at takes FRAME WxH, got {other:?}"),
    };
    if let Some(dir) = args.screenshot.as_deref().and_then(|p| p.parent())
        && !dir.as_os_str().is_empty()
        && !dir.is_dir()
    {
        bail!("--screenshot: directory {} does not exist", dir.display());
    }
    Ok(window::Script {
        frames: args.frames,
        screenshot: args.screenshot.clone(),
        resize_at,
    })
}

pub fn run(gpu: &GpuOpts, args: &ViewArgs) -> Result<()> {
    if ![1, 2, 4].contains(&args.scale) {
        bail!("--scale {} must be 1, 2 or 4", args.scale);
    }
    let size =
        parse_size(&format!("{}x{}", args.width, args.height)).context("--width/--height")?;
    let script = script(args)?;
    let parse = crate::render::parse_method;
    let settings = Settings {
        methods: [parse(&args.method)?, parse(&args.method_b)?],
        side: 0,
        spp: args.spp,
        bounces: args.bounces,
        block: args.block,
        accumulate: !args.no_accumulation,
        split: args.split,
        error: args.error_view,
    };
    let template = SceneArgs {
        scene: args.scene.clone(),
        width: size.0,
        height: size.1,
        spp: args.spp,
        bounces: args.bounces,
        block: args.block,
        sampler: None,
        assets: args.assets.clone(),
        initial_seeds: args.initial_seeds.clone(),
        lights: args.lights.clone(),
    };
    config(&template, &args.method)?;
    let opts = gpu::Options {
        scene: load_scene(&args.scene, &args.lights)?,
        assets: load_assets(&template)?,
        template,
        scale: args.scale,
        vsync: args.vsync,
        device_index: gpu.device_index,
    };
    let event_loop = winit::event_loop::EventLoop::new().context(
        "cannot open a window: no X11 display (set DISPLAY, e.g. `Xvfb :99 & export DISPLAY=:99`)",
    )?;
    let mut app = window::App::new(opts, gpu.validation, size, settings, script);
    event_loop.run_app(&mut app).context("window event loop")?;
    app.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_or_explain() {
        assert_eq!(parse_size("128x96").unwrap(), (128, 96));
        assert_eq!(parse_size("64X48").unwrap(), (64, 48));
        for bad in ["128", "0x5", "ax5", "5x99999", ""] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }
}
