//! Loading good files: hierarchy transforms, generated normals, GLB, external buffers,
//! materials, textures, cameras, environment, warnings for unsupported content.

mod common;

use blueshift_scene::presets::GltfBuilder;
use blueshift_scene::{LIGHT_TRIANGLE_MASK, LoadOptions, QuadFrame, Scene, SceneGpu};
use common::{embedded_uri, emissive_material, load, one_quad, quad, write, write_json};
use glam::Vec3;
use serde_json::{Value, json};

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

#[test]
fn node_hierarchy_transforms_compose() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("quad", &quad(true), None);
    // child: rotate 90 deg about y, then parent: scale 2 then translate (10, 0, 0).
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let child = b.add_node(json!({ "mesh": mesh, "rotation": [0.0, s, 0.0, s] }));
    let parent = b.add_node(json!({
        "children": [child], "translation": [10.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0]
    }));
    b.add_root(parent);
    let scene = load(&write(dir.path(), "tree.gltf", &b.to_gltf_embedded())).unwrap();
    assert_eq!(scene.triangles.len(), 2);
    let t = &scene.triangles[0];
    // Local (-1,-1,0) -> rotated (0,-1,1) -> scaled (0,-2,2) -> translated (10,-2,2).
    assert!(
        close(t.positions[0], Vec3::new(10.0, -2.0, 2.0)),
        "{:?}",
        t.positions
    );
    // Normal +z rotated about y by 90 degrees is +x, still unit length after the scale.
    assert!(close(t.normals[0], Vec3::X), "{:?}", t.normals);
}

#[test]
fn matrix_nodes_and_non_uniform_scale_use_inverse_transpose() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    // A tilted quad: normal (0, 1, 1)/sqrt2 in local space.
    let mut m = quad(true);
    m.positions = vec![
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
    ];
    let n = std::f32::consts::FRAC_1_SQRT_2;
    m.normals = Some(vec![[0.0, n, n]; 4]);
    let mesh = b.add_mesh("tilted", &m, None);
    // Scale y by 4 as a column-major matrix.
    let node = b.add_node(json!({
        "mesh": mesh,
        "matrix": [1.0,0.0,0.0,0.0, 0.0,4.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0]
    }));
    b.add_root(node);
    let scene = load(&write(dir.path(), "matrix.gltf", &b.to_gltf_embedded())).unwrap();
    let t = &scene.triangles[0];
    let face = (t.positions[1] - t.positions[0])
        .cross(t.positions[2] - t.positions[0])
        .normalize();
    // The transformed shading normal stays perpendicular to the transformed surface.
    assert!(
        close(t.normals[0], face),
        "normal {:?} face {face}",
        t.normals[0]
    );
}

#[test]
fn mirroring_transform_keeps_front_face() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("quad", &quad(false), None);
    let node = b.add_node(json!({ "mesh": mesh, "scale": [-1.0, 1.0, 1.0] }));
    b.add_root(node);
    let scene = load(&write(dir.path(), "mirror.gltf", &b.to_gltf_embedded())).unwrap();
    for t in &scene.triangles {
        let face = (t.positions[1] - t.positions[0]).cross(t.positions[2] - t.positions[0]);
        assert!(face.z > 0.0, "winding must be flipped under mirroring");
        assert!(close(t.normals[0], Vec3::Z));
    }
}

#[test]
fn flat_normals_are_generated_when_missing() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("quad", &quad(false), None);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let node = b.add_node(json!({ "mesh": mesh, "rotation": [s, 0.0, 0.0, s] }));
    b.add_root(node);
    let scene = load(&write(dir.path(), "nonormals.gltf", &b.to_gltf_embedded())).unwrap();
    for t in &scene.triangles {
        // +z rotated 90 degrees about x is -y.
        for n in t.normals {
            assert!(close(n, Vec3::NEG_Y), "{n}");
        }
    }
}

#[test]
fn glb_loads() {
    let dir = tmp();
    let p = write(dir.path(), "quad.glb", &one_quad().to_glb());
    let scene = load(&p).unwrap();
    assert_eq!(scene.triangles.len(), 2);
    assert!(close(scene.materials[0].emissive, Vec3::new(4.0, 2.0, 1.0)));
}

#[test]
fn external_buffer_loads() {
    let dir = tmp();
    let (json, bin) = one_quad().to_gltf_external("quad.bin");
    write(dir.path(), "quad.bin", &bin);
    let scene = load(&write(dir.path(), "quad.gltf", &json)).unwrap();
    assert_eq!(scene.triangles.len(), 2);
}

