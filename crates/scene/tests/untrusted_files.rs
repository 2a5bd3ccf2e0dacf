//! Files from outside ("Untrusted files, second round"): reads outside the scene directory,
//! special files, buffers shorter or longer than declared, values that overflow f32, spec
//! violations. Each gets a clear error naming the file and the problem, or a warning and a
//! correct scene.

mod common;

use blueshift_scene::presets::GltfBuilder;
use blueshift_scene::{LoadOptions, Scene, SceneError};
use common::{assert_contains, embedded_uri, load, one_quad, write, write_json};
use serde_json::{Value, json};
use std::path::Path;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

/// How many triangles the scene at `p` has; it must load (with `options`, else quietly).
fn triangles(p: &Path, options: Option<&LoadOptions>) -> usize {
    let scene = match options {
        Some(o) => Scene::load_with(p, o),
        None => load(p),
    };
    scene.expect("the scene loads").triangles.len()
}

/// The one-quad scene's JSON, its buffer embedded.
fn quad_doc() -> Value {
    let b = one_quad();
    b.json(Some(embedded_uri(b.bin())))
}

#[test]
fn many_unsupported_extensions_are_one_warning_line() {
    let dir = tmp();
    let mut doc = quad_doc();
    let mut used: Vec<String> = (0..1000).map(|i| format!("EXT_thing_{i}")).collect();
    used.push("KHR_texture_transform".into());
    doc["extensionsUsed"] = json!(used);
    let s = load(&write_json(dir.path(), "ext.gltf", &doc)).expect("loads");
    assert_eq!(
        s.warnings,
        [
            "1,000 extensions not supported, ignored (first: EXT_thing_0)",
            "extension KHR_texture_transform ignored: textures are sampled without the transform",
        ]
    );
}

/// A quad mesh named "big" whose vertex 2 is at `corner`, under a node with `node`'s fields.
fn quad_at(corner: [f32; 3], node: Value) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mut mesh = common::quad(true);
    mesh.positions[2] = corner;
    let m = b.add_mesh("big", &mesh, None);
    let mut node = node;
    node["mesh"] = json!(m);
    let n = b.add_node(node);
    b.add_root(n);
    b.to_gltf_embedded()
}

#[test]
fn coordinates_of_1e13_or_more_are_refused_naming_mesh_and_accessor() {
    let dir = tmp();
    let far = quad_at([1e13, 1.0, 0.0], json!({}));
    let p = write(dir.path(), "far.gltf", &far);
    let e = load(&p).unwrap_err();
    let place = match &e {
        SceneError::PositionOutOfRange {
            accessor,
            vertex,
            world,
            ..
        } => (*accessor, *vertex, *world),
        _ => panic!("wrong error {e}"),
    };
    assert_eq!(place, (0, 2, false));
    let parts = [
        "far.gltf: mesh 0 ('big') primitive 0: POSITION accessor 0: vertex 2 is at \
         [10000000000000.0, 1.0, 0.0], beyond the limit of 1e13 on any coordinate",
    ];
    assert_contains(&e.to_string(), &parts);
    // Just below the limit loads.
    let p = write(
        dir.path(),
        "near.gltf",
        &quad_at([9.9e12, 1.0, 0.0], json!({})),
    );
    assert_eq!(triangles(&p, None), 2);
}

#[test]
fn an_extent_that_overflows_f32_is_named_not_called_zero_area() {
    // Finite world positions of +-2e38 once had edges of 4e38 (inf in f32): every triangle
    // was "zero-area" and the scene "had no non-zero-area triangles". Such positions are now
    // refused first, as beyond the coordinate limit after the node transform.
    let dir = tmp();
    let node = json!({ "scale": [2.0e38, 2.0e38, 1.0] });
    let p = write(dir.path(), "wide.gltf", &quad_at([1.0, 1.0, 0.0], node));
    let e = load(&p).unwrap_err();
    let world = matches!(e, SceneError::PositionOutOfRange { world: true, .. });
    assert!(world, "{e}");
    let parts = [
        "vertex 0 is at [-2e38, -2e38, 0.0] after the node transform, beyond the limit of 1e13",
        "overflows the tracer's f32 arithmetic",
    ];
    assert_contains(&e.to_string(), &parts);
}

#[test]
fn unreadable_position_data_says_why() {
    let dir = tmp();
    let base = quad_doc();
    // A sparse POSITION accessor whose indices lie past their view, and one whose indices
    // do not increase: the reader used to return nothing ("POSITION data cannot be read").
    let sparse = |indices_offset: usize| {
        json!({ "count": 2,
            "indices": { "bufferView": 3, "byteOffset": indices_offset, "componentType": 5125 },
            "values": { "bufferView": 0 } })
    };
    // bufferView 3 holds the quad's indices 0, 1, 2, 2, 3, 0 (u32).
    let cases = [
        (
            sparse(200),
            "sparse indices: 2 elements from byte 200, 4 bytes apart, run past the end of bufferView 3 (24 bytes)",
        ),
        (
            sparse(8),
            "sparse indices must strictly increase, but 2 is followed by 2",
        ),
    ];
    for (s, want) in cases {
        let mut doc = base.clone();
        doc["accessors"][0]["sparse"] = s;
        doc["accessors"][0]
            .as_object_mut()
            .map(|a| a.remove("bufferView"));
        let e = load(&write_json(dir.path(), "pos.gltf", &doc)).unwrap_err();
        assert!(matches!(e, SceneError::Primitive { .. }), "{e}");
        let msg = e.to_string();
        assert!(
            msg.contains("POSITION data cannot be read: accessor 0: "),
            "{msg}"
        );
        assert!(msg.contains(want), "{msg}");
    }
}

