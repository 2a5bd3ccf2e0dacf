//! Lighting end to end on lavapipe: environment maps (a furnace against the constant
//! environment, importance sampling against BRDF sampling, the map's orientation) and punctual
//! lights against their closed forms; seeds stay a permutation with all of it on.
use crate::Gpu;
use crate::lights_twin::test_map;
use crate::trace::{assets, mean_center, scene, sphere};
use blueshift_render::{Method, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::{
    Camera, EnvMap, EnvSampling, LightKind, Material, PunctualLight, Scene, Triangle,
};
use glam::{Vec2, Vec3};
use std::sync::Arc;

fn lambert(albedo: f32) -> Material {
    Material {
        base_color: [albedo, albedo, albedo, 1.0],
        metallic: 0.0,
        roughness: 1.0,
        specular: 0.0,
        ..Material::default()
    }
}

/// The square `|x|, |z| <= half` at y = 0, facing +Y.
fn plane(half: f32) -> Vec<Triangle> {
    let q = [
        Vec3::new(-half, 0.0, -half),
        Vec3::new(-half, 0.0, half),
        Vec3::new(half, 0.0, half),
        Vec3::new(half, 0.0, -half),
    ];
    [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
        .map(|positions| Triangle {
            positions,
            normals: [Vec3::Y; 3],
            uvs: [Vec2::ZERO; 3],
            material: 0,
        })
        .to_vec()
}

fn with_map(mut s: Scene, map: EnvMap, sampling: EnvSampling) -> Scene {
    s.environment_map = Some(Arc::new(map));
    s.environment_sampling = sampling;
    s
}

fn render(gpu: &Gpu, s: &Scene, cfg: RenderConfig, frames: u32) -> Vec<[f32; 4]> {
    let mut r = Renderer::new(gpu.dev(), s, &assets(), cfg).unwrap();
    for _ in 0..frames {
        r.render_frame().unwrap();
    }
    r.read_accum().unwrap()
}

fn sphere_scene() -> Scene {
    let cam = Camera {
        position: Vec3::new(0.0, 0.0, 4.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        yfov: 0.5,
    };
    scene(sphere(0, 32, 64), vec![lambert(1.0)], Vec3::ZERO, cam)
}

/// A Lambert sphere of albedo 1 reflects a uniform environment of 0.5 whether it is the
/// constant environment (BRDF sampling alone), a constant map with importance sampling and MIS,
/// or the same map without: ratios within 0.99..1.005 (the bound of the white furnace in
/// trace.rs) and within 0.5% of each other.
#[test]
fn constant_map_lights_like_the_constant_environment() {
    let gpu = Gpu::new();
    let cfg = || RenderConfig {
        spp: 64,
        bounces: 8,
        method: Method::Sobol,
        ..RenderConfig::new(48, 48)
    };
    let env = 0.5;
    let constant = Scene {
        environment: Vec3::splat(env),
        ..sphere_scene()
    };
    let map = EnvMap::constant(16, 8, Vec3::splat(env));
    let runs = [
        constant,
        with_map(sphere_scene(), map.clone(), EnvSampling::Importance),
        with_map(sphere_scene(), map, EnvSampling::Brdf),
    ]
    .map(|s| mean_center(&render(&gpu, &s, cfg(), 4), 48, 12) / env);
    for m in &runs {
        assert!(
            m.to_array().iter().all(|c| (0.99..=1.005).contains(c)),
            "furnace ratio {m}"
        );
    }
    assert!((runs[0] - runs[1]).abs().max_element() < 0.005, "{runs:?}");
    assert!((runs[1] - runs[2]).abs().max_element() < 0.005, "{runs:?}");
}

/// Importance sampling converges to the same image as uniform sampling (both next-event
/// estimation with MIS) and as BRDF sampling alone, under a map with a bright patch and a
/// black one. Tolerance: 0.5% on the mean over the sphere's centre and 4% per 4x4-pixel
/// block, about four times the largest differences measured at this sample count (importance
/// against BRDF: 0.13% and 1.3%): loose enough for Monte Carlo noise, tight enough to catch a
/// density off by a sin(theta) or a texel.
#[test]
fn importance_sampling_converges_to_uniform_and_brdf_sampling() {
    let gpu = Gpu::new();
    let cfg = || RenderConfig {
        spp: 128,
        bounces: 2,
        method: Method::Sobol,
        ..RenderConfig::new(32, 32)
    };
    let mut s = sphere_scene();
    s.materials = vec![lambert(0.8)];
    let run = |how| render(&gpu, &with_map(s.clone(), test_map(32, 16), how), cfg(), 8);
    let is = run(EnvSampling::Importance);
    for (name, other) in [
        ("uniform", run(EnvSampling::Uniform)),
        ("BRDF", run(EnvSampling::Brdf)),
    ] {
        let (a, b) = (mean_center(&is, 32, 8), mean_center(&other, 32, 8));
        assert!(
            ((a - b) / b).abs().max_element() < 0.005,
            "centre mean: importance {a}, {name} {b}"
        );
        for by in 2..6 {
            for bx in 2..6 {
                let block = |img: &[[f32; 4]]| {
                    let mut sum = Vec3::ZERO;
                    for y in by * 4..by * 4 + 4 {
                        for x in bx * 4..bx * 4 + 4 {
                            let p = img[y * 32 + x];
                            sum += Vec3::new(p[0], p[1], p[2]);
                        }
                    }
                    sum / 16.0
                };
                let (a, b) = (block(&is), block(&other));
                assert!(
                    ((a - b) / b).abs().max_element() < 0.04,
                    "block {bx},{by}: importance {a}, {name} {b}"
                );
            }
        }
    }
}

/// The documented orientation: with +Y up, the map's left half (u < 0.5) lies towards -X and
/// its right half towards +X; a rotation of 180 degrees swaps them.
#[test]
fn map_halves_face_the_documented_directions() {
    let gpu = Gpu::new();
    let (red, blue) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
    let mut map = EnvMap::constant(8, 4, red);
    for j in 0..4 {
        for i in 4..8 {
            map.texels[j * 8 + i] = blue;
        }
    }
    let look = |towards: Vec3, rotation_deg: f32| {
        let cam = Camera {
            position: Vec3::ZERO,
            target: towards,
            up: Vec3::Y,
            yfov: 0.3,
        };
        // One small triangle behind the camera: the scene must have geometry.
        let tri = plane(0.01)
            .into_iter()
            .map(|mut t| {
                t.positions = t.positions.map(|p| p - towards * 5.0);
                t
            })
            .collect();
        let mut m = map.clone();
        m.rotation = rotation_deg.to_radians();
        let s = with_map(
            scene(tri, vec![lambert(0.5)], Vec3::ZERO, cam),
            m,
            EnvSampling::Importance,
        );
        let cfg = RenderConfig {
            method: Method::White,
            ..RenderConfig::new(8, 8)
        };
        mean_center(&render(&gpu, &s, cfg, 1), 8, 4)
    };
    assert_eq!(look(Vec3::NEG_X, 0.0), red);
    assert_eq!(look(Vec3::X, 0.0), blue);
    assert_eq!(look(Vec3::NEG_X, 180.0), blue);
    assert_eq!(look(Vec3::X, 180.0), red);
}

/// A camera high above the plane looking straight down, pixel-centre rays, direct light only.
fn lit_plane(gpu: &Gpu, light: PunctualLight, yfov: f32, size: u32) -> (Vec<[f32; 4]>, Camera) {
    let cam = Camera {
        position: Vec3::new(0.0, 4.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::Z,
        yfov,
    };
    let mut s = scene(plane(50.0), vec![lambert(1.0)], Vec3::ZERO, cam);
    s.lights = vec![light];
    let cfg = RenderConfig {
        bounces: 1,
        method: Method::White,
        no_jitter: true,
        ..RenderConfig::new(size, size)
    };
    (render(gpu, &s, cfg, 1), cam)
}

/// Where pixel (x, y)'s centre ray meets the plane.
fn plane_point(cam: &Camera, x: u32, y: u32, size: u32) -> Vec3 {
    let ray = cam.basis(1.0).primary_ray(x, y, size, size);
    ray.origin + ray.dir * (-ray.origin.y / ray.dir.y)
}

/// A point light of intensity I at height h over a Lambertian plane of albedo 1: radiance
/// I / (pi h^2) right below it (the centre pixels, within 0.01 degrees of the vertical).
#[test]
fn point_light_follows_the_inverse_square_law() {
    let gpu = Gpu::new();
    let (i, h) = (Vec3::new(2.0, 3.0, 0.5), 1.5);
    let light = PunctualLight {
        kind: LightKind::Point,
        position: Vec3::new(0.0, h, 0.0),
        direction: Vec3::NEG_Y,
        intensity: i,
    };
    let (img, _) = lit_plane(&gpu, light, 0.001, 16);
    let want = i / (std::f32::consts::PI * h * h);
    let got = mean_center(&img, 16, 2);
    assert!(
        ((got - want) / want).abs().max_element() < 1e-4,
        "{got} vs {want}"
    );
}

/// A spot light: exactly zero outside its outer cone; inside the inner cone the point light's
/// I cos^3(theta) / (pi h^2).
#[test]
fn spot_light_is_zero_outside_its_outer_cone() {
    let gpu = Gpu::new();
    let (inner, outer, h) = (0.3f32, 0.5f32, 1.0f32);
    let light = PunctualLight {
        kind: LightKind::Spot { inner, outer },
        position: Vec3::new(0.0, h, 0.0),
        direction: Vec3::NEG_Y,
        intensity: Vec3::splat(4.0),
    };
    let size = 48;
    let (img, cam) = lit_plane(&gpu, light, 1.2, size);
    let (mut outside, mut inside) = (0, 0);
    for y in 0..size {
        for x in 0..size {
            let p = plane_point(&cam, x, y, size);
            let theta = (p.x.hypot(p.z) / h).atan();
            let l = img[(y * size + x) as usize][0];
            if theta > outer + 0.01 {
                assert_eq!(l, 0.0, "pixel {x},{y} at {theta} rad");
                outside += 1;
            } else if theta < inner - 0.01 {
                let want = 4.0 * theta.cos().powi(3) / (std::f32::consts::PI * h * h);
                assert!(
                    (l - want).abs() < 1e-3 * want,
                    "pixel {x},{y}: {l} vs {want}"
                );
                inside += 1;
            }
        }
    }
    assert!(
        outside > 100 && inside > 20,
        "{outside} outside, {inside} inside"
    );
}

/// A directional light of irradiance E at theta from the normal: E cos(theta) / pi everywhere.
#[test]
fn directional_light_gives_e_cos_theta_over_pi() {
    let gpu = Gpu::new();
    let theta = 60f32.to_radians();
    let e = Vec3::new(2.0, 1.0, 0.5);
    let light = PunctualLight {
        kind: LightKind::Directional,
        position: Vec3::ZERO,
        direction: Vec3::new(theta.sin(), -theta.cos(), 0.0),
        intensity: e,
    };
    let (img, _) = lit_plane(&gpu, light, 0.8, 16);
    let want = e * theta.cos() / std::f32::consts::PI;
    for p in img {
        let got = Vec3::new(p[0], p[1], p[2]);
        assert!(
            ((got - want) / want).abs().max_element() < 1e-4,
            "{got} vs {want}"
        );
    }
}

/// Seeds stay a permutation under the default and the paper's method with a map and a
/// punctual light added to the Cornell box.
#[test]
fn seeds_stay_a_permutation_with_maps_and_punctual_lights() {
    let gpu = Gpu::new();
    let mut s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    s.environment_map = Some(Arc::new(test_map(16, 8)));
    s.lights.push(PunctualLight {
        kind: LightKind::Point,
        position: Vec3::new(0.0, 1.0, 0.0),
        direction: Vec3::NEG_Y,
        intensity: Vec3::ONE,
    });
    for method in ["sort-cycle", "sort-retarget"] {
        let cfg = RenderConfig {
            bounces: 2,
            method: method.parse().unwrap(),
            ..RenderConfig::new(40, 24)
        };
        let mut r = Renderer::new(gpu.dev(), &s, &assets(), cfg).unwrap();
        let init = r.initial_seeds().to_vec();
        for _ in 0..4 {
            r.render_frame().unwrap();
            assert!(blueshift_permute::is_permutation_of(
                &r.read_seeds().unwrap(),
                &init
            ));
        }
        assert_ne!(r.read_seeds().unwrap(), init, "{method}: seeds never moved");
    }
}