#[test]
fn non_indexed_geometry() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mut m = quad(true);
    m.indices = None;
    m.positions.truncate(3);
    m.normals = None;
    m.uvs = None;
    let mesh = b.add_mesh("tri", &m, None);
    let node = b.add_node(json!({ "mesh": mesh }));
    b.add_root(node);
    let scene = load(&write(dir.path(), "tri.gltf", &b.to_gltf_embedded())).unwrap();
    assert_eq!(scene.triangles.len(), 1);
    // The default material (glTF spec: white, metallic 1, roughness 1) is appended.
    let mat = &scene.materials[scene.triangles[0].material as usize];
    assert_eq!(
        (mat.metallic, mat.roughness, mat.base_color),
        (1.0, 1.0, [1.0; 4])
    );
}

#[test]
fn unsupported_content_gives_one_warning_each() {
    let dir = tmp();
    let b = one_quad();
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    let prim = doc["meshes"][0]["primitives"][0].clone();
    let mut lines = prim.clone();
    lines["mode"] = json!(1);
    doc["meshes"][0]["primitives"] = json!([prim, lines.clone(), lines]);
    doc["extensionsUsed"] = json!([
        "KHR_materials_emissive_strength",
        "KHR_texture_transform",
        "EXT_fancy_thing"
    ]);
    let scene = load(&write_json(dir.path(), "mixed.gltf", &doc)).unwrap();
    assert_eq!(scene.triangles.len(), 2);
    let w = &scene.warnings;
    assert_eq!(w.iter().filter(|w| w.contains("Lines")).count(), 1, "{w:?}");
    assert!(
        w.iter()
            .any(|w| w.contains("Lines") && w.contains("2 occurrences")),
        "{w:?}"
    );
    assert!(
        w.iter().any(|w| w.contains("KHR_texture_transform")),
        "{w:?}"
    );
    assert!(w.iter().any(|w| w.contains("EXT_fancy_thing")), "{w:?}");
    assert!(!w.iter().any(|w| w.contains("emissive_strength")), "{w:?}");
}

#[test]
fn camera_environment_and_override() {
    let dir = tmp();
    let mut b = one_quad();
    let cam = b.add_camera(0.5, 1.0);
    // Camera at (0, 0, 5) rotated 180 degrees about y: looks down +z.
    let c = b.add_node(json!({ "camera": cam, "translation": [0.0, 0.0, 5.0],
                              "rotation": [0.0, 1.0, 0.0, 0.0] }));
    b.add_root(c);
    b.set_scene_extras(json!({ "blueshift_environment": [0.1, 0.2, 0.3] }));
    let p = write(dir.path(), "cam.gltf", &b.to_gltf_embedded());
    let scene = load(&p).unwrap();
    let cam = scene.camera.unwrap();
    assert!(close(cam.position, Vec3::new(0.0, 0.0, 5.0)));
    assert!(close(cam.target - cam.position, Vec3::Z));
    assert_eq!(cam.yfov, 0.5);
    assert!(close(scene.environment, Vec3::new(0.1, 0.2, 0.3)));
    let opts = LoadOptions {
        environment: Some(blueshift_scene::EnvironmentSource::Constant(Vec3::ONE)),
        quiet: true,
        ..Default::default()
    };
    assert_eq!(Scene::load_with(&p, &opts).unwrap().environment, Vec3::ONE);
}

#[test]
fn default_camera_frames_scene_without_camera() {
    let dir = tmp();
    let scene = load(&write(dir.path(), "q.gltf", &one_quad().to_gltf_embedded())).unwrap();
    assert!(scene.camera.is_none());
    let cam = scene.camera_or_default();
    assert!(cam.position.z > 1.0 && close(cam.target, Vec3::ZERO));
}

#[test]
fn textures_are_decoded_and_packed() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    // 2x2 RGBA: red, green / blue, white.
    let rgba = [
        255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255u8,
    ];
    let mut png = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut png),
        &rgba,
        2,
        2,
        image::ExtendedColorType::Rgba8,
    )
    .unwrap();
    let tex = b.add_png_texture("tiny", &png, json!({ "wrapS": 33071, "magFilter": 9728 }));
    let mat = b.add_material(json!({
        "pbrMetallicRoughness": { "baseColorTexture": { "index": tex } },
        "emissiveTexture": { "index": tex }, "emissiveFactor": [1.0, 1.0, 1.0]
    }));
    let mesh = b.add_mesh("quad", &quad(true), Some(mat));
    let n = b.add_node(json!({ "mesh": mesh }));
    b.add_root(n);
    let scene = load(&write(dir.path(), "tex.gltf", &b.to_gltf_embedded())).unwrap();
    assert_eq!(scene.images.len(), 1);
    assert_eq!(scene.images[0].rgba8, rgba.to_vec());
    let m = &scene.materials[0];
    assert_eq!(
        (m.base_color_texture, m.emissive_texture),
        (Some(0), Some(0))
    );
    let gpu = SceneGpu::build(&scene);
    assert_eq!(
        gpu.atlas.to_vec(),
        vec![0xff00_00ff, 0xff00_ff00, 0xffff_0000, 0xffff_ffff]
    );
    let t = gpu.textures[0];
    assert_eq!((t.offset, t.width, t.height), (0, 2, 2));
    assert_eq!(t.flags, 1 | 16, "clamp s, repeat t, nearest");
    // Emissive texture: light power uses the texture's mean, so both triangles are lights.
    assert_eq!(gpu.lights.len(), 2);
    assert_eq!(gpu.materials[0].base_color_tex, 0);
    assert_eq!(gpu.materials[0].mr_tex, -1);
}

