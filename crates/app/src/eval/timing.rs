//! Methods at equal frame time: a method's whole frame (the trace with its sampler, and every
//! pass the method adds) against `white`'s in the same run, and its P1 ratio scaled to what
//! it would be at `white`'s frame time.
//!
//! Why the square root: at a fixed budget a method that takes r times as long per frame
//! renders 1/r as many samples, and Monte Carlo error falls as one over the square root of
//! the samples, so a P1 ratio q at r times the cost is worth q * sqrt(r) at equal time.
use super::ratios::ratio;
use super::{Config, Run};
use anyhow::Result;
use std::fmt::Write as _;

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
    fn twice_the_time_needs_a_ratio_below_one_over_root_two_to_win() {
        // Twice the frames at white's cost average the error down by sqrt(2).
        assert!((equal_time(1.0, 2.0) - 2f64.sqrt()).abs() < 1e-12);
        assert!(equal_time(0.7, 2.0) < 1.0 && equal_time(0.71, 2.0) > 1.0);
        assert_eq!(equal_time(0.8, 1.0), 0.8);
        assert!(equal_time(0.8, f64::NAN).is_nan(), "no timings, no claim");
    }
}
