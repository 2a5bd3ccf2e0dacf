//! The point cycle of `sort-cycle`: its parameters and CPU twin. On the GPU the sorting pass
//! runs it on the way in (`SortInput::cycle`).
//!
//! Seeds keep a fixed set of points (sample index = frame mod [`CYCLE_FRAMES`]) and never
//! leave their sorting block, so the key a seed produced at phase j predicts the key it will
//! produce at phase j one cycle later. The pass records each frame's (seed, key) per phase and
//! hands the sorting pass the next phase's seeds and keys, with the next mask slice.
use crate::{Screen, SortParams};
pub use blueshift_layout::params::{CYCLE_FRAMES, CycleParams};
use blueshift_layout::params::{SAMPLE_KEY_DIM, sample_key_code};
use blueshift_sampling::{Sampler, Samples};

impl Screen {
    /// The point cycle's parameters after tracing `frame`, against a spatio-temporal mask
    /// of tile `mask_size` with `mask_frames` slices; `mean_count` frames are in the running
    /// mean; `sample_keys`: the seeds rank by their next light sample (while the view moves).
    pub fn cycle_params(
        &self,
        frame: u64,
        mask_size: u32,
        mask_frames: u32,
        mean_count: u32,
        sample_keys: bool,
    ) -> CycleParams {
        let cycle = u64::from(CYCLE_FRAMES);
        CycleParams {
            width: self.width,
            height: self.height,
            stride: self.stride(),
            phase: (frame % cycle) as u32,
            next_phase: ((frame + 1) % cycle) as u32,
            next_valid: u32::from(frame + 1 >= cycle),
            mask_size,
            mask_layer: ((frame + 1) % u64::from(mask_frames.max(1))) as u32,
            mean_count,
            sample_keys: u32::from(sample_keys),
        }
    }
}

/// The key a seed ranks by under `sample_keys`: where the block-net point it takes at sample
/// `index` lands in the first vertex's light sample dimensions (its Hilbert index).
pub fn sample_key(samples: &Samples, seed: u32, index: u32) -> f32 {
    let x = samples.bits(Sampler::BlockNet, seed, index, SAMPLE_KEY_DIM);
    let y = samples.bits(Sampler::BlockNet, seed, index, SAMPLE_KEY_DIM + 1);
    sample_key_code(x, y) as f32
}

/// What the point cycle hands the sort besides the seed buffer and the history.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleOutput {
    /// The keys the sorting pass ranks (its `estimate.w`), per visible pixel.
    pub keys: Vec<f32>,
    /// The next frame's mask slice, N*N ranks.
    pub mask: Vec<u32>,
}

/// CPU twin of the point cycle (the sorting pass's `SORT_CYCLE` loads): `keys` is the frame's
/// `estimate.w` per visible pixel, `means` the running mean's `.w`, `seeds` the padded seed
/// buffer (updated in place), `history` the `CYCLE_FRAMES * width * height` (seed, key bits)
/// slots (updated in place), `volume` the spatio-temporal ranks.
pub fn cycle_keys_cpu(
    p: &CycleParams,
    keys: &[f32],
    means: &[f32],
    seeds: &mut [u32],
    history: &mut [[u32; 2]],
    volume: &[u32],
) -> CycleOutput {
    let area = (p.mask_size * p.mask_size) as usize;
    let layer = p.mask_layer as usize * area;
    let mask = volume[layer..layer + area].to_vec();
    let pixels = (p.width * p.height) as usize;
    let samples = Samples::default();
    let mut out = Vec::with_capacity(pixels);
    for (i, &key) in keys.iter().enumerate().take(pixels) {
        let key = if p.mean_count > 0 {
            key - means[i]
        } else {
            key
        };
        let (x, y) = (i as u32 % p.width, i as u32 / p.width);
        let s = (y * p.stride + x) as usize;
        history[p.phase as usize * pixels + i] = [seeds[s], key.to_bits()];
        let key = if p.next_valid != 0 {
            let [seed, bits] = history[p.next_phase as usize * pixels + i];
            seeds[s] = seed;
            f32::from_bits(bits)
        } else {
            key
        };
        out.push(match p.sample_keys {
            0 => key,
            _ => sample_key(&samples, seeds[s], p.next_phase),
        });
    }
    CycleOutput { keys: out, mask }
}

/// Bytes of the history buffer for a `width x height` screen.
pub fn cycle_history_bytes(width: u32, height: u32) -> u64 {
    u64::from(CYCLE_FRAMES) * u64::from(width) * u64::from(height) * 8
}

/// `sort` with the point cycle of `cycle` on the way in (the sorting pass's `SORT_CYCLE`
/// variant): `cycle`'s mask slice and phases.
pub fn with_cycle(sort: SortParams, cycle: &CycleParams) -> SortParams {
    SortParams {
        mask_layer: cycle.mask_layer,
        cycle_phase: cycle.phase,
        cycle_next_phase: cycle.next_phase,
        cycle_next_valid: cycle.next_valid,
        cycle_mean_count: cycle.mean_count,
        cycle_sample_keys: cycle.sample_keys,
        ..sort
    }
}
