//! The demodulated sorting key (`key=demod`, and history keys): the image is the
//! same as without it, and the key is the estimate over the primary hit's base colour, checked
//! against the CPU G-buffer's material per pixel (an independent traversal).
use crate::Gpu;
use blueshift_layout::params::DEMODULATE_MIN_ALBEDO;
use blueshift_render::{
    Method, MethodAssets, RenderConfig, Renderer, default_assets_dir, gbuffer_cpu,
};
use blueshift_scene::{Scene, SceneGpu};
use glam::Vec3;

/// Rec.709 luminance (the analysis crate's, which eval uses too).
fn luminance(c: Vec3) -> f32 {
    blueshift_analysis::luminance(c.to_array())
}

#[test]
fn demodulated_key_divides_by_the_primary_albedo_and_keeps_the_image() {
    let gpu = Gpu::new();
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let sg = SceneGpu::build(&scene);
    let (w, h) = (40, 36);
    let frame = |method| {
        let cfg = RenderConfig {
            bounces: 2,
            spp: 2,
            method,
            no_jitter: true,
            ..RenderConfig::new(w, h)
        };
        let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
        let tp = r.trace_params();
        r.render_frame().unwrap();
        (r.read_estimate().unwrap(), tp)
    };
    let (plain, tp) = frame(Method::SORT_RETARGET);
    let (demod, _) = frame("sort-retarget:key=demod".parse().unwrap());
    let g = gbuffer_cpu(&sg, &tp);
    let mut changed = 0;
    for (i, ((a, b), t)) in plain.iter().zip(&demod).zip(&g).enumerate() {
        // Same seeds, same paths: the image is bit for bit the same.
        assert_eq!(a[..3], b[..3], "pixel {i}: the image changed");
        let rgb = Vec3::new(b[0], b[1], b[2]);
        let albedo = match t.material {
            0 => Vec3::ONE,
            m => Vec3::from_slice(&scene.materials[m as usize - 1].base_color[..3]),
        };
        let want = luminance(rgb / albedo.max(Vec3::splat(DEMODULATE_MIN_ALBEDO)));
        // Float division and the dot product's order may round differently: relative 1e-5.
        let tol = 1e-5 * want.abs().max(1e-3);
        assert!(
            (b[3] - want).abs() <= tol,
            "pixel {i}: key {} vs {want}",
            b[3]
        );
        assert!(
            (a[3] - luminance(rgb)).abs() <= 1e-5 * a[3].abs().max(1e-3),
            "pixel {i}"
        );
        changed += usize::from((a[3] - b[3]).abs() > 1e-3 * a[3].abs());
    }
    // The box's walls are coloured, so most keys differ from the plain luminance.
    assert!(
        changed > (w * h / 2) as usize,
        "only {changed} keys changed"
    );
}
