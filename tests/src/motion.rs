//! Our extensions' passes (edge-aware grouping, seed reprojection, G-buffer): GPU == CPU twin
//! exactly, the seed buffer stays a permutation under random motion fields, and a still
//! camera makes reprojection the identity.
use crate::{Gpu, Lcg};
use blueshift_device::{Buffer, MemoryLocation};
use blueshift_layout::motion::{GBufferTexel, MotionParams, REPROJECT_NONE};
use blueshift_permute::{
    PermutePasses, Reprojection, Screen, SortInput, SortParams, SortVariant, classify_pixels_cpu,
    is_permutation_of, reproject_motion_cpu, reproject_seeds_cpu, sort_seeds_cpu,
};
use blueshift_render::{
    Method, MethodAssets, RenderConfig, Renderer, default_assets_dir, gbuffer_cpu,
};
use blueshift_scene::{Scene, SceneGpu};
use glam::{Vec2, Vec3};

/// A G-buffer of a few planar regions cut by random lines: per region a material, a normal and
/// a plane, some sky pixels; positions on the region's plane. Exercises every branch of
/// `similar` (same/different material, normal, plane, sky).
fn random_gbuffer(w: u32, h: u32, rng: &mut Lcg) -> Vec<GBufferTexel> {
    let lines: Vec<(f32, f32, f32)> = (0..3)
        .map(|_| (rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() * w as f32))
        .collect();
    let regions: Vec<(u32, Vec3, f32)> = (0..8)
        .map(|_| {
            let n = Vec3::new(rng.unit() - 0.5, rng.unit() - 0.5, 1.0).normalize();
            (rng.next_u32() % 3, n, rng.unit() * 0.3)
        })
        .collect();
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32, (i / w) as f32);
            let r = lines.iter().enumerate().fold(0, |r, (k, l)| {
                r | (usize::from(l.0 * x + l.1 * y > l.2 * 0.3) << k)
            });
            let (m, n, d) = regions[r];
            if rng.next_u32() % 17 == 0 {
                return GBufferTexel {
                    position: Vec3::ZERO,
                    material: 0,
                    normal: Vec3::ZERO,
                    depth: 0.0,
                };
            }
            let p = Vec3::new(x * 0.01, y * 0.01, 0.0);
            let position = p + n * (d - n.dot(p));
            GBufferTexel {
                position,
                material: m + 1,
                normal: n,
                depth: 3.0 + 0.01 * x,
            }
        })
        .collect()
}

