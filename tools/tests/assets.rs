//! Checks on the committed assets under `assets/` (see tools/README.md).

use blueshift_assets::{default_assets_dir as assets, load_mask, load_retarget, load_stbn};
use blueshift_tools::cli::regenerate;
use blueshift_tools::manifest;
use blueshift_tools::quality::{mask_quality, seam_ratio, temporal_lf};
use blueshift_tools::retarget::{Problem, exact};

#[test]
fn manifest_hashes_match() {
    let bad = manifest::check(&assets().join("MANIFEST")).unwrap();
    assert!(bad.is_empty(), "{bad:#?}");
}

#[test]
fn manifest_lists_every_required_asset() {
    let text = std::fs::read_to_string(assets().join("MANIFEST")).unwrap();
    let paths: Vec<String> = manifest::parse(&text)
        .unwrap()
        .into_iter()
        .map(|e| e.path)
        .collect();
    for p in [
        "masks/bn32.r16",
        "masks/bn64.r16",
        "masks/bn128.r16",
        "masks/stbn64x32.r16",
        "masks/stbn64x32_t0.5.r16",
        "masks/fast64x32_s1_a0.1.r16",
        "retarget/bn32_s24_18_r6.bin",
        "retarget/bn64_s48_36_r6.bin",
        "retarget/bn128_s97_73_r6.bin",
        "keys/hbo19_t128_spp1.bin",
        "keys/hbo19_t128_spp16.bin",
        "environments/sky.hdr",
    ] {
        assert!(paths.iter().any(|q| q == p), "{p} missing from MANIFEST");
    }
}

#[test]
fn small_assets_regenerate_bit_exactly() {
    // Mask generation and the exact retarget solver must reproduce the committed 32x32
    // outputs byte for byte (the table is computed from the regenerated mask), and the sky
    // generator the committed environment map.
    let text = std::fs::read_to_string(assets().join("MANIFEST")).unwrap();
    let entries = manifest::parse(&text).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for rel in [
        "masks/bn32.r16",
        "retarget/bn32_s24_18_r6.bin",
        "environments/sky.hdr",
    ] {
        regenerate(rel, dir.path()).unwrap();
        let want = &entries.iter().find(|e| e.path == rel).unwrap().sha256;
        let got = manifest::sha256_file(&dir.path().join(rel)).unwrap();
        assert_eq!(&got, want, "{rel} does not regenerate");
    }
}

#[test]
fn committed_masks_are_blue_seamless_permutations() {
    // load_mask rejects anything that is not a permutation of 0..n^2.
    for n in [32, 64, 128] {
        let m = load_mask(&assets().join(format!("masks/bn{n}.r16"))).unwrap();
        assert_eq!(m.n, n);
        let q = mask_quality(&m).unwrap();
        assert!(q.lf < 0.005, "bn{n}: LF {}", q.lf);
        assert!(
            q.peak_ratio < 2.0,
            "bn{n}: radial peak {} x high band",
            q.peak_ratio
        );
        let seam = seam_ratio(&m).unwrap();
        assert!(seam < 2.5, "bn{n}: seam ratio {seam}");
    }
}

#[test]
fn committed_stbn_slices_are_blue_and_pixels_spread_in_time() {
    let v = load_stbn(&assets().join("masks/stbn64x32.r16"), 64).unwrap();
    assert_eq!(v.t, 32);
    for s in 0..v.t {
        let q = mask_quality(&v.slice(s).unwrap()).unwrap();
        assert!(q.lf < 0.005, "slice {s}: LF {}", q.lf);
        assert!(q.peak_ratio < 2.0, "slice {s}: peak {}", q.peak_ratio);
    }
    // White noise: 6/31 = 0.19 of the temporal power below 0.125 cycles/frame.
    let t = temporal_lf(&v);
    assert!(t < 0.05, "temporal LF {t}");
}

#[test]
fn committed_retarget_tables_are_optimal_bijections() {
    for (n, s) in [(32usize, (24u32, 18u32)), (64, (48, 36)), (128, (97, 73))] {
        let path = assets().join(format!("retarget/bn{n}_s{}_{}_r6.bin", s.0, s.1));
        // load_retarget checks the header, the radius bound and bijectivity.
        let t = load_retarget(&path).unwrap();
        assert_eq!((t.n, t.shift, t.radius), (n, s, 6));
        let mask = load_mask(&assets().join(format!("masks/bn{n}.r16"))).unwrap();
        let p = Problem::new(&mask, s, 6).unwrap();
        let target: Vec<usize> = (0..n * n).map(|u| t.target(u % n, u / n)).collect();
        let optimum = exact::solve(&p, &mut |_| {});
        assert_eq!(p.energy(&target), p.energy(&optimum));
        // M(u + d(u) + s) ~= M(u): mean error well under 1% of the rank range.
        let mean = p.energy(&target) as f64 / (n * n) as f64;
        assert!(mean < 0.01 * (n * n) as f64, "bn{n}: mean {mean}");
    }
}
