//! The CPU BVH intersector equals brute force over all triangles.

mod common;

use blueshift_scene::presets::{PRESETS, write_preset};
use blueshift_scene::{Aabb, Ray, Scene, SceneGpu, intersect_triangle};
use common::{Rng, load, random_rays, triangle_soup};
use glam::Vec3;

/// Compares BVH and brute force on every ray; returns the number of rays that hit.
fn compare(gpu: &SceneGpu, rays: &[Ray]) -> usize {
    let bvh_hits = gpu.trace_rays(rays);
    let mut hits = 0;
    for (k, (ray, bvh)) in rays.iter().zip(&bvh_hits).enumerate() {
        let brute = gpu.closest_hit_brute_force(ray);
        assert_eq!(*bvh, brute, "ray {k}: {ray:?}");
        assert_eq!(
            gpu.occluded(ray),
            brute.is_some(),
            "occlusion of ray {k}: {ray:?}"
        );
        if let Some(h) = brute {
            hits += 1;
            assert!(h.t >= ray.tmin && h.t <= ray.tmax);
            let again = intersect_triangle(ray, &gpu.triangles[h.triangle as usize], ray.tmax);
            assert_eq!(again, Some((h.t, h.u, h.v)));
        }
    }
    hits
}

#[test]
fn bvh_equals_brute_force_on_presets() {
    let dir = tempfile::tempdir().unwrap();
    for (i, name) in PRESETS.iter().enumerate() {
        let scene = load(&write_preset(name, dir.path()).unwrap()).unwrap();
        let gpu = SceneGpu::build(&scene);
        let b = scene.bounds();
        let mut rays = random_rays(10_000, b.min, b.max, 100 + i as u64);
        // Camera rays too: the views the renderer actually traces.
        let basis = scene.camera_or_default().basis(1.0);
        for y in 0..32 {
            for x in 0..32 {
                rays.push(basis.primary_ray(x, y, 32, 32));
            }
        }
        let hits = compare(&gpu, &rays);
        assert!(hits > rays.len() / 4, "{name}: only {hits} hits");
    }
}

#[test]
fn bvh_equals_brute_force_on_triangle_soup() {
    let tris = triangle_soup(3000, 4.0, 0.3, 9);
    let gpu = SceneGpu::build(&Scene::from_triangles(tris.iter().copied()));
    gpu.bvh()
        .validate(
            &(0..tris.len())
                .map(|i| Aabb::from_points(&tris[i]))
                .collect::<Vec<_>>(),
        )
        .unwrap();
    let rays = random_rays(10_000, Vec3::splat(-2.0), Vec3::splat(2.0), 5);
    let hits = compare(&gpu, &rays);
    assert!(hits > 2000, "only {hits} hits");
}

#[test]
fn shared_edges_and_grazing_rays_agree() {
    // Rays aimed exactly at the shared diagonal and the outer edges of quads.
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write_preset("cornell-box", dir.path()).unwrap()).unwrap();
    let gpu = SceneGpu::build(&scene);
    let mut rng = Rng::new(77);
    let mut rays = Vec::new();
    for _ in 0..5000 {
        let s = rng.range(-1.0, 1.0);
        let targets = [
            Vec3::new(s, s, -1.0),   // back wall diagonal
            Vec3::new(s, -1.0, s),   // floor diagonal
            Vec3::new(1.0, s, -1.0), // corner edges
            Vec3::new(s, -1.0, -1.0),
        ];
        let t = targets[(rng.next_u64() % 4) as usize];
        let o = Vec3::new(
            rng.range(-0.9, 0.9),
            rng.range(-0.9, 0.9),
            rng.range(-0.9, 3.0),
        );
        rays.push(Ray::new(o, t - o, 0.0, f32::MAX));
    }
    compare(&gpu, &rays);
}

#[test]
fn trace_rays_raw_encodes_misses() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write_preset("edges", dir.path()).unwrap()).unwrap();
    let gpu = SceneGpu::build(&scene);
    let away = Ray::new(Vec3::new(0.0, 100.0, 0.0), Vec3::Y, 0.0, 7.0);
    let raw = gpu.trace_rays_raw(&[away]);
    assert!(raw[0].is_miss() && raw[0].t == 7.0 && raw[0].u == 0.0);
    assert_eq!(gpu.occluded_rays(&[away]), vec![0]);
    // A shadow ray stopping short of the floor is not occluded; one reaching it is.
    let down = |tmax| Ray::new(Vec3::new(0.0, 3.0, 2.5), Vec3::NEG_Y, 0.0, tmax);
    assert!(!gpu.occluded(&down(2.9)));
    assert!(gpu.occluded(&down(3.1)));
}