#[test]
fn classify_and_class_sorting_match_cpu_and_keep_seeds_in_their_class() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(9);
    for (w, h, block) in [(37, 23, 2), (50, 41, 3), (64, 48, 4), (99, 61, 8)] {
        let sc = Screen::new(w, h, 16).unwrap();
        let g = random_gbuffer(w, h, &mut rng);
        let mask: Vec<u32> = {
            let mut m: Vec<u32> = (0..256).collect();
            for i in (1..256).rev() {
                m.swap(i, rng.next_u32() as usize % (i + 1));
            }
            m
        };
        // Keys with a heavy tail in places (one pixel in 16 a firefly), so that the sorting
        // pass's skewness count sees both kinds of classes.
        let lum: Vec<f32> = (0..w * h)
            .map(|_| match rng.next_u32() % 16 {
                0 => 500.0 + (rng.next_u32() % 40) as f32,
                _ => (rng.next_u32() % 40) as f32 * 0.5,
            })
            .collect();
        let est: Vec<[f32; 4]> = lum.iter().map(|&l| [l, l, l, l]).collect();
        // History means (history keys): NaN (rank against the class mean) for a quarter of
        // the pixels, the others near the keys.
        let history = rng.history_means((w * h) as usize, 40);
        let init: Vec<u32> = (0..sc.seed_count() as u32)
            .map(|i| i.wrapping_mul(2654435761))
            .collect();
        // The paper's fixed grid and the moving grid's offsets, with the moving grid's
        // thin-class pairs in both phases (sort-grid-*).
        let grids = [(0, 0), (block / 2, block / 2), (block - 1, 1)];
        let pairs = [(0, 0), (1, 0), (1, 1), (2, 1)];
        for (grid, (pairs, phase)) in grids.into_iter().flat_map(|g| pairs.map(|q| (g, q))) {
            let p = SortParams {
                pairs,
                phase,
                count_skew: u32::from(pairs == 2),
                ..sc.sort_params_on_grid(block, (5, 11), grid).unwrap()
            };
            let gb = Buffer::from_slice(gpu.dev(), "motion.gbuffer", &g).unwrap();
            let classes = gpu.output::<u32>("motion.classes", (w * h) as usize);
            let est_b = Buffer::from_slice(gpu.dev(), "motion.estimate", &est).unwrap();
            let mask_b = Buffer::from_slice(gpu.dev(), "motion.mask", &mask).unwrap();
            let seeds = Buffer::from_slice(gpu.dev(), "motion.seeds", &init).unwrap();
            let history_b = Buffer::from_slice(gpu.dev(), "motion.history", &history).unwrap();
            let stats_b = Buffer::from_slice(gpu.dev(), "motion.sort_stats", &[0u32; 2]).unwrap();
            let gate_b = Buffer::from_slice(gpu.dev(), "motion.pairs_gate", &[0u32; 2]).unwrap();
            let rec = gpu.rec.as_mut().unwrap();
            rec.begin().unwrap();
            rec.begin_pass("classify_pixels").unwrap();
            passes.classify_pixels(rec, &p, &gb, &classes).unwrap();
            rec.begin_pass("sort_seeds").unwrap();
            passes
                .sort_seeds(
                    rec,
                    &p,
                    SortVariant {
                        classes: true,
                        history: true,
                        pairs: true,
                        skew: true,
                        large: SortVariant::large_for(p.block),
                        ..SortVariant::PAPER
                    },
                    &SortInput {
                        estimate: &est_b,
                        mask: &mask_b,
                        classes: Some(&classes),
                        history: Some(&history_b),
                        stats: Some(&stats_b),
                        gate: Some(&gate_b),
                        retarget: None,
                        cycle: None,
                    },
                    &seeds,
                )
                .unwrap();
            rec.submit_and_wait().unwrap();

            let cpu_classes = classify_pixels_cpu(&p, &g);
            assert_eq!(
                classes.read::<u32>().unwrap(),
                cpu_classes,
                "classes {w}x{h} B={block} grid {grid:?}"
            );
            let distinct = cpu_classes.iter().filter(|&&c| c != 0).count();
            assert!(
                distinct > 0,
                "the test G-buffer must have edges inside blocks"
            );
            let mut cpu = init.clone();
            let stats = sort_seeds_cpu(&p, &lum, &mask, &cpu_classes, &history, &mut cpu);
            assert_eq!(
                stats_b.read::<u32>().unwrap(),
                stats,
                "skewed classes {w}x{h} B={block} grid {grid:?} pairs {pairs}"
            );
            if p.count_skew != 0 && block == 8 {
                assert!(
                    stats[0] > 0 && stats[0] < stats[1],
                    "the keys must give skewed and symmetric classes: {stats:?}"
                );
            }
            if pairs != 0 {
                let mut plain = init.clone();
                let p0 = SortParams { pairs: 0, ..p };
                sort_seeds_cpu(&p0, &lum, &mask, &cpu_classes, &history, &mut plain);
                assert_ne!(cpu, plain, "no thin class {w}x{h} B={block} grid {grid:?}");
            }
            assert_eq!(
                seeds.read::<u32>().unwrap(),
                cpu,
                "sort {w}x{h} B={block} grid {grid:?} pairs {pairs} phase {phase}"
            );
            // Within every block, each class holds the same set of seeds as before.
            let key = |s: &[u32], x: u32, y: u32| {
                (
                    (x + grid.0) / block,
                    (y + grid.1) / block,
                    cpu_classes[(y * w + x) as usize],
                    s[(y * sc.stride() + x) as usize],
                )
            };
            let mut before: Vec<_> = (0..w * h).map(|i| key(&init, i % w, i / w)).collect();
            let mut after: Vec<_> = (0..w * h).map(|i| key(&cpu, i % w, i / w)).collect();
            before.sort_unstable();
            after.sort_unstable();
            assert_eq!(
                before, after,
                "a seed left its class {w}x{h} B={block} grid {grid:?}"
            );
        }
    }
}

