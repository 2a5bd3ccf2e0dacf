//! `sort-cycle` (its `target=follow`): while the view moves, the sorting target is the STBN
//! slice read where the image has moved it (the scene centre's projected motion, recomputed
//! here from the cameras), and a still view sorts exactly as `target=screen` does.
use crate::Gpu;
use blueshift_permute::{CYCLE_FRAMES, Screen, sample_key, sequence_mask_shift};
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::{Camera, Scene};

/// The Cornell box and the method assets.
fn box_scene() -> (Scene, MethodAssets) {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    (s, MethodAssets::load(&default_assets_dir()).unwrap())
}

fn renderer(
    gpu: &Gpu,
    s: &Scene,
    assets: &MethodAssets,
    method: &str,
    (w, h): (u32, u32),
    sequence: u32,
) -> Renderer {
    let cfg = RenderConfig {
        // Two bounces: in direct light a moving view skips the sort.
        bounces: 2,
        method: method.parse::<Method>().unwrap(),
        sequence,
        ..RenderConfig::new(w, h)
    };
    Renderer::new(gpu.dev(), s, assets, cfg).unwrap()
}

/// Pixel x of world point `p` seen by `cam` on a `w x h` view: where the ray through that
/// pixel's position meets it (x = 0 at the left edge).
fn pixel_x(cam: &Camera, w: u32, h: u32, p: glam::Vec3) -> f64 {
    let b = cam.basis(w as f32 / h as f32);
    let d = p - b.position;
    // d = z forward + a right + c up, with right and up orthogonal to forward.
    let z = d.dot(b.forward);
    let a = d.dot(b.right) / b.right.length_squared();
    f64::from((a / z + 1.0) * 0.5 * w as f32)
}

/// Pairs of pixels of one 8x8 block whose seeds' next light samples are out of the order of
/// the mask slice of the next frame read at offset `(ox, oy)` (after frame `traced`).
fn out_of_order(
    seeds: &[u32],
    stride: usize,
    assets: &MethodAssets,
    (w, h): (u32, u32),
    traced: u64,
    (ox, oy): (u32, u32),
) -> usize {
    let samples = blueshift_sampling::Samples::default();
    let (n, frames) = (assets.stbn_n, assets.stbn_frames);
    let next = traced + 1;
    let layer = (next % u64::from(frames)) as usize * (n * n) as usize;
    let phase = (next % u64::from(CYCLE_FRAMES)) as u32;
    let at = |x: u32, y: u32| {
        let rank = assets.stbn[layer + (((y + oy) % n) * n + (x + ox) % n) as usize];
        (
            rank,
            sample_key(&samples, seeds[y as usize * stride + x as usize], phase),
        )
    };
    crate::pairs_out_of_order(w, h, at)
}

/// A strafe to the right moves the image, and the target with it, to the left: after every
/// moving frame each block ranks its seeds' next light samples in the order of the slice
/// read at the accumulated motion of the scene centre (rounded), and not in the order of
/// the slice where it stands on the screen once that motion is a few pixels. Sequence 5
/// reads the volume at its own shift on top (`sequence_mask_shift`).
#[test]
fn a_moving_view_sorts_against_the_slice_moved_with_the_image() {
    let gpu = Gpu::new();
    let (s, assets) = box_scene();
    let n = assets.stbn_n;
    let (sx, sy) = sequence_mask_shift(5);
    assert_ne!((sx % n, sy % n), (0, 0), "sequence 5 must move the volume");
    for (sequence, (sx, sy)) in [(0, (0, 0)), (5, (sx, sy))] {
        sorts_with_the_image(&gpu, &s, &assets, sequence, (sx % n, sy % n));
    }
}

fn sorts_with_the_image(
    gpu: &Gpu,
    s: &Scene,
    assets: &MethodAssets,
    sequence: u32,
    (sx, sy): (u32, u32),
) {
    let (w, h) = (40u32, 24u32);
    // The moving sort kept: a moving view of the untextured box skips it (`still_volume.rs`);
    // with textures it sorts like this.
    let form = "sort-cycle:without=white-depth";
    let mut r = renderer(gpu, s, assets, form, (w, h), sequence);
    let rows = Screen::new(w, h, assets.n).unwrap().padded_height() as usize;
    let stride = r.initial_seeds().len() / rows;
    let n = assets.stbn_n;
    let centre = s.bounds().center();
    let cam0 = s.camera_or_default();
    let mut cam = cam0;
    r.render_frame().unwrap();
    let mut screen_disorder = 0;
    for traced in 1..2 * u64::from(CYCLE_FRAMES) {
        cam.position.x += 0.02;
        cam.target.x += 0.02;
        r.set_camera(cam);
        r.render_frame().unwrap();
        let seeds = r.read_seeds().unwrap();
        let shift = pixel_x(&cam, w, h, centre) - pixel_x(&cam0, w, h, centre);
        assert!(shift < 0.0, "the image moved right");
        let ox = (-(shift.round() as i64)).rem_euclid(i64::from(n)) as u32;
        let off = ((ox + sx) % n, sy);
        let bad = out_of_order(&seeds, stride, assets, (w, h), traced, off);
        assert_eq!(
            bad, 0,
            "sequence {sequence}, moving frame {traced}, offset {off:?}"
        );
        if ox != 0 {
            screen_disorder += out_of_order(&seeds, stride, assets, (w, h), traced, (sx, sy));
        }
    }
    assert!(
        screen_disorder > 0,
        "sequence {sequence}: the target never left the screen"
    );
}

/// With the view still, `target=follow` is `target=screen` bit for bit: same seeds, same
/// images.
#[test]
fn a_still_view_sorts_as_the_screen_target() {
    let gpu = Gpu::new();
    let (w, h) = (24u32, 16u32);
    let (s, assets) = box_scene();
    let mut a = renderer(&gpu, &s, &assets, "sort-cycle:target=screen", (w, h), 0);
    let mut b = renderer(&gpu, &s, &assets, "sort-cycle", (w, h), 0);
    for _ in 0..CYCLE_FRAMES + 3 {
        a.render_frame().unwrap();
        b.render_frame().unwrap();
        assert_eq!(a.read_seeds().unwrap(), b.read_seeds().unwrap());
        assert!(crate::same_bits(
            &a.read_estimate().unwrap(),
            &b.read_estimate().unwrap()
        ));
    }
}
