//! The `taa` pass against its CPU twin (`blueshift_render::taa`, what eval measures with) on the
//! Cornell box: a strafing camera over several frames, a still camera (the plain EMA), and the
//! pixels a strafe disoccludes (they restart from their frame).
use crate::Gpu;
use blueshift_layout::motion::GBufferTexel;
use blueshift_layout::params::TraceParams;
use blueshift_permute::Screen;
use blueshift_render::taa::{Reprojection, accumulate};
use blueshift_render::{
    Accumulation, CameraPath, Method, MethodAssets, RenderConfig, Renderer, default_assets_dir,
    motion_params,
};
use blueshift_scene::Scene;

const SIZE: (u32, u32) = (48, 40);

/// One rendered frame as read back.
struct Frame {
    tp: TraceParams,
    est: Vec<[f32; 4]>,
    g: Vec<GBufferTexel>,
    acc: Vec<[f32; 4]>,
}

/// `frames` frames of `method` with `accumulation` along camera path `path` (laid out as eval
/// and `render` lay it out), direct light; the view window drifts down by `drift` px per frame
/// (a strafe alone moves only along x, where two of the four bilinear taps weigh 0).
fn run(
    gpu: &Gpu,
    method: Method,
    accumulation: Accumulation,
    (path, drift): (&str, f32),
    frames: u32,
) -> Vec<Frame> {
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    let path = CameraPath::parse(path).unwrap();
    let (view, base_offset) = path.view_window(frames, SIZE.0, SIZE.1);
    let cfg = RenderConfig {
        bounces: 1,
        method,
        accumulation,
        view_size: Some(view),
        ..RenderConfig::new(SIZE.0, SIZE.1)
    };
    let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
    let base = scene.camera_or_default();
    let path = path.fit(&scene.bounds(), &base, view);
    (0..frames)
        .map(|f| {
            r.set_camera(path.camera(&base, f));
            let o = path.view_offset(f);
            let y = base_offset.1 + o.1 + drift * f as f32;
            r.set_view_offset((base_offset.0 + o.0, y));
            let tp = r.trace_params();
            r.render_frame().unwrap();
            Frame {
                tp,
                est: r.read_estimate().unwrap(),
                g: r.read_gbuffer().unwrap().expect("the TAA keeps G-buffers"),
                acc: r.read_accum().unwrap(),
            }
        })
        .collect()
}

/// The twin's reprojection from frame `a` into frame `b` (the screen's padding is irrelevant
/// here: tile 1).
fn reprojection(a: &Frame, b: &Frame) -> Reprojection {
    let screen = Screen::new(SIZE.0, SIZE.1, 1).unwrap();
    Reprojection::new(&b.g, &a.g, &motion_params(&a.tp, &screen), SIZE.0)
}

fn flat(px: &[[f32; 4]]) -> &[f32] {
    bytemuck::cast_slice(px)
}

/// Tolerance of one value (`want` from the twin): the pass does the twin's float operations in
/// its order (`precise`), so the taps and weights are the same; only the renormalising
/// division may round differently on a device (Vulkan allows 2.5 ulp), which moves each weight
/// by ~3e-7 relative and the history by no more than 4 of those. 1e-5 of the magnitude (plus
/// 1e-5 absolute, for values near 0) bounds that with margin, while a dropped tap or another
/// alpha moves a 1-spp value by percents.
fn close(got: f32, want: f32) -> bool {
    (got - want).abs() <= 1e-5 * (1.0 + want.abs())
}

