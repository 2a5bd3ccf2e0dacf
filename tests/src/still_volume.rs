//! A still `sort-cycle` frame in direct light on a scene without textures takes the camera
//! jitter and the first vertex from the spatio-temporal volume (`Method::volume_vertex`): it
//! renders `stbn`'s frames bit for bit (an independent recipe of the same volume), sorts
//! nothing and leaves the seeds alone. At depth and with textures the default sorts.
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
fn a_still_direct_frame_renders_stbn_and_sorts_nothing() {
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
        let init = default.initial_seeds().to_vec();
        // Past a point cycle, so a phase-keyed slice would repeat where stbn's does not.
        for frame in 0..CYCLE_FRAMES + 3 {
            assert!(!sorted(&mut default), "spp {spp}: frame {frame} sorted");
            stbn.render_frame().unwrap();
            assert_eq!(
                bits(default.read_estimate().unwrap()),
                bits(stbn.read_estimate().unwrap()),
                "spp {spp}: frame {frame} is not stbn's"
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
