//! `blueshift soak`: a long run of the frame loop, optionally with a moving camera, that
//! checks every `--check-every` frames that the seed buffer is still a permutation of the
//! initial seeds, that every buffer the method carries between frames is finite, and that
//! host RSS and device memory in use (bytes and live allocations) have not grown since the
//! warm-up. Prints the figures of every check; fails (exit 1) on the first violation.
use crate::GpuOpts;
use crate::args::MethodArgs;
use anyhow::{Result, bail};
use blueshift_permute::is_permutation_of;
use blueshift_render::{CameraPath, Method, Renderer};
use std::time::Instant;

/// `soak`'s flags. `--method` must permute seeds (a sort preset or a spelled-out `sort:...`).
#[derive(clap::Args, Debug)]
pub struct SoakArgs {
    #[command(flatten)]
    pub method: MethodArgs,
    #[arg(long, default_value_t = 10_000)]
    pub frames: u32,
    /// Camera motion, as for `render` (static, pan:PX, orbit:DEG, swing:DEG, strafe:PX,
    /// orbit-view:DEG or a keyframe file): moving views exercise the reprojection, the
    /// G-buffer and the restarts of the running mean.
    #[arg(long, default_value = "static", value_parser = CameraPath::parse)]
    pub camera_path: CameraPath,
    /// Check the seeds and memory every this many frames [default: 1000, or --frames if
    /// fewer].
    #[arg(long)]
    pub check_every: Option<u32>,
    /// Frames before the memory baseline is taken (allocator pools, lazy pipeline compiles);
    /// at most --check-every.
    #[arg(long, default_value_t = 100)]
    pub warmup: u32,
    /// Allowed host RSS growth over the baseline, KiB (any u64: 18446744073709551615 allows
    /// any growth).
    #[arg(long, default_value_t = 8192)]
    pub rss_tolerance_kib: u64,
    /// Allowed growth of device memory in use over the baseline, bytes (allocations are exact).
    #[arg(long, default_value_t = 0)]
    pub device_tolerance: u64,
}

/// Resident set size of this process in KiB (`VmRSS` of /proc/self/status).
pub fn rss_kib() -> Result<u64> {
    let status = std::fs::read_to_string("/proc/self/status")?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .ok_or_else(|| anyhow::anyhow!("no VmRSS line in /proc/self/status"))
}

/// `--check-every` when it is not given: this, or `--frames` if fewer.
const DEFAULT_CHECK_EVERY: u32 = 1000;

/// `now - base` as a signed number, saturating at the ends of i64 (never wraps).
fn growth(now: u64, base: u64) -> i64 {
    if now >= base {
        i64::try_from(now - base).unwrap_or(i64::MAX)
    } else {
        i64::try_from(base - now).map_or(i64::MIN, |d| -d)
    }
}

/// Whether `growth` exceeds `tolerance` (any u64, compared without conversion to i64).
fn over(growth: i64, tolerance: u64) -> bool {
    u64::try_from(growth).is_ok_and(|g| g > tolerance)
}

struct Baseline {
    rss_kib: u64,
    device_bytes: u64,
    allocations: usize,
}

impl Baseline {
    fn now(dev: &blueshift_device::Device) -> Result<Self> {
        Ok(Self {
            rss_kib: rss_kib()?,
            device_bytes: dev.allocated_bytes(),
            allocations: dev.allocations().len(),
        })
    }
}

/// The first buffer carried between frames with a value that is not finite, as an error
/// message; the number of values checked otherwise.
fn check_history(r: &Renderer) -> Result<usize, String> {
    let mut checked = 0;
    for h in r.read_history_state().map_err(|e| e.to_string())? {
        let bad = h.bad_values();
        if bad > 0 {
            return Err(format!(
                "{bad} of the {} values of {} are not finite",
                h.values.len(),
                h.name
            ));
        }
        checked += h.values.len();
    }
    Ok(checked)
}

