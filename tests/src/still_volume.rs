//! A still or slowly moving `sort-cycle` frame in direct light on a scene without textures
//! takes the camera jitter and the first vertex from the spatio-temporal volume
//! (`Method::volume_vertex`): it renders `stbn`'s frames bit for bit (an independent recipe of
//! the same volume), sorts nothing and leaves the seeds alone; moving faster, it renders
//! `mask-r2`'s. At depth and with textures the default sorts.
use crate::Gpu;
use blueshift_permute::CYCLE_FRAMES;
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;

fn scene(name: &str) -> Scene {
    Scene::load(default_assets_dir().join(format!("scenes/{name}.gltf"))).unwrap()
}

fn sorted(r: &mut Renderer) -> bool {
    let stats = r.render_frame().unwrap();
    stats.passes.iter().any(|p| p.name == "sort_seeds")
}

fn bits(px: Vec<[f32; 4]>) -> Vec<[u32; 4]> {
    px.iter().map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn a_still_or_slow_direct_frame_renders_stbn_and_sorts_nothing() {
    let gpu = Gpu::new();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let cornell = scene("cornell-box");
    let cfg = |method, spp, bounces| RenderConfig {
        method,
        spp,
        bounces,
        ..RenderConfig::new(23, 17)
    };
    for spp in [1, 3] {
        let new = |m| Renderer::new(gpu.dev(), &cornell, &assets, cfg(m, spp, 1)).unwrap();
        let (mut default, mut stbn) = (new(Method::SORT_CYCLE), new(Method::Stbn));
        // Frame for frame beside the default: its mask offsets depend on the frame.
        let mut mask_r2 = new(Method::MaskR2);
        // Without the slow view's rule: slowly moving, the 2D mask's frames.
        let mut ablation = new("sort-cycle:without=slow-volume".parse().unwrap());
        let init = default.initial_seeds().to_vec();
        // Past a point cycle, so a phase-keyed slice would repeat where stbn's does not.
        for frame in 0..CYCLE_FRAMES + 3 {
            assert!(!sorted(&mut default), "spp {spp}: frame {frame} sorted");
            stbn.render_frame().unwrap();
            mask_r2.render_frame().unwrap();
            ablation.render_frame().unwrap();
            let want = bits(stbn.read_estimate().unwrap());
            assert_eq!(
                bits(default.read_estimate().unwrap()),
                want,
                "spp {spp}: frame {frame} is not stbn's"
            );
            assert_eq!(bits(ablation.read_estimate().unwrap()), want, "spp {spp}");
        }
        assert_eq!(default.read_seeds().unwrap(), init, "spp {spp}");
        // Moving: a hundredth of the box per frame is a small fraction of a pixel here (slow,
        // the volume's frames), one unit several pixels (the 2D mask's, `mask=vertex`); no
        // sort either way.
        let mut cam = cornell.camera_or_default();
        for (frame, step) in [0.01, 0.01, 0.01, 1.0, -1.0, 1.0].into_iter().enumerate() {
            cam.position.x += step;
            for r in [&mut default, &mut stbn, &mut mask_r2, &mut ablation] {
                r.set_camera(cam);
            }
            assert!(
                !sorted(&mut default),
                "spp {spp}: moving frame {frame} sorted"
            );
            stbn.render_frame().unwrap();
            mask_r2.render_frame().unwrap();
            ablation.render_frame().unwrap();
            let mask_frame = bits(mask_r2.read_estimate().unwrap());
            let (want, of) = if step.abs() < 0.1 {
                (bits(stbn.read_estimate().unwrap()), "stbn")
            } else {
                (mask_frame.clone(), "mask-r2")
            };
            assert_eq!(
                bits(default.read_estimate().unwrap()),
                want,
                "spp {spp}: moving frame {frame} (step {step}) is not {of}'s"
            );
            assert_eq!(
                bits(ablation.read_estimate().unwrap()),
                mask_frame,
                "spp {spp}: the ablation's moving frame {frame} is not mask-r2's"
            );
        }
        assert_eq!(default.read_seeds().unwrap(), init, "spp {spp}");
    }
    // Where the seeds are read, the default sorts: at depth, and in direct light with
    // textures (the volume's jitter accumulates worse on them) or without the rule.
    let textured = scene("textured");
    let ablation = "sort-cycle:without=still-volume".parse().unwrap();
    for (scene, method, bounces) in [
        (&cornell, Method::SORT_CYCLE, 2),
        (&textured, Method::SORT_CYCLE, 1),
        (&cornell, ablation, 1),
    ] {
        let mut r = Renderer::new(gpu.dev(), scene, &assets, cfg(method, 1, bounces)).unwrap();
        assert!(sorted(&mut r), "{method} b{bounces} did not sort");
    }
}
