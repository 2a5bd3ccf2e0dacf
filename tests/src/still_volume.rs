//! A still `sort-cycle` frame in direct light on a scene without textures takes the camera
//! jitter and the first vertex from the spatio-temporal volume (`Method::volume_vertex`): it
//! renders `stbn`'s frames bit for bit (an independent recipe of the same volume), sorts
//! nothing and leaves the seeds alone. Moving, it renders the frames `stbn` renders on the
//! motion volume (`Method::motion_volume`), and its ablation `mask-r2`'s; at depth it sorts
//! only while still (`Method::reads_seeds`). With textures the default sorts.
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
fn a_direct_frame_without_textures_renders_a_volume_and_sorts_nothing() {
    let gpu = Gpu::new();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let cornell = scene("cornell-box");
    let cfg = |method, spp, bounces| RenderConfig {
        method,
        spp,
        bounces,
        ..RenderConfig::new(23, 17)
    };
    // `stbn` on the motion volume: the moving default's frames by an independent recipe.
    let motion_assets = MethodAssets {
        stbn: assets.motion.clone(),
        ..assets.clone()
    };
    assert_ne!(motion_assets.stbn, assets.stbn, "a volume of its own");
    for spp in [1, 3] {
        let on = |a, m| Renderer::new(gpu.dev(), &cornell, a, cfg(m, spp, 1)).unwrap();
        let new = |m| on(&assets, m);
        let (mut default, mut stbn) = (new(Method::SORT_CYCLE), new(Method::Stbn));
        // Frame for frame beside the default: their mask offsets and slices depend on the
        // frame.
        let mut mask_r2 = new(Method::MaskR2);
        let mut stbn_motion = on(&motion_assets, Method::Stbn);
        let mut ablation = new("sort-cycle:without=motion-volume".parse().unwrap());
        let init = default.initial_seeds().to_vec();
        let others = |rs: [&mut Renderer; 4]| {
            for r in rs {
                r.render_frame().unwrap();
            }
        };
        // Past a point cycle, so a phase-keyed slice would repeat where stbn's does not.
        for frame in 0..CYCLE_FRAMES + 3 {
            assert!(!sorted(&mut default), "spp {spp}: frame {frame} sorted");
            others([&mut stbn, &mut mask_r2, &mut stbn_motion, &mut ablation]);
            let want = bits(stbn.read_estimate().unwrap());
            assert_eq!(
                bits(default.read_estimate().unwrap()),
                want,
                "spp {spp}: frame {frame} is not stbn's"
            );
            assert_eq!(bits(ablation.read_estimate().unwrap()), want, "spp {spp}");
        }
        assert_eq!(default.read_seeds().unwrap(), init, "spp {spp}");
        // Moving (`mask=vertex`, no sort either): the motion volume's frames; without it, the
        // 2D mask's.
        let mut cam = cornell.camera_or_default();
        for frame in 0..4 {
            cam.position.x += 0.01;
            for r in [
                &mut default,
                &mut stbn,
                &mut mask_r2,
                &mut stbn_motion,
                &mut ablation,
            ] {
                r.set_camera(cam);
            }
            assert!(
                !sorted(&mut default),
                "spp {spp}: moving frame {frame} sorted"
            );
            others([&mut stbn, &mut mask_r2, &mut stbn_motion, &mut ablation]);
            assert_eq!(
                bits(default.read_estimate().unwrap()),
                bits(stbn_motion.read_estimate().unwrap()),
                "spp {spp}: moving frame {frame} is not the motion volume's"
            );
            assert_eq!(
                bits(ablation.read_estimate().unwrap()),
                bits(mask_r2.read_estimate().unwrap()),
                "spp {spp}: the ablation's moving frame {frame} is not mask-r2's"
            );
        }
        assert_eq!(default.read_seeds().unwrap(), init, "spp {spp}");
    }
    // Where the seeds are read, the default sorts: still at depth, and in direct light with
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

/// Moving at depth on a scene without textures the default sorts nothing (its seeds stay
/// put: `cycle.rs`, `a_moving_view_without_seeds_skips_the_sort`); `without=white-depth`
/// sorts there and renders other frames, and both sort with a still view.
#[test]
fn a_moving_frame_at_depth_sorts_nothing() {
    let gpu = Gpu::new();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let cornell = scene("cornell-box");
    let new = |m| {
        let cfg = RenderConfig {
            method: m,
            bounces: 3,
            ..RenderConfig::new(23, 17)
        };
        Renderer::new(gpu.dev(), &cornell, &assets, cfg).unwrap()
    };
    let mut default = new(Method::SORT_CYCLE);
    let mut ablation = new("sort-cycle:without=white-depth".parse().unwrap());
    assert!(
        sorted(&mut default) && sorted(&mut ablation),
        "still frames sort"
    );
    let mut cam = cornell.camera_or_default();
    for frame in 0..3 {
        cam.position.x += 0.01;
        default.set_camera(cam);
        ablation.set_camera(cam);
        assert!(!sorted(&mut default), "moving frame {frame} sorted");
        assert!(sorted(&mut ablation), "the ablation's moving frame {frame}");
        let px = bits(default.read_estimate().unwrap());
        assert_ne!(px, bits(ablation.read_estimate().unwrap()), "frame {frame}");
    }
}
