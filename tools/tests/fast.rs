//! `fast` and `fast-bench` end to end, and the committed FAST texture against STBN.

mod common;

use common::{fails, ok, s};

use blueshift_assets::{default_assets_dir as assets, load_stbn};
use blueshift_tools::fast::bench::{Integrand, filtered_rmse};
use blueshift_tools::fast::{Params, Temporal, Volume};

#[test]
fn fast_writes_a_stbn_format_volume_and_benchmarks_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (fast, stbn) = (d.join("f.r16"), d.join("st.r16"));
    let small = ["--size", "8", "--frames", "4"];
    let out = ok(&[
        &["fast"][..],
        &small,
        &["--iterations", "16", "--rounds", "4", "--out", s(&fast)],
    ]
    .concat());
    assert!(out.contains("loss L/N") && out.contains("RMSE"), "{out}");
    let v = load_stbn(&fast, 8).unwrap();
    assert_eq!(v.t, 4);
    assert_eq!(image::open(d.join("f.png")).unwrap().height(), 8 * 4);
    ok(&[&["mask"][..], &small, &["--out", s(&stbn)]].concat());
    let out = ok(&[
        &["fast-bench", "--fast", s(&fast), "--stbn", s(&stbn)][..],
        &["--size", "8", "--trials", "8"],
    ]
    .concat());
    for row in ["FAST f.r16", "STBN st.r16", "white noise", "stratified"] {
        assert!(out.contains(row), "{row}: {out}");
    }
    // 2D vectors: the same file format, decoded as cells of an 8x8 grid.
    let v2 = d.join("v2.r16");
    ok(&[
        &["fast", "--dims", "2"][..],
        &small,
        &["--iterations", "8", "--rounds", "2", "--out", s(&v2)],
    ]
    .concat());
    let out = ok(&[
        "fast-bench",
        "--fast",
        s(&v2),
        "--dims",
        "2",
        "--size",
        "8",
        "--trials",
        "4",
    ]);
    assert!(!out.contains("STBN"), "{out}");
}

#[test]
fn bad_flags_give_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.r16");
    let o = s(&out);
    fails(
        &["fast", "--size", "48", "--out", o],
        "--size 48: must be a power of two",
    );
    fails(&["fast", "--frames", "24", "--out", o], "--frames 24");
    fails(&["fast", "--dims", "3", "--out", o], "--dims 3");
    fails(
        &["fast", "--sigma", "0", "--out", o],
        "--sigma 0: must be a finite number > 0",
    );
    fails(&["fast", "--sigma", "-1", "--out", o], "--sigma -1");
    fails(
        &["fast", "--alpha", "1.5", "--out", o],
        "--alpha 1.5: must be in (0, 1]",
    );
    fails(&["fast", "--alpha", "0", "--out", o], "--alpha 0");
    fails(
        &["fast", "--temporal", "gauss", "--sigma-t", "0", "--out", o],
        "--sigma-t 0",
    );
    fails(&["fast", "--iterations", "0", "--out", o], "--iterations");
    fails(&["fast-bench", "--fast", o], "loading");
    assert!(!out.exists());
}

#[test]
fn committed_fast_beats_committed_stbn_on_its_filter() {
    // The paper's measure on the committed textures: one step integrand shared by the
    // screen, spatial Gaussian sigma 1 then EMA alpha 0.1, filtered RMSE.
    let fast = load_stbn(&assets().join("masks/fast64x32_s1_a0.1.r16"), 64).unwrap();
    let stbn = load_stbn(&assets().join("masks/stbn64x32.r16"), 64).unwrap();
    let (fast, stbn) = (
        Volume::from_ranks(64, fast.t, 1, &fast.ranks),
        Volume::from_ranks(64, stbn.t, 1, &stbn.ranks),
    );
    assert!(fast.temporally_stratified());
    let filter = |t: usize| {
        Params {
            n: 64,
            frames: t,
            dims: 1,
            sigma: 1.0,
            temporal: Temporal::Ema { alpha: 0.1 },
            model: blueshift_tools::fast::Model::Shared,
            iterations: 1,
            rounds: 1,
            seed: 1,
        }
        .filter()
    };
    let rmse = |v: &Volume| filtered_rmse(v, &filter(v.frames), Integrand::Const, 48, 5);
    let (f, s) = (rmse(&fast), rmse(&stbn));
    assert!(f < 0.95 * s, "FAST {f} vs STBN {s}");
}
