//! Where `sort-cycle` takes its anti-aliasing jitter: from the mask, except on pixels whose
//! previous primary hit was textured (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES`), which take the
//! seed's, as `mask=none` does; and with a still view the rotating mask's jitter walks a
//! sequence per pixel (`mask_jitter` is its CPU twin): `sort-cycle`'s Sobol's points where the
//! previous primary hit was untextured (`TRACE_FLAG_SOBOL_JITTER`), R2's elsewhere and for
//! `mask-rot`.
use crate::Gpu;
use blueshift_layout::params::{MASK_DIM_OFFSET_X, MASK_DIM_OFFSET_Y, PRIMARY_TEXTURED};
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
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

/// Marked pixels take another jitter than unmarked ones: the seed's while the view moves, the
/// mask's R2 walk instead of Sobol's while it stands still (each walk is checked point by
/// point in `a_still_jitter_walks_its_sequence_per_pixel`).
#[test]
fn marked_pixels_take_the_seed_jitter_while_the_view_moves() {
    let gpu = Gpu::new();
    let s = textured_scene();
    let frame = |marks: u32, moving: bool| {
        second_frame_with_flags(&gpu, &s, Method::SORT_CYCLE, &[marks; 24 * 16], moving)
    };
    assert!(
        frame(PRIMARY_TEXTURED, false) != frame(0, false),
        "a still view's marked pixels kept the Sobol walk"
    );
    assert!(
        frame(PRIMARY_TEXTURED, true) != frame(0, true),
        "a moving view's marked pixels kept the mask's jitter"
    );
}

/// The estimate (bits, rgba per pixel) of the second frame of `method` at 24x16 and 2
/// bounces, after writing `flags` into the trace's `primary_flags` (one per pixel); `moving`:
/// the camera moved before it. (In direct light on a scene without textures the default's
/// still frame reads no flag: it takes the volume, `still_volume.rs`.)
fn second_frame_with_flags(
    gpu: &Gpu,
    scene: &Scene,
    method: Method,
    flags: &[u32],
    moving: bool,
) -> Vec<u32> {
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let cfg = RenderConfig {
        bounces: 2,
        method,
        ..RenderConfig::new(24, 16)
    };
    let mut r = Renderer::new(gpu.dev(), scene, &assets, cfg).unwrap();
    r.render_frame().unwrap();
    if moving {
        let mut cam = r.camera();
        cam.position.x += 0.01;
        r.set_camera(cam);
    }
    r.write_primary_flags(flags).unwrap();
    r.render_frame().unwrap();
    let e = r.read_estimate().unwrap();
    e.iter().flatten().map(|v| v.to_bits()).collect()
}

/// The jitter a rotating mask gives pixel `px` after `step` frames (CPU twin of path.glsl's
/// `sample_dim` for dimensions 0 and 1, one sample per pixel): the mask's value at the
/// dimension's offset, turned by `step` R2 steps, or with `sobol` (its direction numbers)
/// shifted by Sobol point `step`. Fractions in f32 as the shader computes them.
fn mask_jitter(
    a: &MethodAssets,
    off: (u32, u32),
    px: (u32, u32),
    step: u32,
    sobol: Option<&[[u32; 32]; 4]>,
) -> [f32; 2] {
    use blueshift_sampling::{r2, rng::to_unit};
    let n = a.n;
    [0u32, 1].map(|dim| {
        let q = (
            (px.0 + off.0 + dim * MASK_DIM_OFFSET_X) % n,
            (px.1 + off.1 + dim * MASK_DIM_OFFSET_Y) % n,
        );
        let rank = a.mask[(q.1 * n + q.0) as usize];
        let x = (rank as f32 + 0.5) / (n * n) as f32;
        let x = x - x.floor();
        let turn = match sobol {
            Some(dirs) => blueshift_sampling::sobol::sobol(step, dim, dirs),
            None => step.wrapping_mul(r2::ALPHA[dim as usize]),
        };
        let y = x + to_unit(turn);
        y - y.floor()
    })
}

/// A still view's jitter is the rotating mask's, frame after frame and past the point cycle
/// (the sampler's index repeats every 16 frames, the jitter's walk does not): `sort-cycle`'s
/// walks Sobol's points on a pixel whose previous primary hit was untextured and R2's on one
/// whose hit was textured; `mask-rot`'s walks R2's everywhere. The scene is a black square
/// (plain, or with a black texture) on a white sky, so each pixel's estimate says whether its
/// jittered ray hit the square, which the CPU decides from the twin's jitter (rays within
/// float rounding of the square's border are skipped); the previous frame's estimate says
/// whether the pixel's previous hit was the square.
#[test]
fn a_still_jitter_walks_its_sequence_per_pixel() {
    use crate::trace::{assets, scene};
    use blueshift_layout::params::CYCLE_FRAMES;
    use blueshift_render::Method;
    use blueshift_scene::{Camera, Image, Material, Texture, Triangle, Wrap};
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
    let plain = scene(square.clone(), vec![black.clone()], Vec3::ONE, cam);
    let textured_black = Material {
        base_color: [1.0; 4],
        base_color_texture: Some(0),
        ..black
    };
    let textured = Scene {
        textures: vec![Texture {
            image: 0,
            wrap_s: Wrap::Repeat,
            wrap_t: Wrap::Repeat,
            nearest: true,
        }],
        images: std::sync::Arc::new([Image {
            name: None,
            width: 1,
            height: 1,
            rgba8: vec![0, 0, 0, 255],
        }]),
        ..scene(square, vec![textured_black], Vec3::ONE, cam)
    };
    let a = assets();
    let dirs = blueshift_sampling::sobol::direction_numbers();
    let (w, h) = (24u32, 24u32);
    let frames = CYCLE_FRAMES + 4;
    let cases = [
        (Method::SORT_CYCLE, &plain, true),
        (Method::SORT_CYCLE, &textured, true),
        (Method::MaskRot, &plain, false),
    ];
    for (method, s, sobol_walk) in cases {
        let square_textured = !s.textures.is_empty();
        // Two bounces (the square is black: the image is still hit or miss): in direct light
        // without textures the default's still jitter is the volume's (`still_volume.rs`).
        let cfg = RenderConfig {
            bounces: 2,
            method,
            sequence: 3,
            ..RenderConfig::new(w, h)
        };
        let mut r = Renderer::new(gpu.dev(), s, &a, cfg).unwrap();
        let (mut checked, mut changed, mut r2_walks) = (0, 0, 0);
        let mut first = vec![None; (w * h) as usize];
        // Whether each pixel's previous primary hit was the square (none before frame 0).
        let mut prev_hit = vec![false; (w * h) as usize];
        for step in 0..frames {
            let tp = r.trace_params();
            r.render_frame().unwrap();
            let e = r.read_estimate().unwrap();
            let hits: Vec<bool> = e.iter().map(|v| v[1] == 0.0).collect();
            for (i, v) in e.iter().enumerate() {
                let px = (i as u32 % w, i as u32 / w);
                let off = (tp.mask_offset_x, tp.mask_offset_y);
                // The R2 walk on a pixel whose previous primary hit was textured.
                let sobol_here = sobol_walk && !(square_textured && prev_hit[i]);
                r2_walks += usize::from(sobol_walk && !sobol_here);
                let j = mask_jitter(&a, off, px, step, sobol_here.then_some(&dirs));
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
            prev_hit = hits;
        }
        assert_eq!(
            r2_walks > 0,
            sobol_walk && square_textured,
            "{}: {r2_walks} R2 walks among Sobol's",
            method.name()
        );
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
