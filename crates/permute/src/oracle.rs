//! Oracle keys (`permute/oracle_key`, method `sort-grid-oracle`): the sorting pass ranks each
//! pixel's exact luminance error against the frame's reference instead of an estimate of it.
//! No renderer has the reference, so only `blueshift eval` drives it: it measures the ceiling
//! of any choice of sorting key. The pass, its reference buffer and the CPU twin.
use crate::{PermuteError, Result};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, MemoryLocation, Recorder};
use blueshift_layout::motion::OracleParams;

/// The pass and the reference luminance it subtracts.
pub struct OracleKeys {
    pass: ComputePipeline,
    reference: Buffer,
    pixels: usize,
}

impl std::fmt::Debug for OracleKeys {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OracleKeys")
            .field("pixels", &self.pixels)
            .finish_non_exhaustive()
    }
}

impl OracleKeys {
    pub fn new(dev: &Device, width: u32, height: u32) -> Result<Self> {
        let bindings = [
            Binding::storage(0, "estimate"),
            Binding::storage(1, "reference"),
        ];
        let pass = blueshift_shaders::pipeline(
            dev,
            "permute/oracle_key",
            &bindings,
            size_of::<OracleParams>(),
        )?;
        let pixels = width as usize * height as usize;
        let reference = Buffer::new(
            dev,
            "oracle.reference",
            pixels as u64 * 4,
            MemoryLocation::CpuToGpu,
        )?;
        Ok(Self {
            pass,
            reference,
            pixels,
        })
    }

    /// Sets the reference luminance (W*H, row-major) the next pass subtracts.
    pub fn set_reference(&mut self, luminance: &[f32]) -> Result<()> {
        if luminance.len() != self.pixels {
            return Err(PermuteError::Invalid(format!(
                "oracle reference has {} pixels, the screen {}",
                luminance.len(),
                self.pixels
            )));
        }
        self.reference.write(0, luminance)?;
        Ok(())
    }

    /// Records the pass: `estimate`'s fourth channel (W*H vec4) becomes luminance(rgb) minus
    /// the reference.
    pub fn oracle_key(
        &self,
        rec: &mut Recorder,
        p: &OracleParams,
        estimate: &Buffer,
    ) -> Result<()> {
        rec.dispatch(
            &self.pass,
            &[estimate.into(), (&self.reference).into()],
            bytemuck::bytes_of(p),
            [p.width.div_ceil(8), p.height.div_ceil(8), 1],
        )?;
        Ok(())
    }
}

/// CPU twin of `oracle_key`: sets each estimate's key (its fourth channel) to its Rec.709
/// luminance minus `reference`, with the shader's operations in its order.
pub fn oracle_key_cpu(estimate: &mut [[f32; 4]], reference: &[f32]) {
    for (e, r) in estimate.iter_mut().zip(reference) {
        e[3] = blueshift_layout::luminance([e[0], e[1], e[2]]) - r;
    }
}
