//! Where `sort-cycle` takes its anti-aliasing jitter: from the mask, except on pixels whose
//! previous primary hit was textured (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES`), which take the
//! seed's, as `mask=none` does; and with a still view the rotating mask's jitter walks R2
//! per pixel (`mask_jitter` is its CPU twin).
use crate::Gpu;
use blueshift_layout::params::PRIMARY_TEXTURED;
use blueshift_render::{MethodAssets, RenderConfig, Renderer, default_assets_dir};
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

/// The jitter a rotating mask gives pixel `px` after `step` frames (CPU twin of path.glsl's
/// `sample_dim` for dimensions 0 and 1, one sample per pixel): the mask's value at the
/// dimension's offset, turned by `step` R2 steps. Fractions in f32 as the shader computes
/// them.
fn mask_jitter(a: &MethodAssets, off: (u32, u32), px: (u32, u32), step: u32) -> [f32; 2] {
    use blueshift_sampling::{r2, rng::to_unit};
    let n = a.n;
    [0u32, 1].map(|dim| {
        let q = ((px.0 + off.0 + dim * 37) % n, (px.1 + off.1 + dim * 71) % n);
        let rank = a.mask[(q.1 * n + q.0) as usize];
        let x = (rank as f32 + 0.5) / (n * n) as f32;
        let x = x - x.floor();
        let y = x + to_unit(step.wrapping_mul(r2::ALPHA[dim as usize]));
        y - y.floor()
    })
}

/// A still view's jitter is the rotating mask's, frame after frame and past the point cycle
/// (the sampler's index repeats every 16 frames, the jitter's walk does not), for
/// `sort-cycle` as for `mask-rot`. The scene is a
/// black square on a white sky, so each pixel's estimate says whether its jittered ray hit
/// the square, which the CPU decides from the twin's jitter (rays within float rounding of
/// the square's border are skipped).
#[test]
fn a_still_jitter_walks_its_sequence_per_pixel() {
    use crate::trace::{assets, scene};
    use blueshift_layout::params::CYCLE_FRAMES;
    use blueshift_render::Method;
    use blueshift_scene::{Camera, Material, Triangle};
    use glam::{Vec2, Vec3};
    let gpu = Gpu::new();
    let black = Material {
        base_color: [0.0, 0.0, 0.0, 1.0],
        metallic: 0.0,
        specular: 0.0,
        ..Material::default()
    };
    let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, 0.0));
    let square = [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
        .map(|positions| Triangle {
            positions,
            normals: [Vec3::Z; 3],
            uvs: [Vec2::ZERO; 3],
            material: 0,
        })
        .to_vec();
    let cam = Camera {
        position: Vec3::new(0.0, 0.0, 3.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        yfov: 0.9,
    };
    let s = scene(square, vec![black], Vec3::ONE, cam);
    let a = assets();
    let (w, h) = (24u32, 24u32);
    let frames = CYCLE_FRAMES + 4;
    for method in [Method::SORT_CYCLE, Method::MaskRot] {
        let cfg = RenderConfig {
            bounces: 1,
            method,
            sequence: 3,
            ..RenderConfig::new(w, h)
        };
        let mut r = Renderer::new(gpu.dev(), &s, &a, cfg).unwrap();
        let (mut checked, mut changed) = (0, 0);
        let mut first = vec![None; (w * h) as usize];
        for step in 0..frames {
            let tp = r.trace_params();
            r.render_frame().unwrap();
            let e = r.read_estimate().unwrap();
            for (i, v) in e.iter().enumerate() {
                let px = (i as u32 % w, i as u32 / w);
                let off = (tp.mask_offset_x, tp.mask_offset_y);
                let j = mask_jitter(&a, off, px, step);
                let ndc = Vec2::new(
                    (px.0 as f32 + tp.view_offset.x + j[0]) / tp.view_size.x * 2.0 - 1.0,
                    (px.1 as f32 + tp.view_offset.y + j[1]) / tp.view_size.y * 2.0 - 1.0,
                );
                let basis = blueshift_scene::CameraBasis {
                    position: tp.cam_origin,
                    forward: tp.cam_forward,
                    right: tp.cam_right,
                    up: tp.cam_up,
                };
                // The trace's NDC y grows downwards; the basis' upwards.
                let dir = basis.direction(ndc.x, -ndc.y);
                let p = tp.cam_origin - dir * (tp.cam_origin.z / dir.z);
                let border = (p.x.abs() - 1.0).abs().min((p.y.abs() - 1.0).abs());
                if border < 1e-3 {
                    continue;
                }
                let hit = p.x.abs() < 1.0 && p.y.abs() < 1.0;
                let want = if hit { 0.0 } else { 1.0 };
                assert_eq!(v[1], want, "{} frame {step} pixel {px:?}", method.name());
                checked += 1;
                match first[i] {
                    None => first[i] = Some(hit),
                    Some(h0) if h0 != hit => changed += 1,
                    _ => {}
                }
            }
        }
        assert!(
            changed > 0,
            "{}: no jitter crossed the square's border",
            method.name()
        );
        assert!(
            checked > (w * h * frames) as usize * 9 / 10,
            "{checked} checked"
        );
    }
}
