//! Rules of the glTF 2.0 specification the loader checks itself (byte strides, the version,
//! required extensions), input it accepts (a byte-order mark, deeply nested `extras`) and
//! POSITION data it cannot read: each refused with the file and the reason, or loaded.
mod common;

use blueshift_scene::SceneError;
use common::{load, one_quad, quad_doc, triangles, write, write_json};
use serde_json::json;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
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
