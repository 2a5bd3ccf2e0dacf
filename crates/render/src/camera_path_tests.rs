//! Camera path tests: parsing, pans, swings, keyframes, strafes and in-view orbits.
use super::*;

fn base() -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 4.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        yfov: 0.7,
    }
}

#[test]
fn presets_parse() {
    assert_eq!(CameraPath::parse("static").unwrap(), CameraPath::Static);
    assert_eq!(
        CameraPath::parse("pan:8").unwrap(),
        CameraPath::Pan { px_per_frame: 8.0 }
    );
    assert!(CameraPath::parse("pan:abc").is_err());
    for bad in ["static:5", "static:"] {
        let e = CameraPath::parse(bad).unwrap_err();
        assert!(e.contains("static takes no argument"), "{bad}: {e}");
    }
    assert_eq!(
        CameraPath::parse("swing:2").unwrap(),
        CameraPath::Swing {
            degrees_per_frame: 2.0
        }
    );
    assert!(
        CameraPath::parse("/nonexistent/path.json")
            .unwrap_err()
            .contains("presets")
    );
}

#[test]
fn keyframes_far_apart_interpolate_to_finite_cameras() {
    let text = r#"{"keyframes": [
        {"frame": 0, "position": [-3e38, 0, 0], "target": [0, 0, 0], "yfov_degrees": 40},
        {"frame": 9, "position": [3e38, 0, 0], "target": [0, 0, 1], "yfov_degrees": 40}]}"#;
    let path = CameraPath::from_json(text, "far").unwrap();
    for f in 0..10 {
        assert!(path.camera(&base(), f).position.is_finite(), "frame {f}");
    }
    assert!(CameraPath::from_json(r#"{"keyframes": []}"#, "x").is_err());
    assert!(CameraPath::from_json("{", "x").unwrap_err().contains("'x'"));
}

#[test]
fn pan_shifts_the_view_not_the_camera() {
    let p = CameraPath::Pan { px_per_frame: 2.0 };
    assert_eq!(p.camera(&base(), 10), base());
    assert_eq!(p.view_offset(10), (20.0, 0.0));
    assert_eq!(CameraPath::Static.view_offset(10), (0.0, 0.0));
}

#[test]
fn pans_turn_back_and_stay_inside_their_sensor() {
    let p = CameraPath::Pan { px_per_frame: 8.0 };
    let xs: Vec<f32> = (0..20).map(|t| p.view_offset(t).0).collect();
    assert_eq!(
        &xs[..10],
        &[0.0, 8.0, 16.0, 24.0, 32.0, 40.0, 48.0, 56.0, 64.0, 56.0]
    );
    assert_eq!(xs[16], 0.0);
    let (view, base) = p.view_window(48, 128, 100);
    assert_eq!(view, (128 + PAN_SPAN as u32, 128 + PAN_SPAN as u32));
    assert_eq!(base, (0.0, ((view.1 - 100) / 2) as f32));
    for t in 0..48 {
        let x = base.0 + p.view_offset(t).0;
        assert!(x >= 0.0 && x + 128.0 <= view.0 as f32, "frame {t}");
    }
    // A slow pan uses only the sensor it needs; leftward pans start at the right.
    let slow = CameraPath::Pan { px_per_frame: 1.0 };
    assert_eq!(slow.view_window(10, 32, 32), ((41, 41), (0.0, 4.0)));
    let left = CameraPath::Pan { px_per_frame: -1.0 };
    assert_eq!(
        left.view_window(10, 32, 32).1.0 + left.view_offset(9).0,
        0.0
    );
    assert_eq!(
        CameraPath::Static.view_window(5, 32, 16),
        ((32, 16), (0.0, 0.0))
    );
}

/// A swing follows the orbit up to SWING_SPAN degrees, then turns back to where it began.
#[test]
fn swings_turn_back_at_their_span() {
    let (swing, orbit) = (
        CameraPath::Swing {
            degrees_per_frame: 1.0,
        },
        CameraPath::Orbit {
            degrees_per_frame: 1.0,
        },
    );
    let b = base();
    let span = SWING_SPAN as u32;
    for f in 0..=span {
        assert_eq!(swing.camera(&b, f), orbit.camera(&b, f), "frame {f}");
    }
    for f in 0..=span {
        let (a, c) = (swing.camera(&b, span + f), orbit.camera(&b, span - f));
        assert!(
            (a.position - c.position).length() < 1e-5,
            "frame {}",
            span + f
        );
    }
    assert!((swing.camera(&b, 2 * span).position - b.position).length() < 1e-5);
}

#[test]
fn keyframes_interpolate_linearly() {
    let k = vec![
        Keyframe {
            frame: 0,
            position: [0.0, 0.0, 4.0],
            target: [0.0; 3],
            yfov_degrees: 40.0,
        },
        Keyframe {
            frame: 10,
            position: [2.0, 0.0, 4.0],
            target: [0.0; 3],
            yfov_degrees: 60.0,
        },
    ];
    let c = CameraPath::Keyframes(k).camera(&base(), 5);
    assert!((c.position.x - 1.0).abs() < 1e-6);
    assert!((c.yfov.to_degrees() - 50.0).abs() < 1e-4);
}

/// The bundled scenes with their own cameras.
fn bundled() -> Vec<(String, Aabb, Camera)> {
    ["cornell-box", "textured", "edges"]
        .iter()
        .map(|n| {
            let dir = crate::default_assets_dir().join(format!("scenes/{n}.gltf"));
            let s = blueshift_scene::Scene::load(dir).unwrap();
            (n.to_string(), s.bounds(), s.camera_or_default())
        })
        .collect()
}

/// Where camera `c` shows world point `p` on a `view` frame: pixel coordinates and depth,
/// from the basis' definition (direction = forward + ndc.x right + ndc.y up).
fn project(c: &Camera, view: (u32, u32), p: Vec3) -> (f32, f32, f32) {
    let b = c.basis(view.0 as f32 / view.1 as f32);
    let d = p - b.position;
    let z = d.dot(b.forward);
    let nx = d.dot(b.right) / (z * b.right.length_squared());
    let ny = d.dot(b.up) / (z * b.up.length_squared());
    (
        (nx + 1.0) * 0.5 * view.0 as f32,
        (1.0 - ny) * 0.5 * view.1 as f32,
        z,
    )
}

#[test]
fn strafes_move_the_scene_centre_by_their_pixels_per_frame() {
    let view = (128, 128);
    for (name, bounds, cam) in bundled() {
        for px in [1.0f32, 2.5, 5.0] {
            let path = CameraPath::parse(&format!("strafe:{px}"))
                .unwrap()
                .fit(&bounds, &cam, view);
            assert_eq!(path.label(), format!("strafe:{px}"));
            // Frames 0 and 1 (the first leg: the span is several frames long).
            let (a, b) = (path.camera(&cam, 0), path.camera(&cam, 1));
            assert_eq!(a, cam, "{name}: frame 0 is the base camera");
            assert_eq!((a.target - a.position), (b.target - b.position));
            let (x0, y0, _) = project(&a, view, bounds.center());
            let (x1, y1, _) = project(&b, view, bounds.center());
            let moved = ((x1 - x0).powi(2) + (y1 - y0).powi(2)).sqrt();
            assert!(
                (moved / px - 1.0).abs() < 0.1,
                "{name} strafe:{px}: {moved} px"
            );
        }
    }
}

#[test]
fn in_view_orbits_keep_the_whole_scene_in_the_frustum() {
    for view in [(128u32, 128u32), (160, 90)] {
        for (name, bounds, cam) in bundled() {
            for deg in [0.5f32, 1.0, 3.0] {
                let path = CameraPath::parse(&format!("orbit-view:{deg}"))
                    .unwrap()
                    .fit(&bounds, &cam, view);
                let mut turned = 0.0f32;
                for f in 0..64 {
                    let c = path.camera(&cam, f);
                    for i in 0..8 {
                        let pick =
                            |bit: u32, lo: f32, hi: f32| if i >> bit & 1 == 0 { lo } else { hi };
                        let corner = Vec3::new(
                            pick(0, bounds.min.x, bounds.max.x),
                            pick(1, bounds.min.y, bounds.max.y),
                            pick(2, bounds.min.z, bounds.max.z),
                        );
                        let (x, y, z) = project(&c, view, corner);
                        let inside = z > 0.0
                            && (0.0..=view.0 as f32).contains(&x)
                            && (0.0..=view.1 as f32).contains(&y);
                        assert!(
                            inside,
                            "{name} orbit-view:{deg} frame {f} {view:?}: {corner}"
                        );
                    }
                    let (a, b) = (c.position - bounds.center(), cam.position - bounds.center());
                    turned = turned.max(a.angle_between(b).to_degrees());
                }
                // It does turn, and no further than its span.
                let want = (deg * 63.0).min(fit::ORBIT_VIEW_SPAN);
                assert!(
                    turned > 0.5 * want && turned < want + 0.5,
                    "{name} orbit-view:{deg}: {turned}"
                );
            }
        }
    }
}

#[test]
fn scene_paths_parse_cleanly_and_hold_still_until_fitted() {
    for bad in [
        "strafe:x",
        "strafe:1e9",
        "orbit-view:nan",
        "strafe:",
        "orbit-view:inf",
    ] {
        let e = CameraPath::parse(bad).unwrap_err();
        assert!(e.contains("is not a number"), "{bad}: {e}");
    }
    let p = CameraPath::parse("orbit-view").unwrap();
    assert_eq!(p.label(), "orbit-view:1");
    assert_eq!(p.camera(&base(), 9), base());
    let s = CameraPath::parse("strafe").unwrap();
    assert_eq!(s.camera(&base(), 9), base());
    // Fitting leaves the other paths alone.
    let b = Aabb::from_points(&[Vec3::splat(-1.0), Vec3::splat(1.0)]);
    let orbit = CameraPath::Orbit {
        degrees_per_frame: 0.5,
    };
    assert_eq!(orbit.clone().fit(&b, &base(), (64, 64)), orbit);
}
