//! `blueshift bench`: throughput of the path-tracing pass from GPU timestamps (on lavapipe,
//! CPU time per pass), as Msamples/s; plus primary-ray Mrays/s with `--bounces 0`.
//! The results are printed only once every frame (`--loop-stats` ones included) has rendered:
//! a run that fails halfway prints its error and no numbers, rather than a partial table.
use crate::GpuOpts;
use crate::args::{MethodArgs, comparison_parser, preset_name};
use anyhow::{Result, bail};
use blueshift_render::{
    CameraPath, LLVMPIPE_LOOP_LIMIT, LoopStats, Method, RenderConfig, Renderer, TraceLoop,
};
use std::fmt::Write as _;

/// `bench`'s flags.
#[derive(clap::Args, Debug)]
#[command(mut_arg("method", |a| a.default_value(preset_name(Method::White))
    .value_parser(comparison_parser())))]
pub struct BenchArgs {
    #[command(flatten)]
    pub method: MethodArgs,
    /// Timed frames (after the warm-up frames).
    #[arg(long, default_value_t = 3)]
    pub frames: u32,
    /// Untimed frames first, along the same camera path. The default reaches every method's
    /// steady state: lavapipe compiles pipelines on first use, and `sort-cycle` ranks the
    /// keys its seeds recorded a point cycle (16 frames) earlier only once a whole cycle has
    /// run.
    #[arg(long, default_value_t = DEFAULT_WARMUP)]
    pub warmup: u32,
    /// Camera motion over the timed frames, as for `render` (static, pan:PX, orbit:DEG,
    /// swing:DEG or a keyframe file). A still view lets methods that group by surface reuse
    /// the G-buffer and classes, so their pass costs differ under motion.
    #[arg(long, default_value = "static", value_parser = CameraPath::parse)]
    pub camera_path: CameraPath,
    /// Also render the same frames with the loop-counting shader and print, per loop of the
    /// path tracer, its share of the SIMD batches' iterations and how many lanes were busy
    /// in them (the timings come from the normal shader).
    #[arg(long)]
    pub loop_stats: bool,
}

/// Untimed frames by default: the first compiles lavapipe's pipelines, and after a whole
/// point cycle of `sort-cycle` (`CYCLE_FRAMES`) its sort ranks the keys recorded a cycle
/// earlier, its steady state; one frame more, so the first timed frame is past it.
const DEFAULT_WARMUP: u32 = blueshift_layout::params::CYCLE_FRAMES + 1;

