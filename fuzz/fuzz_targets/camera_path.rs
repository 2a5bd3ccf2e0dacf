//! Camera paths: keyframe JSON and preset specs (`strafe:PX`, `orbit-view:DEG`, ...). A path
//! that parses gives a finite camera at every frame, fitted to a scene or not; one that does
//! not parse is an error message, never a panic.
#![no_main]
use blueshift_render::CameraPath;
use blueshift_scene::{Aabb, Camera};
use glam::Vec3;
use libfuzzer_sys::fuzz_target;

/// The presets `CameraPath::parse` knows (anything else is a keyframe file to read, which a
/// fuzzer must not open).
const PRESETS: [&str; 6] = ["static", "pan", "orbit", "swing", "strafe", "orbit-view"];

fn check(path: &CameraPath, base: &Camera) {
    for f in [0, 1, 7, 1000, u32::MAX / 2, u32::MAX] {
        let c = path.camera(base, f);
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

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let base = Camera {
        position: Vec3::new(0.0, 0.0, 4.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        yfov: 0.7,
    };
    if let Ok(path) = CameraPath::from_json(text, "fuzz.json") {
        check(&path, &base);
    }
    let name = text.split(':').next().unwrap_or("");
    if PRESETS.contains(&name) {
        if let Ok(path) = CameraPath::parse(text) {
            check(&path, &base);
            let bounds = Aabb::from_points(&[Vec3::splat(-1.0), Vec3::new(1.0, 2.0, 0.5)]);
            check(&path.fit(&bounds, &base, (320, 180)), &base);
        }
    }
});
