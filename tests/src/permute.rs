//! Sorting and retargeting passes: GPU == CPU twin exactly, and the seed buffer stays a
//! permutation of the initial seeds after every pass.
use crate::{Gpu, Lcg};
use blueshift_device::{Buffer, MemoryLocation};
use blueshift_layout::params::{
    PAIRS_GATE_LIMIT, PAIRS_GATE_ONE, PRIMARY_SHADE_EDGE, PRIMARY_TEXTURED, SHADE_EDGE_MIN_FRAMES,
    SORT_PAIRS_FROM_GATE,
};
use blueshift_permute::{
    CYCLE_FRAMES, CycleInput, CycleParams, PairsGate, PermutePasses, Screen, SortInput, SortParams,
    SortVariant, cycle_keys_cpu, is_permutation_of, mask_offset, pack_mask_moves,
    retarget_seeds_cpu, shade_edges_cpu, sort_seeds_cpu, with_cycle,
};

/// A random tile permutation with displacements <= r: disjoint random swaps within radius.
fn random_table(n: u32, r: i32, rng: &mut Lcg) -> Vec<[i32; 2]> {
    let mut table = vec![[0i32; 2]; (n * n) as usize];
    let mut moved = vec![false; (n * n) as usize];
    for u in rng.perm(n * n) {
        let (dx, dy) = (
            (rng.next_u32() % (2 * r as u32 + 1)) as i32 - r,
            (rng.next_u32() % (2 * r as u32 + 1)) as i32 - r,
        );
        if dx * dx + dy * dy > r * r {
            continue;
        }
        let (ux, uy) = ((u % n) as i32, (u / n) as i32);
        let v =
            (((uy + dy).rem_euclid(n as i32)) * n as i32 + (ux + dx).rem_euclid(n as i32)) as usize;
        if moved[u as usize] || moved[v] || v == u as usize {
            continue;
        }
        moved[u as usize] = true;
        moved[v] = true;
        table[u as usize] = [dx, dy];
        table[v] = [-dx, -dy];
    }
    table
}

fn estimate(lum: &[f32]) -> Vec<[f32; 4]> {
    lum.iter().map(|&l| [l, l, l, l]).collect()
}

/// Block grid offsets: the paper's fixed grid on every third frame, otherwise offsets that
/// leave partial blocks on every side (the moving grid of sort-grid-*).
fn grid_of(frame: u64, block: u32) -> (u32, u32) {
    let f = frame as u32;
    if f % 3 == 0 {
        (0, 0)
    } else {
        (f % block, (f * 3 + 1) % block)
    }
}

/// Sorting parameters of `frame`: the block grid of `grid_of`, and the thin-class pairs of the
/// moving grid (sort-grid-*): none, thin classes (here only partial blocks at the screen
/// edges) or every class, in both phases.
fn sort_params_of(sc: &Screen, block: u32, frame: u64, off: (u32, u32)) -> SortParams {
    SortParams {
        pairs: (frame % 3) as u32,
        phase: (frame / 2 % 2) as u32,
        ..sc.sort_params_on_grid(block, off, grid_of(frame, block))
            .unwrap()
    }
}

/// Records and runs one sorting pass on `seeds`: in place, or retargeted into `retarget`
/// (then `mask` holds `pack_mask_moves` texels). One class per block, raw keys.
fn gpu_sort(
    gpu: &mut Gpu,
    passes: &mut PermutePasses,
    sp: &SortParams,
    lum: &[f32],
    mask: &Buffer,
    seeds: &Buffer,
    retarget: Option<&Buffer>,
) {
    let est = Buffer::from_slice(gpu.dev(), "permute.estimate", &estimate(lum)).unwrap();
    let input = SortInput {
        retarget,
        ..SortInput::new(&est, mask)
    };
    let variant = SortVariant {
        pairs: retarget.is_none(),
        retarget: retarget.is_some(),
        large: SortVariant::large_for(sp.block),
        ..SortVariant::PAPER
    };
    let rec = gpu.rec.as_mut().unwrap();
    rec.begin().unwrap();
    rec.begin_pass("permute.sort_seeds").unwrap();
    passes.sort_seeds(rec, sp, variant, &input, seeds).unwrap();
    rec.submit_and_wait().unwrap();
}