fn motion_params(w: u32, h: u32, sc: &Screen) -> MotionParams {
    MotionParams {
        cam_origin: Vec3::new(0.0, 0.0, 3.9),
        cam_forward: Vec3::NEG_Z,
        cam_right: Vec3::X * 0.36,
        cam_up: Vec3::Y * 0.36,
        view_offset: Vec2::ZERO,
        view_size: Vec2::new(w as f32, h as f32),
        width: w,
        height: h,
        padded_width: sc.stride(),
        padded_height: sc.padded_height(),
    }
}

/// Random motion fields with collisions, holes and off-screen sources, several resolutions.
#[test]
fn reprojection_matches_cpu_and_is_a_bijection_under_random_motion() {
    let mut gpu = Gpu::new();
    let mut rng = Lcg(77);
    for (w, h, tile, spread) in [
        (37, 23, 16, 3),
        (64, 64, 32, 9),
        (99, 61, 32, 2),
        (13, 7, 16, 20),
    ] {
        let sc = Screen::new(w, h, tile).unwrap();
        let p = motion_params(w, h, &sc);
        let mut r = Reprojection::new(gpu.dev(), &sc).unwrap();
        let pw = sc.stride() as i32;
        let src: Vec<u32> = (0..sc.seed_count() as i32)
            .map(|q| {
                let (x, y) = (q % pw, q / pw);
                let (sx, sy) = (
                    x + (rng.next_u32() % (2 * spread + 1)) as i32 - spread as i32,
                    y + (rng.next_u32() % 3) as i32 - 1,
                );
                let ok = x < w as i32
                    && y < h as i32
                    && sx >= 0
                    && sy >= 0
                    && sx < w as i32
                    && sy < h as i32
                    && rng.next_u32() % 5 != 0;
                if ok {
                    (sy * pw + sx) as u32
                } else {
                    REPROJECT_NONE
                }
            })
            .collect();
        let init: Vec<u32> = (0..sc.seed_count() as u32)
            .map(|i| i ^ 0x5bd1_e995)
            .collect();
        r.src.write(0, &src).unwrap();
        let a = Buffer::from_slice(gpu.dev(), "motion.seeds_in", &init).unwrap();
        let b = Buffer::new(
            gpu.dev(),
            "motion.seeds_out",
            a.size,
            MemoryLocation::GpuToCpu,
        )
        .unwrap();
        for _ in 0..2 {
            // Twice: the scratch buffers must be reset between frames.
            let rec = gpu.rec.as_mut().unwrap();
            rec.begin().unwrap();
            rec.begin_pass("reproject").unwrap();
            r.reproject_seeds(rec, &p, &a, &b).unwrap();
            rec.submit_and_wait().unwrap();
        }
        let cpu = reproject_seeds_cpu(&p, &src, &init);
        assert_eq!(b.read::<u32>().unwrap(), cpu.seeds, "{w}x{h}");
        assert_eq!(r.read_motion().unwrap(), cpu.motion, "{w}x{h}");
        assert!(is_permutation_of(&cpu.seeds, &init), "{w}x{h}");
    }
}

fn cornell() -> (Scene, MethodAssets) {
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    (s, MethodAssets::load(&default_assets_dir()).unwrap())
}