#[test]
fn undecodable_image_is_a_warning() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let tex = b.add_png_texture("junk", b"not a png at all", json!({}));
    let mat = b.add_material(json!({
        "pbrMetallicRoughness": { "baseColorTexture": { "index": tex } }
    }));
    let mesh = b.add_mesh("quad", &quad(true), Some(mat));
    let n = b.add_node(json!({ "mesh": mesh }));
    b.add_root(n);
    let scene = load(&write(dir.path(), "junk.gltf", &b.to_gltf_embedded())).unwrap();
    assert_eq!(scene.materials[0].base_color_texture, None);
    assert!(
        scene.warnings.iter().any(|w| w.contains("image 0")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn light_cdf_is_power_weighted() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let bright = b.add_material(common::emissive_material(3.0));
    let dim = b.add_material(common::emissive_material(1.0));
    let m1 = b.add_mesh("bright", &quad(true), Some(bright));
    let m2 = b.add_mesh("dim", &quad(true), Some(dim));
    for (m, x) in [(m1, 0.0), (m2, 5.0)] {
        let n = b.add_node(json!({ "mesh": m, "translation": [x, 0.0, 0.0] }));
        b.add_root(n);
    }
    let scene = load(&write(dir.path(), "lights.gltf", &b.to_gltf_embedded())).unwrap();
    let gpu = SceneGpu::build(&scene);
    // Each quad is one light: its two triangles form a parallelogram.
    assert_eq!(gpu.lights.len(), 2);
    let sum: f32 = gpu.lights.iter().map(|l| l.pdf).sum();
    assert!((sum - 1.0).abs() < 1e-6);
    assert_eq!(gpu.lights.last().unwrap().cdf, 1.0);
    for w in gpu.lights.windows(2) {
        assert!(w[0].cdf <= w[1].cdf);
    }
    for (k, l) in gpu.lights.iter().enumerate() {
        assert!(QuadFrame::of_light(l.triangle).is_some(), "light {k}");
        let first = (l.triangle & LIGHT_TRIANGLE_MASK) as usize;
        let mat = gpu.shading[first].material;
        let expected = if mat == bright as u32 {
            3.0 / 4.0
        } else {
            1.0 / 4.0
        };
        assert!((l.pdf - expected).abs() < 1e-6, "light {k}: {}", l.pdf);
        let members = gpu.shading.iter().filter(|s| s.light == k as i32).count();
        assert_eq!(members, 2, "light {k}: both triangles point at it");
        assert_eq!(gpu.shading[first].light, k as i32);
        assert!((l.area - 4.0).abs() < 1e-6);
    }
    // power = luminance(emission) * area * pi; emission (1, .5, .25) * strength.
    let lum = 0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25;
    let total = lum * std::f32::consts::PI * (3.0 + 1.0) * 4.0; // two quads of area 4
    assert!((gpu.info.total_light_power - total).abs() < 1e-3 * total);
}

/// KHR_materials_specular: factors are read (clamped, non-finite -> default), its textures are
/// skipped with one warning, and materials without it keep the plain glTF dielectric (1, white).
#[test]
fn specular_extension_factors_are_read() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let tex = b.add_png_texture("junk", b"not a png at all", json!({}));
    let spec = |ext: Value| {
        let mut m = emissive_material(1.0);
        m["extensions"]["KHR_materials_specular"] = ext;
        m
    };
    let lambert = b.add_material(spec(json!({ "specularFactor": 0.0 })));
    let tinted = b.add_material(spec(json!({
        "specularFactor": 2.5,
        "specularColorFactor": [0.5, 2.0, -1.0],
        "specularTexture": { "index": tex },
        "specularColorTexture": { "index": tex }
    })));
    let plain = b.add_material(emissive_material(1.0));
    for (i, m) in [lambert, tinted, plain].into_iter().enumerate() {
        let mesh = b.add_mesh(&format!("quad{i}"), &quad(true), Some(m));
        let n = b.add_node(json!({ "mesh": mesh }));
        b.add_root(n);
    }
    let scene = load(&write(dir.path(), "spec.gltf", &b.to_gltf_embedded())).unwrap();
    let m = &scene.materials;
    assert_eq!((m[0].specular, m[0].specular_color), (0.0, Vec3::ONE));
    assert_eq!(
        (m[1].specular, m[1].specular_color),
        (1.0, Vec3::new(0.5, 2.0, 0.0))
    );
    assert_eq!((m[2].specular, m[2].specular_color), (1.0, Vec3::ONE));
    let w = &scene.warnings;
    assert_eq!(
        w.iter().filter(|w| w.contains("specular")).count(),
        1,
        "{w:?}"
    );
    assert_eq!(m[1].base_color_texture, None);
    assert!(!w.iter().any(|w| w.contains("extension")), "{w:?}");
}

