//! The view-state rules that give a frame a volume and leave its seeds unread: the still
//! volume in direct light, the motion volume, and the moving frame at depth without a sort.
use super::tests::{config, every_method, of};
use super::*;
use blueshift_layout::params::MASK_DIMS;

/// A still direct-light frame of the default in a scene without textures is `stbn`'s frame:
/// the volume's mode and buffer, every mask dimension, no seed-side rule (Sobol walk) and no
/// sort; the frame time is the mask's. Its ablation keeps the sorted seeds,
/// exactly the recipe the default runs where textures are (which only the volume rule tells
/// apart from a scene without them, while still), and changes no moving frame.
#[test]
fn a_still_direct_frame_without_textures_takes_the_volume() {
    use blueshift_layout::params::{MASK_MODE_SPATIOTEMPORAL, TRACE_FLAG_SOBOL_JITTER};
    let stbn = of("stbn", ViewState::Still, 1, false);
    for bounces in [0, 1] {
        let r = of("sort-cycle", ViewState::Still, bounces, false);
        assert_eq!(
            (r.trace.mask_mode, r.trace.mask),
            (MASK_MODE_SPATIOTEMPORAL, MaskSource::Stbn)
        );
        assert_eq!(
            (r.trace.mask_mode, r.trace.mask),
            (stbn.trace.mask_mode, stbn.trace.mask)
        );
        let dims = r.trace.flags >> TRACE_FLAG_MASK_DIMS_SHIFT & ((1 << MASK_DIMS) - 1);
        assert_eq!(
            dims,
            (1 << MASK_DIMS) - 1,
            "b{bounces}: every mask dimension"
        );
        assert_eq!(r.trace.flags & TRACE_FLAG_SOBOL_JITTER, 0);
        assert_eq!(r.sort, None, "b{bounces}");
        let ablation = "sort-cycle:without=still-volume";
        assert_eq!(
            of(ablation, ViewState::Still, bounces, false),
            of("sort-cycle", ViewState::Still, bounces, true),
            "b{bounces}: the ablation sorts as with textures"
        );
        assert_eq!(
            of(ablation, ViewState::Moving, bounces, false),
            of("sort-cycle", ViewState::Moving, bounces, false),
            "b{bounces}: the ablation changed a moving frame"
        );
    }
    // Not at depth, not with textures, not moving: there the seeds are read.
    for (view, bounces, textured) in [
        (ViewState::Still, 2, false),
        (ViewState::Still, 1, true),
        (ViewState::Moving, 1, false),
    ] {
        let r = of("sort-cycle", view, bounces, textured);
        assert_ne!(
            r.trace.mask,
            MaskSource::Stbn,
            "{view:?} b{bounces} {textured}"
        );
    }
}