pub fn run(gpu: &GpuOpts, a: &BenchArgs) -> Result<()> {
    if !(1..=1000).contains(&a.frames) {
        bail!("--frames {} is outside 1..=1000", a.frames);
    }
    if !(1..=1000).contains(&a.warmup) {
        bail!("--warmup {} is outside 1..=1000", a.warmup);
    }
    let mut cfg = a.method.config();
    let path = &a.camera_path;
    let (view, base_offset) = path.view_window(a.warmup + a.frames, cfg.width, cfg.height);
    cfg.view_size = Some(view);
    let dev = gpu.device()?;
    let scene = a.method.scene.load_scene(dev.info())?;
    let assets = a.method.scene.load_assets()?;
    let base = scene.camera_or_default();
    let path = path.clone().fit(&scene.bounds(), &base, view);
    let run = Frames {
        dev: &dev,
        scene: &scene,
        assets: &assets,
        path: &path,
        base_offset,
        warmup: a.warmup,
        frames: a.frames,
    };
    let timed = run.time(cfg.clone())?;
    // `white` in the same run, for the frame-time ratio (a method's sampler and passes are
    // part of its cost).
    let white = match cfg.method {
        Method::White => None,
        _ => Some(run.time(RenderConfig {
            method: Method::White,
            block: None,
            sampler: None,
            ..cfg.clone()
        })?),
    };
    let Timed {
        mut ms,
        per_pass,
        loop_iterations,
        cpu,
        ..
    } = timed.clone();
    ms.sort_by(f64::total_cmp);
    let mut out = String::new();
    let median = ms[ms.len() / 2];
    let samples = cfg.width as f64 * cfg.height as f64 * cfg.spp as f64;
    writeln!(
        out,
        "scene {} {}x{} spp {} bounces {} method {} on {}",
        a.method.scene.scene,
        cfg.width,
        cfg.height,
        cfg.spp,
        cfg.bounces,
        cfg.method,
        dev.info().name
    )?;
    // Medians per pass; each also per pixel and as a share of the trace pass, the measure of
    // what a permutation method costs on top of the path tracing.
    // A pass skipped in some frames (the G-buffer of a still view) counts 0 ms there.
    let medians: Vec<(String, f64, usize)> = per_pass
        .into_iter()
        .map(|(name, v)| {
            let ran = v.len();
            (name, pass_median(v, a.frames as usize), ran)
        })
        .collect();
    let pixels = cfg.width as f64 * cfg.height as f64;
    let trace = medians
        .iter()
        .find(|(n, ..)| n == "trace")
        .map_or(f64::NAN, |p| p.1);
    for (name, m, ran) in &medians {
        let skipped = if *ran < a.frames as usize {
            format!(" (ran in {ran} of {} frames)", a.frames)
        } else {
            String::new()
        };
        writeln!(
            out,
            "  pass {name:<16} median {m:9.3} ms {:8.2} ns/px {:7.2}% of trace{skipped}",
            m * 1e6 / pixels,
            100.0 * m / trace
        )?;
    }
    let permute: f64 = medians
        .iter()
        .filter(|(n, ..)| blueshift_render::PERMUTE_PASSES.contains(&n.as_str()))
        .fold(0.0, |sum, p| sum + p.1); // (an empty f64 sum is -0.0)
    writeln!(
        out,
        "  permutation passes {permute:.3} ms {:.2} ns/px: {:.2}% of trace",
        permute * 1e6 / pixels,
        100.0 * permute / trace
    )?;
    writeln!(
        out,
        "  trace loop iterations per SIMD batch: at most {loop_iterations} \
         (llvmpipe limit {LLVMPIPE_LOOP_LIMIT})"
    )?;
    writeln!(
        out,
        "trace median {median:.1} ms: {:.3} Msamples/s",
        samples / median / 1e3
    )?;
    if let Some(cpu) = cpu {
        // Less sensitive to other jobs on the machine than the wall-clock timestamps.
        writeln!(
            out,
            "process CPU time per timed frame {cpu:.3} s: {:.3} Msamples per CPU second",
            samples / cpu / 1e6
        )?;
    }
    let frame = timed.frame_median();
    write!(out, "frame median {frame:.3} ms (every pass)")?;
    match &white {
        Some(w) => {
            let r = frame / w.frame_median();
            writeln!(
                out,
                "; white's {:.3} ms in the same run: {r:.3}x \
                 (at equal frame time a P1 ratio q counts as q * {:.3})",
                w.frame_median(),
                r.sqrt()
            )?;
        }
        None => writeln!(out)?,
    }
    if cfg.bounces == 0 {
        writeln!(out, "primary rays: {:.3} Mrays/s", samples / median / 1e3)?;
    }
    if a.loop_stats {
        let cfg = RenderConfig {
            loop_stats: true,
            ..cfg
        };
        let mut r = Renderer::new(&dev, &scene, &assets, cfg)?;
        for _ in 0..a.warmup {
            r.render_frame()?; // still frames: only the counts are kept
        }
        let mut loops = LoopStats::default();
        for _ in 0..a.frames {
            if let Some(l) = r.render_frame()?.loops {
                loops.add(&l);
            }
        }
        loop_table(
            &mut out,
            &loops,
            samples * f64::from(a.frames),
            dev.info().subgroup_size,
        )?;
    }
    crate::check_validation(&dev)?;
    print!("{out}");
    Ok(())
}

