//! Methods at equal frame time: a method's whole frame (the trace with its sampler, and every
//! pass the method adds) against `white`'s in the same run, and its P1 ratio scaled to what
//! it would be at `white`'s frame time.
//!
//! Why the square root: at a fixed budget a method that takes r times as long per frame
//! renders 1/r as many samples, and Monte Carlo error falls as one over the square root of
//! the samples, so a P1 ratio q at r times the cost is worth q * sqrt(r) at equal time.
//!
//! The frames are timed in a phase of their own after the quality runs: one renderer per
//! method follows the camera path once, the methods taking turns every [`CHUNK`] frames (the
//! first method of a turn rotating), so that a load or clock change on the machine falls on
//! every method alike. Timed one method after another, a 128x128 frame's ratio to `white`'s
//! moved by up to 0.09 between runs.
use super::ratios::ratio;
use super::{Config, PathRenderer, Run, RunContext};
use anyhow::Result;
use blueshift_render::{Method, SeedMap};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Frames a method renders in one turn of the timing phase.
const CHUNK: u32 = 8;

/// Each method's median time per pass over the path's frames, rendered in turns
/// ([`schedule`]; medians by `bench::pass_median`, a skipped pass counting 0 ms).
pub fn measure(
    ctx: &RunContext,
    config: &Config,
    methods: &[Method],
    seed_map: SeedMap,
) -> Result<Vec<BTreeMap<String, f64>>> {
    let mut renderers = methods
        .iter()
        .map(|&m| PathRenderer::new(ctx, config, m, ctx.args.first_sequence, seed_map))
        .collect::<Result<Vec<_>>>()?;
    let mut times = vec![BTreeMap::<String, Vec<f64>>::new(); methods.len()];
    for (m, frames) in schedule(methods.len(), ctx.args.frames) {
        for t in frames {
            for p in renderers[m].render(t)?.passes {
                times[m].entry(p.name).or_default().push(p.ms);
            }
        }
    }
    let frames = ctx.args.frames as usize;
    Ok(times
        .into_iter()
        .map(|per_pass| {
            per_pass
                .into_iter()
                .map(|(name, v)| (name, crate::bench::pass_median(v, frames)))
                .collect()
        })
        .collect())
}

/// The order of the timing phase: (method, its frames) turns, each method's frames in path
/// order and every frame once; turn r starts with method r mod `methods`.
fn schedule(methods: usize, frames: u32) -> Vec<(usize, std::ops::Range<u32>)> {
    let mut turns = Vec::new();
    for (r, start) in (0..frames).step_by(CHUNK as usize).enumerate() {
        let chunk = start..(start + CHUNK).min(frames);
        turns.extend((0..methods).map(|k| ((r + k) % methods, chunk.clone())));
    }
    turns
}

/// The whole frame: the sum of the medians over the run's frames of every timed pass (a
/// pass a frame skipped counts 0 there).
pub fn frame_ms(r: &Run) -> f64 {
    r.pass_ms.values().sum()
}

/// `run`'s frame time over `white`'s (NaN without timings).
pub fn time_ratio(run: &Run, white: &Run) -> f64 {
    ratio(frame_ms(run), frame_ms(white))
}

/// A P1 ratio at equal frame time.
pub fn equal_time(p1_ratio: f64, time_ratio: f64) -> f64 {
    p1_ratio * time_ratio.sqrt()
}

/// One row per method, one column per configuration: equal-time per-frame P1 / TAA P1
/// (emitter-free, ratios to white) and the frame-time ratio.
pub fn table(md: &mut String, configs: &[Config], runs: &[Run]) -> Result<()> {
    writeln!(
        md,
        "## Per frame / accumulated at equal frame time\n\n\
         The ratios above times the square root of the method's frame time over `white`'s \
         (whole frames: the trace and every pass, medians over this run's frames, GPU \
         timestamps): per frame / TAA, and (the frame-time ratio).\n"
    )?;
    super::report_taa::method_rows(md, configs, runs, |r, w| {
        let t = time_ratio(r, w);
        format!(
            "{:.3} / {:.3} ({t:.2}x)",
            equal_time(ratio(r.metrics.raw.p1.clean, w.metrics.raw.p1.clean), t),
            equal_time(ratio(r.metrics.taa.p1.clean, w.metrics.taa.p1.clean), t)
        )
    })?;
    writeln!(md)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schedule_renders_each_methods_frames_once_in_order_and_rotates_who_goes_first() {
        for (methods, frames) in [(1, 1), (3, 64), (17, 20), (4, 7)] {
            let turns = schedule(methods, frames);
            for m in 0..methods {
                let mine: Vec<u32> = turns
                    .iter()
                    .filter(|(k, _)| *k == m)
                    .flat_map(|(_, f)| f.clone())
                    .collect();
                assert_eq!(mine, (0..frames).collect::<Vec<_>>(), "{methods} {frames}");
            }
            // Between two turns of a method every other method has one turn.
            let firsts: Vec<usize> = turns.chunks(methods).map(|c| c[0].0).collect();
            let rotating: Vec<usize> = (0..firsts.len()).map(|r| r % methods).collect();
            assert_eq!(firsts, rotating);
            for c in turns.chunks(methods) {
                let mut ms: Vec<usize> = c.iter().map(|t| t.0).collect();
                ms.sort();
                assert_eq!(ms, (0..methods).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn twice_the_time_needs_a_ratio_below_one_over_root_two_to_win() {
        // Twice the frames at white's cost average the error down by sqrt(2).
        assert!((equal_time(1.0, 2.0) - 2f64.sqrt()).abs() < 1e-12);
        assert!(equal_time(0.7, 2.0) < 1.0 && equal_time(0.71, 2.0) > 1.0);
        assert_eq!(equal_time(0.8, 1.0), 0.8);
        assert!(equal_time(0.8, f64::NAN).is_nan(), "no timings, no claim");
    }
}
