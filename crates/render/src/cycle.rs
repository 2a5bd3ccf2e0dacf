//! State of `sort-cycle` (`Points::Cycle`): the per-phase history that the sorting pass's
//! point cycle reads and writes.
use crate::Result;
use blueshift_device::{Buffer, Device, MemoryLocation, Recorder};
use blueshift_permute::{Screen, cycle_history_bytes};

/// (seed, key bits) per phase slot and visible pixel: made the first time a frame needs it.
pub(crate) struct CycleHistory {
    pub history: Buffer,
}

impl CycleHistory {
    pub fn new(dev: &Device, screen: &Screen) -> Result<Self> {
        let bytes = cycle_history_bytes(screen.width, screen.height);
        let history = Buffer::new(dev, "cycle.history", bytes, MemoryLocation::GpuOnly)?;
        // Touches the whole history now (its contents are never read before written): on a
        // CPU device the first touch of each page costs a fault, which would otherwise slow
        // the sorting pass over the whole first cycle.
        Recorder::one_shot(dev, "cycle.clear", |rec| rec.fill_buffer(&history, 0))?;
        Ok(Self { history })
    }
}
