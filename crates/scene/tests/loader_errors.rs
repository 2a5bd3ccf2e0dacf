//! Bad input gives a clear error (naming the file and the problem), never a panic.

mod common;

use blueshift_scene::presets::{GltfBuilder, MeshData};
use blueshift_scene::{DeviceLimits, Scene, SceneError};
use common::{embedded_uri, load, one_quad, write, write_json};
use serde_json::json;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

#[test]
fn missing_file() {
    let dir = tmp();
    let p = dir.path().join("nope.gltf");
    let e = load(&p).unwrap_err();
    assert!(matches!(e, SceneError::NotFound { .. }), "{e}");
    assert!(e.to_string().contains("nope.gltf") && e.to_string().contains("not found"));
}

#[test]
fn malformed_json() {
    let dir = tmp();
    let p = write(
        dir.path(),
        "broken.gltf",
        b"{ \"asset\": { \"version\": \"2.0\" }, ",
    );
    let e = load(&p).unwrap_err();
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    assert!(e.to_string().contains("broken.gltf"), "{e}");
}

#[test]
fn invalid_references_fail_validation() {
    let dir = tmp();
    let mut doc = one_quad().json(Some(embedded_uri(one_quad().bin())));
    doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99);
    let e = load(&write_json(dir.path(), "badref.gltf", &doc)).unwrap_err();
    // gltf-json's validator itself indexes out of bounds here (a panic the loader used to
    // catch); the loader's pre-check now reports it as a validation error.
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    assert!(e.to_string().contains("badref.gltf"), "{e}");
    assert!(e.to_string().contains("Index out of bounds"), "{e}");
}

#[test]
fn missing_external_buffer() {
    let dir = tmp();
    let (json, _bin) = one_quad().to_gltf_external("gone.bin");
    let p = write(dir.path(), "external.gltf", &json);
    let e = load(&p).unwrap_err();
    match &e {
        SceneError::Buffer { index, uri, .. } => {
            assert_eq!((*index, uri.as_str()), (0, "gone.bin"));
        }
        _ => panic!("wrong error {e}"),
    }
    assert!(e.to_string().contains("gone.bin"), "{e}");
}

#[test]
fn buffer_shorter_than_declared() {
    let dir = tmp();
    let b = one_quad();
    let (json, bin) = b.to_gltf_external("short.bin");
    write(dir.path(), "short.bin", &bin[..bin.len() / 2]);
    let e = load(&write(dir.path(), "short.gltf", &json)).unwrap_err();
    assert!(matches!(e, SceneError::Buffer { .. }), "{e}");
    assert!(e.to_string().contains("byteLength"), "{e}");
}

#[test]
fn out_of_range_indices() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mesh = MeshData {
        indices: Some(vec![0, 1, 7]),
        ..common::quad(true)
    };
    let m = b.add_mesh("bad-indices", &mesh, None);
    let n = b.add_node(json!({ "mesh": m }));
    b.add_root(n);
    let e = load(&write(dir.path(), "indices.gltf", &b.to_gltf_embedded())).unwrap_err();
    match &e {
        SceneError::IndexOutOfRange {
            index,
            vertex_count,
            ..
        } => assert_eq!((*index, *vertex_count), (7, 4)),
        _ => panic!("wrong error {e}"),
    }
    assert!(e.to_string().contains("bad-indices"), "{e}");
}

#[test]
fn accessor_past_end_of_buffer_view() {
    let dir = tmp();
    let b = one_quad();
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    doc["accessors"][0]["count"] = json!(1000);
    let e = load(&write_json(dir.path(), "overrun.gltf", &doc)).unwrap_err();
    assert!(
        matches!(e, SceneError::Primitive { .. } | SceneError::Parse { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("overrun.gltf"), "{e}");
}

#[test]
fn wrong_accessor_type() {
    let dir = tmp();
    let b = one_quad();
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    doc["accessors"][0]["type"] = json!("SCALAR");
    doc["accessors"][0].as_object_mut().map(|a| {
        a.remove("min");
        a.remove("max")
    });
    let e = load(&write_json(dir.path(), "type.gltf", &doc)).unwrap_err();
    assert!(
        matches!(e, SceneError::Primitive { .. } | SceneError::Parse { .. }),
        "{e}"
    );
}

#[test]
fn nan_positions_are_an_error() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mut mesh = common::quad(true);
    mesh.positions[2] = [f32::NAN, 0.0, 0.0];
    let m = b.add_mesh("nan", &mesh, None);
    let n = b.add_node(json!({ "mesh": m }));
    b.add_root(n);
    // (The builder's min/max skip the NaN, so the JSON itself stays valid.)
    let e = load(&write(dir.path(), "nan.gltf", &b.to_gltf_embedded())).unwrap_err();
    match &e {
        SceneError::PositionOutOfRange { vertex, .. } => assert_eq!(*vertex, 2),
        _ => panic!("wrong error {e}"),
    }
}

#[test]
fn infinite_positions_after_transform_are_an_error() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let m = b.add_mesh("huge", &common::quad(true), None);
    // Finite matrix, finite local positions, but x = 3e38 + 3e38 overflows.
    let n = b.add_node(json!({
        "mesh": m, "scale": [3.0e38, 1.0, 1.0], "translation": [3.0e38, 0.0, 0.0]
    }));
    b.add_root(n);
    let e = load(&write(dir.path(), "inf.gltf", &b.to_gltf_embedded())).unwrap_err();
    assert!(matches!(e, SceneError::PositionOutOfRange { .. }), "{e}");
    assert!(e.to_string().contains("has a non-finite position"), "{e}");
}

