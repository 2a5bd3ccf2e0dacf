//! Per-run metric accumulation (docs/results.md): RMSE, LF, P1, P2 over a frame window, on all,
//! smooth, edge and emitter-free pixels, and P4, P8 on pixels far from emitters, for raw
//! frames, their exponential moving average (alpha 0.1) and their accumulation along the
//! motion (`taa`).
use super::masks::{Masks, WIDE_SIGMAS};
use anyhow::Result;
use blueshift_analysis::{
    Boundary, Gray, LF_CUTOFF, RadialProfile, Spectrum, SpectrumAccumulator, Window, gaussian_blur,
    low_frequency_fraction, radial_profile,
};
use blueshift_render::taa::{self, Reprojection};
use serde::Serialize;

/// Spectrum tile edge (docs/results.md: 64x64 tiles).
pub const TILE: usize = 64;
/// EMA weight of the newest frame.
pub const EMA_ALPHA: f32 = 0.1;
/// Mean squares (or their roots) on all / smooth / edge / emitter-free pixels.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct Split {
    pub all: f64,
    pub smooth: f64,
    pub edge: f64,
    /// Emitter-free pixels ([`Masks::clean`]).
    pub clean: f64,
    /// The emitter-free edge pixels' part of `clean`: their squares summed over the count of
    /// all emitter-free pixels, so that `clean_edge^2 / clean^2` is the share of the
    /// emitter-free error that lies at edges, and `clean^2 - clean_edge^2` the rest's part
    /// (after the roots of [`StreamMetrics`]: squares of these).
    pub clean_edge: f64,
}

impl Split {
    /// `f` applied to each pixel set.
    pub fn map(self, f: impl Fn(f64) -> f64) -> Split {
        Split {
            all: f(self.all),
            smooth: f(self.smooth),
            edge: f(self.edge),
            clean: f(self.clean),
            clean_edge: f(self.clean_edge),
        }
    }
    /// `f` applied to each pixel set of `self` and `o`.
    pub fn zip(self, o: Split, f: impl Fn(f64, f64) -> f64) -> Split {
        Split {
            all: f(self.all, o.all),
            smooth: f(self.smooth, o.smooth),
            edge: f(self.edge, o.edge),
            clean: f(self.clean, o.clean),
            clean_edge: f(self.clean_edge, o.clean_edge),
        }
    }
}

/// Mean squares of `img` on each pixel set; 0 for an empty set (e.g. a frame filled by a
/// light has no emitter-free pixel).
fn mean_squares(img: &Gray, masks: &Masks) -> Split {
    // Sets: all, smooth, edge, emitter-free, emitter-free edge.
    let (mut s, mut n) = ([0.0f64; 5], [0usize; 5]);
    for ((v, &e), &c) in img.data.iter().zip(&masks.edge).zip(&masks.clean) {
        let v2 = (*v as f64) * (*v as f64);
        for (k, on) in [true, !e, e, c, c && e].into_iter().enumerate() {
            if on {
                s[k] += v2;
                n[k] += 1;
            }
        }
    }
    // Mean of set k's squares over set `over`'s count.
    let m = |k: usize, over: usize| {
        if n[over] == 0 {
            0.0
        } else {
            s[k] / n[over] as f64
        }
    };
    Split {
        all: m(0, 0),
        smooth: m(1, 1),
        edge: m(2, 2),
        clean: m(3, 3),
        clean_edge: m(4, 3),
    }
}

/// Root-mean-square metrics of one stream (raw frames, EMA or TAA) over the window.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StreamMetrics {
    pub rmse: Split,
    pub p1: Split,
    pub p2: Split,
    pub lf: f64,
    /// P4 and P8 (the blurs of [`WIDE_SIGMAS`]) on the pixels away from emitters by 3 sigma
    /// ([`Masks::far`]): the error a spatial denoiser keeps.
    pub p4: f64,
    pub p8: f64,
}

/// The EMA's step: `acc` moves `EMA_ALPHA` of the way to `e`.
pub fn ema_step(acc: &mut [f32], e: &[f32]) {
    for (a, &b) in acc.iter_mut().zip(e) {
        *a += EMA_ALPHA * (b - *a);
    }
}