/// `KHR_lights_punctual`: kinds, units (color x intensity), node transforms (position, -Z as
/// the direction), cones; a negative intensity or bad cones are
/// skipped with a warning naming the light.
#[test]
fn punctual_lights_are_read_in_world_space() {
    let dir = tmp();
    let mut b = one_quad();
    let s = std::f64::consts::FRAC_1_SQRT_2;
    // Rotated -90 degrees about x: local -Z points down (-Y).
    let down = json!([-s, 0.0, 0.0, s]);
    for (light, translation) in [
        (0, [1.0, 2.0, 3.0]),
        (1, [0.0, 4.0, 0.0]),
        (2, [9.0, 9.0, 9.0]),
    ] {
        let n = b.add_node(json!({ "translation": translation, "rotation": down,
            "extensions": { "KHR_lights_punctual": { "light": light } } }));
        b.add_root(n);
    }
    for light in [3, 4] {
        let n = b.add_node(json!({ "extensions": { "KHR_lights_punctual": { "light": light } } }));
        b.add_root(n);
    }
    let mut doc: Value = serde_json::from_slice(&b.to_gltf_embedded()).unwrap();
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "point", "color": [1.0, 0.5, 0.25], "intensity": 8.0, "range": 10.0 },
        { "type": "spot", "intensity": 2.0, "spot": { "innerConeAngle": 0.1, "outerConeAngle": 0.4 } },
        { "type": "directional", "intensity": 3.0 },
        { "type": "point", "intensity": -1.0 },
        { "type": "spot", "spot": { "innerConeAngle": 0.5, "outerConeAngle": 0.2 } },
    ] } });
    let p = write_json(dir.path(), "lights.gltf", &doc);
    let scene = load(&p).unwrap();
    use blueshift_scene::LightKind;
    let l = &scene.lights;
    assert_eq!(l.len(), 3, "{l:?}");
    assert_eq!(l[0].kind, LightKind::Point);
    assert!(close(l[0].position, Vec3::new(1.0, 2.0, 3.0)));
    assert!(close(l[0].intensity, Vec3::new(8.0, 4.0, 2.0)));
    assert_eq!(
        l[1].kind,
        LightKind::Spot {
            inner: 0.1,
            outer: 0.4
        }
    );
    assert!(close(l[1].direction, Vec3::NEG_Y));
    assert!(close(l[1].intensity, Vec3::splat(2.0)));
    assert_eq!(l[2].kind, LightKind::Directional);
    assert!(close(l[2].direction, Vec3::NEG_Y));
    let w = scene.warnings.join("\n");
    assert!(w.contains("light 3 has intensity -1"), "{w}");
    assert!(w.contains("light 4 has cone angles"), "{w}");
    assert!(w.contains("`range` is ignored"), "{w}");
    assert!(!w.contains("extension KHR_lights_punctual"), "{w}");
    assert!(scene.has_light());
}

/// A scene with nothing that emits is lit by the default environment, with one warning that
/// names --environment; a lit scene is left alone.
#[test]
fn dark_scenes_get_the_default_environment_and_one_warning() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh("quad", &quad(true), None);
    let n = b.add_node(json!({ "mesh": mesh }));
    b.add_root(n);
    let mut scene = load(&write(dir.path(), "dark.gltf", &b.to_gltf_embedded())).unwrap();
    assert!(!scene.has_light());
    let w = scene.light_if_dark().expect("a warning");
    assert!(w.contains("--environment"), "{w}");
    assert_eq!(scene.environment, blueshift_scene::DEFAULT_ENVIRONMENT);
    assert!(scene.light_if_dark().is_none());
}
