//! GLSL sampling.glsl == Rust blueshift_sampling for every sampler, bit for bit, one
//! dimension at a time and as the trace draws a path vertex's seven (from pairs).
use crate::{Gpu, groups_for};
use blueshift_device::{Binding, Buffer};
use blueshift_sampling::hbo19::KeyTable;
use blueshift_sampling::rng::hash3;
use blueshift_sampling::{Sampler, Samples};

#[test]
fn glsl_samplers_match_rust_twins_bit_for_bit() {
    let mut gpu = Gpu::new();
    let p = gpu.pipeline(
        "test/sampling",
        &[
            Binding::storage(0, "inputs"),
            Binding::storage(1, "results"),
            Binding::storage(2, "keys"),
        ],
        4,
    );
    // An 8x8 tile of hashed HBO+19 keys (4 pairs, spp 16): the twins must agree on the lookup
    // (seed mod tile^2, pair) and on the fallback past dimension 8, whatever the keys are.
    let (tile, spp, pairs) = (8u32, 16u32, 4u32);
    let keys = (0..tile * tile * pairs)
        .map(|i| [hash3(i, 5, 6), hash3(i, 7, 8) % spp])
        .collect();
    let table = KeyTable::new(tile, spp, pairs, keys).unwrap();
    let keyb = Buffer::from_slice(gpu.dev(), "sampling.keys", &table.gpu_words()).unwrap();
    let n: u32 = 1 << 18;
    // Random seeds, indices spanning small and large values, dimensions 0..64.
    let inputs: Vec<[u32; 3]> = (0..n)
        .map(|i| {
            [
                hash3(i, 1, 2),
                if i % 2 == 0 { i % 4096 } else { hash3(i, 3, 4) },
                i % 64,
            ]
        })
        .collect();
    let inb = Buffer::from_slice(gpu.dev(), "sampling.inputs", &inputs).unwrap();
    let out = gpu.output::<[u32; 12]>("sampling.results", n as usize);
    gpu.run(
        &p,
        &[
            ("inputs", (&inb).into()),
            ("results", (&out).into()),
            ("keys", (&keyb).into()),
        ],
        bytemuck::bytes_of(&n),
        [groups_for(n, 64), 1, 1],
    );
    let got = out.read::<[u32; 12]>().unwrap();
    let s = Samples::with_keys(table);
    for (q, g) in inputs.iter().zip(&got) {
        let want = [
            Sampler::White,
            Sampler::Sobol,
            Sampler::R2,
            Sampler::Hbo19,
            Sampler::BlockNet,
        ]
        .map(|m| s.bits(m, q[0], q[1], q[2]));
        assert_eq!(g[..5], want, "seed {} index {} dim {}", q[0], q[1], q[2]);
        // Odd and even first dimensions both occur (dim = i mod 64).
        let vertex: [u32; 7] =
            std::array::from_fn(|k| s.bits(Sampler::BlockNet, q[0], q[1], q[2] + k as u32));
        assert_eq!(
            g[5..],
            vertex,
            "vertex from dim {}: seed {} index {}",
            q[2],
            q[0],
            q[1]
        );
    }
}
