//! History keys (`permute/history_key`): the sorting pass ranks each pixel's key minus the mean
//! key its surface showed in earlier frames (fetched through the reprojection's source map), so
//! blocks rank seeds by their error rather than by the image's own variation. The pass, its
//! two history buffers (ping-pong) and the CPU twin.
use crate::similar;
use crate::{Result, Screen};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, MemoryLocation, Recorder};
use blueshift_layout::motion::{
    GBufferTexel, HISTORY_COLUMNS, HISTORY_STRIP, HistoryParams, REPROJECT_NONE,
};

/// The pass and the history means (mean key, frames) of the last two frames.
pub struct HistoryKeys {
    pass: ComputePipeline,
    hist: [Buffer; 2],
    /// Index of the history the next pass writes.
    next: usize,
    /// Per visible pixel: the history mean its key is ranked against, NaN for none yet.
    pub mean: Buffer,
}

impl std::fmt::Debug for HistoryKeys {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HistoryKeys").finish_non_exhaustive()
    }
}

impl HistoryKeys {
    pub fn new(dev: &Device, screen: &Screen) -> Result<Self> {
        let bindings = [
            Binding::storage(0, "estimate"),
            Binding::storage(1, "src"),
            Binding::storage(2, "hist_in"),
            Binding::storage(3, "hist_out"),
            Binding::storage(4, "hist_mean"),
            Binding::storage(5, "gbuffer"),
        ];
        let pass = blueshift_shaders::pipeline(
            dev,
            "permute/history_key",
            &bindings,
            size_of::<HistoryParams>(),
        )?;
        let bytes = screen.seed_count() as u64 * 8;
        let buf = |name: &str| Buffer::new(dev, name, bytes, MemoryLocation::GpuOnly);
        Ok(Self {
            pass,
            hist: [buf("history.a")?, buf("history.b")?],
            next: 0,
            mean: Buffer::new(
                dev,
                "history.mean",
                screen.width as u64 * screen.height as u64 * 4,
                MemoryLocation::GpuOnly,
            )?,
        })
    }

    /// Records the pass: from `estimate`'s keys (W*H vec4, key in w), `src`, the
    /// reprojection's source map (read only when `p.has_history` is 1), and this frame's
    /// G-buffer (W*H, for the window's surface test), the new history and [`Self::mean`].
    pub fn history_key(
        &mut self,
        rec: &mut Recorder,
        p: &HistoryParams,
        estimate: &Buffer,
        src: &Buffer,
        gbuffer: &Buffer,
    ) -> Result<()> {
        let (hin, hout) = (&self.hist[1 - self.next], &self.hist[self.next]);
        rec.dispatch(
            &self.pass,
            &[
                ("estimate", estimate.into()),
                ("src", src.into()),
                ("hist_in", hin.into()),
                ("hist_out", hout.into()),
                ("hist_mean", (&self.mean).into()),
                ("gbuffer", gbuffer.into()),
            ],
            bytemuck::bytes_of(p),
            [
                p.width.div_ceil(64 * HISTORY_COLUMNS),
                p.height.div_ceil(HISTORY_STRIP),
                1,
            ],
        )?;
        self.next = 1 - self.next;
        Ok(())
    }

    /// The history the last recorded pass wrote (padded, (mean, frames) per pixel).
    pub fn current(&self) -> &Buffer {
        &self.hist[1 - self.next]
    }
}

/// CPU twin of `history_key`: from this frame's keys (W*H), the source map `src` and the
/// previous history `hist` (both padded) and this frame's G-buffer (W*H), the new history
/// (padded; pixels outside the visible screen keep `hist`'s values) and the mean each visible
/// pixel ranks against (NaN: rank against the class mean; 0 on a sequence's first frame).
pub fn history_key_cpu(
    p: &HistoryParams,
    keys: &[f32],
    src: &[u32],
    hist: &[[f32; 2]],
    gbuffer: &[GBufferTexel],
) -> (Vec<[f32; 2]>, Vec<f32>) {
    let mut out = hist.to_vec();
    let mut mean = vec![0.0; (p.width * p.height) as usize];
    for y in 0..p.height {
        for x in 0..p.width {
            let at = (y * p.width + x) as usize;
            let here = (y * p.padded_width + x) as usize;
            let key = keys[at];
            if p.has_history == 0 {
                out[here] = [key, 1.0];
                continue;
            }
            let [m, frames] = match src[here] {
                REPROJECT_NONE => [0.0, 0.0],
                s => hist[s as usize],
            };
            let n = (frames + 1.0).min(p.max_frames as f32);
            out[here] = [m + (key - m) * (1.0 / n), n];
            mean[at] = window_mean(p, x, y, src, hist, gbuffer);
        }
    }
    (out, mean)
}

/// The mean of the previous histories in (x, y)'s 3x3 window that show its surface and have at
/// least `min_frames` frames, summed row by row; NaN for none.
fn window_mean(
    p: &HistoryParams,
    x: u32,
    y: u32,
    src: &[u32],
    hist: &[[f32; 2]],
    gbuffer: &[GBufferTexel],
) -> f32 {
    let (w, h, r) = (p.width as i64, p.height as i64, 1);
    let centre = &gbuffer[(y * p.width + x) as usize];
    let (mut sum, mut count) = (0.0f32, 0.0f32);
    for ny in y as i64 - r..=y as i64 + r {
        for nx in x as i64 - r..=x as i64 + r {
            if nx < 0 || ny < 0 || nx >= w || ny >= h {
                continue;
            }
            let s = src[(ny * p.padded_width as i64 + nx) as usize];
            if s == REPROJECT_NONE {
                continue;
            }
            let [m, frames] = hist[s as usize];
            if frames < p.min_frames as f32 || !similar(centre, &gbuffer[(ny * w + nx) as usize]) {
                continue;
            }
            sum += m;
            count += 1.0;
        }
    }
    if count > 0.0 {
        sum * (1.0 / count)
    } else {
        f32::NAN
    }
}