/// The G-buffer pass against the CPU traversal; then the motion pass against its twin between
/// two real G-buffers of a moving camera (orbit step plus a sub-pixel pan).
#[test]
fn gbuffer_and_motion_match_cpu() {
    let mut gpu = Gpu::new();
    let (scene, assets) = cornell();
    let sg = SceneGpu::build(&scene);
    let (w, h) = (61, 47);
    let cfg = RenderConfig {
        bounces: 1,
        method: "sort-retarget:motion=reproject,grouping=surfaces,key=demod"
            .parse()
            .unwrap(),
        ..RenderConfig::new(w, h)
    };
    let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
    let mut bufs = Vec::new();
    let mut params = Vec::new();
    for f in 0..2 {
        let mut cam = scene.camera_or_default();
        let a = 0.03 * f as f32;
        let d = cam.position - cam.target;
        cam.position = cam.target
            + Vec3::new(
                d.x * a.cos() + d.z * a.sin(),
                d.y,
                d.z * a.cos() - d.x * a.sin(),
            );
        r.set_camera(cam);
        r.set_view_offset((0.37 * f as f32, -0.6 * f as f32));
        let tp = r.trace_params();
        r.render_frame().unwrap();
        let got = r.read_gbuffer().unwrap().expect("plus uses a G-buffer");
        let cpu = gbuffer_cpu(&sg, &tp);
        for (i, (g, c)) in got.iter().zip(&cpu).enumerate() {
            // Same traversal (bit-exact, tests/src/bvh.rs); the ray direction's normalize and
            // o + t*d may round differently (FMA/rsqrt), hence a relative 1e-5.
            assert_eq!(g.material, c.material, "pixel {i}");
            assert!(
                (g.depth - c.depth).abs() <= 1e-5 * c.depth.max(1.0),
                "pixel {i}: {} vs {}",
                g.depth,
                c.depth
            );
            assert!(
                (g.position - c.position).length() <= 1e-5 * c.depth.max(1.0),
                "pixel {i}"
            );
            assert!((g.normal - c.normal).length() <= 1e-5, "pixel {i}");
        }
        bufs.push(got);
        params.push(tp);
    }
    // The motion pass on exactly these G-buffers (uploaded), GPU vs CPU.
    let sc = Screen::new(w, h, assets.n).unwrap();
    let rp = Reprojection::new(gpu.dev(), &sc).unwrap();
    let p = blueshift_render::motion_params(&params[0], &sc);
    let g0 = Buffer::from_slice(gpu.dev(), "motion.prev", &bufs[0]).unwrap();
    let g1 = Buffer::from_slice(gpu.dev(), "motion.cur", &bufs[1]).unwrap();
    let rec = gpu.rec.as_mut().unwrap();
    rec.begin().unwrap();
    rec.begin_pass("reproject_motion").unwrap();
    rp.reproject_motion(rec, &p, &g0, &g1).unwrap();
    rec.submit_and_wait().unwrap();
    let got = rp.src.read::<u32>().unwrap();
    let cpu = reproject_motion_cpu(&p, &bufs[0], &bufs[1]);
    let found = cpu.iter().filter(|&&s| s != REPROJECT_NONE).count();
    assert!(
        found > (w * h) as usize / 2,
        "most pixels should reproject: {found}"
    );
    assert_eq!(got[..cpu.len()], cpu[..]);
}

/// With a still camera every surface pixel claims itself and the rest (sky, padding) are
/// refilled in scan order from themselves: the reprojecting method equals the paper's
/// method seed for seed.
#[test]
fn still_camera_reprojection_is_the_identity() {
    let gpu = Gpu::new();
    let (scene, assets) = cornell();
    let run = |method| {
        let cfg = RenderConfig {
            bounces: 1,
            method,
            block: Some(4),
            ..RenderConfig::new(45, 38)
        };
        let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
        (0..5)
            .map(|_| {
                r.render_frame().unwrap();
                r.read_seeds().unwrap()
            })
            .collect::<Vec<_>>()
    };
    let paper = run(Method::SORT_RETARGET);
    let ours = run("sort-retarget:motion=reproject".parse().unwrap());
    assert_ne!(paper[0], paper[4]);
    assert_eq!(paper, ours);
}
