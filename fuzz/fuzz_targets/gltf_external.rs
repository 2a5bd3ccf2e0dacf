//! The glTF loader on a file next to external buffers and images (`quad.bin`, `tex.png`), as
//! `Scene::load` reads it: relative and percent-encoded URIs are resolved; those that lead
//! outside the directory (`..`, absolute paths, `file:` URIs) are refused.
#![no_main]
use blueshift_scene::{LoadOptions, Scene, SceneError};
use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

/// A private directory holding the sidecar files (from the committed seed corpus).
fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("blueshift-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("temp dir");
        let sidecar = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("sidecar");
        for f in ["quad.bin", "tex.png"] {
            std::fs::copy(sidecar.join(f), d.join(f)).expect("sidecar file");
        }
        d
    })
}

fuzz_target!(|data: &[u8]| {
    let path = dir().join("scene.gltf");
    if std::fs::write(&path, data).is_err() {
        return;
    }
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    if let Err(SceneError::Internal { message, .. }) = Scene::load_with(&path, &options) {
        panic!("the loader or the glTF reader panicked (caught): {message}");
    }
});
