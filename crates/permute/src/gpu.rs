//! The GPU passes: `permute/sort_seeds` and `permute/retarget_seeds`.
use crate::{PermuteError, Result, RetargetParams, SortParams};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};

/// Pipelines of both permutation passes.
pub struct PermutePasses {
    sort: ComputePipeline,
    retarget: ComputePipeline,
}

impl std::fmt::Debug for PermutePasses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PermutePasses").finish_non_exhaustive()
    }
}

fn pipeline(
    dev: &Device,
    name: &str,
    bindings: &[Binding],
    push: usize,
) -> Result<ComputePipeline> {
    Ok(blueshift_shaders::pipeline(dev, name, bindings, push)?)
}

impl PermutePasses {
    pub fn new(dev: &Device) -> Result<Self> {
        let sort = pipeline(
            dev,
            "permute/sort_seeds",
            &[
                Binding::storage(0, "estimate"),
                Binding::storage(1, "mask"),
                Binding::storage(2, "seeds"),
            ],
            std::mem::size_of::<SortParams>(),
        )?;
        let retarget = pipeline(
            dev,
            "permute/retarget_seeds",
            &[
                Binding::storage(0, "table"),
                Binding::storage(1, "seeds_in"),
                Binding::storage(2, "seeds_out"),
            ],
            std::mem::size_of::<RetargetParams>(),
        )?;
        Ok(Self { sort, retarget })
    }

    /// Records the sorting pass (in place on `seeds`). `estimate` holds vec4 (rgb, luminance).
    pub fn sort_seeds(
        &self,
        rec: &mut Recorder,
        p: &SortParams,
        estimate: &Buffer,
        mask: &Buffer,
        seeds: &Buffer,
    ) -> Result<()> {
        if !(2..=8).contains(&p.block) {
            return Err(PermuteError::BlockSize(p.block));
        }
        let blocks = p.width.div_ceil(p.block) * p.height.div_ceil(p.block);
        let groups = [blocks.div_ceil(64), 1, 1];
        rec.dispatch(
            &self.sort,
            &[estimate.into(), mask.into(), seeds.into()],
            bytemuck::bytes_of(p),
            groups,
        )?;
        Ok(())
    }

    /// Records the retargeting pass from `seeds_in` to `seeds_out`. `table` holds ivec2 D.
    pub fn retarget_seeds(
        &self,
        rec: &mut Recorder,
        p: &RetargetParams,
        table: &Buffer,
        seeds_in: &Buffer,
        seeds_out: &Buffer,
    ) -> Result<()> {
        let groups = [p.padded_width.div_ceil(8), p.padded_height.div_ceil(8), 1];
        rec.dispatch(
            &self.retarget,
            &[table.into(), seeds_in.into(), seeds_out.into()],
            bytemuck::bytes_of(p),
            groups,
        )?;
        Ok(())
    }
}
