//! `sort-cycle`'s shading edges in the renderer: the sorting pass marks them in the trace's
//! `primary_flags` (its twin is checked in `permute::every_sort_variant_matches_cpu`), and
//! the next still frame takes exactly the marked pixels' light sample from the mask.
use crate::Gpu;
use crate::jitter::second_frame_with_flags;
use blueshift_layout::params::PRIMARY_SHADE_EDGE;
use blueshift_render::{Method, default_assets_dir};
use blueshift_scene::Scene;

/// The estimate (bits, one [rgba] per pixel) of frame 2 of `method` on the Cornell box after
/// writing `marks` (`PRIMARY_SHADE_EDGE` on every other pixel, or none) into the flags;
/// `moving`: the camera moved before it.
fn frame_with_marks(gpu: &Gpu, method: Method, marks: bool, moving: bool) -> Vec<[u32; 4]> {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let w = 24;
    let flags: Vec<u32> = (0..w * 16)
        .map(|i| u32::from(marks && (i % w + i / w) % 2 == 0) * PRIMARY_SHADE_EDGE)
        .collect();
    let bits = second_frame_with_flags(gpu, &s, method, &flags, moving);
    bits.chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// With a still view, marked pixels (a checkerboard) change their estimate (another light
/// sample) and unmarked ones keep it bit for bit. Moving, or with a form of `sort-cycle`
/// that does not take the light sample from the mask, the marks change nothing.
#[test]
fn marked_shading_edges_take_the_masks_light_sample_in_still_frames() {
    let gpu = Gpu::new();
    let w = 24usize;
    let still = frame_with_marks(&gpu, Method::SORT_CYCLE, true, false);
    let plain = frame_with_marks(&gpu, Method::SORT_CYCLE, false, false);
    let (mut changed, mut marked) = (0, 0);
    for (i, (a, b)) in still.iter().zip(&plain).enumerate() {
        if (i % w + i / w) % 2 == 0 {
            marked += 1;
            changed += usize::from(a != b);
        } else {
            assert_eq!(a, b, "unmarked pixel {i} changed");
        }
    }
    // Pixels that see the light, the black frame of the view or a surface wholly in shadow
    // keep their estimate whatever the light sample (at 24x16 about half of them).
    assert!(
        changed * 4 > marked,
        "{changed} of {marked} marked pixels changed"
    );
    assert_eq!(
        frame_with_marks(&gpu, Method::SORT_CYCLE, true, true),
        frame_with_marks(&gpu, Method::SORT_CYCLE, false, true),
        "a moving frame read the marks"
    );
    let jitter_only: Method = "sort-cycle:mask=jitter".parse().unwrap();
    assert_eq!(
        frame_with_marks(&gpu, jitter_only, true, false),
        frame_with_marks(&gpu, jitter_only, false, false),
        "mask=jitter read the marks"
    );
}
