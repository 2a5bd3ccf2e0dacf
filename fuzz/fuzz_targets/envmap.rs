//! Environment-map decoding on bytes (the first byte picks `.hdr` or `.exr`), then, for a map
//! that decodes, the importance-sampling tables, a few samples and their densities, as
//! `blueshift render --environment FILE` does.
#![no_main]
use blueshift_scene::EnvMap;
use glam::Vec2;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let name = if pick & 1 == 0 { "map.hdr" } else { "map.exr" };
    // Decoder panics are caught by from_bytes (a decode error); libFuzzer still reports them.
    if let Ok((map, _)) = EnvMap::from_bytes(Path::new(name), bytes) {
        if map.texels.len() > 1 << 20 {
            return;
        }
        let tables = map.tables();
        let rotation = map.rotation_cs();
        for k in 0..16u32 {
            let u = Vec2::new((k as f32 + 0.5) / 16.0, ((k * 7) % 16) as f32 / 16.0);
            let (d, pdf) = tables.sample(u, rotation);
            assert!(d.is_finite() && pdf >= 0.0, "sample {u}: {d} {pdf}");
            let _ = tables.pdf(d, rotation);
            let _ = map.radiance(d);
        }
    }
});