pub fn run(gpu: &GpuOpts, a: &SoakArgs) -> Result<()> {
    if !(1..=10_000_000).contains(&a.frames) {
        bail!("--frames {} is outside 1..=10000000", a.frames);
    }
    let check_every = a.check_every.unwrap_or(a.frames.min(DEFAULT_CHECK_EVERY));
    if check_every == 0 || check_every > a.frames {
        bail!(
            "--check-every {check_every} is outside 1..=--frames ({})",
            a.frames
        );
    }
    // The baseline is taken at the latest at the first check.
    let warmup = a.warmup.clamp(1, check_every);
    let cfg = a.method.config();
    if !cfg.method.sorts() {
        let permuting: Vec<&str> = Method::PRESETS
            .iter()
            .filter(|(_, m)| m.sorts())
            .map(|(n, _)| *n)
            .collect();
        bail!(
            "soak checks the seed permutation: --method must permute seeds ({} or a spelled-out \
             PRESET:field=value form of them), not {}",
            permuting.join(", "),
            cfg.method
        );
    }
    let dev = gpu.device()?;
    let scene = a.method.scene.load_scene(dev.info())?;
    let assets = a.method.scene.load_assets()?;
    let path = &a.camera_path;
    let (view, base_offset) = path.view_window(a.frames, cfg.width, cfg.height);
    let cfg = blueshift_render::RenderConfig {
        view_size: Some(view),
        ..cfg
    };
    let mut r = Renderer::new(&dev, &scene, &assets, cfg.clone())?;
    let start = scene.camera_or_default();
    let path = path.clone().fit(&scene.bounds(), &start, view);
    println!(
        "soak: {} frames of {} at {}x{}, camera {}, spp {}, bounces {}, block {} on {}; \
         check every {}",
        a.frames,
        cfg.method,
        cfg.width,
        cfg.height,
        path.label(),
        cfg.spp,
        cfg.bounces,
        cfg.effective_block(),
        dev.info().name,
        check_every
    );
    let mut base: Option<Baseline> = None;
    let mut window = Instant::now();
    let mut worst = (0i64, 0i64);
    for f in 1..=a.frames {
        // Frame f - 1 of the path: the first frame shows the path's start.
        let g = f - 1;
        r.set_camera(path.camera(&start, g));
        let o = path.view_offset(g);
        r.set_view_offset((base_offset.0 + o.0, base_offset.1 + o.1));
        r.render_frame()?;
        if f == warmup {
            let b = Baseline::now(&dev)?;
            println!(
                "baseline after {f} frames: RSS {} KiB, device memory {} bytes in {} \
                 allocations",
                b.rss_kib, b.device_bytes, b.allocations
            );
            base = Some(b);
        }
        if f % check_every != 0 && f != a.frames {
            continue;
        }
        let ms = window.elapsed().as_secs_f64() * 1e3 / f64::from(check_every);
        let seeds = r.read_seeds()?;
        let permutation = is_permutation_of(&seeds, r.initial_seeds());
        let history = check_history(&r);
        // Taken after the read-backs, whose staging buffers are gone by then.
        let now = Baseline::now(&dev)?;
        let (rss, device) = (now.rss_kib, now.device_bytes);
        let b = base.as_ref().unwrap_or(&now);
        let (d_rss, d_dev) = (growth(rss, b.rss_kib), growth(device, b.device_bytes));
        let d_alloc = growth(now.allocations as u64, b.allocations as u64);
        worst = (worst.0.max(d_rss), worst.1.max(d_dev));
        println!(
            "frame {f:>8}: seeds {} ({} seeds), history {}, RSS {rss} KiB ({d_rss:+} KiB), \
             device memory {device} bytes ({d_dev:+} bytes) in {} allocations ({d_alloc:+}), \
             {ms:.2} ms/frame",
            if permutation {
                "a permutation"
            } else {
                "NOT a permutation"
            },
            seeds.len(),
            match &history {
                Ok(n) => format!("finite ({n} values)"),
                Err(_) => "NOT finite".to_string(),
            },
            now.allocations,
        );
        if !permutation {
            bail!("frame {f}: the seed buffer is no longer a permutation of the initial seeds");
        }
        if let Err(e) = history {
            bail!("frame {f}: {e}");
        }
        if over(d_rss, a.rss_tolerance_kib) {
            bail!(
                "frame {f}: host RSS grew by {d_rss} KiB since the warm-up (tolerance {} KiB)",
                a.rss_tolerance_kib
            );
        }
        if d_alloc > 0 {
            bail!("frame {f}: {d_alloc} more device allocations live than after the warm-up");
        }
        if over(d_dev, a.device_tolerance) {
            bail!(
                "frame {f}: device memory in use grew by {d_dev} bytes since the warm-up \
                 (tolerance {})",
                a.device_tolerance
            );
        }
        window = Instant::now();
    }
    crate::check_validation(&dev)?;
    println!(
        "soak passed: {} frames, camera {}, seeds a permutation and history finite at every \
         check, max growth RSS {:+} KiB, device memory {:+} bytes",
        a.frames,
        path.label(),
        worst.0,
        worst.1
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn growth_and_tolerance_never_wrap() {
        assert_eq!(growth(10, 4), 6);
        assert_eq!(growth(4, 10), -6);
        assert_eq!(growth(u64::MAX, 0), i64::MAX);
        assert_eq!(growth(0, u64::MAX), i64::MIN);
        assert!(over(9, 8));
        assert!(!over(8, 8));
        assert!(!over(-5, 0));
        // Once `u64::MAX as i64` = -1: every growth, even 0, was over it.
        assert!(!over(0, u64::MAX));
        assert!(!over(i64::MAX, u64::MAX));
    }
}
