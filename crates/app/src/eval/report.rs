//! report.json (every number, machine-readable) and report.md (tables + figures).
use super::metrics::{Split, StreamMetrics};
use super::{Config, EvalArgs, Run, figures};
use crate::output::write_atomic;
use anyhow::Result;
use blueshift_device::Device;
use blueshift_render::Method;
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// Ratios of a run's metrics to white noise of the same configuration.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Ratios {
    pub rmse: f64,
    pub p1: f64,
    pub p2: f64,
    pub lf: f64,
    pub p1_smooth: f64,
    pub p1_edge: f64,
    pub ema_p1: f64,
    pub ema_lf: f64,
}

pub fn ratios(
    m: &StreamMetrics,
    ema: &StreamMetrics,
    w: &StreamMetrics,
    wema: &StreamMetrics,
) -> Ratios {
    let r = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::NAN };
    Ratios {
        rmse: r(m.rmse.all, w.rmse.all),
        p1: r(m.p1.all, w.p1.all),
        p2: r(m.p2.all, w.p2.all),
        lf: r(m.lf, w.lf),
        p1_smooth: r(m.p1.smooth, w.p1.smooth),
        p1_edge: r(m.p1.edge, w.p1.edge),
        ema_p1: r(ema.p1.all, wema.p1.all),
        ema_lf: r(ema.lf, wema.lf),
    }
}

/// Standard error of the P1 ratio to white across sequences: the ratios of sequence i of both
/// runs (same camera and references), their sample standard deviation over sqrt(n). NaN for
/// fewer than 2 sequences. Tells whether two methods (or a method and a bar) differ by more
/// than the choice of initial seeds.
pub fn p1_ratio_stderr(m: &[f64], w: &[f64]) -> f64 {
    let r: Vec<f64> = m.iter().zip(w).map(|(a, b)| a / b).collect();
    let n = r.len() as f64;
    if r.len() < 2 {
        return f64::NAN;
    }
    let mean = r.iter().sum::<f64>() / n;
    let var = r.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (var / n).sqrt()
}

/// `p1_ratio_stderr` of one pixel set (`all` or `edge`) of two runs.
fn stderr_of(r: &Run, w: &Run, pick: fn(&Split) -> f64) -> f64 {
    let m: Vec<f64> = r.p1_per_sequence.iter().map(pick).collect();
    let w: Vec<f64> = w.p1_per_sequence.iter().map(pick).collect();
    p1_ratio_stderr(&m, &w)
}

/// `value ± se` when the spread is known (2 or more sequences), else the value alone.
fn with_se(value: f64, se: f64) -> String {
    if se.is_finite() {
        format!("{value:.3} ± {se:.3}")
    } else {
        format!("{value:.3}")
    }
}

fn white_of<'a>(runs: &'a [Run], c: &Config) -> Option<&'a Run> {
    runs.iter()
        .find(|r| r.method == Method::White && &r.config == c)
}

fn commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map_or_else(
            || "unknown".into(),
            |o| String::from_utf8_lossy(&o.stdout).trim().to_string(),
        )
}

