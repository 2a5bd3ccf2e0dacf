//! The point cycle of sort-cycle (run by the sorting pass): GPU == CPU twins exactly over
//! whole cycles, and the renderer's seeds stay a permutation that never leaves its block.
use crate::{Gpu, Lcg};
use blueshift_device::{Buffer, MemoryLocation};
use blueshift_permute::{
    CYCLE_FRAMES, CycleInput, PermutePasses, Screen, SortInput, SortVariant, cycle_keys_cpu,
    is_permutation_of, sort_seeds_cpu, with_cycle,
};
use blueshift_render::{Method, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;
use std::collections::BTreeMap;

/// A volume of `t` random permutations of `n * n` ranks.
fn volume(n: u32, t: u32, rng: &mut Lcg) -> Vec<u32> {
    (0..t).flat_map(|_| rng.perm(n * n)).collect()
}

/// The sorting pass with the point cycle on the way in, frame after frame, against the CPU
/// twins (cycle_keys_cpu then sort_seeds_cpu): the seeds it leaves and the history slots agree
/// bit for bit, over more than a cycle (so the history slots are written, then read back), with ties and NaN keys,
/// with and without running means, ranking the recorded keys or (every fourth frame, as
/// while the view moves) the seeds' next light samples, on screens with more and with fewer
/// pixels than a mask slice.
#[test]
fn cycle_keys_and_sort_match_cpu_over_cycles() {
    let mut gpu = Gpu::new();
    let dev = gpu.dev().clone();
    let mut permute = PermutePasses::new(&dev).unwrap();
    let mut rng = Lcg(0xc7c1e);
    for (w, h, n) in [(37u32, 23u32, 16u32), (10, 7, 16)] {
        let sc = Screen::new(w, h, n).unwrap();
        let vol = volume(n, 4, &mut rng);
        let init: Vec<u32> = rng.perm(sc.seed_count() as u32);
        let pixels = (w * h) as usize;
        let host = MemoryLocation::GpuToCpu;
        let seeds = Buffer::from_slice(&dev, "cycle.seeds", &init).unwrap();
        let history_len = CYCLE_FRAMES as usize * pixels;
        let mut history = Buffer::new(&dev, "cycle.history", history_len as u64 * 8, host).unwrap();
        history.write(0, &vec![[0u32; 2]; history_len]).unwrap();
        let volb = Buffer::from_slice(&dev, "cycle.volume", &vol).unwrap();
        let mut est = Buffer::new(&dev, "cycle.estimate", pixels as u64 * 16, host).unwrap();
        let mut accum = Buffer::new(&dev, "cycle.accum", pixels as u64 * 16, host).unwrap();
        let (mut cpu_seeds, mut cpu_hist) = (init.clone(), vec![[0u32; 2]; history_len]);
        for frame in 0..u64::from(CYCLE_FRAMES) + 5 {
            // Few distinct values (ties), a NaN now and then.
            let lum: Vec<f32> = (0..pixels)
                .map(|_| match rng.next_u32() % 9 {
                    0 => f32::NAN,
                    k => k as f32 * 0.25,
                })
                .collect();
            est.write(0, &lum.iter().map(|&l| [l, l, l, l]).collect::<Vec<_>>())
                .unwrap();
            // Running means from a coarser set of values (key - mean ties too); none on
            // every third frame (an accumulation restart: raw keys).
            let means: Vec<f32> = (0..pixels)
                .map(|_| (rng.next_u32() % 5) as f32 * 0.5)
                .collect();
            accum
                .write(0, &means.iter().map(|&m| [m, m, m, m]).collect::<Vec<_>>())
                .unwrap();
            let count = if frame % 3 == 0 { 0 } else { frame as u32 };
            let cp = sc.cycle_params(frame, n, 4, count, frame % 4 == 1);
            let sp = blueshift_permute::SortParams {
                mask_size: n,
                ..sc.sort_params(8, (0, 0)).unwrap()
            };
            let sp = with_cycle(sp, &cp);
            let rec = gpu.rec.as_mut().unwrap();
            rec.begin().unwrap();
            rec.begin_pass("sort_seeds").unwrap();
            let input = SortInput {
                cycle: Some(CycleInput {
                    history: &history,
                    accum: &accum,
                }),
                ..SortInput::new(&est, &volb)
            };
            let variant = SortVariant {
                cycle: true,
                sample_keys: cp.sample_keys != 0,
                large: SortVariant::large_for(sp.block),
                ..SortVariant::PAPER
            };
            permute
                .sort_seeds(rec, &sp, variant, &input, &seeds)
                .unwrap();
            rec.submit_and_wait().unwrap();

            let out = cycle_keys_cpu(&cp, &lum, &means, &mut cpu_seeds, &mut cpu_hist, &vol);
            let zeros = vec![0u32; pixels];
            let no_history = vec![0f32; pixels];
            sort_seeds_cpu(
                &sp,
                &out.keys,
                &out.mask,
                &zeros,
                &no_history,
                &mut cpu_seeds,
            );
            let got: Vec<u32> = seeds.read().unwrap();
            assert_eq!(got[..init.len()], cpu_seeds[..], "{w}x{h} frame {frame}");
            assert_eq!(
                history.read::<[u32; 2]>().unwrap()[..history_len],
                cpu_hist[..]
            );
            assert!(is_permutation_of(&cpu_seeds, &init));
        }
    }
}

/// `method` (a `sort-cycle` form) on the Cornell box at `bounces` and `w x h`: the scene, the
/// method assets (the tests read the STBN volume), the renderer and its seed buffer's row
/// stride.
fn box_sort_cycle(
    gpu: &Gpu,
    method: Method,
    bounces: u32,
    (w, h): (u32, u32),
) -> (Scene, blueshift_render::MethodAssets, Renderer, usize) {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    let cfg = RenderConfig {
        bounces,
        method,
        ..RenderConfig::new(w, h)
    };
    let r = Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap();
    let rows = Screen::new(w, h, assets.n).unwrap().padded_height() as usize;
    let stride = r.initial_seeds().len() / rows;
    (s, assets, r, stride)
}

/// The sorted seeds of each 8x8 block of a `w x h` view (padded rows of `stride`).
fn block_sets(seeds: &[u32], stride: usize, w: u32, h: u32) -> BTreeMap<(u32, u32), Vec<u32>> {
    let mut sets = BTreeMap::<(u32, u32), Vec<u32>>::new();
    for y in 0..h {
        for x in 0..w {
            let v = seeds[y as usize * stride + x as usize];
            sets.entry((x / 8, y / 8)).or_default().push(v);
        }
    }
    sets.values_mut().for_each(|v| v.sort_unstable());
    sets
}

/// The renderer's sort-cycle seeds over two cycles: a permutation of the initial seeds at
/// every frame, and each 8x8 block keeps its own seeds (the history slots stay valid only so).
#[test]
fn sort_cycle_seeds_stay_in_their_blocks() {
    let gpu = Gpu::new();
    let (w, h) = (37u32, 21u32);
    let (_, _, mut r, stride) = box_sort_cycle(&gpu, Method::SORT_CYCLE, 2, (w, h));
    let init = r.initial_seeds().to_vec();
    let want = block_sets(&init, stride, w, h);
    for _ in 0..2 * CYCLE_FRAMES + 1 {
        r.render_frame().unwrap();
        let seeds = r.read_seeds().unwrap();
        assert!(is_permutation_of(&seeds, &init));
        assert_eq!(block_sets(&seeds, stride, w, h), want);
    }
    assert_ne!(r.read_seeds().unwrap(), init, "seeds never moved");
}

/// While the view moves, the renderer's sort-cycle ranks each block's seeds by where their
/// next light sample lands: in every 8x8 block, a pixel with a lower mask rank (the slice of
/// the next frame) holds a seed whose block-net point at the next phase has a lower or equal
/// Hilbert index, computed here from the sampler and the mask alone. With the view still again,
/// the seeds rank by their recorded keys, and that order no longer holds everywhere. The
/// target stays on the screen here (`follow.rs` tests the one that moves with the image).
#[test]
fn a_moving_view_ranks_seeds_by_their_next_light_sample() {
    let gpu = Gpu::new();
    let (w, h) = (40u32, 24u32);
    // Two bounces and the sort kept while moving: on this untextured box a moving view skips
    // it (`a_moving_view_without_seeds_skips_the_sort`); with textures it sorts like this.
    let screen = "sort-cycle:target=screen,without=white-depth"
        .parse()
        .unwrap();
    let (s, assets, mut r, stride) = box_sort_cycle(&gpu, screen, 2, (w, h));
    let samples = blueshift_sampling::Samples::default();
    let (n, frames) = (assets.stbn_n, assets.stbn_frames);
    // Pairs of pixels of one block whose seeds' next light samples are out of the mask's
    // order, after the frame `traced` (0-based) was rendered.
    let out_of_order = |seeds: &[u32], traced: u64| {
        let next = traced + 1;
        let layer = (next % u64::from(frames)) as usize * (n * n) as usize;
        let phase = (next % u64::from(CYCLE_FRAMES)) as u32;
        let at = |x: u32, y: u32| {
            let rank = assets.stbn[layer + ((y % n) * n + x % n) as usize];
            let seed = seeds[y as usize * stride + x as usize];
            (rank, blueshift_permute::sample_key(&samples, seed, phase))
        };
        crate::pairs_out_of_order(w, h, at)
    };
    let mut cam = s.camera_or_default();
    r.render_frame().unwrap();
    for traced in 1..2 * u64::from(CYCLE_FRAMES) + 3 {
        cam.position.x += 0.01;
        r.set_camera(cam);
        r.render_frame().unwrap();
        let seeds = r.read_seeds().unwrap();
        assert_eq!(out_of_order(&seeds, traced), 0, "moving frame {traced}");
    }
    let mut still_disorder = 0;
    for traced in 2 * u64::from(CYCLE_FRAMES) + 3..3 * u64::from(CYCLE_FRAMES) + 3 {
        r.render_frame().unwrap();
        still_disorder += out_of_order(&r.read_seeds().unwrap(), traced);
    }
    assert!(still_disorder > 0, "a still view ranked by the samples too");
}

/// A still view reuses the G-buffer and the surface classes: after the first frame neither
/// pass runs, until the camera or the view window moves; then both run and the G-buffer is
/// the moved camera's (CPU twin). `grouping=surfaces` classifies every moved frame; the
/// default's `still-surfaces` gives a moved frame one class per block (zeroed classes, no
/// G-buffer) and classifies the first still frame after it.
#[test]
fn still_view_reuses_gbuffer_and_classes() {
    let gpu = Gpu::new();
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let sg = blueshift_scene::SceneGpu::build(&s);
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    let renderer = |method: Method| {
        let cfg = RenderConfig {
            bounces: 2,
            method,
            ..RenderConfig::new(29, 19)
        };
        Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap()
    };
    let ran = |r: &mut Renderer| {
        let names: Vec<String> = r
            .render_frame()
            .unwrap()
            .passes
            .into_iter()
            .map(|p| p.name)
            .collect();
        let has = |n: &str| names.iter().any(|p| p == n);
        assert_eq!(has("gbuffer"), has("classify_pixels"), "{names:?}");
        has("gbuffer")
    };
    let mut cam = s.camera_or_default();
    cam.position.x += 0.05;
    // The moving sort kept (on this untextured box a moving frame of the default skips it,
    // `still_volume.rs`; with textures it sorts like this).
    let form = |f: &str| -> Method {
        format!("sort-cycle:{f}without=white-depth")
            .parse()
            .unwrap()
    };
    for (m, still_only) in [(form("grouping=surfaces,"), false), (form(""), true)] {
        let mut r = renderer(m);
        assert!(ran(&mut r), "{m}: the first frame needs a G-buffer");
        assert!(
            !ran(&mut r) && !ran(&mut r),
            "{m}: a still view recomputed its G-buffer"
        );
        r.set_camera(cam);
        let tp = r.trace_params();
        if still_only {
            assert!(!ran(&mut r), "{m}: a moved frame traced a G-buffer");
            let classes = r.read_classes().unwrap().expect("classes");
            assert!(
                classes.iter().all(|&c| c == 0),
                "{m}: not one class per block"
            );
            assert!(
                ran(&mut r),
                "{m}: the still frame after a move did not classify"
            );
            let classes = r.read_classes().unwrap().expect("classes");
            assert!(
                classes.iter().any(|&c| c != 0),
                "{m}: no surfaces after the move"
            );
        } else {
            assert!(ran(&mut r), "{m}: a moved camera kept the old G-buffer");
        }
        let got = r
            .read_gbuffer()
            .unwrap()
            .expect("sort-cycle has a G-buffer");
        let want = blueshift_render::gbuffer_cpu(&sg, &tp);
        let same = got
            .iter()
            .zip(&want)
            .filter(|(g, c)| g.material == c.material)
            .count();
        // Materials agree exactly (the traversal is bit-exact; tests/src/motion.rs checks the
        // rest).
        assert_eq!(same, want.len(), "{m}");
        assert!(!ran(&mut r), "{m}");
        r.set_view_offset((0.5, 0.0));
        assert_eq!(
            ran(&mut r),
            !still_only,
            "{m}: after moving the view window"
        );
        assert!(
            ran(&mut r) == still_only,
            "{m}: the view window stands still"
        );
    }

    // Reprojecting methods keep two G-buffers (this frame's and the last): with a still view
    // each is traced once, then both stand until the camera moves. The reprojection runs from
    // the second frame; once it repeats with the same inputs and moved no seed, it stops.
    let mut r = renderer(Method::SORT_GRID_ADAPTIVE);
    let traced = |r: &mut Renderer| {
        let stats = r.render_frame().unwrap();
        let has = |n: &str| stats.passes.iter().any(|p| p.name == n);
        assert_eq!(has("reproject_motion"), has("reproject_seeds"));
        (has("gbuffer"), has("reproject_seeds"))
    };
    let still: Vec<_> = (0..5).map(|_| traced(&mut r)).collect();
    let (t, f) = (true, false);
    assert_eq!(still, [(t, f), (t, t), (f, f), (f, f), (f, f)]);
    r.set_camera(cam);
    let moved: Vec<_> = (0..4).map(|_| traced(&mut r)).collect();
    assert_eq!(
        moved,
        [(t, t), (t, t), (f, f), (f, f)],
        "after a camera move"
    );
    let seeds = r.read_seeds().unwrap();
    let mut sorted = seeds.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(
        sorted.len(),
        seeds.len(),
        "the seeds are no longer a permutation"
    );
}

/// Which dimensions sort-cycle leaves to the mask (`Method::mask_dims`), seen in its images:
/// without anti-aliasing jitter a still view renders exactly what `mask=none` renders (the
/// light and BSDF samples stay the seeds'), with jitter it does not (the mask moves the
/// rays); a moving view takes the first vertex's light and BSDF samples from the mask too,
/// which `mask=jitter` never does, and `mask=motion` only its BSDF sample. At 2 bounces: in
/// direct light on the box a still view takes the whole first vertex from the volume
/// (`still_volume.rs`).
#[test]
fn sort_cycle_leaves_the_jitter_and_a_moving_first_bounce_to_the_mask() {
    let gpu = Gpu::new();
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    let frames = |method: &str, no_jitter: bool, moving: bool| {
        let cfg = RenderConfig {
            bounces: 2,
            method: method.parse().unwrap(),
            no_jitter,
            ..RenderConfig::new(24, 16)
        };
        let mut r = Renderer::new(gpu.dev(), &s, &assets, cfg).unwrap();
        let mut cam = s.camera_or_default();
        (0..4)
            .map(|_| {
                if moving {
                    cam.position.x += 0.01;
                    r.set_camera(cam);
                }
                r.render_frame().unwrap();
                r.read_estimate().unwrap()
            })
            .collect::<Vec<_>>()
    };
    let bits = |f: &[Vec<[f32; 4]>]| -> Vec<u32> {
        f.iter().flatten().flatten().map(|v| v.to_bits()).collect()
    };
    let same = |a: &str, b: &str, no_jitter: bool, moving: bool| {
        bits(&frames(a, no_jitter, moving)) == bits(&frames(b, no_jitter, moving))
    };
    // (method, no jitter, moving view, renders as mask=none, what a failure means)
    let cases = [
        (
            "sort-cycle",
            true,
            false,
            true,
            "still: the mask drove a light or BSDF sample",
        ),
        (
            "sort-cycle",
            false,
            false,
            false,
            "still: the jitter is not the mask's",
        ),
        (
            "sort-cycle:mask=jitter",
            true,
            true,
            true,
            "mask=jitter drove more than the jitter",
        ),
        (
            "sort-cycle",
            true,
            true,
            false,
            "moving: the first vertex is not the mask's",
        ),
        (
            "sort-cycle:mask=motion",
            true,
            true,
            false,
            "mask=motion moving: the first bounce is not the mask's",
        ),
    ];
    for (m, no_jitter, moving, as_none, what) in cases {
        assert_eq!(
            same(m, "sort-cycle:mask=none", no_jitter, moving),
            as_none,
            "{what}"
        );
    }
    // `mask=motion` renders as the default while still; moving, it leaves the light sample
    // to the seeds.
    let motion = "sort-cycle:mask=motion";
    assert!(
        same(motion, "sort-cycle", false, false),
        "mask=motion changed a still view"
    );
    assert!(
        !same(motion, "sort-cycle", true, true),
        "moving: the light sample is not the mask's"
    );
}

/// On an untextured scene the trace of a moving `sort-cycle` frame reads no seed, in direct
/// light (the mask draws the jitter and the first vertex) and at depth (white noise behind
/// the motion volume), so the frame runs no sort and the seeds stay where they were; the first
/// still frame sorts again, and every block keeps its own seeds throughout. (The default's
/// still frames in direct light take the volume and do not sort either, `still_volume.rs`:
/// its ablation sorts them, as the default does with textures.)
#[test]
fn a_moving_view_without_seeds_skips_the_sort() {
    let gpu = Gpu::new();
    let (w, h) = (37u32, 21u32);
    let still_sorts = "sort-cycle:without=still-volume".parse().unwrap();
    for (method, bounces) in [(still_sorts, 1), (Method::SORT_CYCLE, 3)] {
        moving_frames_skip_the_sort(&gpu, method, bounces, (w, h));
    }
}

fn moving_frames_skip_the_sort(gpu: &Gpu, method: Method, bounces: u32, (w, h): (u32, u32)) {
    let at = format!("{method} b{bounces}");
    let (s, _, mut r, stride) = box_sort_cycle(gpu, method, bounces, (w, h));
    let init = r.initial_seeds().to_vec();
    let want = block_sets(&init, stride, w, h);
    let sorted = |r: &mut Renderer| {
        let stats = r.render_frame().unwrap();
        stats.passes.iter().any(|p| p.name == "sort_seeds")
    };
    for _ in 0..CYCLE_FRAMES + 1 {
        assert!(sorted(&mut r), "{at}: a still frame skipped the sort");
    }
    let before = r.read_seeds().unwrap();
    assert_ne!(before, init, "{at}: the still frames moved no seed");
    let mut cam = s.camera_or_default();
    for frame in 0..2 * CYCLE_FRAMES {
        cam.position.x += 0.01;
        r.set_camera(cam);
        assert!(!sorted(&mut r), "{at}: moving frame {frame} sorted");
        assert_eq!(
            r.read_seeds().unwrap(),
            before,
            "{at}: moving frame {frame}"
        );
    }
    for frame in 0..2 * CYCLE_FRAMES {
        assert!(
            sorted(&mut r),
            "{at}: still frame {frame} after the motion skipped the sort"
        );
        let seeds = r.read_seeds().unwrap();
        assert_eq!(
            block_sets(&seeds, stride, w, h),
            want,
            "{at}: still frame {frame}"
        );
    }
    assert_ne!(
        r.read_seeds().unwrap(),
        before,
        "{at}: the still view sorted nothing"
    );
}
