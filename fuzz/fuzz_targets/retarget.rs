//! Retarget table (`.bin`) reader: a table that parses is a bijection of the tile and writes
//! back the same bytes.
#![no_main]
use blueshift_analysis::assets::RetargetTable;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Ok(t) = RetargetTable::from_bytes(data, Path::new("fuzz.bin")) {
        assert_eq!(
            t.to_bytes(),
            data,
            "a table that parses writes back the same bytes"
        );
        let mut hit = vec![false; t.n * t.n];
        for y in 0..t.n {
            for x in 0..t.n {
                assert!(!std::mem::replace(&mut hit[t.target(x, y)], true));
            }
        }
    }
});
