//! The pairs gate pass (`permute/pairs_gate`) against its CPU twin `PairsGate`.
use crate::{Gpu, Lcg};
use blueshift_device::{Buffer, MemoryLocation};
use blueshift_permute::{PairsGate, PermutePasses};

/// The pairs gate pass against its twin over a run of counts: frames with nothing counted,
/// the first count, a crossing of the limit each way, counts in the millions (a 4K screen's
/// classes: the fixed-point product needs 64 bits), more skewed than counted (clamped).
#[test]
fn pairs_gate_matches_cpu() {
    let mut gpu = Gpu::new();
    let passes = PermutePasses::new(gpu.dev()).unwrap();
    let dev = gpu.dev().clone();
    let mut stats = Buffer::new(&dev, "gate.sort_stats", 8, MemoryLocation::CpuToGpu).unwrap();
    let gate = Buffer::from_slice(&dev, "gate.pairs_gate", &[0u32, 0]).unwrap();
    let mut rng = Lcg(5);
    let mut run: Vec<[u32; 2]> = vec![[0, 0], [3, 100], [0, 0], [40, 100], [90, 97]];
    run.extend((0..20).map(|_| [0, 50]));
    run.extend([[4_000_000, 4_100_000], [7, 5], [0, 0]]);
    run.extend((0..30).map(|_| {
        let counted = rng.next_u32() % 5000;
        [rng.next_u32() % (counted + 1) / 4, counted]
    }));
    let mut cpu = PairsGate::default();
    let mut seen = [false; 2];
    for (k, c) in run.iter().enumerate() {
        stats.write(0, c).unwrap();
        let rec = gpu.rec.as_mut().unwrap();
        rec.begin().unwrap();
        rec.begin_pass("pairs_gate").unwrap();
        passes.pairs_gate(rec, &stats, &gate).unwrap();
        rec.submit_and_wait().unwrap();
        cpu.update(*c);
        let got: Vec<u32> = gate.read().unwrap();
        assert_eq!(got, cpu.words(), "step {k}: counts {c:?}");
        seen[usize::from(cpu.pairs() == 2)] = true;
    }
    assert_eq!(seen, [true, true], "the run crosses the limit");
}