/// The median of a pass's times over `frames` frames, of which it ran in `times.len()`: a
/// frame that skipped the pass (a still view's G-buffer) counts 0 ms.
pub(crate) fn pass_median(mut times: Vec<f64>, frames: usize) -> f64 {
    times.resize(frames.max(times.len()), 0.0);
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// The loop table of `--loop-stats` for `samples` samples in all.
fn loop_table(out: &mut String, loops: &LoopStats, samples: f64, width: u32) -> Result<()> {
    let total = loops.total();
    let pct = |u: Option<f64>| u.map_or("-".to_string(), |u| format!("{:.1}%", 100.0 * u));
    writeln!(
        out,
        "loops of the trace pass (same frames, counting shader; SIMD batches of {width}):"
    )?;
    writeln!(
        out,
        "  {:<16} {:>14} {:>12} {:>11}",
        "loop", "batch iter. %", "per sample", "lanes busy"
    )?;
    for l in TraceLoop::ALL {
        let c = loops.get(l);
        writeln!(
            out,
            "  {:<16} {:>14} {:>12.2} {:>11}",
            format!("{}{}", if l.nested() { "  " } else { "" }, l.name()),
            format!(
                "{:.1}",
                100.0 * c.batches as f64 / total.batches.max(1) as f64
            ),
            c.lanes as f64 / samples,
            pct(c.utilization(width)),
        )?;
    }
    writeln!(
        out,
        "  {:<16} {:>14} {:>12.2} {:>11}",
        "all loops",
        "100.0",
        total.lanes as f64 / samples,
        pct(total.utilization(width)),
    )?;
    Ok(())
}

/// User + system CPU time of this process (all threads, lavapipe's included), from
/// /proc/self/stat (clock ticks of 1/100 s); None where that is unavailable.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name: state is field 3, utime 14, stime 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// What [`Frames::time`] measured: per timed frame, the trace's and the whole frame's time;
/// per pass, its times in the frames it ran.
#[derive(Clone, Debug)]
struct Timed {
    ms: Vec<f64>,
    frame_ms: Vec<f64>,
    per_pass: std::collections::BTreeMap<String, Vec<f64>>,
    loop_iterations: u32,
    cpu: Option<f64>,
}

impl Timed {
    /// The median whole frame (the sum of its passes).
    fn frame_median(&self) -> f64 {
        let mut v = self.frame_ms.clone();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    }
}

/// The frames `bench` times: warm-up frames, then timed ones, along the camera path.
struct Frames<'a> {
    dev: &'a blueshift_device::Device,
    scene: &'a blueshift_scene::Scene,
    assets: &'a blueshift_render::MethodAssets,
    path: &'a CameraPath,
    base_offset: (f32, f32),
    warmup: u32,
    frames: u32,
}

impl Frames<'_> {
    fn time(&self, cfg: RenderConfig) -> Result<Timed> {
        let mut r = Renderer::new(self.dev, self.scene, self.assets, cfg)?;
        let base = self.scene.camera_or_default();
        let move_to = |r: &mut Renderer, f: u32| {
            r.set_camera(self.path.camera(&base, f));
            let o = self.path.view_offset(f);
            r.set_view_offset((self.base_offset.0 + o.0, self.base_offset.1 + o.1));
        };
        for f in 0..self.warmup {
            move_to(&mut r, f);
            r.render_frame()?;
        }
        let mut t = Timed {
            ms: Vec::new(),
            frame_ms: Vec::new(),
            per_pass: Default::default(),
            loop_iterations: 0,
            cpu: None,
        };
        let cpu0 = process_cpu_seconds();
        for f in self.warmup..self.warmup + self.frames {
            move_to(&mut r, f);
            let s = r.render_frame()?;
            t.ms.push(s.ms("trace"));
            t.frame_ms.push(s.passes.iter().map(|p| p.ms).sum());
            t.loop_iterations = t.loop_iterations.max(s.trace_loop_iterations);
            for p in s.passes {
                t.per_pass.entry(p.name).or_default().push(p.ms);
            }
        }
        t.cpu = process_cpu_seconds()
            .zip(cpu0)
            .map(|(t1, t0)| (t1 - t0) / f64::from(self.frames));
        Ok(t)
    }
}
