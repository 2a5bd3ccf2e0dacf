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
