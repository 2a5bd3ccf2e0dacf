//! `permute/cycle_keys`: the point cycle of `sort-cycle`, on the GPU and as its CPU twin.
//!
//! Seeds keep a fixed set of points (sample index = frame mod [`CYCLE_FRAMES`]) and never
//! leave their sorting block, so the key a seed produced at phase j predicts the key it will
//! produce at phase j one cycle later. The pass records each frame's (seed, key) per phase and
//! hands the sorting pass the next phase's seeds and keys, with the next mask slice.
use crate::{Result, Screen};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};
pub use blueshift_layout::params::{CYCLE_FRAMES, CycleParams};

impl Screen {
    /// Push constants of `cycle_keys` after tracing `frame`, against a spatio-temporal mask
    /// of tile `mask_size` with `mask_frames` slices; `mean_count` frames are in the running
    /// mean.
    pub fn cycle_params(
        &self,
        frame: u64,
        mask_size: u32,
        mask_frames: u32,
        mean_count: u32,
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
        }
    }
}

/// What `cycle_keys` writes besides the seed buffer and the history.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleOutput {
    /// The keys the sorting pass ranks (its `estimate.w`), per visible pixel.
    pub keys: Vec<f32>,
    /// The next frame's mask slice, N*N ranks.
    pub mask: Vec<u32>,
}

/// CPU twin of `cycle_keys`: `keys` is the frame's `estimate.w` per visible pixel, `means` the
/// running mean's `.w`, `seeds` the padded seed buffer (updated in place), `history` the
/// `CYCLE_FRAMES * width * height` (seed, key bits) slots (updated in place), `volume` the
/// spatio-temporal ranks.
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
        if p.next_valid != 0 {
            let [seed, bits] = history[p.next_phase as usize * pixels + i];
            seeds[s] = seed;
            out.push(f32::from_bits(bits));
        } else {
            out.push(key);
        }
    }
    CycleOutput { keys: out, mask }
}

/// The `cycle_keys` pipeline.
pub struct CyclePass {
    pipeline: ComputePipeline,
}

impl std::fmt::Debug for CyclePass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CyclePass").finish_non_exhaustive()
    }
}

/// The buffers `cycle_keys` reads and writes.
#[derive(Debug, Clone, Copy)]
pub struct CycleBuffers<'a> {
    pub estimate: &'a Buffer,
    pub seeds: &'a Buffer,
    pub history: &'a Buffer,
    pub volume: &'a Buffer,
    /// vec4 per visible pixel: the sorting pass's `estimate` input.
    pub keys: &'a Buffer,
    /// N*N u32: the sorting pass's `mask` input.
    pub mask: &'a Buffer,
    /// vec4 per visible pixel: the running mean of the earlier frames.
    pub accum: &'a Buffer,
}

impl CyclePass {
    pub fn new(dev: &Device) -> Result<Self> {
        let bindings = [
            Binding::storage(0, "estimate"),
            Binding::storage(1, "seeds"),
            Binding::storage(2, "cycle_history"),
            Binding::storage(3, "volume"),
            Binding::storage(4, "cycle_estimate"),
            Binding::storage(5, "cycle_mask"),
            Binding::storage(6, "accum"),
        ];
        let pipeline = blueshift_shaders::pipeline(
            dev,
            "permute/cycle_keys",
            &bindings,
            std::mem::size_of::<CycleParams>(),
        )?;
        Ok(Self { pipeline })
    }

    /// Bytes of the history buffer for a `width x height` screen.
    pub fn history_bytes(width: u32, height: u32) -> u64 {
        u64::from(CYCLE_FRAMES) * u64::from(width) * u64::from(height) * 8
    }

    /// Records the pass.
    pub fn cycle_keys(&self, rec: &mut Recorder, p: &CycleParams, b: &CycleBuffers) -> Result<()> {
        let (w, h) = (p.width.max(p.mask_size), p.height.max(p.mask_size));
        rec.dispatch(
            &self.pipeline,
            &[
                ("estimate", b.estimate.into()),
                ("seeds", b.seeds.into()),
                ("cycle_history", b.history.into()),
                ("volume", b.volume.into()),
                ("cycle_estimate", b.keys.into()),
                ("cycle_mask", b.mask.into()),
                ("accum", b.accum.into()),
            ],
            bytemuck::bytes_of(p),
            [w.div_ceil(64), h, 1],
        )?;
        Ok(())
    }
}
