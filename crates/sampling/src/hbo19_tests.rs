use super::*;
use crate::rng::hash3;
use crate::sobol::{direction_numbers, is_0m2_net};

/// A table of hashed keys with ranks below spp (what the optimiser permutes).
fn table(tile: u32, spp: u32, pairs: u32) -> KeyTable {
    let keys = (0..tile * tile * pairs)
        .map(|i| [hash3(i, 7, 1), hash3(i, 7, 2) % spp])
        .collect();
    KeyTable::new(tile, spp, pairs, keys).expect("valid table")
}

#[test]
fn first_2m_points_of_every_pixel_are_0m2_nets_in_every_pair() {
    let dirs = direction_numbers();
    for spp in [1u32, 4, 16] {
        let t = table(4, spp, 4);
        for seed in 0..16 {
            for pair in 0..4 {
                for m in 0..=10 {
                    let pts: Vec<_> = (0..1u32 << m)
                        .map(|i| {
                            (
                                t.bits(seed, i, 2 * pair, &dirs),
                                t.bits(seed, i, 2 * pair + 1, &dirs),
                            )
                        })
                        .collect();
                    assert!(
                        is_0m2_net(&pts, m),
                        "spp {spp} seed {seed} pair {pair} m {m}"
                    );
                }
            }
        }
    }
}

#[test]
fn dimensions_past_the_table_are_plain_owen_sobol() {
    let dirs = direction_numbers();
    let t = table(2, 1, 2);
    for dim in 4..12 {
        assert_eq!(
            t.bits(3, 5, dim, &dirs),
            owen_sobol_bits(3, 5, dim, &dirs),
            "dim {dim}"
        );
    }
}

#[test]
fn seeds_wrap_modulo_the_tile() {
    let dirs = direction_numbers();
    let t = table(4, 2, 1);
    assert_eq!(t.bits(3, 1, 0, &dirs), t.bits(3 + 16, 1, 0, &dirs));
    assert_ne!(t.bits(3, 1, 0, &dirs), t.bits(4, 1, 0, &dirs));
}

#[test]
fn bytes_round_trip() {
    let t = table(8, 4, 3);
    let back = KeyTable::from_bytes(&t.to_bytes(), Path::new("t.bin")).expect("parses");
    assert_eq!(back, t);
}

fn rejects(bytes: &[u8], needle: &str) {
    match KeyTable::from_bytes(bytes, Path::new("bad.bin")) {
        Ok(_) => panic!("accepted bytes that should fail with {needle:?}"),
        Err(e) => {
            let s = e.to_string();
            assert!(s.contains("bad.bin") && s.contains(needle), "{s}");
        }
    }
}

#[test]
fn loader_rejects_bad_files_with_clear_errors() {
    let good = table(4, 4, 2).to_bytes();
    rejects(&[], "shorter than");
    rejects(&good[..10], "shorter than");
    let mut b = good.clone();
    b[0] = b'X';
    rejects(&b, "magic");
    let mut b = good.clone();
    b[4] = 9;
    rejects(&b, "version 9");
    rejects(&good[..good.len() - 1], "bytes of keys");
    let mut b = good.clone();
    b.extend_from_slice(&[0; 8]);
    rejects(&b, "bytes of keys");
    let mut b = good.clone();
    b[6] = 3; // tile 3: 9 * 2 keys
    b.truncate(KEYS_HEADER_LEN + 9 * 2 * 8);
    rejects(&b, "power of two");
    let mut b = good.clone();
    b[KEYS_HEADER_LEN + 4] = 4; // rank 4 with spp 4
    rejects(&b, "rank 4");
    let mut b = good.clone();
    b[10] = 0; // zero pairs, zero keys
    b.truncate(KEYS_HEADER_LEN);
    rejects(&b, "pairs");
    let mut b = good;
    b[8] = 3; // spp 3
    rejects(&b, "spp 3");
    match KeyTable::load(Path::new("/nonexistent/keys.bin")) {
        Err(KeysError::Io { path, .. }) => assert!(path.contains("keys.bin")),
        other => panic!("{other:?}"),
    }
}
