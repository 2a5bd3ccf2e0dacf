//! GLSL lights.glsl == Rust twins (environment.rs, lights.rs): the map's importance sampling,
//! its texel lookup and density, and the punctual lights' incident light.
use crate::{Gpu, groups_for};
use blueshift_device::{Binding, Buffer};
use blueshift_sampling::rng::{hash3, to_unit};
use blueshift_scene::{Camera, EnvMap, LightKind, PunctualLight, Scene, SceneGpu, env_direction};
use glam::{Vec2, Vec3, Vec4};
use std::sync::Arc;

/// A map with structure: a gradient, a bright patch and a black patch (never sampled).
pub fn test_map(w: u32, h: u32) -> EnvMap {
    let mut m = EnvMap::constant(w, h, Vec3::ZERO);
    for j in 0..h {
        for i in 0..w {
            let bright = (i * 4 / w == 1) && (j * 4 / h == 1);
            let black = (i * 4 / w == 3) && (j * 2 / h == 1);
            let c = if bright {
                Vec3::new(20.0, 16.0, 10.0)
            } else if black {
                Vec3::ZERO
            } else {
                Vec3::new(0.2 + i as f32 / w as f32, 0.5, 0.3 + j as f32 / h as f32)
            };
            m.texels[(j * w + i) as usize] = c;
        }
    }
    m
}

fn lights() -> Vec<PunctualLight> {
    let l = |kind, position, direction: Vec3, intensity| PunctualLight {
        kind,
        position,
        direction: direction.normalize(),
        intensity,
    };
    vec![
        l(
            LightKind::Point,
            Vec3::new(0.5, 2.0, -1.0),
            Vec3::NEG_Y,
            Vec3::new(3.0, 2.0, 1.0),
        ),
        l(
            LightKind::Spot {
                inner: 0.3,
                outer: 0.6,
            },
            Vec3::new(-1.0, 1.5, 0.5),
            Vec3::new(0.2, -1.0, 0.1),
            Vec3::splat(5.0),
        ),
        l(
            LightKind::Directional,
            Vec3::ZERO,
            Vec3::new(1.0, -2.0, 0.5),
            Vec3::ONE,
        ),
    ]
}

#[test]
fn glsl_lights_match_rust_twins() {
    let mut gpu = Gpu::new();
    let mut map = test_map(24, 12);
    map.rotation = 0.8;
    let scene = Scene {
        camera: Some(Camera::framing(&Default::default())),
        environment_map: Some(Arc::new(map.clone())),
        lights: lights(),
        ..Scene::from_triangles([[Vec3::ZERO, Vec3::X, Vec3::Y]])
    };
    let sg = SceneGpu::build(&scene);
    let images = blueshift_trace::SceneImages::new(gpu.dev(), &sg).unwrap();
    let info = Buffer::from_slice(gpu.dev(), "lights.info", &[sg.info]).unwrap();
    let p = gpu.pipeline(
        "test/lights",
        &[
            Binding::image(0, "scene_lights"),
            Binding::storage(1, "scene"),
            Binding::storage(2, "inputs"),
            Binding::storage(3, "results"),
        ],
        8,
    );
    let tables = map.tables();
    let rot = map.rotation_cs();
    let n = 4096u32;
    let (w, h) = (map.width, map.height);
    let mut inputs = Vec::new();
    let mut centres = Vec::new();
    for i in 0..n {
        let u = Vec2::new(to_unit(hash3(i, 1, 0)), to_unit(hash3(i, 2, 0)));
        // Texel centres: the lookup must agree exactly away from texel edges.
        let t = (i % w, (i / w) % h);
        let c = Vec2::new((t.0 as f32 + 0.5) / w as f32, (t.1 as f32 + 0.5) / h as f32);
        let d = env_direction(c, rot);
        let p = Vec3::new(to_unit(hash3(i, 3, 0)), to_unit(hash3(i, 4, 0)), 0.0) * 2.0 - 1.0;
        inputs.extend([u.extend(0.0).extend(0.0), d.extend(0.0), p.extend(0.0)]);
        centres.push((t, d, p, u));
    }
    let inb = Buffer::from_slice(gpu.dev(), "lights.inputs", &inputs).unwrap();
    let k = scene.lights.len() as u32;
    let stride = 2 + 2 * k as usize;
    let out = gpu.output::<Vec4>("lights.results", n as usize * stride);
    gpu.run(
        &p,
        &[
            ("scene_lights", (&images.lights).into()),
            ("scene", (&info).into()),
            ("inputs", (&inb).into()),
            ("results", (&out).into()),
        ],
        bytemuck::bytes_of(&[n, k]),
        [groups_for(n, 64), 1, 1],
    );
    let got = out.read::<Vec4>().unwrap();
    // Tolerances: the twins run the same f32 operations, but GLSL's sin, cos, atan and acos
    // (llvmpipe's polynomial approximations) differ from Rust's libm by a few ulp; the CDF
    // search sees identical inputs and tables, so it picks the same texel.
    for (q, r) in centres.iter().zip(got.chunks(stride)) {
        let (t, d, p, u) = *q;
        let (wi, pdf) = tables.sample(u, rot);
        assert!(
            (r[0].truncate() - wi).length() < 2e-5,
            "sample {u}: {} vs {wi}",
            r[0]
        );
        assert!(
            (r[0].w - pdf).abs() <= 1e-4 * pdf,
            "pdf {u}: {} vs {pdf}",
            r[0].w
        );
        assert_eq!((r[1].x as u32, r[1].y as u32), t, "texel of {d}");
        let want = tables.pdf(d, rot);
        assert!(
            (r[1].z - want).abs() <= 1e-4 * want,
            "env_pdf {d}: {} vs {want}",
            r[1].z
        );
        for (j, l) in scene.lights.iter().enumerate() {
            let (wi, dist, e) = l.incident(p);
            let (gw, ge) = (r[2 + 2 * j], r[3 + 2 * j]);
            assert!(
                (gw.truncate() - wi).length() < 1e-5,
                "light {j} at {p}: {gw} vs {wi}"
            );
            let dist = if dist.is_finite() { dist } else { 1e30 };
            assert!((gw.w - dist).abs() <= 1e-5 * dist, "light {j} distance");
            assert!(
                (ge.truncate() - e).length() <= 1e-5 * e.length().max(1e-3),
                "light {j} at {p}: {ge} vs {e}"
            );
        }
    }
}
