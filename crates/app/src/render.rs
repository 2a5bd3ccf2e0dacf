//! `blueshift render`: headless frames of a scene to PNG (tonemapped) and EXR (linear raw).
use crate::GpuOpts;
use crate::args::MethodArgs;
use crate::output::{Staged, exr_rgb32f, png_rgba8, write_atomic};
use anyhow::{Result, bail};
use blueshift_render::{CameraPath, Completed, Renderer};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

/// `render`'s flags.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub method: MethodArgs,
    #[arg(long, default_value_t = 16)]
    pub frames: u32,
    /// static, pan:PX (image-space pan, px/frame), orbit:DEG (deg/frame), swing:DEG (an orbit
    /// turning back after 12 degrees), or a keyframe JSON file.
    #[arg(long, default_value = "static", value_parser = CameraPath::parse)]
    pub camera_path: CameraPath,
    /// Experiment: hash the frame into fixed seeds (breaks temporal correlation).
    #[arg(long)]
    pub frame_salt: bool,
    /// Write every frame (default: only the last).
    #[arg(long)]
    pub all_frames: bool,
    #[arg(long, default_value = "out/render")]
    pub out: PathBuf,
}

pub fn run(gpu: &GpuOpts, args: &RenderArgs) -> Result<()> {
    if args.frames == 0 || args.frames > 100_000 {
        bail!("--frames {} is outside 1..=100000", args.frames);
    }
    let mut cfg = args.method.config();
    cfg.frame_salt = args.frame_salt;
    let path = &args.camera_path;
    let (view, base_offset) = path.view_window(args.frames, cfg.width, cfg.height);
    cfg.view_size = Some(view);
    // The device first: the scene is loaded within what it can hold.
    let dev = gpu.device()?;
    let scene = args.method.scene.load_scene(dev.info())?;
    let assets = args.method.scene.load_assets()?;
    let mut r = Renderer::new(&dev, &scene, &assets, cfg.clone())?;
    // Only now that every input is known to be good. The frames appear in the output
    // directory only if the whole run succeeds: a failed run leaves it as it was (or absent).
    let out = Staged::new(&args.out)?;
    let base = scene.camera_or_default();
    let path = path.clone().fit(&scene.bounds(), &base, view);
    let bar = ProgressBar::new(args.frames as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} frames, {msg} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    // Frames stay in flight: each finished frame is written while the next ones render.
    r.set_output_readback(args.all_frames)?;
    let size = (cfg.width, cfg.height);
    let finished = |done: Vec<Completed>| -> Result<()> {
        for c in done {
            bar.set_message(format!("trace {:.1} ms", c.stats.ms("trace")));
            bar.inc(1);
            if let Some(o) = &c.output {
                write_frame(size, out.path(), c.stats.frame, &o.ldr, &o.estimate)?;
            }
        }
        Ok(())
    };
    for f in 0..args.frames {
        r.set_camera(path.camera(&base, f));
        let o = path.view_offset(f);
        r.set_view_offset((base_offset.0 + o.0, base_offset.1 + o.1));
        finished(r.submit_frame()?)?;
    }
    finished(r.finish_frames()?)?;
    if !args.all_frames {
        let last = u64::from(args.frames - 1);
        write_frame(size, out.path(), last, &r.read_ldr()?, &r.read_estimate()?)?;
    }
    bar.finish();
    crate::check_validation(&dev)?;
    out.commit()?;
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

fn write_frame(
    (w, h): (u32, u32),
    dir: &Path,
    f: u64,
    ldr: &[u8],
    estimate: &[[f32; 4]],
) -> Result<()> {
    write_atomic(
        &dir.join(format!("frame_{f:05}.png")),
        &png_rgba8(w, h, ldr)?,
    )?;
    write_atomic(
        &dir.join(format!("frame_{f:05}.exr")),
        &exr_rgb32f(w, h, estimate)?,
    )?;
    Ok(())
}
