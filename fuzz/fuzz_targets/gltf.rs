//! The glTF loader on bytes: `.gltf` JSON (embedded data URIs) and `.glb` (binary chunk), no
//! file system. A scene that loads is also built for the GPU (BVH, light CDF, texture atlas)
//! and checked against a device limit, as `blueshift render` does.
#![no_main]
use blueshift_scene::{DeviceLimits, LoadOptions, Scene, SceneError, SceneGpu};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    match Scene::from_slice(data, None, &options) {
        Ok(scene) => {
            let limits = DeviceLimits {
                max_storage_buffer_range: 16 << 20,
                ..DeviceLimits::LAVAPIPE
            };
            if scene.check_limits(&limits).is_ok() && scene.triangles.len() <= 4096 {
                let gpu = SceneGpu::build(&scene);
                let _ = gpu.check_limits(16 << 20);
            }
        }
        // The loader turns a panic (its own or the glTF reader's) into this error, so the
        // binary never crashes; the fuzzer still reports it, to be fixed by a pre-check.
        Err(SceneError::Internal { message, .. }) => {
            panic!("the loader or the glTF reader panicked (caught): {message}");
        }
        Err(_) => {}
    }
});