/// Mean square of `img` over the pixels of `mask` (0 for none).
fn masked_mean_square(img: &Gray, mask: &[bool]) -> f64 {
    let (s, n) = img
        .data
        .iter()
        .zip(mask)
        .filter(|&(_, &on)| on)
        .fold((0.0f64, 0usize), |(s, n), (&v, _)| {
            (s + f64::from(v) * f64::from(v), n + 1)
        });
    if n == 0 { 0.0 } else { s / n as f64 }
}

struct Stream {
    sq: [Split; 3],
    wide: [f64; WIDE_SIGMAS.len()],
    frames: usize,
    spectrum: SpectrumAccumulator,
}

impl Stream {
    fn new() -> Result<Self> {
        Ok(Self {
            sq: [Split::default(); 3],
            wide: [0.0; WIDE_SIGMAS.len()],
            frames: 0,
            spectrum: SpectrumAccumulator::new(TILE, Window::Hann)?,
        })
    }
    /// Adds one error image. The blur sees the whole image (emitters included); the masks
    /// only select which blurred pixels count.
    fn add(&mut self, e: &Gray, masks: &Masks) -> Result<()> {
        let b1 = gaussian_blur(e, 1.0, Boundary::Clamp)?;
        let b2 = gaussian_blur(e, 2.0, Boundary::Clamp)?;
        for (acc, img) in self.sq.iter_mut().zip([e, &b1, &b2]) {
            *acc = acc.zip(mean_squares(img, masks), |a, b| a + b);
        }
        for ((acc, &sigma), mask) in self.wide.iter_mut().zip(&WIDE_SIGMAS).zip(&masks.far) {
            *acc += masked_mean_square(&gaussian_blur(e, sigma, Boundary::Clamp)?, mask);
        }
        self.frames += 1;
        if e.w >= TILE && e.h >= TILE {
            self.spectrum.add_image(e)?;
        }
        Ok(())
    }
    fn finish(&self) -> Result<(StreamMetrics, Option<Spectrum>)> {
        let n = self.frames.max(1) as f64;
        let root = |s: Split| s.map(|v| (v / n).sqrt());
        let spectrum = if self.spectrum.count() > 0 {
            Some(self.spectrum.mean()?)
        } else {
            None
        };
        let lf = spectrum
            .as_ref()
            .map_or(f64::NAN, |s| low_frequency_fraction(s, LF_CUTOFF));
        Ok((
            StreamMetrics {
                rmse: root(self.sq[0]),
                p1: root(self.sq[1]),
                p2: root(self.sq[2]),
                lf,
                p4: (self.wide[0] / n).sqrt(),
                p8: (self.wide[1] / n).sqrt(),
            },
            spectrum,
        ))
    }
}

/// Accumulates one run (method x spp x camera x bounces).
pub struct RunAccumulator {
    window_start: usize,
    raw: Stream,
    ema_stream: Stream,
    taa_stream: Stream,
    ema: Option<Gray>,
    taa: Option<Gray>,
    /// Share of pixels that kept their TAA history, summed over the window's frames.
    kept: f64,
    /// Screen-space motion (px) of the pixel-centre hit points, summed over frames 1 on.
    motion: f64,
    /// P1 (all pixels) of every frame.
    pub p1_per_frame: Vec<f64>,
    /// P1 on emitter-free pixels of every frame, for the P1-over-frames figure.
    pub p1_clean_per_frame: Vec<f64>,
    pub last_error: Option<Gray>,
}

/// Final metrics of a run.
#[derive(Debug, Clone, Serialize)]
pub struct RunMetrics {
    pub raw: StreamMetrics,
    pub ema: StreamMetrics,
    /// Accumulated along the motion ([`Reprojection`]): the EMA for a still camera.
    pub taa: StreamMetrics,
    /// Share of pixels that kept their TAA history, mean over the window.
    pub history_share: f64,
    /// Mean screen-space motion of the pixel-centre hit points, px/frame.
    pub motion_px: f64,
    pub p1_per_frame: Vec<f64>,
    pub p1_clean_per_frame: Vec<f64>,
    #[serde(skip)]
    pub spectrum: Option<Spectrum>,
    #[serde(skip)]
    pub radial: Option<RadialProfile>,
}