#[test]
fn a_light_whose_radiance_overflows_is_an_error() {
    // shared/inputs/light_overflow_black.gltf: colour 1e38 x intensity 1e38 rendered black.
    let dir = tmp();
    let seed = include_bytes!("data/light_overflow_black.gltf");
    let p = write(dir.path(), "light.gltf", seed);
    let e = load(&p).unwrap_err();
    assert!(matches!(e, SceneError::Light { .. }), "{e}");
    let parts = [
        "light.gltf: KHR_lights_punctual light 0 has color",
        "[1e38, 1e38, 1e38] times intensity 1e38, which overflows f32",
    ];
    assert_contains(&e.to_string(), &parts);

    // The same for an emissive material: factor x strength.
    let mut doc = quad_doc();
    doc["materials"][0]["name"] = json!("lamp");
    doc["materials"][0]["emissiveFactor"] = json!([4.0, 1.0, 1.0]);
    doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
        json!(1.0e38);
    let e = load(&write_json(dir.path(), "lamp.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::Light { .. }), "{e}");
    assert!(
        e.to_string()
            .contains("lamp.gltf: material 0 ('lamp') has emissiveFactor [4.0, 1.0, 1.0]"),
        "{e}"
    );
    // A strength beyond f32 (read as infinity) once made the emission silently zero.
    doc["materials"][0]["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
        json!(1.0e39);
    let e = load(&write_json(dir.path(), "inf.gltf", &doc)).unwrap_err();
    assert!(
        e.to_string()
            .contains("times emissiveStrength inf, which is not finite"),
        "{e}"
    );
}

#[test]
fn a_byte_stride_that_is_not_a_multiple_of_4_is_refused() {
    let dir = tmp();
    for stride in [6, 2, 256] {
        let mut doc = quad_doc();
        doc["bufferViews"][0]["byteStride"] = json!(stride);
        let e = load(&write_json(dir.path(), "stride.gltf", &doc)).unwrap_err();
        assert!(matches!(e, SceneError::Spec { .. }), "{e}");
        let want = format!(
            "stride.gltf: not a valid glTF 2.0 file: bufferViews[0].byteStride is {stride}; it \
             must be a multiple of 4 from 4 to 252"
        );
        assert!(e.to_string().ends_with(&want), "{e}");
    }
}

#[test]
fn only_gltf_2_is_read() {
    let dir = tmp();
    let good = quad_doc();
    let cases = [
        (
            json!({ "version": "3.0" }),
            "asset.version 3.0: only glTF 2.0 is supported",
        ),
        (
            json!({ "version": "2.0", "minVersion": "2.1" }),
            "asset.minVersion 2.1: only glTF 2.0 is supported",
        ),
        (
            json!({ "version": "20.0" }),
            "asset.version 20.0: only glTF 2.0 is supported",
        ),
    ];
    for (asset, want) in cases {
        let mut doc = good.clone();
        doc["asset"] = asset;
        let e = load(&write_json(dir.path(), "v.gltf", &doc)).unwrap_err();
        assert!(matches!(e, SceneError::Version { .. }), "{e}");
        assert!(e.to_string().ends_with(&format!("v.gltf: {want}")), "{e}");
    }
    // A glTF 1.0 file (objects keyed by id, not arrays) is named by its version, not by the
    // first field the 2.0 reader trips over.
    let v1 = json!({ "asset": { "version": "1.0" }, "meshes": { "m": { "primitives": [] } } });
    let e = load(&write_json(dir.path(), "v1.gltf", &v1)).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("asset.version 1.0: only glTF 2.0 is supported"),
        "{e}"
    );
    // 2.x minor versions are glTF 2.0 files.
    let mut doc = good;
    doc["asset"]["version"] = json!("2.1");
    assert_eq!(
        triangles(&write_json(dir.path(), "v21.gltf", &doc), None),
        2
    );
}

#[test]
fn a_required_extension_the_loader_lacks_is_named() {
    let dir = tmp();
    for (ext, refused) in [
        ("EXT_unknown", true),
        ("KHR_texture_transform", true),
        ("KHR_materials_emissive_strength", false),
    ] {
        let mut doc = quad_doc();
        doc["extensionsUsed"] = json!([ext]);
        doc["extensionsRequired"] = json!([ext]);
        let p = write_json(dir.path(), "req.gltf", &doc);
        if refused {
            let e = load(&p).unwrap_err();
            assert!(matches!(e, SceneError::UnsupportedExtension { .. }), "{e}");
            assert!(
                e.to_string()
                    .ends_with(&format!("req.gltf: requires unsupported extension {ext}")),
                "{e}"
            );
        } else {
            assert_eq!(triangles(&p, None), 2);
        }
    }
}

#[test]
fn a_byte_order_mark_is_accepted() {
    let dir = tmp();
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend_from_slice(&one_quad().to_gltf_embedded());
    assert_eq!(triangles(&write(dir.path(), "bom.gltf", &bytes), None), 2);
}

#[test]
fn the_environment_survives_a_deeply_nested_sibling_in_extras() {
    // serde_json stops at 128 levels; a sibling 200 deep once dropped the whole `extras`.
    let dir = tmp();
    let mut doc = quad_doc();
    doc["scenes"][0]["extras"] = json!("EXTRAS");
    let deep = format!("{}1{}", "[".repeat(200), "]".repeat(200));
    let extras = format!(r#"{{"deep":{deep},"blueshift_environment":[0.5,0.25,1.0]}}"#);
    let text = serde_json::to_string(&doc)
        .expect("json")
        .replace("\"EXTRAS\"", &extras);
    let s = load(&write(dir.path(), "deep.gltf", text.as_bytes())).expect("loads");
    assert_eq!(s.environment, glam::Vec3::new(0.5, 0.25, 1.0));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}
