//! A quad light's samples follow its corners, not the order of its triangles' indices
//! (crates/scene/src/gpu/quads.rs): the bundled Cornell box renders the same with its light's
//! triangles rotated, which turns `0 1 2 2 3 0` into `0 1 2 0 2 3` and so on. With a radial
//! map per triangle the two orders sampled unrelated points of the light, and the masks kept
//! their blue noise on one file of the box and lost most of it on the other.
use crate::Gpu;
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;

fn luminance_of_frames(gpu: &Gpu, scene: &Scene, frames: u32) -> Vec<f32> {
    let cfg = RenderConfig {
        spp: 1,
        bounces: 1,
        method: Method::MaskR2,
        ..RenderConfig::new(64, 64)
    };
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let mut r = Renderer::new(gpu.dev(), scene, &assets, cfg).unwrap();
    let mut out = Vec::new();
    for _ in 0..frames {
        r.render_frame().unwrap();
        let est = r.read_estimate().unwrap();
        out.extend(est.iter().map(|p| p[0] + p[1] + p[2]));
    }
    out
}

#[test]
fn a_quad_lights_samples_follow_its_corners_not_its_index_order() {
    let gpu = Gpu::new();
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let mut turned = scene.clone();
    let mut n = 0;
    for t in turned.triangles.iter_mut() {
        if scene.materials[t.material as usize].emissive.max_element() > 0.0 {
            // The first triangle once, the second twice: every vertex order differs.
            n += 1;
            for _ in 0..n {
                t.positions.rotate_left(1);
                t.normals.rotate_left(1);
                t.uvs.rotate_left(1);
            }
        }
    }
    assert_eq!(n, 2, "the box's light is one quad of two triangles");
    let (a, b) = (
        luminance_of_frames(&gpu, &scene, 2),
        luminance_of_frames(&gpu, &turned, 2),
    );
    let lit = a.iter().filter(|&&v| v > 0.0).count();
    assert!(lit > a.len() / 2, "{lit} of {} pixels lit", a.len());
    // The same sample points give the same estimates up to the rounding of the light's
    // corners (computed from another vertex of the same triangle): a few ulp, which can move
    // a rare shadow ray across an edge. Other sample points change almost every lit pixel.
    let differing = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| (*x - *y).abs() > 1e-3 * x.abs().max(1e-2))
        .count();
    assert!(
        differing * 200 < lit,
        "{differing} of {lit} lit pixels differ"
    );
}
