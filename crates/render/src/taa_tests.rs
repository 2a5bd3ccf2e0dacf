//! Properties of the TAA operator, each on synthetic G-buffers and images.
use super::*;
use glam::Vec3;

/// The plain EMA the still camera must reproduce: `acc` moves ALPHA of the way to `e`.
fn ema_step(acc: &mut [f32], e: &[f32]) {
    for (a, &b) in acc.iter_mut().zip(e) {
        *a += 0.1 * (b - *a);
    }
}

/// A texel of surface `material` (all surfaces here are the plane z = -2 facing the camera:
/// only the material tells them apart).
fn texel(material: u32) -> GBufferTexel {
    GBufferTexel {
        position: Vec3::new(0.0, 0.0, -2.0),
        material,
        normal: Vec3::Z,
        depth: 2.0,
    }
}

/// A deterministic error value in [-1, 1) for (x, y, t).
fn noise(x: i64, y: i64, t: u32) -> f32 {
    let h = blueshift_sampling::rng::hash3(x as u32, y as u32, t);
    (h >> 8) as f32 / (1u32 << 23) as f32 - 1.0
}

fn image(w: u32, h: u32, f: impl Fn(i64, i64) -> f32) -> Vec<f32> {
    (0..w * h)
        .map(|i| f(i64::from(i % w), i64::from(i / w)))
        .collect()
}

/// Sources that move every pixel's surface by `d` pixels since the previous frame.
fn shifted(w: u32, h: u32, d: Vec2) -> Vec<Option<Vec2>> {
    (0..w * h)
        .map(|i| Some(Vec2::new((i % w) as f32, (i / w) as f32) + 0.5 + d))
        .collect()
}

#[test]
fn still_camera_is_the_ema_bit_for_bit() {
    let (w, h) = (23u32, 17u32);
    let g = vec![texel(1); (w * h) as usize];
    // Both ways to a still camera: the shortcut, and pixel-centre sources through the taps.
    let ops = [
        Reprojection::still((w * h) as usize),
        Reprojection::from_sources(&g, &g, &shifted(w, h, Vec2::ZERO), w),
    ];
    for op in ops {
        assert_eq!(op.kept_share(), 1.0);
        let mut ema = image(w, h, |x, y| noise(x, y, 0));
        let mut taa = ema.clone();
        for t in 1..40 {
            let e = image(w, h, |x, y| noise(x, y, t) * 1e3f32.powi(t as i32 % 3 - 1));
            ema_step(&mut ema, &e);
            taa = op.step(&taa, &e, 1);
            let same = ema
                .iter()
                .zip(&taa)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "frame {t}: TAA differs from the EMA");
        }
    }
}

/// A pattern that moves with the image by a whole number of pixels per frame accumulates like
/// the unmoved pattern: frame t's TAA at p is the still sequence's EMA at p + t v, wherever the
/// surface stayed on screen since frame 0.
#[test]
fn an_integer_pan_accumulates_like_the_unmoved_pattern() {
    let (w, h, frames) = (40u32, 30u32, 12u32);
    let v = (2i64, 1i64);
    let g = vec![texel(3); (w * h) as usize];
    let op = Reprojection::from_sources(&g, &g, &shifted(w, h, Vec2::new(2.0, 1.0)), w);
    // The unmoved pattern lives on the scene, which frame t shows from (t v) on.
    let (sw, sh) = (w + v.0 as u32 * frames, h + v.1 as u32 * frames);
    let mut still = image(sw, sh, |x, y| noise(x, y, 0));
    let mut taa = image(w, h, |x, y| noise(x, y, 0));
    for t in 1..frames {
        let s = i64::from(t);
        ema_step(&mut still, &image(sw, sh, |x, y| noise(x, y, t)));
        let moved = image(w, h, |x, y| noise(x + s * v.0, y + s * v.1, t));
        taa = op.step(&taa, &moved, 1);
        let mut compared = 0;
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                // Away from the border: the surface's whole path was on screen.
                if x + s * v.0 >= w as i64 || y + s * v.1 >= h as i64 {
                    continue;
                }
                let want = still[((y + s * v.1) * sw as i64 + x + s * v.0) as usize];
                let got = taa[(y * w as i64 + x) as usize];
                assert_eq!(got.to_bits(), want.to_bits(), "frame {t} ({x}, {y})");
                compared += 1;
            }
        }
        assert!(compared > 0, "frame {t}");
    }
}

