//! `blueshift view`: the desktop demo. A window (winit, X11) shows the path tracer live with a
//! fly camera; keys switch methods and settings, split-screen compares two methods on the same
//! frame, the error view shows |error| against a progressively accumulated Sobol reference.
//! `--frames N --screenshot FILE` makes a scripted run.
mod controls;
mod gpu;
mod input;
mod renderers;
mod window;

use crate::GpuOpts;
use crate::args::{MethodArgs, method_help, method_parser, preset_name};
use anyhow::{Context, Result, bail};
use blueshift_render::Method;
use controls::Settings;
use std::path::PathBuf;

/// `view`'s flags: the shared ones with the window's size, the view's defaults and key hints.
#[derive(clap::Args, Debug)]
#[command(
    mut_arg("method", |a| a.help(format!("The view's method (the left side in split-screen). {}",
        method_help()))),
    mut_arg("width", |a| a.default_value("640").help("Window width in pixels")),
    mut_arg("height", |a| a.default_value("480").help("Window height in pixels")),
    mut_arg("spp", |a| a.help("Samples per pixel per frame (keys + and -)")),
    mut_arg("bounces", |a| a.default_value("4")
        .help("Path vertices after the camera (keys [ and ])")),
    mut_arg("block", |a| a.help("Sorting block edge of sort-retarget, 2..=8 [default: 4] (keys B and Shift+B)")),
)]
pub struct ViewArgs {
    #[command(flatten)]
    pub method: MethodArgs,
    /// Render resolution divisor (1, 2 or 4); the image is upscaled (nearest) to the window.
    #[arg(long, default_value_t = 2)]
    pub scale: u32,
    /// Method of the right side in split-screen.
    #[arg(long, default_value = preset_name(Method::White), value_parser = method_parser())]
    pub method_b: Method,
    /// Start in split-screen (key S).
    #[arg(long)]
    pub split: bool,
    /// Start in the error view (key E).
    #[arg(long)]
    pub error_view: bool,
    /// Show single frames instead of the running mean (key A).
    #[arg(long)]
    pub no_accumulation: bool,
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
    let m = &args.method;
    let size = parse_size(&format!("{}x{}", m.width, m.height)).context("--width/--height")?;
    let script = script(args)?;
    let settings = Settings {
        methods: [m.method, args.method_b],
        side: 0,
        spp: m.spp,
        bounces: m.bounces,
        block: m.scene.block.unwrap_or(blueshift_render::PAPER_BLOCK),
        accumulate: !args.no_accumulation,
        split: args.split,
        error: args.error_view,
    };
    // The scene is loaded within what the device can hold; the window's device (made with
    // its surface, later) is picked by the same rule, so its limits are read from a headless
    // one now.
    let limits = gpu.device()?.info().clone();
    let opts = gpu::Options {
        scene: m.scene.load_scene(&limits)?,
        assets: m.scene.load_assets()?,
        template: m.config(),
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
