//! Ratios to `white` and to `sobol` of the same configuration, and their spread across
//! sequences: the numbers report.md and report.json share.
use super::metrics::{RunMetrics, Split, StreamMetrics};
use super::{Config, Run};
use blueshift_render::Method;

/// Ratios of a run's metrics to white noise of the same configuration (`_clean`: on
/// emitter-free pixels).
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Ratios {
    pub p1_clean: f64,
    pub ema_p1_clean: f64,
    pub rmse_clean: f64,
    pub p2_clean: f64,
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
    let r = ratio;
    Ratios {
        p1_clean: r(m.p1.clean, w.p1.clean),
        ema_p1_clean: r(ema.p1.clean, wema.p1.clean),
        rmse_clean: r(m.rmse.clean, w.rmse.clean),
        p2_clean: r(m.p2.clean, w.p2.clean),
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

/// Ratios to white of the accumulation along the motion and of the wide blurs (P4, P8), all on
/// emitter-free pixels.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct TaaRatios {
    pub taa_p1_clean: f64,
    /// TAA P1 on the emitter-free pixels off / at reference edges ([`Split::clean_edge`]).
    pub taa_p1_smooth: f64,
    pub taa_p1_edge: f64,
    /// The edge pixels' share of the method's own emitter-free TAA P1 error (squared).
    pub taa_edge_share: f64,
    pub p4: f64,
    pub p8: f64,
    pub taa_p4: f64,
    pub taa_p8: f64,
}

pub fn taa_ratios(m: &RunMetrics, w: &RunMetrics) -> TaaRatios {
    // Squared parts of the emitter-free TAA P1: (smooth, edge).
    let parts = |s: &Split| {
        let edge = s.clean_edge * s.clean_edge;
        ((s.clean * s.clean - edge).max(0.0), edge)
    };
    let ((ms, me), (ws, we)) = (parts(&m.taa.p1), parts(&w.taa.p1));
    TaaRatios {
        taa_p1_clean: ratio(m.taa.p1.clean, w.taa.p1.clean),
        taa_p1_smooth: ratio(ms, ws).sqrt(),
        taa_p1_edge: ratio(me, we).sqrt(),
        taa_edge_share: ratio(me, ms + me),
        p4: ratio(m.raw.p4, w.raw.p4),
        p8: ratio(m.raw.p8, w.raw.p8),
        taa_p4: ratio(m.taa.p4, w.taa.p4),
        taa_p8: ratio(m.taa.p8, w.taa.p8),
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

/// `p1_ratio_stderr` of one pixel set (`all`, `edge`, `clean`) of two runs' per-frame P1.
pub fn stderr_of(r: &Run, w: &Run, pick: fn(&Split) -> f64) -> f64 {
    stderr_in(r, w, |r| &r.p1_per_sequence, pick)
}

/// `p1_ratio_stderr` of one pixel set of two runs' per-sequence P1 of one stream (`series`:
/// per frame, EMA or TAA).
pub fn stderr_in(
    r: &Run,
    w: &Run,
    series: fn(&Run) -> &Vec<Split>,
    pick: fn(&Split) -> f64,
) -> f64 {
    let m: Vec<f64> = series(r).iter().map(pick).collect();
    let w: Vec<f64> = series(w).iter().map(pick).collect();
    p1_ratio_stderr(&m, &w)
}

/// `value ± se` when the spread is known (2 or more sequences), else the value alone.
pub fn with_se(value: f64, se: f64) -> String {
    if se.is_finite() {
        format!("{value:.3} ± {se:.3}")
    } else {
        format!("{value:.3}")
    }
}

pub fn method_of<'a>(runs: &'a [Run], c: &Config, m: Method) -> Option<&'a Run> {
    runs.iter().find(|r| r.method == m && &r.config == c)
}

pub fn white_of<'a>(runs: &'a [Run], c: &Config) -> Option<&'a Run> {
    method_of(runs, c, Method::White)
}

/// `a / b`, NaN when `b` is not positive.
pub fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 { a / b } else { f64::NAN }
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
