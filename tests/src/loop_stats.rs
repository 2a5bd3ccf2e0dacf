//! The loop-counting trace shader (`RenderConfig::loop_stats`, `blueshift bench --loop-stats`):
//! its counts agree with the CPU traversal's, and it renders what the other variants render.
use crate::{Gpu, same_bits};
use blueshift_render::{
    LoopStats, Method, MethodAssets, RenderConfig, Renderer, TraceLoop, default_assets_dir,
};
use blueshift_scene::{Ray, Scene, SceneGpu, TraversalCounts, closest_hit_counted};
use glam::Vec2;

fn cornell() -> Scene {
    Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap()
}

fn assets() -> MethodAssets {
    MethodAssets::load(&default_assets_dir()).unwrap()
}

/// Primary rays only (`--bounces 0`, pixel centres): one path vertex per pixel, no light
/// choice or shadow ray, and the closest-hit loops run as often, summed over the pixels, as
/// the CPU twin's loops for the same rays. Every loop's batch count lies between its lane
/// count over the batch width and its lane count.
#[test]
fn loop_stats_count_what_the_cpu_traversal_counts() {
    let gpu = Gpu::new();
    let scene = cornell();
    let (w, h) = (64u32, 48u32); // multiples of the 8x8 workgroup: no idle invocations
    let cfg = RenderConfig {
        spp: 1,
        bounces: 0,
        method: Method::White,
        no_jitter: true,
        loop_stats: true,
        ..RenderConfig::new(w, h)
    };
    let mut r = Renderer::new(gpu.dev(), &scene, &assets(), cfg).unwrap();
    let p = r.trace_params();
    let loops: LoopStats = r.render_frame().unwrap().loops.expect("loop statistics");

    let sg = SceneGpu::build(&scene);
    let mut cpu = TraversalCounts::default();
    for y in 0..h {
        for x in 0..w {
            // The camera ray of path_start / gbuffer_cpu.
            let ndc = (Vec2::new(x as f32, y as f32) + p.view_offset + Vec2::splat(0.5))
                / p.view_size
                * 2.0
                - 1.0;
            let dir = (p.cam_forward + ndc.x * p.cam_right - ndc.y * p.cam_up).normalize();
            let ray = Ray::new(p.cam_origin, dir, 0.0, 1e30);
            closest_hit_counted(&sg.nodes, &sg.triangles, &ray, &mut cpu);
        }
    }
    assert!(cpu.triangles > 0 && cpu.pops > 0, "{cpu:?}");
    let pixels = (w * h) as u64;
    assert_eq!(loops.get(TraceLoop::PathVertex).lanes, pixels);
    for l in [
        TraceLoop::LightChoice,
        TraceLoop::Occlusion,
        TraceLoop::OcclusionWalk,
        TraceLoop::OcclusionLeaf,
    ] {
        assert_eq!(loops.get(l).batches, 0, "{l:?}");
    }
    // The GPU's ray directions may round differently from these (normalize's rsqrt: see the
    // G-buffer test), which can change a grazing ray's traversal; on this image they did not
    // (measured equal), so the bound only absorbs such a ray or two.
    for (l, want) in [
        (TraceLoop::ClosestHit, cpu.descents),
        (TraceLoop::ClosestDescend, cpu.interior),
        (TraceLoop::ClosestLeaf, cpu.triangles),
        (TraceLoop::ClosestPop, cpu.pops),
    ] {
        let got = loops.get(l).lanes;
        assert!(got.abs_diff(want) <= 16, "{l:?}: GPU {got}, CPU {want}");
    }
    let width = gpu.dev().info().subgroup_size as u64;
    for l in TraceLoop::ALL {
        let c = loops.get(l);
        assert!(
            c.batches <= c.lanes && c.lanes <= width * c.batches,
            "{l:?}: {c:?}"
        );
    }
}

/// The counting shaders (`trace_loop_stats` and its hbo19 twin) render bit for bit what the
/// specialised variants render, over frames that move the seeds; without `loop_stats` a frame
/// has no loop counts.
#[test]
fn loop_stats_shader_renders_the_same_image() {
    let gpu = Gpu::new();
    let scene = cornell();
    for method in [Method::SORT_RETARGET, Method::Hbo19] {
        let render = |loop_stats| {
            let cfg = RenderConfig {
                spp: 2,
                bounces: 4,
                method,
                loop_stats,
                ..RenderConfig::new(32, 32)
            };
            let mut r = Renderer::new(gpu.dev(), &scene, &assets(), cfg).unwrap();
            let mut counted = Vec::new();
            for _ in 0..2 {
                counted.push(r.render_frame().unwrap().loops.is_some());
            }
            (r.read_accum().unwrap(), counted)
        };
        let ((a, counted_a), (b, counted_b)) = (render(false), render(true));
        assert_eq!((counted_a, counted_b), (vec![false; 2], vec![true; 2]));
        assert!(a.iter().any(|p| p[0] > 0.0), "{method}: black image");
        assert!(
            same_bits(&a, &b),
            "{method}: the counting shader renders another image"
        );
    }
}