fn gpu_seeds(gpu: &Gpu, name: &str, size: u64) -> Buffer {
    Buffer::new(gpu.dev(), name, size, MemoryLocation::GpuToCpu).unwrap()
}

/// Random estimates (with ties: values from a small set), random masks and tables, several
/// block sizes and resolutions that are multiples of neither B nor N. Every frame: the sort
/// that retargets == the CPU sort then retarget (fixed and moving grids), and the in-place
/// sort with pairs == the CPU sort.
#[test]
fn sort_and_retarget_match_cpu_and_stay_permutations() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(42);
    for (w, h, n, block, frames) in [
        (37, 23, 16, 2, 12),
        (50, 41, 16, 3, 12),
        (64, 64, 32, 4, 8),
        (99, 61, 32, 8, 8),
        (13, 7, 16, 8, 4),
        (29, 17, 16, 5, 3),
        (22, 30, 16, 7, 3),
    ] {
        let sc = Screen::new(w, h, n).unwrap();
        let mask_data = rng.perm(n * n);
        let table_data = random_table(n, 6, &mut rng);
        let mask = Buffer::from_slice(gpu.dev(), "permute.mask", &mask_data).unwrap();
        let packed = pack_mask_moves(&mask_data, &table_data).unwrap();
        let moves = Buffer::from_slice(gpu.dev(), "permute.mask_moves", &packed).unwrap();
        let init: Vec<u32> = (0..sc.seed_count() as u32)
            .map(|i| i.wrapping_mul(2654435761))
            .collect();
        let mut a = Buffer::from_slice(gpu.dev(), "permute.seeds_a", &init).unwrap();
        let b = gpu_seeds(&gpu, "permute.seeds_b", a.size);
        let mut cpu = init.clone();
        for f in 0..frames {
            let lum: Vec<f32> = (0..w * h)
                .map(|_| (rng.next_u32() % 50) as f32 * 0.25)
                .collect();
            let off = mask_offset(f, (12, 9), n);
            let sp = sort_params_of(&sc, block, f, off);

            // In place, with this frame's pairs.
            a.write(0, &cpu).unwrap();
            gpu_sort(&mut gpu, &mut passes, &sp, &lum, &mask, &a, None);
            let mut sorted = cpu.clone();
            let none = (vec![0; (w * h) as usize], vec![0.0; (w * h) as usize]);
            sort_seeds_cpu(&sp, &lum, &mask_data, &none.0, &none.1, &mut sorted);
            assert_eq!(
                a.read::<u32>().unwrap()[..cpu.len()],
                sorted[..],
                "sort {w}x{h} B={block} frame {f}"
            );

            // Sorted and retargeted in one pass (no pairs: they belong to the moving grid).
            let sp = SortParams { pairs: 0, ..sp };
            a.write(0, &cpu).unwrap();
            gpu_sort(&mut gpu, &mut passes, &sp, &lum, &moves, &a, Some(&b));
            sort_seeds_cpu(&sp, &lum, &mask_data, &none.0, &none.1, &mut cpu);
            cpu = retarget_seeds_cpu(&sp, &table_data, &cpu);
            assert_eq!(
                b.read::<u32>().unwrap()[..cpu.len()],
                cpu[..],
                "sort + retarget {w}x{h} B={block} frame {f}"
            );
            assert!(is_permutation_of(&cpu, &init));
        }
    }
}

