//! The `hbo19` method end to end: its trace variant runs with the committed key tables, frame 0
//! (no temporal help) is bluer than white noise's frame 0, and `sort-retarget` can start from
//! the HBO+19 seed map and keeps it a permutation.
use crate::Gpu;
use blueshift_analysis::{
    Gray, LF_CUTOFF, SpectrumAccumulator, Window, low_frequency_fraction, rmse,
};
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, SeedMap, default_assets_dir};
use blueshift_sampling::Sampler;
use blueshift_scene::Scene;

const W: u32 = 128;

/// LF fraction and RMSE of frame 0's error against `reference`.
fn frame0(gpu: &Gpu, scene: &Scene, a: &MethodAssets, m: Method, reference: &[f32]) -> (f64, f64) {
    let cfg = RenderConfig {
        bounces: 1,
        method: m,
        no_jitter: true,
        ..RenderConfig::new(W, W)
    };
    let mut r = Renderer::new(gpu.dev(), scene, a, cfg).unwrap();
    r.render_frame().unwrap();
    let est = r.read_estimate().unwrap();
    let e: Vec<f32> = est.iter().zip(reference).map(|(a, b)| a[3] - b).collect();
    let g = Gray::new(W as usize, W as usize, e).unwrap();
    let mut acc = SpectrumAccumulator::new(64, Window::Hann).unwrap();
    acc.add_image(&g).unwrap();
    (
        low_frequency_fraction(&acc.mean().unwrap(), LF_CUTOFF),
        rmse(&g),
    )
}

#[test]
fn hbo19_frame0_error_is_bluer_than_white() {
    let gpu = Gpu::new();
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    assert!(!assets.keys.is_empty(), "no key tables under assets/keys");
    let reference = crate::cornell_reference(&gpu, &scene, &assets, W);
    let white = frame0(&gpu, &scene, &assets, Method::White, &reference);
    let hbo = frame0(&gpu, &scene, &assets, Method::Hbo19, &reference);
    eprintln!("frame 0 LF / RMSE: white {white:?}, hbo19 {hbo:?}");
    assert!(hbo.0 < 0.8 * white.0, "LF {} vs white {}", hbo.0, white.0);
    let ratio = hbo.1 / white.1;
    assert!((0.8..=1.1).contains(&ratio), "RMSE ratio {ratio}");
}

#[test]
fn sort_retarget_from_hbo19_seeds_starts_at_tile_positions_and_stays_a_permutation() {
    let gpu = Gpu::new();
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let tile = assets.keys_for(1).unwrap().tile;
    let cfg = RenderConfig {
        bounces: 1,
        method: Method::SORT_RETARGET,
        seed_map: SeedMap::Hbo19,
        ..RenderConfig::new(70, 45)
    };
    assert_eq!(cfg.effective_sampler(), Sampler::Hbo19);
    let mut r = Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap();
    let init = r.initial_seeds().to_vec();
    let stride = r.screen().stride() as usize;
    for (i, &seed) in init.iter().enumerate() {
        let (x, y) = ((i % stride) as u32 % tile, (i / stride) as u32 % tile);
        assert_eq!(seed, y * tile + x, "pixel {i}");
    }
    for _ in 0..4 {
        r.render_frame().unwrap();
        assert!(blueshift_permute::is_permutation_of(
            &r.read_seeds().unwrap(),
            &init
        ));
    }
    assert_ne!(r.read_seeds().unwrap(), init, "seeds never moved");
    // Switching to spp 4 picks another table of the same tile (seeds stay valid).
    r.set_quality(4, 1, Some(4)).unwrap();
    r.render_frame().unwrap();
}
