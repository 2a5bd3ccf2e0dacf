//! The `taa` pass (shaders/image/taa.comp): the accumulation along the motion on the GPU, whose
//! CPU twin is [`crate::taa`]; and which frames the renderer accumulates with it
//! ([`Accumulation`]). It reads this frame's and the previous frame's G-buffers (the
//! [`crate::motion::Surfaces`] ping-pong the reprojecting methods use, written here when the
//! recipe does not) and the previous frame's camera.
use crate::motion::{Surfaces, ViewInputs};
use crate::resources::FrameResources;
use crate::{Accumulation, Result, motion_params};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, MemoryLocation, Recorder, Res};
use blueshift_layout::motion::TaaParams;
use blueshift_layout::params::TraceParams;
use blueshift_permute::Screen;

/// Frames the running mean of [`Accumulation::Follow`] counts after a TAA step: its next step
/// weighs the new frame by 1 / (9 + 1) = ALPHA, as the TAA did.
pub(crate) const MEAN_FRAMES_AFTER_TAA: u32 = 9;

const BINDINGS: [&str; 5] = ["cur", "prev", "history", "estimate", "accum"];

/// The pass's pipeline, its copy of the previous accumulation and the previous frame's camera.
pub(crate) struct TaaPass {
    pipeline: ComputePipeline,
    /// The previous accumulation, copied before the pass overwrites it: a pixel reads it at
    /// other pixels than the one it writes.
    history: Buffer,
    /// The camera of the frame accumulated last (`None` after a reset).
    prev: Option<TraceParams>,
}

/// How one frame enters the accumulation.
pub(crate) enum Step {
    /// From this frame alone.
    Restart,
    /// The running mean.
    Mean,
    /// Along the motion from the frame seen by `camera` (`still`: the same camera).
    Taa { camera: TraceParams, still: bool },
}

impl TaaPass {
    pub fn new(dev: &Device, pixels: u64) -> Result<Self> {
        let bindings: Vec<Binding> = (0..)
            .zip(BINDINGS)
            .map(|(i, n)| Binding::storage(i, n))
            .collect();
        let push = size_of::<TaaParams>();
        Ok(Self {
            pipeline: blueshift_shaders::pipeline(dev, "image/taa", &bindings, push)?,
            history: Buffer::new(
                dev,
                "frame.taa.history",
                pixels * 16,
                MemoryLocation::GpuOnly,
            )?,
            prev: None,
        })
    }

    /// Forgets the previous frame (sequence restart).
    pub fn reset(&mut self) {
        self.prev = None;
    }

    /// Records the pass: `accum` (the previous frame's accumulation) becomes this frame's, from
    /// `estimate` and the G-buffers `cur` and `prev` (the previous frame's).
    pub fn taa(
        &self,
        rec: &mut Recorder,
        p: &TaaParams,
        [cur, prev, estimate, accum]: [&Buffer; 4],
    ) -> Result<()> {
        rec.copy_buffer(accum, &self.history, None)?;
        let res = [cur, prev, &self.history, estimate, accum];
        let resources: Vec<(&str, Res<'_>)> = BINDINGS
            .iter()
            .zip(res)
            .map(|(n, b)| (*n, b.into()))
            .collect();
        let (w, h) = (p.camera.width, p.camera.height);
        rec.dispatch(
            &self.pipeline,
            &resources,
            bytemuck::bytes_of(p),
            [w.div_ceil(8), h.div_ceil(8), 1],
        )?;
        Ok(())
    }
}

impl TaaPass {
    /// Records this frame's G-buffer (camera `tp`, unless written already) and decides how the
    /// frame enters the accumulation of `accumulated` frames under `mode`.
    pub fn step(
        &mut self,
        rec: &mut Recorder,
        st: &mut Surfaces,
        res: &FrameResources,
        tp: &TraceParams,
        accumulated: u32,
        mode: Accumulation,
    ) -> Result<Step> {
        let view = ViewInputs::of(tp);
        // This frame's G-buffer, unless the recipe wrote it or the camera is still.
        if st.current_view() != Some(view) {
            st.record_gbuffer(rec, tp, &res.scene, &res.images)?;
        }
        Ok(match self.prev.replace(*tp) {
            _ if accumulated == 0 => Step::Restart,
            None => Step::Restart,
            Some(p) if ViewInputs::of(&p) == view => match mode {
                Accumulation::Follow => Step::Mean,
                _ => Step::Taa {
                    camera: p,
                    still: true,
                },
            },
            // The previous G-buffer shows the previous camera's view unless a frame was
            // skipped (then nothing to follow).
            Some(p) if st.previous_view() == Some(ViewInputs::of(&p)) => Step::Taa {
                camera: p,
                still: false,
            },
            Some(_) => Step::Restart,
        })
    }

    /// Records the `taa` pass: the accumulation of `res` followed from the frame seen by
    /// `camera` (`still`: the same camera) into this frame's, along `st`'s G-buffers.
    pub fn record(
        &self,
        rec: &mut Recorder,
        st: &Surfaces,
        res: &FrameResources,
        screen: &Screen,
        camera: &TraceParams,
        still: bool,
    ) -> Result<()> {
        let p = TaaParams {
            camera: motion_params(camera, screen),
            still: u32::from(still),
        };
        rec.begin_pass("taa")?;
        let g = [st.current_gbuffer(), st.previous_gbuffer()];
        self.taa(rec, &p, [g[0], g[1], &res.estimate, &res.accum])
    }
}

#[cfg(test)]
mod tests {
    /// After motion the running mean's next step weighs the new frame as the TAA does.
    #[test]
    fn the_mean_after_motion_goes_on_with_the_taa_weight() {
        let next_weight = 1.0 / (super::MEAN_FRAMES_AFTER_TAA + 1) as f32;
        assert_eq!(next_weight, crate::taa::ALPHA);
    }
}
