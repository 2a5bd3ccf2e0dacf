//! History keys (`permute/history_key` and the sorting pass's history input): GPU == CPU twin
//! over a sequence of frames with random source maps (holes, collisions, off-screen padding),
//! and a still image whose history keys rank pixels by their error, not their value.
use crate::{Gpu, Lcg};
use blueshift_device::Buffer;
use blueshift_layout::motion::{GBufferTexel, HistoryParams, REPROJECT_NONE};
use blueshift_permute::{HistoryKeys, Screen, history_key_cpu, sort_seeds_cpu};

/// A source map like reproject_motion's: every visible pixel maps to a random visible pixel of
/// the previous frame (so some sources are shared), or to none for about one in five.
fn random_src(sc: &Screen, rng: &mut Lcg) -> Vec<u32> {
    let (w, h, pw) = (sc.width, sc.height, sc.stride());
    let mut src = vec![REPROJECT_NONE; sc.seed_count()];
    for y in 0..h {
        for x in 0..w {
            if rng.next_u32() % 5 != 0 {
                let (sx, sy) = (rng.next_u32() % w, rng.next_u32() % h);
                src[(y * pw + x) as usize] = sy * pw + sx;
            }
        }
    }
    src
}

/// A G-buffer of two surfaces (materials 1 and 2, random per pixel) and sky (0) on one plane,
/// so `similar` is "same material".
fn random_gbuffer(w: u32, h: u32, rng: &mut Lcg) -> Vec<GBufferTexel> {
    (0..w * h)
        .map(|i| GBufferTexel {
            position: glam::Vec3::new((i % w) as f32, (i / w) as f32, 5.0),
            material: rng.next_u32() % 3,
            normal: glam::Vec3::Z,
            depth: 5.0,
        })
        .collect()
}

#[test]
fn history_keys_match_cpu_over_frames() {
    let mut gpu = Gpu::new();
    let mut rng = Lcg(17);
    // 300 columns: two workgroups across (each covers 256).
    for (w, h) in [(37, 23), (64, 48), (300, 20)] {
        let sc = Screen::new(w, h, 16).unwrap();
        let mut keys_pass = HistoryKeys::new(gpu.dev(), &sc).unwrap();
        let mut cpu_hist = vec![[0.0f32; 2]; sc.seed_count()];
        // min 2, max 3: within six frames every branch runs (young, capped, restarted).
        for frame in 0..6u32 {
            let p = HistoryParams {
                width: w,
                height: h,
                padded_width: sc.stride(),
                has_history: u32::from(frame > 0),
                min_frames: 2,
                max_frames: 3,
            };
            let keys: Vec<f32> = (0..w * h).map(|_| rng.unit() * 10.0 - 2.0).collect();
            let est: Vec<[f32; 4]> = keys.iter().map(|&k| [1.0, 2.0, 3.0, k]).collect();
            let src = random_src(&sc, &mut rng);
            let est_b = Buffer::from_slice(gpu.dev(), "history.estimate", &est).unwrap();
            let src_b = Buffer::from_slice(gpu.dev(), "history.src", &src).unwrap();
            let g = random_gbuffer(w, h, &mut rng);
            let g_b = Buffer::from_slice(gpu.dev(), "history.gbuffer", &g).unwrap();
            let rec = gpu.rec.as_mut().unwrap();
            rec.begin().unwrap();
            rec.begin_pass("history_key").unwrap();
            keys_pass
                .history_key(rec, &p, &est_b, &src_b, &g_b)
                .unwrap();
            rec.submit_and_wait().unwrap();

            let (hist, mean) = history_key_cpu(&p, &keys, &src, &cpu_hist, &g);
            let gpu_hist = keys_pass.current().read::<[f32; 2]>().unwrap();
            let gpu_mean = keys_pass.mean.read::<f32>().unwrap();
            for y in 0..h {
                for x in 0..w {
                    let (at, here) = ((y * w + x) as usize, (y * sc.stride() + x) as usize);
                    // Bit for bit: the same float operations in the same order (`precise`).
                    let what = format!("{w}x{h} frame {frame} pixel ({x}, {y})");
                    assert_eq!(gpu_hist[here], hist[here], "history {what}");
                    assert_eq!(gpu_mean[at].to_bits(), mean[at].to_bits(), "mean {what}");
                }
            }
            let nan = mean.iter().filter(|m| m.is_nan()).count();
            if frame == 0 {
                assert_eq!(nan, 0, "the first frame ranks raw keys");
            } else if frame == 1 {
                assert_eq!(nan, mean.len(), "one frame of history is below min_frames");
            } else {
                assert!(nan < mean.len(), "frame {frame}: {nan} NaN means");
            }
            cpu_hist = hist;
        }
    }
}