/// Bilinear taps reproduce a linear history exactly at a fractional motion: every one of the
/// four taps and its weight matters. Positions snap to 1/SNAP px, and no further.
#[test]
fn fractional_motion_fetches_a_linear_history_exactly() {
    let (w, h) = (20u32, 16u32);
    let g = vec![texel(1); (w * h) as usize];
    let ramp = |x: f32, y: f32| 0.25 * x - 0.75 * y + 3.0;
    // Motions on the 1/SNAP px grid the positions snap to.
    for d in [
        Vec2::new(0.3125, 0.625),
        Vec2::new(-1.6875, 0.25),
        Vec2::new(0.5, -2.5),
    ] {
        let op = Reprojection::from_sources(&g, &g, &shifted(w, h, d), w);
        let acc = image(w, h, |x, y| ramp(x as f32, y as f32));
        let out = op.step(&acc, &vec![0.0; (w * h) as usize], 1);
        for y in 3..h as i64 - 3 {
            for x in 3..w as i64 - 3 {
                let want = (1.0 - ALPHA) * ramp(x as f32 + d.x, y as f32 + d.y);
                let got = out[(y * w as i64 + x) as usize];
                assert!((got - want).abs() < 1e-4, "{d} ({x}, {y}): {got} vs {want}");
            }
        }
    }
    // Off the grid by a third of a step: the position rounds to the nearest step.
    let d = Vec2::new(0.25 + 1.0 / (3.0 * SNAP), 0.0);
    let op = Reprojection::from_sources(&g, &g, &shifted(w, h, d), w);
    let out = op.step(
        &image(w, h, |x, _| x as f32),
        &vec![0.0; (w * h) as usize],
        1,
    );
    let want = (1.0 - ALPHA) * 5.25;
    assert!((out[5] - want).abs() < 1e-5, "{} vs {want}", out[5]);
}

/// A foreground object (material 2) moves 4 px right over a still background (material 1):
/// the background it uncovers has no history (every tap shows the object) and restarts from
/// this frame's value; every other pixel keeps its history.
#[test]
fn disoccluded_pixels_restart() {
    let (w, h) = (32u32, 8u32);
    let layout = |x0: i64| -> Vec<GBufferTexel> {
        (0..w * h)
            .map(|i| {
                texel(if (x0..x0 + 10).contains(&i64::from(i % w)) {
                    2
                } else {
                    1
                })
            })
            .collect()
    };
    let (prev, cur) = (layout(10), layout(14));
    let sources: Vec<Option<Vec2>> = cur
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let p = Vec2::new((i as u32 % w) as f32, (i as u32 / w) as f32) + 0.5;
            Some(if g.material == 2 {
                p - Vec2::X * 4.0
            } else {
                p
            })
        })
        .collect();
    let op = Reprojection::from_sources(&cur, &prev, &sources, w);
    let acc = image(w, h, |x, y| noise(x, y, 0));
    let e = image(w, h, |x, y| noise(x, y, 1));
    let out = op.step(&acc, &e, 1);
    assert!((op.kept_share() - (1.0 - 4.0 / w as f64)).abs() < 1e-12);
    for i in 0..(w * h) as usize {
        let uncovered = (10..14).contains(&(i as u32 % w));
        assert_eq!(out[i] == e[i], uncovered, "pixel {i}");
    }
}

/// Taps on another surface do not leak into the history: with sources between two surfaces'
/// pixels, each pixel's history is its own surface's value, renormalised.
#[test]
fn rejected_taps_are_renormalised_away() {
    let (w, h) = (16u32, 6u32);
    let m = |x: i64| if x < 8 { 1 } else { 2 };
    let g: Vec<GBufferTexel> = (0..w * h).map(|i| texel(m(i64::from(i % w)))).collect();
    let op = Reprojection::from_sources(&g, &g, &shifted(w, h, Vec2::new(0.5, 0.5)), w);
    let acc = image(w, h, |x, _| if m(x) == 1 { 1.0 } else { 100.0 });
    let out = op.step(&acc, &vec![0.0; (w * h) as usize], 2 - 1);
    for y in 0..h as i64 - 1 {
        for x in 0..w as i64 - 1 {
            let want = (1.0 - ALPHA) * if m(x) == 1 { 1.0 } else { 100.0 };
            let got = out[(y * w as i64 + x) as usize];
            assert!((got - want).abs() <= 1e-5 * want, "({x}, {y}): {got}");
        }
    }
}

/// Interleaved channels accumulate independently: a 4-channel step is four 1-channel steps.
#[test]
fn channels_accumulate_independently() {
    let (w, h) = (9u32, 7u32);
    let g = vec![texel(1); (w * h) as usize];
    let op = Reprojection::from_sources(&g, &g, &shifted(w, h, Vec2::new(0.4, -0.3)), w);
    let plane = |c: u32, t: u32| image(w, h, |x, y| noise(x + 100 * i64::from(c), y, t));
    let interleave = |t: u32| -> Vec<f32> {
        let p: Vec<Vec<f32>> = (0..4).map(|c| plane(c, t)).collect();
        (0..(w * h) as usize)
            .flat_map(|i| p.iter().map(move |q| q[i]))
            .collect()
    };
    let out = op.step(&interleave(0), &interleave(1), 4);
    for c in 0..4 {
        let one = op.step(&plane(c, 0), &plane(c, 1), 1);
        for (i, v) in one.iter().enumerate() {
            assert_eq!(out[i * 4 + c as usize].to_bits(), v.to_bits());
        }
    }
}
