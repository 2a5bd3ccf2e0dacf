//! The trace pass's push constants (the method's part comes from the frame's recipe), and the
//! mask offsets of `mask-r2`.
use crate::recipe::TracePlan;
use crate::{MethodAssets, RenderConfig, RenderError};
use blueshift_layout::params::{
    MASK_MODE_2D, MASK_MODE_ROTATE, MASK_MODE_SPATIOTEMPORAL, TraceParams,
};
use blueshift_permute::Screen;
use blueshift_permute::{CYCLE_FRAMES, add_mask_shift, sequence_mask_shift};
use blueshift_scene::Camera;

/// What the path tracer's push constants are made of besides the recipe's trace plan.
pub(crate) struct TraceInputs<'a> {
    pub cfg: &'a RenderConfig,
    pub screen: &'a Screen,
    pub assets: &'a MethodAssets,
    pub camera: &'a Camera,
    pub view_offset: (f32, f32),
    /// The frame being recorded.
    pub frame: u64,
}

/// The path tracer's push constants for a frame (camera, view window, method).
pub(crate) fn trace_params(trace: &TracePlan, i: &TraceInputs) -> TraceParams {
    let c = i.cfg;
    let (vw, vh) = c.view_size.unwrap_or((c.width, c.height));
    let basis = i.camera.basis(vw as f32 / vh as f32);
    let n = i.assets.n;
    // The mode alone says which mask and offsets: whichever method chose it.
    let (mask_size, mask_step, off) = match trace.mask_mode {
        MASK_MODE_2D => (n, 0, r2_offset(i.frame, n)),
        MASK_MODE_SPATIOTEMPORAL => {
            let slices = u64::from(i.assets.stbn_frames.max(1));
            (i.assets.stbn_n, (i.frame % slices) as u32, (0, 0))
        }
        // Steps of a 32-bit fixed-point rotation: wrapping at 2^32 is exact.
        MASK_MODE_ROTATE => (n, i.frame as u32, (0, 0)),
        _ => (n, 0, (0, 0)),
    };
    let off = add_mask_shift(off, sequence_mask_shift(c.sequence), mask_size);
    TraceParams {
        cam_origin: basis.position,
        cam_forward: basis.forward,
        cam_right: basis.right,
        cam_up: basis.up,
        width: c.width,
        height: c.height,
        stride: i.screen.stride(),
        // The sampler's frame: with a point cycle, the phase (the index repeats).
        frame: if trace.cycle_phase {
            (i.frame % u64::from(CYCLE_FRAMES)) as u32
        } else {
            i.frame as u32
        },
        spp: c.spp,
        sample_index: 0,
        sample_count: 1,
        max_bounces: c.bounces,
        sampler_kind: if trace.no_seeds {
            blueshift_sampling::Sampler::White
        } else {
            c.effective_sampler()
        } as u32,
        flags: trace.flags,
        mask_mode: trace.mask_mode,
        mask_size,
        mask_step,
        mask_offset_x: off.0,
        mask_offset_y: off.1,
        view_offset: glam::Vec2::new(i.view_offset.0, i.view_offset.1),
        view_size: glam::Vec2::new(vw as f32, vh as f32),
    }
}

pub(crate) fn no_fast() -> RenderError {
    RenderError::Asset(blueshift_assets::AssetError::Missing(format!(
        "no FAST mask ({}; `blueshift-tools fast` makes it)",
        blueshift_assets::FAST_FILE
    )))
}

pub(crate) fn no_motion() -> RenderError {
    RenderError::Asset(blueshift_assets::AssetError::Missing(format!(
        "no motion volume ({}; `blueshift-tools assets` makes it)",
        blueshift_assets::MOTION_FILE
    )))
}

/// Per-frame mask offset of `mask-r2`: the R2 sequence scaled to the tile (rounded, which is
/// fine here: no retarget table depends on it).
pub fn r2_offset(frame: u64, n: u32) -> (u32, u32) {
    let g = blueshift_sampling::r2::PLASTIC;
    let t = frame as f64;
    let fx = (0.5 + t / g).fract();
    let fy = (0.5 + t / (g * g)).fract();
    ((fx * n as f64) as u32 % n, (fy * n as f64) as u32 % n)
}
