//! report.json (every number, machine-readable) and report.md (tables + figures).
use super::metrics::Split;
use super::ratios::{
    method_of, ratio, ratios, stderr_in, stderr_of, taa_ratios, white_of, with_se,
};
use super::{Config, EvalArgs, Run, figures, front, masks, report_taa, timing};
use crate::output::write_atomic;
use anyhow::Result;
use blueshift_device::Device;
use blueshift_render::Method;
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// The commit the binary was built from (build.rs).
fn commit() -> &'static str {
    env!("BLUESHIFT_COMMIT")
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
        let sobol = method_of(runs, &r.config, Method::Sobol);
        let time_ratio = white.map_or(f64::NAN, |w| timing::time_ratio(r, w));
        let equal_time = |q: fn(&Run) -> f64| {
            white.map_or(f64::NAN, |w| {
                timing::equal_time(ratio(q(r), q(w)), time_ratio)
            })
        };
        let vs_white = white.map(|w| {
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
            "ratios_vs_white": vs_white,
            "p1_ratio_stderr": white.map_or(f64::NAN, |w| stderr_of(r, w, |s| s.all)),
            "p1_edge_ratio_stderr": white.map_or(f64::NAN, |w| stderr_of(r, w, |s| s.edge)),
            "p1_clean_ratio_stderr": white.map_or(f64::NAN, |w| stderr_of(r, w, |s| s.clean)),
            "p1_per_sequence": r.p1_per_sequence,
            "taa": r.metrics.taa,
            "taa_ratios_vs_white": white.map(|w| taa_ratios(&r.metrics, &w.metrics)),
            "ema_p1_clean_ratio_stderr": white.map_or(f64::NAN, |w| {
                stderr_in(r, w, |r| &r.ema_p1_per_sequence, |s| s.clean)
            }),
            "taa_p1_clean_ratio_stderr": white.map_or(f64::NAN, |w| {
                stderr_in(r, w, |r| &r.taa_p1_per_sequence, |s| s.clean)
            }),
            "ema_p1_per_sequence": r.ema_p1_per_sequence,
            "taa_p1_per_sequence": r.taa_p1_per_sequence,
            "taa_flip": num(r.taa_flip),
            "taa_flip_clean": num(r.taa_flip_clean),
            "history_share": r.metrics.history_share,
            "motion_px_per_frame": r.metrics.motion_px,
            "flip": num(r.flip),
            "flip_clean": num(r.flip_clean),
            "flip_ratio_vs_sobol": num(sobol.map_or(f64::NAN, |s| ratio(r.flip, s.flip))),
            "flip_clean_ratio_vs_sobol":
                num(sobol.map_or(f64::NAN, |s| ratio(r.flip_clean, s.flip_clean))),
            "clean_fraction": r.clean_fraction,
            "pass_ms_median": r.pass_ms,
            "frame_ms": timing::frame_ms(r),
            "frame_time_ratio_vs_white": num(time_ratio),
            "equal_time_p1_clean_ratio": num(equal_time(|r| r.metrics.raw.p1.clean)),
            "equal_time_taa_p1_clean_ratio": num(equal_time(|r| r.metrics.taa.p1.clean)),
            "p1_per_frame": r.metrics.p1_per_frame,
            "p1_clean_per_frame": r.metrics.p1_clean_per_frame,
            "seconds": r.seconds,
        });
        if let Some(obj) = v.as_object_mut() {
            // NaN is not JSON: LF is NaN when the image is smaller than one 64x64 tile.
            for k in ["raw", "ema", "taa"] {
                if let Some(lf) = obj.get_mut(k).and_then(|s| s.get_mut("lf")) {
                    *lf = num(lf.as_f64().unwrap_or(f64::NAN));
                }
            }
        }
        json_runs.push(v);
    }
    let report = json!({
        "settings": {
            "scene": a.scene.scene, "width": a.width, "height": a.height, "frames": a.frames,
            "window": [a.frames / 2, a.frames - 1], "block": a.scene.block.unwrap_or(blueshift_render::PAPER_BLOCK),
            "sampler": a.scene.sampler.map(|s| s.name()),
            "reference_spp": a.reference_spp, "sequences": a.sequences,
            "first_sequence": a.first_sequence, "jitter": !a.no_jitter,
            "ema_alpha": super::metrics::EMA_ALPHA, "spectrum_tile": super::metrics::TILE,
            "edge_threshold": masks::EDGE_THRESHOLD, "display_white": masks::DISPLAY_WHITE,
            "emitter_dilation_px": masks::EMITTER_DILATION,
            "wide_sigmas": masks::WIDE_SIGMAS,
            "wide_dilation_sigmas": masks::WIDE_DILATION_SIGMAS,
            "taa_alpha": blueshift_render::taa::ALPHA,
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
    writeln!(md, "# Blueshift evaluation: {}\n", a.scene.scene)?;
    writeln!(
        md,
        "{}x{}, {} frames (metrics over frames {}-{}), block {} (sort-grid-*, sort-cycle: {}), reference {} spp, {} sequence(s){}, {}; \
         device {} ({} {}); commit {}; {:.0} s.\n",
        a.width,
        a.height,
        a.frames,
        a.frames / 2,
        a.frames - 1,
        a.scene.block.unwrap_or(blueshift_render::PAPER_BLOCK),
        blueshift_render::GRID_BLOCK,
        a.reference_spp,
        a.sequences,
        if a.first_sequence == 0 {
            String::new()
        } else {
            format!(" from number {}", a.first_sequence)
        },
        if a.no_jitter {
            "primary rays through pixel centres (--no-jitter)"
        } else {
            "anti-aliasing jitter"
        },
        info.name,
        info.driver_name,
        info.driver_info,
        commit(),
        seconds
    )?;
    if let Some(s) = a.scene.sampler {
        writeln!(
            md,
            "Every method samples with `{}` (--sampler).\n",
            s.name()
        )?;
    }
    writeln!(
        md,
        "Ratios are against `white` (fresh seeds every frame) of the same configuration; below 1 is better. \
        The first columns are on emitter-free pixels: reference luminance below display white ({}) and \
        more than {} px (square) from any pixel at or above it; they are the headline. \
        P1/P2: RMSE of the error blurred with sigma 1/2 px; LF: share of error power below 0.125 cycles/px \
        (64x64 Hann tiles); smooth/edge: pixels by reference gradient; EMA: exponential moving average, alpha 0.1; \
        FLIP: of the accumulated image at the last frame, absolute (lower is better), and as a ratio to `sobol` \
        when the run has it. With 2 or more sequences, the P1 columns show ± the standard error of the \
        per-sequence ratio.\n",
        masks::DISPLAY_WHITE,
        masks::EMITTER_DILATION
    )?;
    report_taa::headline(&mut md, configs, runs)?;
    timing::table(&mut md, configs, runs)?;
    let points = front::front_points(configs, runs);
    if points.len() > 1 {
        writeln!(
            md,
            "## Per frame against accumulated\n\n\
             Geometric means over the configurations below (emitter-free P1 ratios to white; \
             accumulated: TAA, which is the EMA for a still camera); lower left is better on both.\n\n\
             | method | per-frame P1 | TAA P1 |\n|---|---|---|"
        )?;
        for p in &points {
            writeln!(md, "| {} | {:.3} | {:.3} |", p.method, p.per_frame, p.taa)?;
        }
        front::plot(&points, "per frame vs TAA", &out.join("front.png"))?;
        writeln!(md, "\n![front](front.png)\n")?;
    }
    for c in configs {
        let cr: Vec<&Run> = runs.iter().filter(|r| &r.config == c).collect();
        let Some(white) = white_of(runs, c) else {
            continue;
        };
        let sobol = method_of(runs, c, Method::Sobol);
        writeln!(md, "## {}\n", c.label())?;
        let mut cols = vec![
            "method",
            "P1 emitter-free",
            "EMA P1 emitter-free",
            "FLIP emitter-free",
        ];
        if sobol.is_some() {
            cols.push("FLIP emitter-free / sobol");
        }
        cols.extend([
            "RMSE",
            "P1",
            "P2",
            "LF",
            "P1 smooth",
            "P1 edge",
            "EMA P1",
            "EMA LF",
            "FLIP (accum)",
            "permutation passes / trace",
        ]);
        writeln!(md, "| {} |", cols.join(" | "))?;
        writeln!(md, "|{}", "---|".repeat(cols.len()))?;
        for r in &cr {
            let q = ratios(
                &r.metrics.raw,
                &r.metrics.ema,
                &white.metrics.raw,
                &white.metrics.ema,
            );
            // White against itself has no spread.
            let se = |pick: fn(&Split) -> f64| {
                if r.method == Method::White {
                    f64::NAN
                } else {
                    stderr_of(r, white, pick)
                }
            };
            let (p1, p1_edge, p1_clean) = (
                with_se(q.p1, se(|s| s.all)),
                with_se(q.p1_edge, se(|s| s.edge)),
                with_se(q.p1_clean, se(|s| s.clean)),
            );
            let flip_vs_sobol = sobol.map_or(String::new(), |s| {
                format!(" {:.3} |", ratio(r.flip_clean, s.flip_clean))
            });
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
                "| {} | {} | {:.3} | {:.4} |{} {:.3} | {} | {:.3} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.4} | {} |",
                r.method.name(),
                p1_clean,
                q.ema_p1_clean,
                r.flip_clean,
                flip_vs_sobol,
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
        report_taa::config_table(&mut md, &cr, white)?;
        let slug = c.slug();
        figures::radial(
            &cr,
            &format!("radial error spectrum, {}", c.label()),
            &out.join(format!("{slug}_radial.png")),
        )?;
        figures::p1_over_frames(
            &cr,
            &format!("P1 ratio vs white (emitter-free pixels), {}", c.label()),
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
            "\nAbsolute white: P1 emitter-free {:.4}, EMA P1 emitter-free {:.4}; RMSE {:.4}, P1 {:.4}, LF {:.4}. \
             Emitter-free pixels: {:.1}% of the last frame.\n",
            white.metrics.raw.p1.clean,
            white.metrics.ema.p1.clean,
            white.metrics.raw.rmse.all,
            white.metrics.raw.p1.all,
            white.metrics.raw.lf,
            100.0 * white.clean_fraction
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