#[test]
fn zero_area_triangles_are_skipped_with_one_warning() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let mut mesh = common::quad(true);
    // Two extra degenerate triangles: a repeated vertex and three collinear points.
    mesh.positions.push([2.0, 0.0, 0.0]);
    mesh.positions.push([3.0, 0.0, 0.0]);
    mesh.positions.push([4.0, 0.0, 0.0]);
    if let Some(ix) = &mut mesh.indices {
        ix.extend_from_slice(&[0, 0, 1, 4, 5, 6]);
    }
    mesh.normals = None;
    mesh.uvs = None;
    let m = b.add_mesh("degenerate", &mesh, None);
    let n = b.add_node(json!({ "mesh": m }));
    b.add_root(n);
    let scene = load(&write(dir.path(), "degenerate.gltf", &b.to_gltf_embedded())).unwrap();
    assert_eq!(scene.triangles.len(), 2);
    let w: Vec<_> = scene
        .warnings
        .iter()
        .filter(|w| w.contains("zero-area"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", scene.warnings);
    assert!(w[0].contains("skipped 2 zero-area triangles"), "{}", w[0]);
}

#[test]
fn empty_scene_is_an_error() {
    let dir = tmp();
    let mut b = GltfBuilder::new();
    let n = b.add_node(json!({ "name": "empty" }));
    b.add_root(n);
    let e = load(&write(dir.path(), "empty.gltf", &b.to_gltf_embedded())).unwrap_err();
    assert!(matches!(e, SceneError::EmptyScene { .. }), "{e}");
    assert!(e.to_string().contains("empty.gltf"), "{e}");

    let doc = json!({ "asset": { "version": "2.0" } });
    let e = load(&write_json(dir.path(), "noscenes.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::EmptyScene { .. }), "{e}");
}

#[test]
fn only_unsupported_primitives_is_empty() {
    let dir = tmp();
    let b = one_quad();
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    doc["meshes"][0]["primitives"][0]["mode"] = json!(1); // LINES
    let e = load(&write_json(dir.path(), "lines.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::EmptyScene { .. }), "{e}");
}

#[test]
fn truncated_glb() {
    let dir = tmp();
    let glb = one_quad().to_glb();
    let e = load(&write(dir.path(), "cut.glb", &glb[..glb.len() - 20])).unwrap_err();
    assert!(matches!(e, SceneError::Glb { .. }), "{e}");
    assert!(
        e.to_string().contains("cut.glb: not a valid glTF 2.0 file"),
        "{e}"
    );
    let e = load(&write(dir.path(), "junk.glb", b"glTF\x02\0\0\0garbage")).unwrap_err();
    assert!(matches!(e, SceneError::Glb { .. }), "{e}");
    // A JSON chunk that is not JSON still fails in the reader.
    let mut bad_json = glb.clone();
    bad_json[20] = b'#';
    let e = load(&write(dir.path(), "json.glb", &bad_json)).unwrap_err();
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
}

#[test]
fn cyclic_node_hierarchy() {
    let dir = tmp();
    let b = one_quad();
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    doc["nodes"][0]["children"] = json!([0]);
    let e = load(&write_json(dir.path(), "cycle.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::NodeCycle { node: 0, .. }), "{e}");
}

#[test]
fn check_limits_names_the_buffer() {
    let dir = tmp();
    let p = write(dir.path(), "quad.gltf", &one_quad().to_gltf_embedded());
    let scene = load(&p).unwrap();
    let range = |max_storage_buffer_range| DeviceLimits {
        max_storage_buffer_range,
        ..DeviceLimits::LAVAPIPE
    };
    scene.check_limits(&range(128 << 20)).unwrap();
    // Two triangles: 2 * 68 shading bytes > 120 (the 3 BVH nodes take 108).
    let e = scene.check_limits(&range(120)).unwrap_err();
    assert!(matches!(e, SceneError::OverLimit { .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("triangle shading") && msg.contains("136 bytes"),
        "{msg}"
    );
    assert!(msg.contains("maxStorageBufferRange = 120"), "{msg}");

    let gpu = blueshift_scene::SceneGpu::build(&scene);
    gpu.check_limits(128 << 20).unwrap();
    let e = gpu.check_limits(40).unwrap_err();
    assert!(e.to_string().contains("BVH"), "{e}");
}

#[test]
fn unknown_preset() {
    let dir = tmp();
    let e = blueshift_scene::presets::write_preset("teapot", dir.path()).unwrap_err();
    assert!(e.to_string().contains("teapot") && e.to_string().contains("cornell-box"));
}

#[test]
fn scene_load_is_the_public_entry() {
    // Scene::load prints warnings; make sure it works on a good file too.
    let dir = tmp();
    let p = write(dir.path(), "ok.gltf", &one_quad().to_gltf_embedded());
    assert_eq!(Scene::load(&p).unwrap().triangles.len(), 2);
}

#[test]
fn from_slice_loads_embedded_and_glb_but_not_external_buffers() {
    let opts = blueshift_scene::LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let b = one_quad();
    let embedded = Scene::from_slice(&b.to_gltf_embedded(), None, &opts).unwrap();
    assert_eq!(embedded.triangles.len(), 2);
    assert_eq!(
        Scene::from_slice(&b.to_glb(), None, &opts)
            .unwrap()
            .triangles
            .len(),
        2
    );
    let (json, _) = b.to_gltf_external("quad.bin");
    let e = Scene::from_slice(&json, None, &opts).unwrap_err();
    assert!(matches!(e, SceneError::Buffer { .. }), "{e}");
    assert!(e.to_string().contains("<memory>"), "{e}");
}

#[test]
fn device_files_and_bad_percent_encoding_are_errors_not_hangs_or_panics() {
    let dir = tmp();
    let allowed = blueshift_scene::LoadOptions {
        quiet: true,
        allow_outside_paths: true,
        ..Default::default()
    };
    for uri in ["/dev/zero", "file:///dev/zero", "%FF%FE.bin"] {
        let mut doc = one_quad().json(Some(embedded_uri(one_quad().bin())));
        doc["buffers"][0]["uri"] = json!(uri);
        let p = write_json(dir.path(), "uri.gltf", &doc);
        // Outside the scene directory: refused before anything is opened.
        let e = load(&p).unwrap_err();
        let outside = matches!(e, SceneError::OutsidePath { .. });
        assert!(outside == uri.contains("dev"), "{uri}: {e}");
        // Allowed, the device is still refused, unopened.
        let e = Scene::load_with(&p, &allowed).unwrap_err();
        assert!(matches!(e, SceneError::Buffer { .. }), "{uri}: {e}");
        if uri.contains("dev") {
            let want = "/dev/zero: not a regular file (a character device)";
            assert!(e.to_string().contains(want), "{e}");
        }
    }
}

#[test]
fn fuzz_findings_are_errors_not_caught_reader_panics() {
    // Each of these made the glTF reader panic (caught as SceneError::Internal before the
    // loader's pre-checks): an image with a bufferView but no mimeType, an image with neither
    // uri nor bufferView, and a relative URI whose percent-encoding is not UTF-8 (decoded by
    // the reader even when loading from memory).
    let opts = blueshift_scene::LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let mut no_mime = one_quad().json(Some(embedded_uri(one_quad().bin())));
    no_mime["images"] = json!([{ "bufferView": 0 }]);
    let mut no_source = one_quad().json(Some(embedded_uri(one_quad().bin())));
    no_source["images"] = json!([{ "name": "nothing" }]);
    let mut bad_uri = one_quad().json(None);
    bad_uri["buffers"][0]["uri"] = json!("%AA%BB");
    for (what, doc) in [("mimeType", no_mime), ("uri", no_source), ("uri", bad_uri)] {
        let bytes = serde_json::to_vec(&doc).unwrap();
        let e = Scene::from_slice(&bytes, None, &opts).unwrap_err();
        assert!(
            matches!(e, SceneError::Parse { .. } | SceneError::Buffer { .. }),
            "{what}: {e}"
        );
    }
}
