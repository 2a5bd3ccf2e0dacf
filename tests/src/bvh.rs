//! GPU BVH traversal (shaders/include/bvh.glsl) == CPU traversal (blueshift-scene) on random
//! and camera rays over every bundled scene, a random-triangle soup and a quad.
use crate::{Gpu, groups_for};
use blueshift_device::Binding;
use blueshift_device::Buffer;
use blueshift_sampling::rng::{hash3, to_unit};
use blueshift_scene::{Hit, Ray, Scene, SceneGpu};
use glam::Vec3;

fn rand3(i: u32, k: u32) -> Vec3 {
    Vec3::new(
        to_unit(hash3(i, k, 1)),
        to_unit(hash3(i, k, 2)),
        to_unit(hash3(i, k, 3)),
    )
}

/// Random rays from points in the (slightly enlarged) bounds in random directions, plus one
/// camera ray per pixel of a 64x64 image.
fn rays(scene: &Scene, n: u32) -> Vec<Ray> {
    let b = scene.bounds();
    let (lo, ext) = (b.min - 0.1 * (b.max - b.min), 1.2 * (b.max - b.min));
    let mut v: Vec<Ray> = (0..n)
        .map(|i| {
            let o = lo + rand3(i, 0) * ext;
            let d = (rand3(i, 1) * 2.0 - 1.0).normalize_or(Vec3::X);
            Ray::new(
                o,
                d,
                0.0,
                if i % 3 == 0 {
                    1e30
                } else {
                    ext.length() * to_unit(hash3(i, 7, 7))
                },
            )
        })
        .collect();
    let cam = scene.camera_or_default().basis(1.0);
    v.extend((0..64 * 64).map(|p| cam.primary_ray(p % 64, p / 64, 64, 64)));
    v
}

/// `n` random small triangles in a 10^3 box, as an in-memory scene.
fn soup(n: u32) -> Scene {
    Scene::from_triangles((0..n).map(|i| {
        let c = rand3(i, 11) * 10.0;
        [0, 1, 2].map(|k| c + rand3(i * 3 + k, 12) - 0.5)
    }))
}

fn check(gpu: &mut Gpu, name: &str, scene: &Scene, n: u32) {
    let g = SceneGpu::build(scene);
    let rays = rays(scene, n);
    let dev = gpu.dev().clone();
    let nodes = Buffer::from_slice(&dev, "bvh.nodes", &g.nodes).unwrap();
    let tris = Buffer::from_slice(&dev, "bvh.triangles", &g.triangles).unwrap();
    let rb = Buffer::from_slice(&dev, "bvh.rays", &rays).unwrap();
    let hits = gpu.output::<Hit>("bvh.hits", rays.len());
    let occ = gpu.output::<u32>("bvh.occluded", rays.len());
    let p = gpu.pipeline(
        "test/bvh_trace",
        &[
            Binding::storage(0, "bvh_nodes"),
            Binding::storage(1, "bvh_triangles"),
            Binding::storage(2, "rays"),
            Binding::storage(3, "hits"),
            Binding::storage(4, "occluded"),
        ],
        4,
    );
    let count = rays.len() as u32;
    gpu.run(
        &p,
        &[
            ("bvh_nodes", (&nodes).into()),
            ("bvh_triangles", (&tris).into()),
            ("rays", (&rb).into()),
            ("hits", (&hits).into()),
            ("occluded", (&occ).into()),
        ],
        bytemuck::bytes_of(&count),
        [groups_for(count, 64), 1, 1],
    );
    let got_hits = hits.read::<Hit>().unwrap();
    let got_occ = occ.read::<u32>().unwrap();
    let want_hits = g.trace_rays_raw(&rays);
    let want_occ = g.occluded_rays(&rays);
    let mut hit_count = 0;
    for i in 0..rays.len() {
        // Same operation order on both sides (`precise` in GLSL, no FMA in Rust): exact.
        assert_eq!(got_hits[i], want_hits[i], "{name}: ray {i} {:?}", rays[i]);
        assert_eq!(got_occ[i], want_occ[i], "{name}: occlusion of ray {i}");
        hit_count += usize::from(!want_hits[i].is_miss());
    }
    // The test must exercise hits, not only misses.
    assert!(hit_count > rays.len() / 10, "{name}: only {hit_count} hits");
}

#[test]
fn gpu_traversal_matches_cpu_on_bundled_scenes_and_a_soup() {
    let mut gpu = Gpu::new();
    let dir = blueshift_render::default_assets_dir().join("scenes");
    for name in ["cornell-box", "textured", "edges"] {
        let scene = Scene::load(dir.join(format!("{name}.gltf"))).unwrap();
        check(&mut gpu, name, &scene, 30_000);
    }
    check(&mut gpu, "soup", &soup(3000), 30_000);
    // A root that is a leaf (the stackless occlusion must test it too): a quad.
    let mut quad = soup(2);
    let c = [Vec3::ZERO, Vec3::X, Vec3::ONE.with_z(0.0), Vec3::Y];
    quad.triangles[0].positions = [c[0], c[1], c[2]];
    quad.triangles[1].positions = [c[0], c[2], c[3]];
    assert_eq!(SceneGpu::build(&quad).nodes.len(), 1);
    check(&mut gpu, "quad", &quad, 1_000);
}
