use super::test_view as view;
use super::*;
use crate::camera_path::fit as camera_fit;
use blueshift_scene::{Aabb, Camera};

/// A quad in the plane z = `z`, 2 units wide about (0, 1).
fn wall(z: f32) -> Vec<[Vec3; 3]> {
    let c = |x: f32, y: f32| Vec3::new(x, y, z);
    vec![
        [c(-1.0, 0.0), c(1.0, 0.0), c(1.0, 2.0)],
        [c(-1.0, 0.0), c(1.0, 2.0), c(-1.0, 2.0)],
    ]
}

/// The six faces of the box [-1, 1] x [0, 2] x [-1, 1].
fn cube() -> Vec<[Vec3; 3]> {
    let mut t = Vec::new();
    for axis in 0..3 {
        for side in [-1.0f32, 1.0] {
            let at = |u: f32, v: f32| {
                let mut p = [0.0f32; 3];
                p[axis] = side;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = v;
                Vec3::from(p) + Vec3::Y
            };
            t.push([at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0)]);
            t.push([at(-1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)]);
        }
    }
    t
}

fn bounds(tris: &[[Vec3; 3]]) -> Aabb {
    Aabb::from_points(&tris.concat())
}

/// Looking down -z at (0, 1, 0) from 4 units away, 45 degrees high.
fn base() -> Camera {
    Camera {
        position: Vec3::new(0.0, 1.0, 4.0),
        target: Vec3::new(0.0, 1.0, 0.0),
        up: Vec3::Y,
        yfov: 45f32.to_radians(),
    }
}

#[test]
fn the_points_cover_the_surfaces_by_area() {
    let s = ViewSpeed::new(cube().into_iter());
    assert_eq!(s.points.len(), POINTS);
    let b = bounds(&cube());
    assert!(s.points.iter().all(|p| {
        let on_face =
            (0..3).any(|i| (p[i] - b.min[i]).abs() < 1e-5 || (p[i] - b.max[i]).abs() < 1e-5);
        on_face && p.cmpge(b.min - 1e-5).all() && p.cmple(b.max + 1e-5).all()
    }));
    // Each face holds its sixth of the points, within the rounding of the area fractions.
    for axis in 0..3 {
        for side in [b.min[axis], b.max[axis]] {
            let n = s
                .points
                .iter()
                .filter(|p| (p[axis] - side).abs() < 1e-5)
                .count();
            assert!(n.abs_diff(POINTS / 6) <= 2, "axis {axis} side {side}: {n}");
        }
    }
    assert!(ViewSpeed::new(std::iter::empty()).points.is_empty());
}

#[test]
fn a_still_view_does_not_move_and_a_pan_moves_by_its_pixels() {
    let s = ViewSpeed::new(cube().into_iter());
    let v = view(&base(), (0.0, 0.0));
    assert_eq!(s.pixels(&v, &v), Some(0.0));
    for px in [0.5f32, 1.0, 3.0] {
        let moved = s.pixels(&v, &view(&base(), (px, 0.0))).expect("in view");
        assert!((moved - px).abs() < 1e-3, "{px}: {moved}");
    }
    assert!(s.slow(&v, &view(&base(), (1.0, 0.0))));
    assert!(!s.slow(&v, &view(&base(), (2.0, 0.0))));
}

/// The strafe presets move the bounds' centre by their pixels per frame: a wall at the
/// centre's depth moves exactly so, nearer surfaces more, farther ones less.
#[test]
fn a_strafe_moves_by_its_pixels_at_the_centre_s_depth() {
    let strafe = |tris: Vec<[Vec3; 3]>, centre: &Aabb, px: f32| {
        let fit = camera_fit::strafe(px, centre, &base(), 96);
        let after = camera_fit::strafed(&base(), &fit, fit.step);
        let (v0, v1) = (view(&base(), (0.0, 0.0)), view(&after, (0.0, 0.0)));
        ViewSpeed::new(tris.into_iter())
            .pixels(&v0, &v1)
            .expect("in view")
    };
    let centre = bounds(&cube());
    for px in [1.0f32, 2.5, 5.0] {
        let flat = strafe(wall(0.0), &centre, px);
        assert!((flat - px).abs() < 1e-3 * px, "{px}: {flat}");
        assert!(strafe(wall(0.5), &centre, px) > 1.1 * px);
        assert!(strafe(wall(-0.5), &centre, px) < 0.9 * px);
    }
}

/// An orbit about the centre leaves the centre's image where it was, but not the scene's.
#[test]
fn an_orbit_about_the_centre_moves_the_image() {
    let b = bounds(&cube());
    let s = ViewSpeed::new(cube().into_iter());
    let fit = camera_fit::orbit(&b, &base(), (128, 96));
    let (v0, v1) = (
        view(&camera_fit::orbited(&base(), &fit, 0.0), (0.0, 0.0)),
        view(&camera_fit::orbited(&base(), &fit, 5.0), (0.0, 0.0)),
    );
    let centre =
        (project_previous(&v1, b.center()).0 - project_previous(&v0, b.center()).0).length();
    assert!(centre < 1e-3, "{centre}");
    let moved = s.pixels(&v0, &v1).expect("in view");
    assert!(moved > SLOW_VIEW_PX, "{moved}");
}

/// Nothing in front of the camera, or nothing in the window: no estimate, and not slow.
#[test]
fn a_scene_out_of_view_has_no_speed() {
    let s = ViewSpeed::new(cube().into_iter());
    let away = Camera {
        target: Vec3::new(0.0, 1.0, 8.0),
        ..base()
    };
    let (a, b) = (view(&away, (0.0, 0.0)), view(&away, (1.0, 0.0)));
    assert_eq!(s.pixels(&a, &b), None);
    assert!(!s.slow(&a, &b));
    let aside = view(&base(), (1000.0, 0.0));
    assert_eq!(s.pixels(&aside, &view(&base(), (1000.5, 0.0))), None);
    let empty = ViewSpeed::new(std::iter::empty());
    let v = view(&base(), (0.0, 0.0));
    assert_eq!(empty.pixels(&v, &v), None);
}
