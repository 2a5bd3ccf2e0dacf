//! The HBO+19 key optimiser: deterministic with a seed, and it lowers its energy.

use blueshift_sampling::hbo19::KeyTable;
use blueshift_tools::cli::run_args;
use blueshift_tools::keys::{KeysParams, Problem, anneal};

fn small(spp: u32, seed: u64) -> Problem {
    let params = KeysParams {
        iterations: 16,
        rounds: 8,
        integrands: 8,
        ..KeysParams::new(16, spp, 2, seed)
    };
    Problem::new(params).expect("valid parameters")
}

#[test]
fn optimisation_lowers_the_energy_and_keeps_the_key_multiset() {
    for spp in [1, 4] {
        let p = small(spp, 3);
        let out = anneal::optimise(&p, &mut |_| {});
        assert!(
            out.energy_final < out.energy_initial * 0.99,
            "spp {spp}: {} -> {}",
            out.energy_initial,
            out.energy_final
        );
        // Swaps only permute keys per pair: same scrambles and ranks, in another arrangement.
        let (a, b) = (p.initial_keys(), out.keys.clone());
        assert_ne!(a, b);
        let pairs = p.params.pairs as usize;
        for pair in 0..pairs {
            let col = |v: &[[u32; 2]], i: usize| {
                let mut c: Vec<u32> = v.iter().skip(pair).step_by(pairs).map(|k| k[i]).collect();
                c.sort_unstable();
                c
            };
            assert_eq!(col(&a, 0), col(&b, 0), "scrambles of pair {pair}");
            assert_eq!(col(&a, 1), col(&b, 1), "ranks of pair {pair}");
        }
        // Energy recomputed from the final keys matches the optimiser's running state.
        let k = p.params.vec_len();
        let mut vecs = vec![0.0; out.keys.len() / pairs * k];
        for (v, kk) in vecs.chunks_mut(k).zip(out.keys.chunks(pairs)) {
            p.eval_pixel(kk, v);
        }
        let e = p.energy(&vecs);
        assert!(
            (e - out.energy_final).abs() < 1e-6 * e,
            "{e} vs {}",
            out.energy_final
        );
    }
}

#[test]
fn command_is_deterministic_with_a_seed() {
    let dir = tempfile::tempdir().unwrap();
    let run = |sub: &str, seed: u64| {
        let out = dir.path().join(sub);
        run_args([
            "keys",
            "--tile",
            "16",
            "--spp",
            "1,2",
            "--dims",
            "4",
            "--iterations",
            "8",
            "--rounds",
            "4",
            "--seed",
            &seed.to_string(),
            "--out",
            out.to_str().unwrap(),
        ])
        .unwrap();
        ["hbo19_t16_spp1.bin", "hbo19_t16_spp2.bin"].map(|f| std::fs::read(out.join(f)).unwrap())
    };
    let (a, b, c) = (run("a", 5), run("b", 5), run("c", 6));
    assert_eq!(a, b, "same seed, different tables");
    assert_ne!(a, c, "different seeds, same tables");
    for bytes in &a {
        let t = KeyTable::from_bytes(bytes, std::path::Path::new("k.bin")).unwrap();
        assert_eq!((t.tile, t.pairs), (16, 2));
    }
}

#[test]
fn bad_arguments_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    for (flag, value, needle) in [
        ("--dims", "3", "even"),
        ("--spp", "3", "power of two"),
        ("--tile", "12", "power of two"),
        ("--spp", "x", "not a number"),
    ] {
        let e = run_args(["keys", flag, value, "--out", out]).unwrap_err();
        assert!(format!("{e:#}").contains(needle), "{flag} {value}: {e:#}");
    }
}
