//! Sorting and retargeting passes: GPU == CPU twin exactly, and the seed buffer stays a
//! permutation of the initial seeds after every pass.
use crate::{Gpu, Lcg};
use blueshift_device::{Buffer, MemoryLocation};
use blueshift_permute::{
    PermutePasses, Screen, SortInput, SortParams, SortVariant, is_permutation_of, mask_offset,
    pack_mask_moves, retarget_seeds_cpu, sort_seeds_cpu,
};

/// A random tile permutation with displacements <= r: disjoint random swaps within radius.
pub(crate) fn random_table(n: u32, r: i32, rng: &mut Lcg) -> Vec<[i32; 2]> {
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

pub(crate) fn estimate(lum: &[f32]) -> Vec<[f32; 4]> {
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
