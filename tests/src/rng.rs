//! GLSL rng.glsl == Rust blueshift_sampling::rng, bit for bit, over 2^20 inputs per run.
use crate::{Gpu, groups_for};
use blueshift_device::Binding;
use blueshift_sampling::rng::{hash3, pcg_hash, pixel_seed, white};

#[test]
fn glsl_rng_matches_rust_twin_bit_for_bit() {
    let mut gpu = Gpu::new();
    let p = gpu.pipeline("test/rng", &[Binding::storage(0, "results")], 8);
    let n: u32 = 1 << 20;
    let out = gpu.output::<[u32; 4]>("rng.results", n as usize);
    // Two windows: small integers and values near u32::MAX (wrap-around arithmetic).
    for base in [0u32, u32::MAX - n + 1] {
        let push: Vec<u8> = bytemuck::cast_slice(&[base, n]).to_vec();
        gpu.run(
            &p,
            &[("results", (&out).into())],
            &push,
            [groups_for(n, 64), 1, 1],
        );
        let got = out.read::<[u32; 4]>().unwrap();
        for (i, g) in got.iter().enumerate().take(n as usize) {
            let v = base.wrapping_add(i as u32);
            let want = [
                pcg_hash(v),
                hash3(v, v.wrapping_mul(3), 7),
                white(v, 5, v & 15).to_bits(),
                pixel_seed(v, !v, 1),
            ];
            assert_eq!(*g, want, "input {v}");
        }
    }
}
