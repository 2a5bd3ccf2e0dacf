//! Bundled presets: load back, have lights and a camera, valid BVH, deterministic bytes.

mod common;

use blueshift_scene::presets::{PRESETS, preset_bytes, write_preset};
use blueshift_scene::{Aabb, SceneGpu};
use common::load;
use glam::Vec3;

#[test]
fn every_preset_loads_with_lights_camera_and_valid_bvh() {
    let dir = tempfile::tempdir().unwrap();
    for name in PRESETS {
        let path = write_preset(name, dir.path()).unwrap();
        assert_eq!(path, dir.path().join(format!("{name}.gltf")));
        let scene = load(&path).unwrap();
        assert!(scene.warnings.is_empty(), "{name}: {:?}", scene.warnings);
        assert!(scene.camera.is_some(), "{name} has no camera");
        let gpu = SceneGpu::build(&scene);
        assert!(!gpu.lights.is_empty(), "{name} has no emissive triangles");
        assert!(gpu.info.total_light_power > 0.0);
        let bounds: Vec<Aabb> = scene
            .triangles
            .iter()
            .map(|t| Aabb::from_points(&t.positions))
            .collect();
        gpu.bvh().validate(&bounds).unwrap();
        gpu.check_limits(128 << 20).unwrap();
        // No stray temporary file is left behind.
        assert!(!dir.path().join(format!(".{name}.gltf.tmp")).exists());
    }
}

#[test]
fn preset_bytes_are_deterministic() {
    for name in PRESETS {
        assert_eq!(preset_bytes(name).unwrap(), preset_bytes(name).unwrap());
    }
}

#[test]
fn cornell_box_matches_mitsuba() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write_preset("cornell-box", dir.path()).unwrap()).unwrap();
    // 5 walls + light (2 triangles each) + 2 cubes (12 each).
    assert_eq!(scene.triangles.len(), 6 * 2 + 2 * 12);
    let b = scene.bounds();
    // Mitsuba's large box reaches 1 cm below the floor.
    assert!(
        (b.min - Vec3::new(-1.0, -1.01, -1.0)).abs().max_element() < 1e-6,
        "{b:?}"
    );
    assert!(
        (b.max - Vec3::splat(1.0)).abs().max_element() < 1e-6,
        "{b:?}"
    );

    let cam = scene.camera.unwrap();
    assert!((cam.position - Vec3::new(0.0, 0.0, 3.9)).length() < 1e-6);
    assert!((cam.yfov.to_degrees() - 39.3077).abs() < 1e-4);
    assert!(((cam.target - cam.position).normalize() - Vec3::NEG_Z).length() < 1e-6);
    assert_eq!(scene.environment, Vec3::ZERO);

    let light = scene
        .materials
        .iter()
        .find(|m| m.name.as_deref() == Some("light"))
        .unwrap();
    assert!(
        (light.emissive - Vec3::new(18.387, 13.9873, 6.75357))
            .abs()
            .max_element()
            < 1e-4
    );
    let white = scene
        .materials
        .iter()
        .find(|m| m.name.as_deref() == Some("white"))
        .unwrap();
    assert_eq!(white.base_color, [0.885809, 0.698859, 0.666422, 1.0]);
    assert_eq!((white.metallic, white.roughness), (0.0, 1.0));

    // The light: 0.46 x 0.38 at y = 0.99, facing down.
    let lights: Vec<_> = scene
        .triangles
        .iter()
        .filter(|t| scene.materials[t.material as usize].emissive != Vec3::ZERO)
        .collect();
    assert_eq!(lights.len(), 2);
    let mut lb = Aabb::EMPTY;
    for t in &lights {
        t.positions.iter().for_each(|p| lb.grow_point(*p));
        let face = (t.positions[1] - t.positions[0]).cross(t.positions[2] - t.positions[0]);
        assert!(face.normalize().dot(Vec3::NEG_Y) > 0.9999);
    }
    let expect_min = Vec3::new(-0.23, 0.99, -0.18);
    let expect_max = Vec3::new(0.23, 0.99, 0.2);
    assert!((lb.min - expect_min).abs().max_element() < 1e-6, "{lb:?}");
    assert!((lb.max - expect_max).abs().max_element() < 1e-6, "{lb:?}");

    // The small box: 0.6 wide, sitting on the floor (y from -1.0 to -0.4).
    // Triangles follow node order: light, 5 walls, small box, large box.
    let (mut small, mut large) = (Aabb::EMPTY, Aabb::EMPTY);
    for (i, t) in scene.triangles.iter().enumerate().skip(12) {
        let target = if i < 24 { &mut small } else { &mut large };
        t.positions.iter().for_each(|p| target.grow_point(*p));
    }
    assert!(
        (small.min.y + 1.0).abs() < 1e-6 && (small.max.y + 0.4).abs() < 1e-6,
        "{small:?}"
    );
    assert!(
        (large.min.y + 1.01).abs() < 1e-6 && (large.max.y - 0.21).abs() < 1e-6,
        "{large:?}"
    );
}

#[test]
fn textured_preset_has_textures_and_environment() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write_preset("textured", dir.path()).unwrap()).unwrap();
    assert_eq!(scene.images.len(), 4);
    assert!(
        scene
            .materials
            .iter()
            .any(|m| m.metallic_roughness_texture.is_some())
    );
    assert_eq!(scene.environment, Vec3::new(0.25, 0.3, 0.4));
    let gpu = SceneGpu::build(&scene);
    let texels: u32 = gpu.textures.iter().map(|t| t.width * t.height).sum();
    assert_eq!(texels as usize, gpu.atlas.len());
}

#[test]
fn edges_preset_uses_a_node_hierarchy() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load(&write_preset("edges", dir.path()).unwrap()).unwrap();
    // 21 posts + 2 rails + 5 slats (12 triangles each), 4 columns, wall, floor, light.
    assert_eq!(scene.triangles.len(), (28 + 4) * 12 + 3 * 2);
    // Posts are children of the fence node translated by z = 0.2.
    let post_z: Vec<f32> = scene
        .triangles
        .iter()
        .take(21 * 12)
        .flat_map(|t| t.positions.map(|p| p.z))
        .collect();
    assert!(
        post_z.iter().all(|z| (z - 0.2).abs() <= 0.0151),
        "{post_z:?}"
    );
}
