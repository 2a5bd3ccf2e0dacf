//! Per-run metric accumulation (docs/results.md): RMSE, LF, P1, P2 over a frame window, on all,
//! smooth and edge pixels, for raw frames and their exponential moving average (alpha 0.1).
use anyhow::Result;
use blueshift_analysis::{
    Boundary, Gray, LF_CUTOFF, RadialProfile, Spectrum, SpectrumAccumulator, Window, gaussian_blur,
    low_frequency_fraction, radial_profile,
};
use serde::Serialize;

/// Spectrum tile edge (docs/results.md: 64x64 tiles).
pub const TILE: usize = 64;
/// EMA weight of the newest frame.
pub const EMA_ALPHA: f32 = 0.1;
/// Relative reference gradient above which a pixel is an edge pixel (before a 1-px dilation).
pub const EDGE_THRESHOLD: f32 = 0.1;

/// Which pixels a metric covers.
#[derive(Debug, Clone)]
pub struct Masks {
    pub edge: Vec<bool>,
}

impl Masks {
    /// Edge pixels: max forward difference of the reference luminance, relative to the image
    /// mean luminance, above [`EDGE_THRESHOLD`], dilated by one pixel. Smooth = the rest.
    pub fn from_reference(r: &Gray) -> Self {
        let (w, h) = (r.w, r.h);
        let scale = (r.mean() as f32).max(1e-6);
        let mut raw = vec![false; w * h];
        for y in 0..h {
            for x in 0..w {
                let v = r.at(x, y);
                let dx = if x + 1 < w {
                    (r.at(x + 1, y) - v).abs()
                } else {
                    0.0
                };
                let dy = if y + 1 < h {
                    (r.at(x, y + 1) - v).abs()
                } else {
                    0.0
                };
                raw[y * w + x] = dx.max(dy) / scale > EDGE_THRESHOLD;
            }
        }
        let mut edge = raw.clone();
        for y in 0..h {
            for x in 0..w {
                if raw[y * w + x] {
                    for (nx, ny) in [
                        (x.wrapping_sub(1), y),
                        (x + 1, y),
                        (x, y.wrapping_sub(1)),
                        (x, y + 1),
                    ] {
                        if nx < w && ny < h {
                            edge[ny * w + nx] = true;
                        }
                    }
                }
            }
        }
        Self { edge }
    }
}

/// Mean squares on all / smooth / edge pixels.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct Split {
    pub all: f64,
    pub smooth: f64,
    pub edge: f64,
}

fn mean_squares(img: &Gray, masks: &Masks) -> Split {
    let (mut s, mut n) = ([0.0f64; 3], [0usize; 3]);
    for (v, &e) in img.data.iter().zip(&masks.edge) {
        let v2 = (*v as f64) * (*v as f64);
        for (k, on) in [true, !e, e].into_iter().enumerate() {
            if on {
                s[k] += v2;
                n[k] += 1;
            }
        }
    }
    let m = |k: usize| if n[k] == 0 { 0.0 } else { s[k] / n[k] as f64 };
    Split {
        all: m(0),
        smooth: m(1),
        edge: m(2),
    }
}

/// Root-mean-square metrics of one stream (raw frames or EMA) over the window.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct StreamMetrics {
    pub rmse: Split,
    pub p1: Split,
    pub p2: Split,
    pub lf: f64,
}

struct Stream {
    sq: [Split; 3],
    frames: usize,
    spectrum: SpectrumAccumulator,
}