/// Frame by frame under a strafe with a vertical drift (sub-pixel motion on both axes, so all
/// four taps weigh; parallax, disocclusion), each step of the
/// GPU accumulation equals the twin's step from the GPU's previous accumulation, and the whole
/// run equals the twin's run; for a method without G-buffers of its own (the pass writes it)
/// and a reprojecting one (the pass reuses the renderer's).
#[test]
fn strafing_taa_matches_the_cpu_twin() {
    let gpu = Gpu::new();
    let reproject: Method = "sort-retarget:motion=reproject".parse().unwrap();
    for method in [Method::White, reproject] {
        let frames = run(&gpu, method, Accumulation::Taa, ("strafe:2.5", 0.3), 6);
        let mut twin = frames[0].est.concat();
        assert_eq!(
            flat(&frames[0].acc),
            flat(&frames[0].est),
            "{method}: frame 0"
        );
        for t in 1..frames.len() {
            let (a, b) = (&frames[t - 1], &frames[t]);
            let op = reprojection(a, b);
            assert!(op.motion_px > 1.0, "{method} frame {t}: the camera moved");
            let step = op.step(flat(&a.acc), flat(&b.est), 4);
            twin = accumulate(Some(&op), &twin, flat(&b.est), 4);
            let got = flat(&b.acc);
            for (i, (g, w)) in got.iter().zip(&step).enumerate() {
                assert!(close(*g, *w), "{method} frame {t} value {i}: {g} vs {w}");
            }
            // Over the run, the steps' differences shrink by 1 - alpha per frame: at most 10x
            // one step's.
            for (i, (g, w)) in got.iter().zip(&twin).enumerate() {
                assert!(
                    (g - w).abs() <= 1e-4 * (1.0 + w.abs()),
                    "{method} run to frame {t} value {i}: {g} vs {w}"
                );
            }
        }
    }
}

/// Under a strafe, exactly the pixels the twin gives no history restart from their frame's
/// estimate, bit for bit; among them are pixels inside the screen that see a surface (the
/// disoccluded background beside the boxes), not only the column entering at the border.
#[test]
fn disoccluded_pixels_restart() {
    let gpu = Gpu::new();
    let frames = run(
        &gpu,
        Method::White,
        Accumulation::Taa,
        ("strafe:2.5", 0.0),
        4,
    );
    let mut disoccluded = 0;
    for t in 1..frames.len() {
        let (a, b) = (&frames[t - 1], &frames[t]);
        let op = reprojection(a, b);
        for i in 0..b.est.len() {
            let same = b.acc[i].map(f32::to_bits) == b.est[i].map(f32::to_bits);
            if !op.kept(i) {
                assert!(same, "frame {t} pixel {i}: no history, yet not restarted");
                let x = i as u32 % SIZE.0;
                disoccluded += usize::from(b.g[i].material != 0 && (4..SIZE.0 - 4).contains(&x));
            }
        }
    }
    assert!(disoccluded > 0, "the strafe disoccluded nothing");
}

/// With a still camera the TAA is the plain EMA of weight 0.1, bit for bit, on every pixel
/// (sky included): frame t's accumulation is a + 0.1 (e - a) of frame t - 1's.
#[test]
fn still_taa_is_the_plain_ema() {
    let gpu = Gpu::new();
    let frames = run(&gpu, Method::White, Accumulation::Taa, ("static", 0.0), 5);
    for t in 1..frames.len() {
        let (a, b) = (&frames[t - 1], &frames[t]);
        let ema: Vec<f32> = flat(&a.acc)
            .iter()
            .zip(flat(&b.est))
            .map(|(a, e)| a + 0.1 * (e - a))
            .collect();
        let same = ema
            .iter()
            .zip(flat(&b.acc))
            .all(|(x, y)| x.to_bits() == y.to_bits());
        assert!(same, "frame {t}: the still TAA is not the EMA");
        assert_ne!(flat(&b.acc), flat(&a.acc), "frame {t}: nothing accumulated");
    }
}

/// The viewer's mode: while the camera moves it accumulates exactly as the TAA mode does; with
/// a still camera it is the running mean.
#[test]
fn follow_is_the_taa_while_moving_and_a_mean_when_still() {
    let gpu = Gpu::new();
    let [taa, follow] = [Accumulation::Taa, Accumulation::Follow]
        .map(|a| run(&gpu, Method::White, a, ("strafe:2.5", 0.3), 3));
    for (t, (a, b)) in taa.iter().zip(&follow).enumerate() {
        assert_eq!(flat(&a.acc), flat(&b.acc), "frame {t}");
    }
    let still = run(
        &gpu,
        Method::White,
        Accumulation::Follow,
        ("static", 0.0),
        3,
    );
    let (a, b) = (&still[1], &still[2]);
    // A still start is the plain running mean: frame 2 weighs its estimate by 1/3.
    for ((acc, prev), e) in flat(&b.acc).iter().zip(flat(&a.acc)).zip(flat(&b.est)) {
        let want = prev + (e - prev) / 3.0;
        assert!(close(*acc, want), "{acc} vs {want}");
    }
}
