//! Exact duplicate triangles are dropped at load with one warning, and only exact ones: the
//! copies a ray would otherwise test one by one (tests/data/coincident_primitives_20k.gltf,
//! 20,000 primitives drawing one triangle, was refused by the trace pass's loop guard).

mod common;

use blueshift_scene::presets::{GltfBuilder, MeshData};
use blueshift_scene::{LoadOptions, Scene, SceneGpu};
use common::{load, triangle_soup, write, write_json};
use glam::Vec3;
use serde_json::{Value, json};

const SEED: &[u8] = include_bytes!("data/coincident_primitives_20k.gltf");

fn seed_json() -> Value {
    serde_json::from_slice(SEED).expect("the seed is JSON")
}

#[test]
fn the_coincident_primitives_seed_loads_one_triangle_with_one_warning() {
    let dir = tempfile::tempdir().expect("tempdir");
    let doc = seed_json();
    let primitives = doc["meshes"][0]["primitives"]
        .as_array()
        .map_or(0, Vec::len);
    assert_eq!(primitives, 20_000);
    let scene = load(&write(dir.path(), "seed.gltf", SEED)).expect("the seed loads");
    assert_eq!(scene.triangles.len(), 1);
    let dropped: Vec<_> = scene
        .warnings
        .iter()
        .filter(|w| w.contains("duplicate triangles dropped"))
        .collect();
    assert_eq!(dropped.len(), 1, "{:?}", scene.warnings);
    assert!(dropped[0].starts_with("19,999 duplicate"), "{}", dropped[0]);
    assert_eq!(
        scene.environment,
        Vec3::ONE,
        "the environment is still read"
    );
}

#[test]
fn coincident_triangles_of_different_materials_are_all_kept() {
    // Which copy shows depends on the tie-break: none is a duplicate. (This scene still
    // reaches the trace pass's loop guard; see docs/errors.md.)
    let dir = tempfile::tempdir().expect("tempdir");
    let mut doc = seed_json();
    let n = 2_000;
    doc["meshes"][0]["primitives"] = (0..n)
        .map(|i| json!({ "attributes": { "POSITION": 0 }, "material": i }))
        .collect();
    doc["materials"] = (0..n)
        .map(|i| json!({ "pbrMetallicRoughness": { "roughness": i as f64 / n as f64 } }))
        .collect();
    let scene = load(&write_json(dir.path(), "materials.gltf", &doc)).expect("loads");
    assert_eq!(scene.triangles.len(), n);
    assert!(
        scene.warnings.iter().all(|w| !w.contains("duplicate")),
        "{:?}",
        scene.warnings
    );
}

/// One mesh of one triangle drawn by a node per translation.
fn instances(translations: &[[f64; 3]]) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mesh = MeshData {
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        ..MeshData::default()
    };
    let mesh = b.add_mesh("tri", &mesh, None);
    for t in translations {
        let n = b.add_node(json!({ "mesh": mesh, "translation": t }));
        b.add_root(n);
    }
    b.to_gltf_embedded()
}

#[test]
fn copies_are_found_in_world_space() {
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let load = |bytes: &[u8]| Scene::from_slice(bytes, None, &options).expect("loads");
    // Two nodes drawing the mesh at the same place: one copy. Apart: two triangles.
    let same = load(&instances(&[
        [0.0, 0.0, 2.0],
        [0.0, 0.0, 2.0],
        [0.0, 0.0, 2.0],
    ]));
    assert_eq!(same.triangles.len(), 1);
    assert!(same.warnings.iter().any(|w| w.starts_with("2 duplicate")));
    let apart = load(&instances(&[[0.0, 0.0, 2.0], [0.0, 0.0, 3.0]]));
    assert_eq!(apart.triangles.len(), 2);
    assert!(apart.warnings.iter().all(|w| !w.contains("duplicate")));
}

#[test]
fn dropping_copies_leaves_every_hit_the_same() {
    // Random triangles, then copies of every third one: the closest hit of every ray has the
    // same distance, barycentrics and triangle (by its vertices) with and without the copies.
    let unique = triangle_soup(300, 4.0, 0.6, 7);
    let mut with_copies = unique.clone();
    with_copies.extend(unique.iter().step_by(3).copied());
    with_copies.extend(unique.iter().step_by(3).copied());
    let a = SceneGpu::build(&Scene::from_triangles(unique));
    let b = SceneGpu::build(&Scene::from_triangles(with_copies));
    let rays = common::random_rays(4000, Vec3::splat(-2.0), Vec3::splat(2.0), 11);
    let mut hits = 0;
    for ray in &rays {
        let (ha, hb) = (a.closest_hit(ray), b.closest_hit(ray));
        match (ha, hb) {
            (Some(x), Some(y)) => {
                hits += 1;
                assert_eq!((x.t, x.u, x.v), (y.t, y.u, y.v), "{ray:?}");
                let (ta, tb) = (
                    a.triangles[x.triangle as usize],
                    b.triangles[y.triangle as usize],
                );
                assert_eq!((ta.v0, ta.e1, ta.e2), (tb.v0, tb.e1, tb.e2), "{ray:?}");
            }
            (None, None) => {}
            other => panic!("{ray:?}: {other:?}"),
        }
    }
    assert!(hits > 400, "only {hits} of the rays hit");
}