/// A moving frame of the default in direct light, or at depth where it reads no seed, reads
/// its mask dimensions from the motion volume (the volume's mode, the motion buffer); the rest
/// of its trace plan is the one its ablation runs on the 2D mask, `mask-r2`'s mode and
/// buffer. Behind the sorted seeds at depth (textures) and with a still view the rule does not
/// act, and the ablation changes nothing there.
#[test]
fn a_moving_frame_takes_the_motion_volume() {
    use blueshift_layout::params::{MASK_MODE_2D, MASK_MODE_SPATIOTEMPORAL};
    let ablation = "sort-cycle:without=motion-volume";
    let mask_r2 = of("mask-r2", ViewState::Moving, 1, false).trace;
    for (bounces, textured) in [
        (0, false),
        (0, true),
        (1, false),
        (1, true),
        (2, false),
        (8, false),
    ] {
        let at = format!("b{bounces} textured {textured}");
        let r = of("sort-cycle", ViewState::Moving, bounces, textured);
        assert_eq!(
            (r.trace.mask_mode, r.trace.mask),
            (MASK_MODE_SPATIOTEMPORAL, MaskSource::Motion),
            "{at}"
        );
        let dims = r.trace.flags >> TRACE_FLAG_MASK_DIMS_SHIFT & ((1 << MASK_DIMS) - 1);
        assert_eq!(dims, (1 << MASK_DIMS) - 1, "{at}: every mask dimension");
        let a = of(ablation, ViewState::Moving, bounces, textured);
        assert_eq!(
            (a.trace.mask_mode, a.trace.mask),
            (mask_r2.mask_mode, mask_r2.mask),
            "{at}"
        );
        assert_eq!(
            (a.trace.mask_mode, a.trace.mask),
            (MASK_MODE_2D, MaskSource::Mask)
        );
        let as_ablation = TracePlan {
            mask_mode: a.trace.mask_mode,
            mask: a.trace.mask,
            ..r.trace
        };
        assert_eq!(as_ablation, a.trace, "{at}: only the mask differs");
        assert_eq!((r.sort, r.passes), (a.sort, a.passes), "{at}");
        assert_eq!(
            of(ablation, ViewState::Still, bounces, textured),
            of("sort-cycle", ViewState::Still, bounces, textured),
            "{at}: the ablation changed a still frame"
        );
    }
    for bounces in [2, 8] {
        assert_eq!(
            of("sort-cycle", ViewState::Moving, bounces, true),
            of(ablation, ViewState::Moving, bounces, true),
            "b{bounces}: the rule acts behind the sorted seeds"
        );
    }
    // Only the point cycle's forms take it; the mask methods keep their own masks.
    for (name, m) in every_method() {
        for bounces in [1, 8] {
            let cfg = RenderConfig {
                bounces,
                ..config(m, None)
            };
            let r = recipe(&cfg, ViewState::Moving, false);
            let vertex = m
                .permutation()
                .is_some_and(|p| p.mask == crate::MaskDims::Vertex);
            let takes = m.cycles_points()
                && m.mask_dims(true) != 0
                && (bounces <= 1 || (vertex && m.keeps(crate::Without::WhiteDepth)))
                && m.keeps(crate::Without::MotionVolume);
            assert_eq!(
                r.trace.mask == MaskSource::Motion,
                takes,
                "{name} b{bounces}"
            );
            let still = recipe(&cfg, ViewState::Still, false);
            assert_ne!(still.trace.mask, MaskSource::Motion, "{name} b{bounces}");
        }
    }
}

/// A moving frame of the default at depth in a scene without textures reads no seed: no sort,
/// the white sampler salted by the frame behind the motion volume, so its frames are `stbn`'s
/// on that volume. Its ablation sorts (the moving frame of a scene with textures but for the
/// seeds' jitter there) and changes no still frame, no direct-light frame and no textured one.
#[test]
fn a_moving_frame_at_depth_reads_no_seed() {
    let ablation = "sort-cycle:without=white-depth";
    for bounces in [2, 8] {
        let r = of("sort-cycle", ViewState::Moving, bounces, false);
        let stbn = of("stbn", ViewState::Moving, bounces, false);
        assert_eq!(r.sort, None, "b{bounces}");
        assert!(r.trace.no_seeds);
        assert_eq!(r.passes, stbn.passes, "b{bounces}: the mask's passes");
        assert_eq!(
            r.trace.flags & TRACE_FLAG_SALT_FRAME,
            stbn.trace.flags & TRACE_FLAG_SALT_FRAME
        );
        assert_eq!(r.trace.mask_mode, stbn.trace.mask_mode, "b{bounces}");
        let a = of(ablation, ViewState::Moving, bounces, false);
        let textured = of("sort-cycle", ViewState::Moving, bounces, true);
        assert_eq!(a.sort, textured.sort, "b{bounces}: the ablation sorts");
        assert!(!a.trace.no_seeds && a.trace.mask == MaskSource::Mask);
        for (view, bounces, tex) in [
            (ViewState::Still, bounces, false),
            (ViewState::Moving, 1, false),
            (ViewState::Moving, bounces, true),
        ] {
            assert_eq!(
                of(ablation, view, bounces, tex),
                of("sort-cycle", view, bounces, tex),
                "{view:?} b{bounces} textured {tex}: the ablation acts there"
            );
        }
    }
}
