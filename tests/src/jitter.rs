//! Where `sort-cycle` takes its anti-aliasing jitter: from the mask, except on pixels whose
//! previous primary hit was textured (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES`), which take the
//! seed's, as `mask=none` does.
use crate::Gpu;
use blueshift_layout::params::PRIMARY_TEXTURED;
use blueshift_render::{RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::{Scene, SceneGpu};

fn textured_scene() -> Scene {
    Scene::load(default_assets_dir().join("scenes/textured.gltf")).unwrap()
}

/// The trace pass marks each pixel whose primary hit is textured: through pixel centres the
/// hits are the CPU G-buffer's, so the marks are its materials' textures, pixel for pixel.
#[test]
fn primary_flags_mark_textured_primary_hits() {
    let gpu = Gpu::new();
    let s = textured_scene();
    let sg = SceneGpu::build(&s);
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    let cfg = RenderConfig {
        bounces: 1,
        method: blueshift_render::Method::SORT_CYCLE,
        no_jitter: true,
        ..RenderConfig::new(40, 30)
    };
    let mut r = Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap();
    let tp = r.trace_params();
    r.render_frame().unwrap();
    let got = r.read_primary_flags().unwrap();
    let want: Vec<u32> = blueshift_render::gbuffer_cpu(&sg, &tp)
        .iter()
        .map(|g| {
            let textured = g.material > 0 && {
                let m = &sg.materials[g.material as usize - 1];
                m.base_color_tex.max(m.emissive_tex).max(m.mr_tex) >= 0
            };
            if textured { PRIMARY_TEXTURED } else { 0 }
        })
        .collect();
    let wrong = got.iter().zip(&want).filter(|(g, w)| g != w).count();
    assert_eq!(wrong, 0, "{wrong} of {} pixels marked wrongly", want.len());
    let marked = want.iter().filter(|&&f| f != 0).count();
    assert!(
        marked > 0 && marked < want.len(),
        "the view must show textured and untextured surfaces ({marked} of {})",
        want.len()
    );
}

/// While the view moves, marked pixels take another jitter than unmarked ones (the seed's);
/// with a still view the marks change nothing (the mask's rotated jitter everywhere).
#[test]
fn marked_pixels_take_the_seed_jitter_while_the_view_moves() {
    let gpu = Gpu::new();
    let s = textured_scene();
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    let (w, h) = (24, 16);
    let frame = |marks: u32, moving: bool| {
        let cfg = RenderConfig {
            bounces: 1,
            method: blueshift_render::Method::SORT_CYCLE,
            ..RenderConfig::new(w, h)
        };
        let mut r = Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap();
        r.render_frame().unwrap();
        if moving {
            let mut cam = r.camera();
            cam.position.x += 0.01;
            r.set_camera(cam);
        }
        r.write_primary_flags(&vec![marks; (w * h) as usize])
            .unwrap();
        r.render_frame().unwrap();
        let e = r.read_estimate().unwrap();
        e.iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect::<Vec<u32>>()
    };
    assert!(
        frame(PRIMARY_TEXTURED, false) == frame(0, false),
        "a still view's jitter depends on the marks"
    );
    assert!(
        frame(PRIMARY_TEXTURED, true) != frame(0, true),
        "a moving view's marked pixels kept the mask's jitter"
    );
}

/// A still view's jitter runs through the rotated mask frame after frame, past the point
/// cycle: `sort-cycle` jitters exactly as `mask-rot` does in every frame, including those
/// after the sampler's index has wrapped (a black sphere against a white sky: the estimate
/// is whether the jittered ray misses the sphere, a function of the jitter alone).
#[test]
fn a_still_jitter_runs_on_past_the_point_cycle() {
    use crate::trace::{assets, scene, sphere};
    use blueshift_layout::params::CYCLE_FRAMES;
    use blueshift_render::Method;
    use blueshift_scene::{Camera, Material};
    use glam::Vec3;
    let gpu = Gpu::new();
    let black = Material {
        base_color: [0.0, 0.0, 0.0, 1.0],
        metallic: 0.0,
        specular: 0.0,
        ..Material::default()
    };
    let cam = Camera {
        position: Vec3::new(0.0, 0.0, 4.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        yfov: 0.6,
    };
    let s = scene(sphere(0, 16, 32), vec![black], Vec3::ONE, cam);
    let a = assets();
    let frames = CYCLE_FRAMES as usize + 4;
    let run = |method: Method| {
        let cfg = RenderConfig {
            bounces: 1,
            method,
            sequence: 3,
            ..RenderConfig::new(24, 24)
        };
        let mut r = Renderer::new(gpu.dev(), &s, &a, cfg).unwrap();
        (0..frames)
            .map(|_| {
                r.render_frame().unwrap();
                let e = r.read_estimate().unwrap();
                e.iter().map(|v| v[1].to_bits()).collect::<Vec<u32>>()
            })
            .collect::<Vec<_>>()
    };
    let (cycle, rot) = (run(Method::SORT_CYCLE), run(Method::MaskRot));
    let (miss, hit) = (1.0f32.to_bits(), 0.0f32.to_bits());
    let neither = cycle[0].iter().filter(|&&v| v != hit && v != miss).count();
    assert_eq!(neither, 0, "the estimate is not the jitter's hit or miss");
    for f in 0..frames {
        assert!(
            cycle[f] == rot[f],
            "frame {f}: the jitter is not the rotated mask's"
        );
    }
    let k = CYCLE_FRAMES as usize;
    assert!(
        cycle[1] != cycle[1 + k],
        "the jitter repeats with the point cycle"
    );
}
