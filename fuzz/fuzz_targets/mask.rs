//! Mask (`.r16`) and spatio-temporal mask readers. The first byte picks the STBN side.
#![no_main]
use blueshift_analysis::assets::{Mask, StbnVolume};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.r16");
    if let Ok(m) = Mask::from_bytes(data, path) {
        assert_eq!(
            m.to_bytes(),
            data,
            "a mask that parses writes back the same bytes"
        );
        let _ = blueshift_analysis::Gray::from(&m);
        let _ = m.rank(-1, i64::from(m.n as u32) + 3);
    }
    if let Some((&n, rest)) = data.split_first() {
        if let Ok(v) = StbnVolume::from_bytes(rest, usize::from(n), path) {
            assert_eq!(v.to_bytes(), rest);
            for s in 0..v.t {
                assert!(v.slice(s).is_ok());
            }
        }
    }
});
