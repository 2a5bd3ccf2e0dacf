//! Every compiled variant of the sorting pass against its CPU twins.
use crate::permute::{estimate, random_table};
use crate::{Gpu, Lcg};
use blueshift_device::Buffer;
use blueshift_layout::params::{PAIRS_GATE_LIMIT, PAIRS_GATE_ONE, SORT_PAIRS_FROM_GATE};
use blueshift_permute::{
    CYCLE_FRAMES, CycleInput, CycleParams, PairsGate, PermutePasses, Screen, SortInput, SortParams,
    SortVariant, cycle_keys_cpu, is_permutation_of, pack_mask_moves, retarget_seeds_cpu,
    sort_seeds_cpu, with_cycle,
};

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
    // Running means with a jump down the middle of the screen and a little noise, one NaN and
    // one negative value.
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
        mean_count: 16,
        sample_keys: 0,
    };
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
            }),
        };
        let rec = gpu.rec.as_mut().unwrap();
        rec.begin().unwrap();
        rec.begin_pass("sort_seeds").unwrap();
        passes.sort_seeds(rec, &p, v, &input, &seeds).unwrap();
        rec.submit_and_wait().unwrap();

        let zeros_u = vec![0u32; px];
        let zeros_f = vec![0f32; px];
        let cls = if v.classes { classes.clone() } else { zeros_u };
        let hist = if v.history { &history } else { &zeros_f };
        let mut cpu = init.clone();
        let (keys, slice) = if v.cycle {
            let mut h = cycle_history.clone();
            let out = cycle_keys_cpu(&cp, &lum, &means, &mut cpu, &mut h, &volume);
            let got: Vec<[u32; 2]> = hist_b.read().unwrap();
            assert_eq!(got, h, "{name}: history slots");
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
