//! State of `sort-cycle` (`Points::Cycle`): the per-phase history and the sorting pass's
//! inputs that `permute/cycle_keys` writes.
use crate::Result;
use blueshift_device::{Buffer, Device, MemoryLocation, Recorder};
use blueshift_permute::{CycleBuffers, CycleParams, CyclePass, Screen};

/// Created the first time a frame needs it.
pub(crate) struct CycleState {
    pass: CyclePass,
    /// (seed, key bits) per phase slot and visible pixel.
    history: Buffer,
    /// The sorting pass's keys (vec4, `.w`) and mask slice for the next frame.
    pub keys: Buffer,
    pub mask: Buffer,
}

impl CycleState {
    pub fn new(dev: &Device, screen: &Screen, mask_size: u32) -> Result<Self> {
        let pixels = u64::from(screen.width) * u64::from(screen.height);
        let gpu = MemoryLocation::GpuOnly;
        Ok(Self {
            pass: CyclePass::new(dev)?,
            history: Buffer::new(
                dev,
                "cycle.history",
                CyclePass::history_bytes(screen.width, screen.height),
                gpu,
            )?,
            keys: Buffer::new(dev, "cycle.keys", pixels * 16, MemoryLocation::GpuToCpu)?,
            mask: Buffer::new(
                dev,
                "cycle.mask",
                u64::from(mask_size) * u64::from(mask_size) * 4,
                gpu,
            )?,
        })
    }

    /// Records `cycle_keys` for the frame just traced into `estimate` with `seeds`; `accum`
    /// holds the running mean of the frames before.
    pub fn record(
        &self,
        rec: &mut Recorder,
        p: &CycleParams,
        estimate: &Buffer,
        seeds: &Buffer,
        volume: &Buffer,
        accum: &Buffer,
    ) -> Result<()> {
        let buffers = CycleBuffers {
            estimate,
            seeds,
            history: &self.history,
            volume,
            keys: &self.keys,
            mask: &self.mask,
            accum,
        };
        self.pass.cycle_keys(rec, p, &buffers)?;
        Ok(())
    }
}