impl Stream {
    fn new() -> Result<Self> {
        Ok(Self {
            sq: [Split::default(); 3],
            frames: 0,
            spectrum: SpectrumAccumulator::new(TILE, Window::Hann)?,
        })
    }
    fn add(&mut self, e: &Gray, masks: &Masks) -> Result<()> {
        let b1 = gaussian_blur(e, 1.0, Boundary::Clamp)?;
        let b2 = gaussian_blur(e, 2.0, Boundary::Clamp)?;
        for (acc, img) in self.sq.iter_mut().zip([e, &b1, &b2]) {
            let m = mean_squares(img, masks);
            acc.all += m.all;
            acc.smooth += m.smooth;
            acc.edge += m.edge;
        }
        self.frames += 1;
        if e.w >= TILE && e.h >= TILE {
            self.spectrum.add_image(e)?;
        }
        Ok(())
    }
    fn finish(&self) -> Result<(StreamMetrics, Option<Spectrum>)> {
        let n = self.frames.max(1) as f64;
        let root = |s: Split| Split {
            all: (s.all / n).sqrt(),
            smooth: (s.smooth / n).sqrt(),
            edge: (s.edge / n).sqrt(),
        };
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
    ema: Option<Gray>,
    /// P1 (all pixels) of every frame, for the P1-over-frames figure.
    pub p1_per_frame: Vec<f64>,
    pub last_error: Option<Gray>,
}

/// Final metrics of a run.
#[derive(Debug, Clone, Serialize)]
pub struct RunMetrics {
    pub raw: StreamMetrics,
    pub ema: StreamMetrics,
    pub p1_per_frame: Vec<f64>,
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
            ema: None,
            p1_per_frame: Vec::new(),
            last_error: None,
        })
    }

    /// Adds the error image of frame `t`.
    pub fn add_frame(&mut self, t: usize, e: Gray, masks: &Masks) -> Result<()> {
        let b1 = gaussian_blur(&e, 1.0, Boundary::Clamp)?;
        self.p1_per_frame.push(mean_squares(&b1, masks).all.sqrt());
        let ema = match self.ema.take() {
            None => e.clone(),
            Some(mut m) => {
                for (a, &b) in m.data.iter_mut().zip(&e.data) {
                    *a += EMA_ALPHA * (b - *a);
                }
                m
            }
        };
        if t >= self.window_start {
            self.raw.add(&e, masks)?;
            self.ema_stream.add(&ema, masks)?;
        }
        self.ema = Some(ema);
        self.last_error = Some(e);
        Ok(())
    }

    pub fn finish(self) -> Result<RunMetrics> {
        let (raw, spectrum) = self.raw.finish()?;
        let (ema, _) = self.ema_stream.finish()?;
        let radial = spectrum.as_ref().map(radial_profile);
        Ok(RunMetrics {
            raw,
            ema,
            p1_per_frame: self.p1_per_frame,
            spectrum,
            radial,
        })
    }
}

/// Running average of runs over sequences: `prev` already averages `n` sequences.
pub fn average(prev: RunMetrics, next: RunMetrics, n: f64) -> RunMetrics {
    let mix = |a: f64, b: f64| (a * n + b) / (n + 1.0);
    let split = |a: Split, b: Split| Split {
        all: mix(a.all, b.all),
        smooth: mix(a.smooth, b.smooth),
        edge: mix(a.edge, b.edge),
    };
    let stream = |a: StreamMetrics, b: StreamMetrics| StreamMetrics {
        rmse: split(a.rmse, b.rmse),
        p1: split(a.p1, b.p1),
        p2: split(a.p2, b.p2),
        lf: mix(a.lf, b.lf),
    };
    RunMetrics {
        raw: stream(prev.raw, next.raw),
        ema: stream(prev.ema, next.ema),
        p1_per_frame: prev
            .p1_per_frame
            .iter()
            .zip(&next.p1_per_frame)
            .map(|(&a, &b)| mix(a, b))
            .collect(),
        spectrum: prev.spectrum,
        radial: prev.radial,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_mark_a_step_edge_and_its_neighbours() {
        let r = Gray::from_fn(8, 8, |x, _| if x < 4 { 1.0 } else { 2.0 });
        let m = Masks::from_reference(&r);
        for y in 0..8 {
            for x in 0..8 {
                assert_eq!(m.edge[y * 8 + x], (2..=4).contains(&x), "({x},{y})");
            }
        }
    }

    #[test]
    fn constant_error_has_equal_split_rmse() {
        let e = Gray::from_fn(64, 64, |_, _| 0.5);
        let masks = Masks {
            edge: (0..64 * 64).map(|i| i % 2 == 0).collect(),
        };
        let mut acc = RunAccumulator::new(0).unwrap();
        acc.add_frame(0, e, &masks).unwrap();
        let m = acc.finish().unwrap();
        for v in [
            m.raw.rmse.all,
            m.raw.rmse.smooth,
            m.raw.rmse.edge,
            m.raw.p1.all,
        ] {
            assert!((v - 0.5).abs() < 1e-6, "{v}");
        }
    }
}