impl RunAccumulator {
    pub fn new(window_start: usize) -> Result<Self> {
        Ok(Self {
            window_start,
            raw: Stream::new()?,
            ema_stream: Stream::new()?,
            taa_stream: Stream::new()?,
            ema: None,
            taa: None,
            kept: 0.0,
            motion: 0.0,
            p1_per_frame: Vec::new(),
            p1_clean_per_frame: Vec::new(),
            last_error: None,
        })
    }

    /// Adds the error image of frame `t`; `motion` carries the previous frame's TAA history
    /// to this one (`None` on frame 0).
    pub fn add_frame(
        &mut self,
        t: usize,
        e: Gray,
        masks: &Masks,
        motion: Option<&Reprojection>,
    ) -> Result<()> {
        let b1 = gaussian_blur(&e, 1.0, Boundary::Clamp)?;
        let p1 = mean_squares(&b1, masks).map(f64::sqrt);
        self.p1_per_frame.push(p1.all);
        self.p1_clean_per_frame.push(p1.clean);
        let ema = match self.ema.take() {
            None => e.clone(),
            Some(mut m) => {
                ema_step(&mut m.data, &e.data);
                m
            }
        };
        let prev = self.taa.take().map(|g| g.data).unwrap_or_default();
        let taa = Gray::new(e.w, e.h, taa::accumulate(motion, &prev, &e.data, 1))?;
        if let Some(op) = motion {
            self.motion += op.motion_px;
        }
        if t >= self.window_start {
            self.raw.add(&e, masks)?;
            self.ema_stream.add(&ema, masks)?;
            self.taa_stream.add(&taa, masks)?;
            self.kept += motion.map_or(0.0, Reprojection::kept_share);
        }
        self.ema = Some(ema);
        self.taa = Some(taa);
        self.last_error = Some(e);
        Ok(())
    }

    pub fn finish(self) -> Result<RunMetrics> {
        let (raw, spectrum) = self.raw.finish()?;
        let (ema, _) = self.ema_stream.finish()?;
        let (taa, _) = self.taa_stream.finish()?;
        let radial = spectrum.as_ref().map(radial_profile);
        let frames = self.p1_per_frame.len();
        Ok(RunMetrics {
            raw,
            ema,
            taa,
            history_share: self.kept / self.raw.frames.max(1) as f64,
            motion_px: self.motion / frames.saturating_sub(1).max(1) as f64,
            p1_per_frame: self.p1_per_frame,
            p1_clean_per_frame: self.p1_clean_per_frame,
            spectrum,
            radial,
        })
    }
}

