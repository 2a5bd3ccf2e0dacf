//! Every sequence reads the blue-noise masks at a window of its own (`sequence_mask_shift`):
//! the trace pass of every mask method, still and moving, and the sorting target (the latter
//! in `follow.rs`). Sequence 0 keeps the masks where they are.
use crate::Gpu;
use blueshift_permute::sequence_mask_shift;
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;

/// The trace pass's mask offset (and the mask's side) after one frame and a move of the
/// camera when `moving`.
fn trace_mask_offset(
    gpu: &Gpu,
    s: &Scene,
    a: &MethodAssets,
    m: Method,
    seq: u32,
    moving: bool,
) -> (u32, u32, u32) {
    let cfg = RenderConfig {
        bounces: 1,
        method: m,
        sequence: seq,
        ..RenderConfig::new(24, 16)
    };
    let mut r = Renderer::new(gpu.dev(), s, a, cfg).unwrap();
    r.render_frame().unwrap();
    if moving {
        let mut cam = s.camera_or_default();
        cam.position.x += 0.05;
        cam.target.x += 0.05;
        r.set_camera(cam);
    }
    let tp = r.trace_params();
    assert_ne!(
        tp.mask_mode,
        blueshift_layout::params::MASK_MODE_NONE,
        "{}",
        m.name()
    );
    (tp.mask_offset_x, tp.mask_offset_y, tp.mask_size)
}

#[test]
fn each_sequence_reads_the_trace_masks_at_its_own_shift() {
    let gpu = Gpu::new();
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let a = MethodAssets::load(&default_assets_dir()).unwrap();
    let (sx, sy) = sequence_mask_shift(5);
    let mut methods = vec![
        Method::MaskR2,
        Method::Stbn,
        Method::MaskRot,
        Method::MaskRotFollow,
        Method::SORT_CYCLE,
    ];
    if !a.fast.is_empty() {
        methods.push(Method::Fast);
    }
    for m in methods {
        for moving in [false, true] {
            let (x0, y0, n) = trace_mask_offset(&gpu, &s, &a, m, 0, moving);
            let (x5, y5, n5) = trace_mask_offset(&gpu, &s, &a, m, 5, moving);
            assert_eq!(n, n5);
            let what = format!("{} moving {moving}", m.name());
            assert_ne!(
                (sx % n, sy % n),
                (0, 0),
                "{what}: sequence 5 does not move the mask"
            );
            assert_eq!(
                ((x5 + n - x0) % n, (y5 + n - y0) % n),
                (sx % n, sy % n),
                "{what}"
            );
        }
    }
}
