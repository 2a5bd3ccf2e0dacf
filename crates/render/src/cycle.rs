//! State of `sort-cycle` (`Points::Cycle`): the per-phase history that the sorting pass's
//! point cycle reads and writes.
use crate::Result;
use blueshift_device::{Buffer, Device, MemoryLocation};
use blueshift_permute::{Screen, cycle_history_bytes};

/// Created the first time a frame needs it.
pub(crate) struct CycleState {
    /// (seed, key bits) per phase slot and visible pixel.
    pub history: Buffer,
}

impl CycleState {
    pub fn new(dev: &Device, screen: &Screen) -> Result<Self> {
        let bytes = cycle_history_bytes(screen.width, screen.height);
        Ok(Self {
            history: Buffer::new(dev, "cycle.history", bytes, MemoryLocation::GpuOnly)?,
        })
    }
}
