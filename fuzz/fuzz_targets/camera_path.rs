//! Camera path keyframe JSON: a path that parses gives a finite camera at every frame.
#![no_main]
use blueshift_render::CameraPath;
use blueshift_scene::Camera;
use glam::Vec3;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(path) = CameraPath::from_json(text, "fuzz.json") {
        let base = Camera {
            position: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            yfov: 0.7,
        };
        for f in [0, 1, 7, 1000, u32::MAX / 2, u32::MAX] {
            let c = path.camera(&base, f);
            assert!(
                c.position.is_finite() && c.target.is_finite() && c.yfov.is_finite(),
                "frame {f}: {c:?}"
            );
            let b = c.basis(16.0 / 9.0);
            assert!(b.forward.is_finite() && b.right.is_finite() && b.up.is_finite());
            let (x, y) = path.view_offset(f);
            assert!(x.is_finite() && y.is_finite());
        }
    }
});