/// Running average of runs over sequences: `prev` already averages `n` sequences.
pub fn average(prev: RunMetrics, next: RunMetrics, n: f64) -> RunMetrics {
    let mix = |a: f64, b: f64| (a * n + b) / (n + 1.0);
    let split = |a: Split, b: Split| a.zip(b, mix);
    let frames =
        |a: &[f64], b: &[f64]| -> Vec<f64> { a.iter().zip(b).map(|(&x, &y)| mix(x, y)).collect() };
    let stream = |a: StreamMetrics, b: StreamMetrics| StreamMetrics {
        rmse: split(a.rmse, b.rmse),
        p1: split(a.p1, b.p1),
        p2: split(a.p2, b.p2),
        lf: mix(a.lf, b.lf),
        p4: mix(a.p4, b.p4),
        p8: mix(a.p8, b.p8),
    };
    RunMetrics {
        raw: stream(prev.raw, next.raw),
        ema: stream(prev.ema, next.ema),
        taa: stream(prev.taa, next.taa),
        history_share: mix(prev.history_share, next.history_share),
        motion_px: mix(prev.motion_px, next.motion_px),
        p1_per_frame: frames(&prev.p1_per_frame, &next.p1_per_frame),
        p1_clean_per_frame: frames(&prev.p1_clean_per_frame, &next.p1_clean_per_frame),
        spectrum: prev.spectrum,
        radial: prev.radial,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_error_has_equal_split_rmse() {
        let e = Gray::from_fn(64, 64, |_, _| 0.5);
        let masks = Masks {
            edge: (0..64 * 64).map(|i| i % 2 == 0).collect(),
            clean: (0..64 * 64).map(|i| i % 3 == 0).collect(),
            far: [(); 2].map(|_| (0..64 * 64).map(|i| i % 5 == 0).collect()),
        };
        let mut acc = RunAccumulator::new(0).unwrap();
        acc.add_frame(0, e, &masks, None).unwrap();
        let m = acc.finish().unwrap();
        for v in [
            m.raw.rmse.all,
            m.raw.rmse.smooth,
            m.raw.rmse.edge,
            m.raw.rmse.clean,
            m.raw.p1.all,
            m.raw.p1.clean,
            m.raw.p4,
            m.raw.p8,
            m.taa.p8,
        ] {
            assert!((v - 0.5).abs() < 1e-6, "{v}");
        }
    }

    #[test]
    fn error_on_emitters_leaves_emitter_free_metrics_at_the_background() {
        // A 6x6 light on a dim background; the error is 0.1 everywhere but 100 on the light,
        // over three frames (the EMA grows on the light and stays 0.1 elsewhere).
        let (w, h) = (40, 32);
        let light = |x: usize, y: usize| (15..21).contains(&x) && (12..18).contains(&y);
        let reference = Gray::from_fn(w, h, |x, y| if light(x, y) { 12.0 } else { 0.4 });
        let masks = Masks::from_reference(&reference);
        let mut acc = RunAccumulator::new(0).unwrap();
        for t in 0..3 {
            let e = Gray::from_fn(w, h, |x, y| if light(x, y) { 100.0 } else { 0.1 });
            acc.add_frame(t, e, &masks, None).unwrap();
        }
        let m = acc.finish().unwrap();
        for (name, v) in [
            ("raw rmse", m.raw.rmse.clean),
            ("raw p1", m.raw.p1.clean),
            ("ema rmse", m.ema.rmse.clean),
            ("ema p1", m.ema.p1.clean),
        ] {
            assert!((v - 0.1).abs() < 1e-6, "{name} on emitter-free pixels: {v}");
        }
        for v in &m.p1_clean_per_frame {
            assert!((v - 0.1).abs() < 1e-6, "{v}");
        }
        // The error is there for the other pixel sets.
        assert!(m.raw.p1.all > 10.0 && m.ema.p1.all > 10.0, "{:?}", m.raw.p1);
    }

    #[test]
    fn edge_part_is_the_edge_pixels_share_of_the_emitter_free_error() {
        // Error 1 on edge pixels, 2 on smooth ones, 50 off the emitter-free set: the edge part
        // is the edge pixels' squares over the emitter-free count, whatever the emitters hold.
        let (w, h) = (16usize, 8usize);
        let edge: Vec<bool> = (0..w * h).map(|i| i % w < 4).collect();
        let clean: Vec<bool> = (0..w * h).map(|i| i / w < 6).collect();
        let masks = Masks {
            edge: edge.clone(),
            clean: clean.clone(),
            far: [(); 2].map(|_| clean.clone()),
        };
        let e = Gray::from_fn(w, h, |x, y| match (clean[y * w + x], edge[y * w + x]) {
            (false, _) => 50.0,
            (true, true) => 1.0,
            (true, false) => 2.0,
        });
        let sq = mean_squares(&e, &masks);
        let (n_edge, n_clean) = (4.0 * 6.0, 16.0 * 6.0);
        let want_edge = n_edge / n_clean;
        let want_clean = (n_edge + 4.0 * (n_clean - n_edge)) / n_clean;
        assert!((sq.clean_edge - want_edge).abs() < 1e-12, "{sq:?}");
        assert!((sq.clean - want_clean).abs() < 1e-12, "{sq:?}");
        // The smooth part is what is left.
        let smooth = (sq.clean - sq.clean_edge) * n_clean / (n_clean - n_edge);
        assert!((smooth - 4.0).abs() < 1e-12, "{smooth}");
    }
}