/// Sorting an image equal to the mask is the identity; sorting a constant image sends the
/// seed of in-block index k to the position of the k-th smallest mask value.
#[test]
fn sort_identity_and_constant_image() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(5);
    let (n, block) = (16u32, 4u32);
    let sc = Screen::new(32, 32, n).unwrap();
    let mask_data = rng.perm(n * n);
    let mask = Buffer::from_slice(gpu.dev(), "permute.mask", &mask_data).unwrap();
    let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
    let off = mask_offset(3, (12, 9), n);
    let sp = sc.sort_params(block, off).unwrap();
    let mask_at = |x: u32, y: u32| mask_data[(((y + off.1) % n) * n + (x + off.0) % n) as usize];
    let like_mask: Vec<f32> = (0..32 * 32)
        .map(|i| mask_at(i % 32, i / 32) as f32)
        .collect();
    let a = Buffer::from_slice(gpu.dev(), "permute.seeds_a", &init).unwrap();
    gpu_sort(&mut gpu, &mut passes, &sp, &like_mask, &mask, &a, None);
    assert_eq!(
        a.read::<u32>().unwrap(),
        init,
        "image == mask must not move seeds"
    );

    let a = Buffer::from_slice(gpu.dev(), "permute.seeds_a", &init).unwrap();
    gpu_sort(&mut gpu, &mut passes, &sp, &[1.5; 32 * 32], &mask, &a, None);
    let got = a.read::<u32>().unwrap();
    for (bx, by) in [(0u32, 0u32), (4, 8), (28, 28)] {
        let mut cells: Vec<(u32, u32)> = (0..16).map(|k| (bx + k % 4, by + k / 4)).collect();
        cells.sort_by_key(|&(x, y)| mask_at(x, y));
        for (k, &(x, y)) in cells.iter().enumerate() {
            let (sx, sy) = (bx + k as u32 % 4, by + k as u32 / 4);
            assert_eq!(got[(y * 32 + x) as usize], init[(sy * 32 + sx) as usize]);
        }
    }
}

/// 1,000 frames of random estimates through the sort that retargets, ping-ponging between two
/// buffers, block sizes 2..=8, fixed and moving grids: a permutation after every frame.
#[test]
fn thousand_frames_stay_a_permutation() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(9);
    let (w, h, n) = (45u32, 29u32, 16u32);
    let sc = Screen::new(w, h, n).unwrap();
    let packed = pack_mask_moves(&rng.perm(n * n), &random_table(n, 6, &mut rng)).unwrap();
    let moves = Buffer::from_slice(gpu.dev(), "permute.mask_moves", &packed).unwrap();
    let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
    let bufs = [
        Buffer::from_slice(gpu.dev(), "permute.seeds_a", &init).unwrap(),
        Buffer::from_slice(gpu.dev(), "permute.seeds_b", &init).unwrap(),
    ];
    for f in 0..1000u64 {
        let lum: Vec<f32> = (0..w * h).map(|_| rng.next_u32() as f32).collect();
        let (src, dst) = (&bufs[(f % 2) as usize], &bufs[1 - (f % 2) as usize]);
        let block = 2 + (f % 7) as u32;
        let sp = SortParams {
            pairs: 0,
            ..sort_params_of(&sc, block, f, mask_offset(f, (12, 9), n))
        };
        gpu_sort(&mut gpu, &mut passes, &sp, &lum, &moves, src, Some(dst));
        if f % 100 == 99 {
            assert!(
                is_permutation_of(&dst.read::<u32>().unwrap()[..init.len()], &init),
                "frame {f}"
            );
        }
    }
}

/// The committed 64x64 retarget table: every displacement within the radius it was made for;
/// through the GPU pass (an image equal to the mask, so the sort keeps every seed in place)
/// == the CPU twin, a bijection on a padded odd-sized screen.
#[test]
fn committed_retarget_table_matches_cpu_and_keeps_radius() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(3);
    let dir = blueshift_render::default_assets_dir();
    let t = blueshift_assets::load_retarget(&dir.join("retarget/bn64_s48_36_r6.bin")).unwrap();
    let r2 = (t.radius * t.radius) as i32;
    let table: Vec<[i32; 2]> = t
        .offsets
        .iter()
        .map(|&(dx, dy)| [dx as i32, dy as i32])
        .collect();
    assert!(table.iter().all(|d| d[0] * d[0] + d[1] * d[1] <= r2));
    let n = t.n as u32;
    let (w, h) = (100u32, 70u32);
    let sc = Screen::new(w, h, n).unwrap();
    let mask_data = rng.perm(n * n);
    let packed = pack_mask_moves(&mask_data, &table).unwrap();
    let moves = Buffer::from_slice(gpu.dev(), "permute.mask_moves", &packed).unwrap();
    let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
    let a = Buffer::from_slice(gpu.dev(), "permute.seeds_a", &init).unwrap();
    let b = gpu_seeds(&gpu, "permute.seeds_b", a.size);
    for frame in [0u64, 1, 7] {
        let off = mask_offset(frame, t.shift, n);
        let sp = sc.sort_params(4, off).unwrap();
        let like_mask: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                mask_data[(((y + off.1) % n) * n + (x + off.0) % n) as usize] as f32
            })
            .collect();
        gpu_sort(&mut gpu, &mut passes, &sp, &like_mask, &moves, &a, Some(&b));
        let want = retarget_seeds_cpu(&sp, &table, &init);
        assert_eq!(b.read::<u32>().unwrap()[..want.len()], want[..]);
        assert!(is_permutation_of(&want, &init));
    }
}

