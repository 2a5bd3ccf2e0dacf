//! The trace pass's push constants per method, and the mask offsets of `mask-r2`.
use crate::{Method, RenderConfig, RenderError, Renderer};
use blueshift_layout::params::{
    MASK_MODE_2D, MASK_MODE_NONE, MASK_MODE_ROTATE, MASK_MODE_SPATIOTEMPORAL,
    TRACE_FLAG_ADVANCE_INDEX, TRACE_FLAG_DEMODULATE, TRACE_FLAG_MASK_ANCHORED,
    TRACE_FLAG_MASK_DIMS_SHIFT, TRACE_FLAG_NO_JITTER, TRACE_FLAG_SALT_FRAME, TraceParams,
};
use blueshift_permute::{CYCLE_FRAMES, add_mask_shift, sequence_mask_shift};
use blueshift_sampling::Sampler;

impl Renderer {
    /// The path tracer's push constants for the next frame (camera, view window, method).
    pub fn trace_params(&self) -> TraceParams {
        let c = &self.cfg;
        let (vw, vh) = c.view_size.unwrap_or((c.width, c.height));
        let basis = self.camera.basis(vw as f32 / vh as f32);
        let m = c.method;
        let n = self.assets.n;
        let moving = self.moving();
        let flags = trace_flags(c)
            | m.mask_dims(moving) << TRACE_FLAG_MASK_DIMS_SHIFT
            | m.jitter_flags(moving);
        let mask_mode = mask_mode_of(c, moving);
        // The mode alone says which mask and offsets: whichever method chose it.
        let (mask_size, mask_step, off) = match mask_mode {
            MASK_MODE_2D => (n, 0, r2_offset(self.frame, n)),
            MASK_MODE_SPATIOTEMPORAL => {
                let slices = u64::from(self.assets.stbn_frames.max(1));
                (self.assets.stbn_n, (self.frame % slices) as u32, (0, 0))
            }
            // Steps of a 32-bit fixed-point rotation: wrapping at 2^32 is exact.
            MASK_MODE_ROTATE => (n, self.frame as u32, (0, 0)),
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
            stride: self.screen.stride(),
            // The sampler's frame: with a point cycle, the phase (the index repeats).
            frame: if m.cycles_points() {
                (self.frame % u64::from(CYCLE_FRAMES)) as u32
            } else {
                self.frame as u32
            },
            spp: c.spp,
            sample_index: 0,
            sample_count: 1,
            max_bounces: c.bounces,
            sampler_kind: c.effective_sampler() as u32,
            flags,
            mask_mode,
            mask_size,
            mask_step,
            mask_offset_x: off.0,
            mask_offset_y: off.1,
            view_offset: glam::Vec2::new(self.view_offset.0, self.view_offset.1),
            view_size: glam::Vec2::new(vw as f32, vh as f32),
        }
    }
}

/// The trace pass's mask mode for configuration `c` and a view that is `moving` or not.
fn mask_mode_of(c: &RenderConfig, moving: bool) -> u32 {
    if c.method.mask_dims(moving) != 0 {
        // Shifted while moving, rotated while still: see `MaskDims::Jitter`.
        return if moving {
            MASK_MODE_2D
        } else {
            MASK_MODE_ROTATE
        };
    }
    match c.method.mask_method() {
        Method::MaskR2 => MASK_MODE_2D,
        Method::MaskRot => MASK_MODE_ROTATE,
        Method::Stbn | Method::Fast => MASK_MODE_SPATIOTEMPORAL,
        _ => MASK_MODE_NONE,
    }
}

/// The trace pass's method flags for configuration `c`.
fn trace_flags(c: &RenderConfig) -> u32 {
    let m = c.method;
    let mut flags = 0;
    // The mask methods drive only the first MASK_DIMS dimensions: the rest are fresh white
    // noise every frame, as `white`'s (unsalted, a pixel would repeat its deeper bounces'
    // directions every frame, and its average would never converge). Behind `mask-rot`'s
    // rotating mask a progressive sampler (Sobol, its default) runs on instead, index advancing
    // per frame, keyed by the pixel (anchored: by the anchor's cell), so a pixel's (a surface
    // point's) deeper dimensions converge like its mask dimensions.
    let sequence_rest =
        m.mask_method() == Method::MaskRot && c.effective_sampler() == Sampler::Sobol;
    let white_rest = matches!(
        m.mask_method(),
        Method::White | Method::MaskR2 | Method::MaskRot | Method::Stbn | Method::Fast
    ) && !sequence_rest;
    if white_rest || c.frame_salt {
        flags |= TRACE_FLAG_SALT_FRAME;
    }
    if m.advances_index() || sequence_rest {
        flags |= TRACE_FLAG_ADVANCE_INDEX;
    }
    if c.no_jitter {
        flags |= TRACE_FLAG_NO_JITTER;
    }
    if m.demodulates() {
        flags |= TRACE_FLAG_DEMODULATE;
    }
    if m.anchors_mask() {
        flags |= TRACE_FLAG_MASK_ANCHORED;
    }
    flags
}

