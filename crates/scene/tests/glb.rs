//! GLB containers: header and chunk problems are clear errors, checked before the glTF reader.

mod common;

use blueshift_scene::{LoadOptions, Scene, SceneError};
use common::one_quad;

#[test]
fn glb_header_problems_are_clear_errors_not_caught_reader_panics() {
    // gltf 1.4.1 subtracts the 12-byte header from the declared total length unchecked: a
    // declared length below 12 panicked in the reader (a caught panic, fuzz finding).
    let opts = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let good = one_quad().to_glb();
    let n = good.len();
    let set = |offset: usize, value: u32| {
        let mut b = good.clone();
        b[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
        b
    };
    let json_len = u32::from_le_bytes([good[12], good[13], good[14], good[15]]) as usize;
    let cases = [
        (
            set(8, 5),
            "GLB header declares a total length of 5 bytes, below the 12-byte header".into(),
        ),
        (
            set(8, n as u32 + 1),
            format!(
                "GLB header declares a total length of {} bytes, but the file has only {n} \
                 bytes (truncated?)",
                n + 1
            ),
        ),
        (
            set(20 + json_len, 1 << 20),
            format!(
                "GLB BIN chunk (chunk 1) at byte {} declares 1048576 bytes of data, past the \
                 declared total length of {n} bytes ({} bytes left after its header)",
                20 + json_len,
                n - 28 - json_len
            ),
        ),
        (
            set(4, 1),
            "GLB header declares version 1, only version 2 is supported".into(),
        ),
    ];
    for (bytes, message) in cases {
        let e = Scene::from_slice(&bytes, None, &opts).unwrap_err();
        assert!(matches!(e, SceneError::Glb { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!("<memory>: not a valid glTF 2.0 file: {message}")
        );
    }
    assert_eq!(
        Scene::from_slice(&good, None, &opts)
            .unwrap()
            .triangles
            .len(),
        2
    );
    // Bytes after the declared length are ignored, with a warning.
    let mut long = good.clone();
    long.extend_from_slice(&[0; 5]);
    let scene = Scene::from_slice(&long, None, &opts).unwrap();
    assert_eq!(scene.triangles.len(), 2);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w == "5 bytes after the GLB's declared total length are ignored"),
        "{:?}",
        scene.warnings
    );
}