/// Packing keeps the rank and both displacements; what does not fit is refused by name.
#[test]
fn mask_moves_pack_and_refuse() {
    let packed = pack_mask_moves(&[0, 65535, 7], &[[-128, 127], [0, -1], [5, 0]]).unwrap();
    for (&p, (rank, dx, dy)) in packed
        .iter()
        .zip([(0, -128, 127), (65535, 0, -1), (7, 5, 0)])
    {
        assert_eq!(p & 0xFFFF, rank);
        assert_eq!((p >> 16) as u8 as i8 as i32, dx);
        assert_eq!((p >> 24) as u8 as i8 as i32, dy);
    }
    for (mask, table, names) in [
        (vec![65536u32], vec![[0, 0]], "mask rank 65536"),
        (vec![1], vec![[128, 0]], "(128, 0)"),
        (vec![1], vec![[0, -129]], "(0, -129)"),
        (
            vec![1, 2],
            vec![[0, 0]],
            "mask of 2 texels and retarget table of 1",
        ),
    ] {
        let e = pack_mask_moves(&mask, &table).unwrap_err().to_string();
        assert!(e.contains(names), "{e}");
    }
}

/// Every shader of the sorting pass (`SortVariant`: classes, history, pairs, skew counts,
/// retargeting, the point cycle with and without sample keys, each compiled in or out, for
/// blocks up to 4x4 and up to 8x8) against the CPU twins given the same inputs: an absent
/// class buffer is one class per block, an absent history the raw key. Classes, NaN
/// histories, tied keys and a firefly tail in places, on a moving grid with partial blocks.
#[test]
fn every_sort_variant_matches_cpu() {
    let mut gpu = Gpu::new();
    let mut passes = PermutePasses::new(gpu.dev()).unwrap();
    let mut rng = Lcg(77);
    let (w, h, n) = (43u32, 29u32, 16u32);
    let sc = Screen::new(w, h, n).unwrap();
    let px = (w * h) as usize;
    let mask = rng.perm(n * n);
    let lum: Vec<f32> = (0..px)
        .map(|_| match rng.next_u32() % 16 {
            0 => 300.0 + (rng.next_u32() % 8) as f32,
            _ => (rng.next_u32() % 30) as f32 * 0.5,
        })
        .collect();
    // In-block class indices as classify_pixels leaves them: a few leaders per block.
    let classes: Vec<u32> = (0..px)
        .map(|_| [0, 0, 9, 27][rng.next_u32() as usize % 4])
        .collect();
    let history = rng.history_means(px, 30);
    let init: Vec<u32> = (0..sc.seed_count() as u32)
        .map(|i| i.wrapping_mul(2654435761))
        .collect();
    let dev = gpu.dev().clone();
    let upload = |name: &str, data: &[u32]| Buffer::from_slice(&dev, name, data).unwrap();
    let est = Buffer::from_slice(&dev, "variant.estimate", &estimate(&lum)).unwrap();
    let mask_b = upload("variant.mask", &mask);
    let table = random_table(n, 6, &mut rng);
    let moves_b = upload(
        "variant.mask_moves",
        &pack_mask_moves(&mask, &table).unwrap(),
    );
    let classes_b = upload("variant.classes", &classes);
    let history_b = Buffer::from_slice(&dev, "variant.history", &history).unwrap();
    // The point cycle: a two-slice volume (the mask is slice 1), running means, and a written
    // next-phase slot holding each pixel's own seed with a random key; each cycle variant runs
    // twice, its seeds ranked by those keys and then (a shader of its own) by their next light
    // sample.
    let volume: Vec<u32> = rng.perm(n * n).into_iter().chain(mask.clone()).collect();
    let volume_b = upload("variant.volume", &volume);
    // Running means with a jump down the middle of the screen and a little noise (shading
    // edges there and nowhere else), one NaN and one negative value.
    let mut means: Vec<f32> = (0..px as u32)
        .map(|i| if i % w < w / 2 { 1.0 } else { 4.0 } + (rng.next_u32() % 3) as f32 * 0.05)
        .collect();
    means[1] = f32::NAN;
    means[px - 2] = -1.0;
    let accum_b = Buffer::from_slice(
        &dev,
        "variant.accum",
        &means.iter().map(|&m| [m; 4]).collect::<Vec<_>>(),
    )
    .unwrap();
    let cp = CycleParams {
        width: w,
        height: h,
        stride: sc.stride(),
        phase: 3,
        next_phase: 4,
        next_valid: 1,
        mask_size: n,
        mask_layer: 1,
        mean_count: SHADE_EDGE_MIN_FRAMES,
        sample_keys: 0,
    };
    // The trace's flags as it leaves them (the textured bit at random, no marks): the pass
    // adds marks and keeps the other bits.
    let flags: Vec<u32> = (0..px)
        .map(|_| rng.next_u32() % 2 * PRIMARY_TEXTURED)
        .collect();
    let mut cycle_history = vec![[0u32; 2]; CYCLE_FRAMES as usize * px];
    for (i, slot) in cycle_history[4 * px..5 * px].iter_mut().enumerate() {
        let at = (i as u32 / w) * sc.stride() + i as u32 % w;
        *slot = [
            init[at as usize],
            ((rng.next_u32() % 40) as f32 * 0.25).to_bits(),
        ];
    }
    let mut checked = 0;
    for (i, v) in SortVariant::all().into_iter().enumerate() {
        let keys = v.sample_keys;
        let cp = CycleParams {
            sample_keys: u32::from(keys),
            ..cp
        };
        let name = v.shader();
        // The largest block of each slot count: 8x8 (64 slots) or 4x4 (16).
        let block = if v.large { 8 } else { 4 };
        // A variant with the pairs gate takes its pairs from the gate's buffer: a share at the
        // limit (none), just under it (every class), or nothing counted yet (every class).
        let from_gate = v.pairs && v.skew;
        let (gate_words, gate_pairs) = match i / 4 % 3 {
            0 => ([PAIRS_GATE_LIMIT, 1], 0),
            1 => ([PAIRS_GATE_LIMIT - 1, 1], 2),
            _ => ([PAIRS_GATE_ONE, 0], 2),
        };
        let p = SortParams {
            pairs: match (v.pairs, from_gate) {
                (false, _) => 0,
                (true, true) => SORT_PAIRS_FROM_GATE,
                (true, false) => 1 + (i as u32 / 4) % 2,
            },
            phase: i as u32 % 2,
            count_skew: u32::from(v.skew),
            ..sc.sort_params_on_grid(block, (3, 7), (i as u32 % block, 5 % block))
                .unwrap()
        };
        let p = if v.cycle { with_cycle(p, &cp) } else { p };
        // Shading edges while the seeds rank by their recorded keys (a still view).
        let p = SortParams {
            cycle_shade_edges: u32::from(v.cycle && !keys),
            ..p
        };
        let flags_b = upload("variant.flags", &flags);
        let hist_b = upload(
            "variant.cycle_history",
            bytemuck::cast_slice(&cycle_history),
        );
        let seeds = upload("variant.seeds", &init);
        let out = upload("variant.seeds_out", &vec![0; init.len()]);
        let stats = upload("variant.sort_stats", &[0, 0]);
        let gate = upload("variant.pairs_gate", &gate_words);
        let input = SortInput {
            estimate: &est,
            mask: match (v.retarget, v.cycle) {
                (true, _) => &moves_b,
                (_, true) => &volume_b,
                _ => &mask_b,
            },
            classes: v.classes.then_some(&classes_b),
            history: v.history.then_some(&history_b),
            stats: v.skew.then_some(&stats),
            gate: from_gate.then_some(&gate),
            retarget: v.retarget.then_some(&out),
            cycle: v.cycle.then_some(CycleInput {
                history: &hist_b,
                accum: &accum_b,
                flags: &flags_b,
            }),
        };
        let rec = gpu.rec.as_mut().unwrap();
        rec.begin().unwrap();
        rec.begin_pass("sort_seeds").unwrap();
        passes.sort_seeds(rec, &p, v, &input, &seeds).unwrap();
        rec.submit_and_wait().unwrap();

        let zeros_u = vec![0u32; px];
        let zeros_f = vec![0f32; px];
        let mut cls = if v.classes { classes.clone() } else { zeros_u };
        let hist = if v.history { &history } else { &zeros_f };
        let mut cpu = init.clone();
        let (keys, slice) = if v.cycle {
            let mut h = cycle_history.clone();
            let out = cycle_keys_cpu(&cp, &lum, &means, &mut cpu, &mut h, &volume);
            let got: Vec<[u32; 2]> = hist_b.read().unwrap();
            assert_eq!(got, h, "{name}: history slots");
            let mut want = flags.clone();
            shade_edges_cpu(&p, &means, &mut cls, &mut want);
            let got: Vec<u32> = flags_b.read().unwrap();
            assert_eq!(got, want, "{name}: shading-edge marks");
            let marked = want
                .iter()
                .filter(|&&f| f & PRIMARY_SHADE_EDGE != 0)
                .count();
            if p.cycle_shade_edges != 0 {
                assert!(
                    marked > 0 && marked < px / 2,
                    "{name}: {marked} of {px} marked"
                );
            } else {
                assert_eq!(marked, 0, "{name}: marks left while ranking sample keys");
            }
            (out.keys, out.mask)
        } else {
            (lum.clone(), mask.clone())
        };
        let resolved = SortParams {
            pairs: match from_gate {
                true => PairsGate::from_words(gate_words).pairs(),
                false => p.pairs,
            },
            ..p
        };
        if from_gate {
            assert_eq!(resolved.pairs, gate_pairs, "{name}: the gate's rule");
        }
        let counts = sort_seeds_cpu(&resolved, &keys, &slice, &cls, hist, &mut cpu);
        let got = if v.retarget {
            cpu = retarget_seeds_cpu(&p, &table, &cpu);
            out.read::<u32>().unwrap()
        } else {
            seeds.read::<u32>().unwrap()
        };
        assert_eq!(got, cpu, "{name}");
        assert!(is_permutation_of(&cpu, &init), "{name}");
        if v.skew {
            assert_eq!(stats.read::<u32>().unwrap(), counts, "{name}");
            assert!(counts[1] > 0, "{name}: no class counted");
        }
        checked += 1;
    }
    // 48 variants, the 8 cycle ones twice.
    assert_eq!(checked, 56);
}