fn num(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

pub fn write(
    out: &Path,
    a: &EvalArgs,
    dev: &Device,
    configs: &[Config],
    runs: &[Run],
    seconds: f64,
) -> Result<()> {
    let info = dev.info();
    let mut json_runs = Vec::new();
    for r in runs {
        let white = white_of(runs, &r.config);
        let ratio = white.map(|w| {
            ratios(
                &r.metrics.raw,
                &r.metrics.ema,
                &w.metrics.raw,
                &w.metrics.ema,
            )
        });
        let mut v = json!({
            "method": r.method.name(),
            "camera": r.config.camera.label(),
            "bounces": r.config.bounces,
            "spp": r.config.spp,
            "raw": r.metrics.raw,
            "ema": r.metrics.ema,
            "ratios_vs_white": ratio,
            "p1_ratio_stderr": white.map_or(f64::NAN, |w| stderr_of(r, w, |s| s.all)),
            "p1_edge_ratio_stderr": white.map_or(f64::NAN, |w| stderr_of(r, w, |s| s.edge)),
            "p1_per_sequence": r.p1_per_sequence,
            "flip": num(r.flip),
            "pass_ms_median": r.pass_ms,
            "p1_per_frame": r.metrics.p1_per_frame,
            "seconds": r.seconds,
        });
        if let Some(obj) = v.as_object_mut() {
            // NaN is not JSON: LF is NaN when the image is smaller than one 64x64 tile.
            for k in ["raw", "ema"] {
                if let Some(lf) = obj.get_mut(k).and_then(|s| s.get_mut("lf")) {
                    *lf = num(lf.as_f64().unwrap_or(f64::NAN));
                }
            }
        }
        json_runs.push(v);
    }
    let report = json!({
        "settings": {
            "scene": a.scene, "width": a.width, "height": a.height, "frames": a.frames,
            "window": [a.frames / 2, a.frames - 1], "block": a.block,
            "reference_spp": a.reference_spp, "sequences": a.sequences, "jitter": a.jitter,
            "ema_alpha": super::metrics::EMA_ALPHA, "spectrum_tile": super::metrics::TILE,
            "edge_threshold": super::metrics::EDGE_THRESHOLD,
        },
        "device": { "name": info.name, "driver": format!("{} {}", info.driver_name, info.driver_info) },
        "commit": commit(),
        "seconds": seconds,
        "runs": json_runs,
    });
    let text = serde_json::to_string_pretty(&report)?.replace("NaN", "null");
    write_atomic(&out.join("report.json"), text.as_bytes())?;
    write_atomic(
        &out.join("report.md"),
        markdown(out, a, dev, configs, runs, seconds)?.as_bytes(),
    )?;
    Ok(())
}

fn markdown(
    out: &Path,
    a: &EvalArgs,
    dev: &Device,
    configs: &[Config],
    runs: &[Run],
    seconds: f64,
) -> Result<String> {
    let mut md = String::new();
    let info = dev.info();
    writeln!(md, "# Blueshift evaluation: {}\n", a.scene)?;
    writeln!(
        md,
        "{}x{}, {} frames (metrics over frames {}-{}), block {} (sort-grid-*: {}), reference {} spp, {} sequence(s); \
         device {} ({} {}); commit {}; {:.0} s.\n",
        a.width,
        a.height,
        a.frames,
        a.frames / 2,
        a.frames - 1,
        a.block,
        blueshift_render::GRID_BLOCK,
        a.reference_spp,
        a.sequences,
        info.name,
        info.driver_name,
        info.driver_info,
        commit(),
        seconds
    )?;
    writeln!(
        md,
        "Ratios are against `white` (fresh seeds every frame) of the same configuration; below 1 is better. \
        P1/P2: RMSE of the error blurred with sigma 1/2 px; LF: share of error power below 0.125 cycles/px \
        (64x64 Hann tiles); smooth/edge: pixels by reference gradient; EMA: exponential moving average, alpha 0.1. \
        With 2 or more sequences, P1 and P1 edge show ± the standard error of the per-sequence ratio.\n"
    )?;
    for c in configs {
        let cr: Vec<&Run> = runs.iter().filter(|r| &r.config == c).collect();
        let Some(white) = white_of(runs, c) else {
            continue;
        };
        writeln!(md, "## {}\n", c.label())?;
        writeln!(
            md,
            "| method | RMSE | P1 | P2 | LF | P1 smooth | P1 edge | EMA P1 | EMA LF | FLIP (accum) | permutation passes / trace |"
        )?;
        writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|")?;
        for r in &cr {
            let q = ratios(
                &r.metrics.raw,
                &r.metrics.ema,
                &white.metrics.raw,
                &white.metrics.ema,
            );
            let (p1, p1_edge) = if r.method == Method::White {
                (with_se(q.p1, f64::NAN), with_se(q.p1_edge, f64::NAN))
            } else {
                (
                    with_se(q.p1, stderr_of(r, white, |s| s.all)),
                    with_se(q.p1_edge, stderr_of(r, white, |s| s.edge)),
                )
            };
            let trace = r.pass_ms.get("trace").copied().unwrap_or(0.0);
            // Every pass a method adds to the path tracer.
            let perm: f64 = blueshift_render::PERMUTE_PASSES
                .iter()
                .map(|p| r.pass_ms.get(*p).copied().unwrap_or(0.0))
                .sum();
            let overhead = if trace > 0.0 && perm > 0.0 {
                format!("{:.2}%", 100.0 * perm / trace)
            } else {
                "-".into()
            };
            writeln!(
                md,
                "| {} | {:.3} | {} | {:.3} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.4} | {} |",
                r.method.name(),
                q.rmse,
                p1,
                q.p2,
                q.lf,
                q.p1_smooth,
                p1_edge,
                q.ema_p1,
                q.ema_lf,
                r.flip,
                overhead
            )?;
        }
        let slug = c.slug();
        figures::radial(
            &cr,
            &format!("radial error spectrum, {}", c.label()),
            &out.join(format!("{slug}_radial.png")),
        )?;
        figures::p1_over_frames(
            &cr,
            &format!("P1 ratio vs white, {}", c.label()),
            &out.join(format!("{slug}_p1.png")),
        )?;
        figures::strip(
            &cr,
            a.width,
            a.height,
            &out.join(format!("{slug}_frames.png")),
        )?;
        writeln!(
            md,
            "\nAbsolute white: RMSE {:.4}, P1 {:.4}, LF {:.4}.\n",
            white.metrics.raw.rmse.all, white.metrics.raw.p1.all, white.metrics.raw.lf
        )?;
        if out.join(format!("{slug}_radial.png")).exists() {
            writeln!(md, "![radial]({slug}_radial.png)\n")?;
        }
        writeln!(md, "![P1 over frames]({slug}_p1.png)\n")?;
        writeln!(
            md,
            "Last frame of each method, left to right: {}.\n",
            cr.iter()
                .map(|r| r.method.name())
                .collect::<Vec<_>>()
                .join(", ")
        )?;
        writeln!(md, "![frames]({slug}_frames.png)\n")?;
        writeln!(
            md,
            "Error of the last frame (signed: blue negative, red positive, centre crop at 2x) and the error spectrum averaged over the window (DC centred, log scale):\n"
        )?;
        for r in &cr {
            let f = format!("{slug}_{}_error.png", r.method.name());
            figures::error_and_spectrum(r, &out.join(&f))?;
            writeln!(
                md,
                "**{}**\n\n![{}]({f})\n",
                r.method.name(),
                r.method.name()
            )?;
        }
    }
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::p1_ratio_stderr;

    #[test]
    fn stderr_of_per_sequence_ratios() {
        // Ratios 0.8 and 0.9: sample sd 0.0707, over sqrt(2) = 0.05.
        let se = p1_ratio_stderr(&[0.8, 1.8], &[1.0, 2.0]);
        assert!((se - 0.05).abs() < 1e-12, "{se}");
        // Equal ratios have no spread; one sequence has none defined.
        assert_eq!(p1_ratio_stderr(&[1.0, 2.0, 3.0], &[2.0, 4.0, 6.0]), 0.0);
        assert!(p1_ratio_stderr(&[1.0], &[2.0]).is_nan());
    }
}
