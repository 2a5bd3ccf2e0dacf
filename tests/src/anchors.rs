//! Anchored masks (`follow_anchors`): GPU == CPU twin on real G-buffers of a moving camera,
//! anchors follow a surface that moves by whole pixels, and a still camera renders exactly the
//! screen-fixed method.
use crate::Gpu;
use blueshift_permute::{anchor_pixel, follow_anchors_cpu, initial_anchors};
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;
use glam::Vec3;

fn cornell() -> (Scene, MethodAssets) {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    (s, MethodAssets::load(&default_assets_dir()).unwrap())
}

fn renderer(gpu: &Gpu, scene: &Scene, assets: &MethodAssets, m: Method) -> Renderer {
    let cfg = RenderConfig {
        bounces: 1,
        method: m,
        ..RenderConfig::new(53, 41)
    };
    Renderer::new(gpu.dev(), scene, assets, cfg).unwrap()
}

/// Three frames of a sideways move with a sub-pixel view offset and a turn (parallax,
/// disocclusion at the boxes): each frame's anchors are the CPU twin's from the previous
/// frame's anchors and the two G-buffers the renderer made, bit for bit.
#[test]
fn follow_anchors_matches_cpu_under_motion() {
    let gpu = Gpu::new();
    let (scene, assets) = cornell();
    let mut r = renderer(&gpu, &scene, &assets, Method::MaskRotFollow);
    let base = scene.camera_or_default();
    let mut prev: Option<(Vec<_>, Vec<u32>, _)> = None;
    let mut moved = 0;
    for f in 0..4 {
        let mut cam = base;
        let side = Vec3::X * 0.04 * f as f32;
        cam.position += side;
        cam.target += side * 0.8;
        r.set_camera(cam);
        r.set_view_offset((0.31 * f as f32, -0.17 * f as f32));
        let tp = r.trace_params();
        let before = r.read_seeds().unwrap();
        r.render_frame().unwrap();
        let g = r
            .read_gbuffer()
            .unwrap()
            .expect("anchored masks use a G-buffer");
        let after = r.read_seeds().unwrap();
        match &prev {
            None => assert_eq!(
                after,
                initial_anchors(after.len(), r.screen().stride()),
                "frame 0 keeps every pixel's own anchor"
            ),
            Some((pg, _, ptp)) => {
                let p = blueshift_render::motion_params(ptp, &r.screen());
                let cpu = follow_anchors_cpu(&p, pg, &g, &before);
                assert_eq!(after, cpu, "frame {f}");
                moved += after.iter().zip(&before).filter(|(a, b)| a != b).count();
            }
        }
        prev = Some((g, after, tp));
    }
    assert!(moved > 53 * 41, "the anchors should move: {moved}");
}

/// A camera translated parallel to the back wall by exactly two pixels' width at the wall's
/// depth moves the wall's image by two pixels: every wall pixel that saw the wall before takes
/// the anchor of the pixel two to its side, so the wall keeps its mask values.
#[test]
fn anchors_stay_on_a_surface_that_moves_by_whole_pixels() {
    let gpu = Gpu::new();
    let (scene, assets) = cornell();
    let mut r = renderer(&gpu, &scene, &assets, Method::MaskRotFollow);
    let cam = scene.camera_or_default();
    r.set_camera(cam);
    r.render_frame().unwrap();
    let g0 = r.read_gbuffer().unwrap().unwrap();
    let a0 = r.read_seeds().unwrap();
    // One pixel at the depth of the wall pixel at the screen centre, in world units.
    let tp = r.trace_params();
    let (w, h, stride) = (tp.width, tp.height, r.screen().stride());
    // The back wall: the surface facing the camera (normal +Z, the camera looks down -Z).
    let facing =
        |g: &blueshift_layout::motion::GBufferTexel| g.material != 0 && g.normal.z > 0.9999;
    let centre = *g0
        .iter()
        .find(|g| facing(g))
        .expect("the back wall is in view");
    // Depth along the view direction (the camera's `forward` has unit length).
    let z = (centre.position - tp.cam_origin).dot(tp.cam_forward.normalize());
    let px_world = 2.0 * tp.cam_right.length() * z / tp.view_size.x;
    let shift = tp.cam_right.normalize() * 2.0 * px_world;
    let mut moved = cam;
    moved.position += shift;
    moved.target += shift;
    r.set_camera(moved);
    r.render_frame().unwrap();
    let a1 = r.read_seeds().unwrap();
    let g1 = r.read_gbuffer().unwrap().unwrap();
    let wall = centre.material;
    let mut checked = 0;
    for y in 0..h {
        for x in 0..w - 2 {
            let there = (y * w + x + 2) as usize;
            // Wall pixels whose wall point the first frame saw two pixels further right.
            // (Both frames must see the wall there: a ray through a triangle edge may miss.)
            let on_wall = |g: &blueshift_layout::motion::GBufferTexel| {
                g.material == wall && facing(g) && (g.position.z - centre.position.z).abs() < 1e-4
            };
            if !on_wall(&g0[there]) || !on_wall(&g1[(y * w + x) as usize]) {
                continue;
            }
            let (to, from) = ((y * stride + x) as usize, (y * stride + x + 2) as usize);
            assert_eq!(
                anchor_pixel(a1[to]),
                anchor_pixel(a0[from]),
                "pixel ({x}, {y})"
            );
            checked += 1;
        }
    }
    assert!(
        checked > (w * h / 8) as usize,
        "too few wall pixels: {checked}"
    );
}

/// With a still camera the anchors stay on their pixels: in direct light (every sample
/// dimension from the mask) the anchored method renders its screen-fixed one bit for bit.
#[test]
fn a_still_camera_renders_the_screen_fixed_mask() {
    let gpu = Gpu::new();
    let (scene, assets) = cornell();
    let mut a = renderer(&gpu, &scene, &assets, Method::MaskRotFollow);
    let mut b = renderer(&gpu, &scene, &assets, Method::MaskRot);
    for f in 0..3 {
        a.render_frame().unwrap();
        b.render_frame().unwrap();
        assert_eq!(
            a.read_estimate().unwrap(),
            b.read_estimate().unwrap(),
            "frame {f}"
        );
    }
}

/// The overhead `bench` and `eval` report is the sum of the passes in PERMUTE_PASSES: every
/// pass any preset records, still or moving, other than the path tracer and the image passes
/// every method runs, must be on that list, or its cost goes unreported.
#[test]
fn every_pass_a_method_adds_counts_in_its_overhead() {
    let gpu = Gpu::new();
    let (scene, assets) = cornell();
    let common = ["trace", "accumulate", "tonemap"];
    for (name, m) in Method::named() {
        if m == Method::Fast && assets.fast.is_empty() {
            continue;
        }
        let cfg = RenderConfig {
            bounces: 1,
            method: m,
            ..RenderConfig::new(16, 16)
        };
        let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
        let mut cam = scene.camera_or_default();
        for _ in 0..3 {
            for p in r.render_frame().unwrap().passes {
                let n = p.name.as_str();
                assert!(
                    common.contains(&n) || blueshift_render::PERMUTE_PASSES.contains(&n),
                    "{name}: pass '{n}' is not counted"
                );
            }
            cam.position.x += 0.05;
            r.set_camera(cam);
        }
    }
}