pub(crate) fn no_fast() -> RenderError {
    RenderError::Asset(blueshift_assets::AssetError::Missing(format!(
        "no FAST mask ({}; `blueshift-tools fast` makes it)",
        blueshift_assets::FAST_FILE
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every method whose samples are not a progressive sequence is salted per frame (else its
    /// deeper dimensions would repeat every frame); `mask-rot`'s Sobol runs on instead, and a
    /// sampler given by hand puts the rotating mask back on white noise.
    #[test]
    fn the_rotating_masks_run_a_sequence_behind_them() {
        let flags = |method: Method, sampler: Option<Sampler>| {
            let c = RenderConfig {
                method,
                sampler,
                ..RenderConfig::new(8, 8)
            };
            let f = trace_flags(&c);
            (
                f & TRACE_FLAG_SALT_FRAME != 0,
                f & TRACE_FLAG_ADVANCE_INDEX != 0,
            )
        };
        for m in [Method::MaskRot, Method::MaskRotFollow] {
            assert_eq!(m.default_sampler(), Sampler::Sobol, "{m}");
            assert_eq!(flags(m, None), (false, true), "{m}");
            assert_eq!(flags(m, Some(Sampler::White)), (true, false), "{m}");
        }
        for m in [Method::White, Method::MaskR2, Method::Stbn, Method::Fast] {
            assert_eq!(flags(m, None), (true, false), "{m}");
            assert_eq!(flags(m, Some(Sampler::Sobol)), (true, false), "{m}");
        }
        assert_eq!(flags(Method::Sobol, None), (false, true));
    }

    /// The trace pass reads anchors only in its mask variants (`#if TRACE_MASK`), so every
    /// anchored method must run one.
    #[test]
    fn anchored_methods_have_a_mask_mode() {
        for (name, m) in Method::PRESETS {
            if m.anchors_mask() {
                let c = RenderConfig {
                    method: m,
                    ..RenderConfig::new(8, 8)
                };
                for moving in [false, true] {
                    assert_ne!(mask_mode_of(&c, moving), MASK_MODE_NONE, "{name}");
                }
            }
        }
    }

    /// A method whose seeds leave some dimensions to the mask runs a mask variant in every
    /// state, within the dimensions the mask modes drive (the flag's bits above them would be
    /// ignored by the shader, and a method would silently lose them).
    #[test]
    fn mask_dimensions_have_a_mask_mode() {
        use blueshift_layout::params::MASK_DIMS;
        let mut some = 0;
        for (name, m) in Method::PRESETS {
            let c = RenderConfig {
                method: m,
                ..RenderConfig::new(8, 8)
            };
            for moving in [false, true] {
                let dims = m.mask_dims(moving);
                if dims != 0 {
                    some += 1;
                    assert_ne!(mask_mode_of(&c, moving), MASK_MODE_NONE, "{name}");
                    assert_eq!(dims >> MASK_DIMS, 0, "{name}");
                    assert_eq!(dims & 3, 3, "{name}: the jitter comes first");
                }
                // Textured pixels' jitter is chosen only where the mask drives the jitter.
                assert_eq!(m.jitter_flags(moving) != 0, dims & 3 != 0, "{name}");
                // The sort only sets shading-edge marks; the trace's record clears them.
                if m.shade_edges() {
                    let record = blueshift_layout::params::TRACE_FLAG_RECORD_PRIMARY;
                    assert_ne!(
                        m.jitter_flags(moving) & record,
                        0,
                        "{name}: marks never cleared"
                    );
                }
            }
        }
        assert!(some > 0, "no preset leaves dimensions to the mask");
    }
}