/// The pairs gate pass against its twin over a run of counts: frames with nothing counted,
/// the first count, a crossing of the limit each way, counts in the millions (a 4K screen's
/// classes: the fixed-point product needs 64 bits), more skewed than counted (clamped).
#[test]
fn pairs_gate_matches_cpu() {
    let mut gpu = Gpu::new();
    let passes = PermutePasses::new(gpu.dev()).unwrap();
    let dev = gpu.dev().clone();
    let mut stats = Buffer::new(&dev, "gate.sort_stats", 8, MemoryLocation::CpuToGpu).unwrap();
    let gate = Buffer::from_slice(&dev, "gate.pairs_gate", &[0u32, 0]).unwrap();
    let mut rng = Lcg(5);
    let mut run: Vec<[u32; 2]> = vec![[0, 0], [3, 100], [0, 0], [40, 100], [90, 97]];
    run.extend((0..20).map(|_| [0, 50]));
    run.extend([[4_000_000, 4_100_000], [7, 5], [0, 0]]);
    run.extend((0..30).map(|_| {
        let counted = rng.next_u32() % 5000;
        [rng.next_u32() % (counted + 1) / 4, counted]
    }));
    let mut cpu = PairsGate::default();
    let mut seen = [false; 2];
    for (k, c) in run.iter().enumerate() {
        stats.write(0, c).unwrap();
        let rec = gpu.rec.as_mut().unwrap();
        rec.begin().unwrap();
        rec.begin_pass("pairs_gate").unwrap();
        passes.pairs_gate(rec, &stats, &gate).unwrap();
        rec.submit_and_wait().unwrap();
        cpu.update(*c);
        let got: Vec<u32> = gate.read().unwrap();
        assert_eq!(got, cpu.words(), "step {k}: counts {c:?}");
        seen[usize::from(cpu.pairs() == 2)] = true;
    }
    assert_eq!(seen, [true, true], "the run crosses the limit");
}
