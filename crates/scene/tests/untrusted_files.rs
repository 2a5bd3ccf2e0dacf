//! Files from outside ("Untrusted files, second round"): reads outside the scene directory,
//! special files, buffers shorter or longer than declared, values that overflow f32, spec
//! violations. Each gets a clear error naming the file and the problem, or a warning and a
//! correct scene.

mod common;

use common::{embedded_uri, load, one_quad, write_json};
use serde_json::{Value, json};

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
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
