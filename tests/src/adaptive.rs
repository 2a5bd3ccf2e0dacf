//! `sort-grid-adaptive`'s choice of pairs on the bundled Cornell box: the sorting pass's count
//! of skewed classes (GPU == CPU in motion.rs) must separate the heavy-tailed keys of 8 bounces
//! at 1 spp, where pairs in every class lose, from direct light, where they win (docs/algorithm.md,
//! "pairs=adaptive"). A renderer reset forgets the counts. The gate lives on the GPU, so the
//! method keeps two frames in flight.
use crate::Gpu;
use blueshift_render::{
    Method, PAIRS_MAX_SKEWED_SHARE, RenderConfig, Renderer, default_assets_dir,
};
use blueshift_scene::Scene;

fn adaptive_renderer(gpu: &Gpu, bounces: u32) -> Renderer {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let cfg = RenderConfig {
        spp: 1,
        bounces,
        method: Method::SORT_GRID_ADAPTIVE,
        // Pixel centres, as `eval`: with anti-aliasing jitter a seed's error at an edge is
        // its coverage of the edge, a heavy tail that turns the pairs off in direct light too.
        no_jitter: true,
        ..RenderConfig::new(64, 64)
    };
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap()
}

fn share_after_frames(gpu: &Gpu, bounces: u32) -> (Renderer, f64) {
    let mut r = adaptive_renderer(gpu, bounces);
    for _ in 0..10 {
        r.render_frame().unwrap();
    }
    let share = r
        .pairs_gate()
        .share()
        .expect("the sorting pass counted no class");
    (r, share)
}

#[test]
fn the_pairs_gate_pairs_direct_light_everywhere_and_not_8_bounces_at_1_spp() {
    let gpu = Gpu::new();
    let (direct, d) = share_after_frames(&gpu, 1);
    let (mut multi, m) = share_after_frames(&gpu, 8);
    assert!(
        d < PAIRS_MAX_SKEWED_SHARE / 2.0 && m > PAIRS_MAX_SKEWED_SHARE * 1.5,
        "skewed share: direct light {d:.3}, 8 bounces {m:.3}"
    );
    assert_eq!(
        (direct.pairs_gate().pairs(), multi.pairs_gate().pairs()),
        (2, 0)
    );
    multi.reset().unwrap();
    assert_eq!(multi.pairs_gate().share(), None, "reset keeps old counts");
    // The gate on the device restarts too: the first frame after the reset leaves the same
    // gate as a new renderer's first frame.
    multi.render_frame().unwrap();
    let mut fresh = adaptive_renderer(&gpu, 8);
    fresh.render_frame().unwrap();
    assert_eq!(multi.pairs_gate(), fresh.pairs_gate());
    assert!(fresh.pairs_gate().share().is_some());
}

/// The gate stays on the GPU (`pairs_gate` pass), so a frame does not wait for the one
/// before it: two frames go in flight, and the third waits only for the first (whose slot it
/// takes).
#[test]
fn adaptive_frames_keep_two_in_flight() {
    let gpu = Gpu::new();
    let mut r = adaptive_renderer(&gpu, 1);
    assert!(r.submit_frame().unwrap().is_empty());
    let second = r.submit_frame().unwrap();
    assert!(second.is_empty(), "frame 1 waited for frame 0");
    let third = r.submit_frame().unwrap();
    let frames: Vec<u64> = third.iter().map(|c| c.stats.frame).collect();
    assert_eq!(frames, [0]);
    assert_eq!(r.finish_frames().unwrap().len(), 2);
}