/// The 3x3 window: over one surface a linear gradient of history means averages to the
/// centre's own value; a pixel of another surface or with a too-short history is left out.
#[test]
fn history_window_keeps_gradients_and_surfaces() {
    let (w, h) = (5u32, 5u32);
    let sc = Screen::new(w, h, 8).unwrap();
    let pw = sc.stride();
    let src: Vec<u32> = (0..sc.seed_count() as u32)
        .map(|i| {
            if i % pw < w && i / pw < h {
                i
            } else {
                REPROJECT_NONE
            }
        })
        .collect();
    let ramp = |x: u32, y: u32| 3.0 * x as f32 + 5.0 * y as f32 + 1.0;
    let mut hist = vec![[0.0f32; 2]; sc.seed_count()];
    for y in 0..h {
        for x in 0..w {
            hist[(y * pw + x) as usize] = [ramp(x, y), 10.0];
        }
    }
    let texel = |material| GBufferTexel {
        position: glam::Vec3::new(0.0, 0.0, 5.0),
        material,
        normal: glam::Vec3::Z,
        depth: 5.0,
    };
    let mut g = vec![texel(1); (w * h) as usize];
    let p = HistoryParams {
        width: w,
        height: h,
        padded_width: pw,
        has_history: 1,
        min_frames: 4,
        max_frames: 64,
    };
    let keys = vec![0.0; (w * h) as usize];
    let centre = (2 * w + 2) as usize;
    let (_, mean) = history_key_cpu(&p, &keys, &src, &hist, &g);
    // One rounding in the division by the count.
    assert!(
        (mean[centre] - ramp(2, 2)).abs() <= 1e-5 * ramp(2, 2),
        "{}",
        mean[centre]
    );
    // Another surface at (1, 1) with a far mean, and a young history at (3, 1).
    g[(w + 1) as usize] = texel(2);
    hist[(pw + 1) as usize][0] = 1000.0;
    hist[(pw + 3) as usize][1] = 2.0;
    let (_, mean) = history_key_cpu(&p, &keys, &src, &hist, &g);
    let kept = [(2, 1), (1, 2), (2, 2), (3, 2), (1, 3), (2, 3), (3, 3)];
    let want = kept.iter().map(|&(x, y)| ramp(x, y)).sum::<f32>() / kept.len() as f32;
    assert!(
        (mean[centre] - want).abs() <= 1e-5 * want,
        "{} vs {want}",
        mean[centre]
    );
    // The other surface's pixel has no neighbour of its surface but itself.
    assert_eq!(mean[(w + 1) as usize], 1000.0);
}

/// A still block whose true values vary (a gradient) under errors of random sign: with the
/// true values as history means, the seeds are ranked by error, so each lands where the mask
/// asks for its error's rank; with raw keys they follow the gradient instead.
#[test]
fn history_means_rank_errors_not_values() {
    let sc = Screen::new(8, 8, 8).unwrap();
    let mut rng = Lcg(5);
    let mask = rng.perm(64);
    let truth: Vec<f32> = (0..64).map(|i| (i % 8) as f32 * 10.0).collect();
    let error: Vec<f32> = (0..64).map(|_| rng.unit() * 2.0 - 1.0).collect();
    let lum: Vec<f32> = truth.iter().zip(&error).map(|(t, e)| t + e).collect();
    let p = sc.sort_params(8, (0, 0)).unwrap();
    let classes = [0u32; 64];
    let init: Vec<u32> = (0..64).collect();
    let (mut ranked, mut raw) = (init.clone(), init.clone());
    sort_seeds_cpu(&p, &lum, &mask, &classes, &truth, &mut ranked);
    sort_seeds_cpu(&p, &lum, &mask, &classes, &[0.0; 64], &mut raw);
    // Seeds are their old pixel: the error each pixel now holds, in mask order.
    let by_mask = |seeds: &[u32]| {
        let mut order: Vec<usize> = (0..64).collect();
        order.sort_by_key(|&i| mask[i]);
        order
            .iter()
            .map(|&i| error[seeds[i] as usize])
            .collect::<Vec<f32>>()
    };
    let e = by_mask(&ranked);
    assert!(
        e.windows(2).all(|w| w[0] <= w[1]),
        "errors follow the mask: {e:?}"
    );
    let r = by_mask(&raw);
    assert!(
        r.windows(2).any(|w| w[0] > w[1]),
        "raw keys would rank errors too"
    );
}
