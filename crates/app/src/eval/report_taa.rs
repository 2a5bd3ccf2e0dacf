//! report.md's tables of what a viewer of a moving camera sees: per-frame P1 against P1 of the
//! accumulation along the motion (TAA), its FLIP, and the error at a denoiser's scale (P4, P8).
use super::masks::{WIDE_DILATION_SIGMAS, WIDE_SIGMAS};
use super::metrics::Split;
use super::ratios::{ratio, stderr_in, taa_ratios, white_of, with_se};
use super::{Config, Run};
use anyhow::Result;
use blueshift_render::Method;
use std::fmt::Write as _;

/// One row per method, one column per configuration: per-frame P1 / TAA P1, emitter-free,
/// ratios to white.
pub fn headline(md: &mut String, configs: &[Config], runs: &[Run]) -> Result<()> {
    writeln!(
        md,
        "## Per frame / accumulated along the motion\n\n\
         Emitter-free P1 ratios to white: per frame / TAA (the accumulation that follows the \
         motion; the EMA for a still camera). Below each configuration: the mean motion of the \
         pixel-centre hit points and the share of pixels that kept their TAA history.\n"
    )?;
    method_rows(md, configs, runs, |r, w| {
        format!(
            "{:.3} / {:.3}",
            ratio(r.metrics.raw.p1.clean, w.metrics.raw.p1.clean),
            ratio(r.metrics.taa.p1.clean, w.metrics.taa.p1.clean)
        )
    })?;
    let motion: Vec<String> = configs
        .iter()
        .map(|c| {
            white_of(runs, c).map_or("-".into(), |w| {
                format!(
                    "{:.2} px/frame, {:.1}% kept",
                    w.metrics.motion_px,
                    100.0 * w.metrics.history_share
                )
            })
        })
        .collect();
    writeln!(md, "| *motion* | {} |\n", motion.join(" | "))?;
    Ok(())
}

/// A table of one row per method (in the order they first ran) and one column per
/// configuration, each cell `cell(run, white of that configuration)`.
pub fn method_rows(
    md: &mut String,
    configs: &[Config],
    runs: &[Run],
    cell: impl Fn(&Run, &Run) -> String,
) -> Result<()> {
    let mut methods: Vec<String> = Vec::new();
    for r in runs {
        if !methods.contains(&r.method.name()) {
            methods.push(r.method.name());
        }
    }
    let head: Vec<String> = configs.iter().map(Config::label).collect();
    writeln!(md, "| method | {} |", head.join(" | "))?;
    writeln!(md, "|---|{}", "---|".repeat(configs.len()))?;
    for name in &methods {
        let cells: Vec<String> = configs
            .iter()
            .map(|c| {
                let run = runs
                    .iter()
                    .find(|r| &r.config == c && &r.method.name() == name);
                match (run, white_of(runs, c)) {
                    (Some(r), Some(w)) => cell(r, w),
                    _ => "-".into(),
                }
            })
            .collect();
        writeln!(md, "| {name} | {} |", cells.join(" | "))?;
    }
    Ok(())
}

/// The configuration's TAA and wide-blur table (`runs`: its runs, `white` among them).
pub fn config_table(md: &mut String, runs: &[&Run], white: &Run) -> Result<()> {
    writeln!(
        md,
        "\nAccumulated along the motion (TAA: hit points reprojected with the previous camera, \
         bilinear taps on another surface dropped, alpha 0.1; the EMA for a still camera): \
         motion {:.2} px/frame, history kept by {:.1}% of the pixels (mean over the window). \
         P{:.0} and P{:.0}: sigma {:.0} and {:.0} px, on pixels more than {:.0} sigma from an emitter. \
         Emitter-free ratios to white, ± the standard error across sequences; TAA FLIP absolute. \
         Smooth / edge: the emitter-free pixels off / at reference edges; at edges: their share \
         of the method's own squared TAA P1 error.\n",
        white.metrics.motion_px,
        100.0 * white.metrics.history_share,
        WIDE_SIGMAS[0],
        WIDE_SIGMAS[1],
        WIDE_SIGMAS[0],
        WIDE_SIGMAS[1],
        WIDE_DILATION_SIGMAS
    )?;
    writeln!(
        md,
        "| method | P1 | EMA P1 | TAA P1 | TAA P1 smooth | TAA P1 edge | TAA error at edges \
         | TAA FLIP | P4 | P8 | TAA P4 | TAA P8 |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
    )?;
    for r in runs {
        let (m, w) = (&r.metrics, &white.metrics);
        let q = taa_ratios(m, w);
        let se = |series: fn(&Run) -> &Vec<Split>| {
            if r.method == Method::White {
                f64::NAN
            } else {
                stderr_in(r, white, series, |s| s.clean)
            }
        };
        writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.1}% | {:.4} | {:.3} | {:.3} | {:.3} | {:.3} |",
            r.method.name(),
            with_se(
                ratio(m.raw.p1.clean, w.raw.p1.clean),
                se(|r| &r.p1_per_sequence)
            ),
            with_se(
                ratio(m.ema.p1.clean, w.ema.p1.clean),
                se(|r| &r.ema_p1_per_sequence)
            ),
            with_se(q.taa_p1_clean, se(|r| &r.taa_p1_per_sequence)),
            q.taa_p1_smooth,
            q.taa_p1_edge,
            100.0 * q.taa_edge_share,
            r.taa_flip_clean,
            q.p4,
            q.p8,
            q.taa_p4,
            q.taa_p8
        )?;
    }
    writeln!(md)?;
    Ok(())
}
