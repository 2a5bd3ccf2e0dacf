//! The GPU passes: `permute/classify_pixels`, `permute/sort_seeds` and
//! `permute/retarget_seeds` (seed reprojection: reproject_gpu.rs).
use crate::{PermuteError, Result, RetargetParams, SortParams};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};

/// What the sorting pass ranks, and where it counts skewed classes.
#[derive(Debug, Clone, Copy)]
pub struct SortInput<'a> {
    /// vec4 (rgb, sorting key) per visible pixel.
    pub estimate: &'a Buffer,
    /// The N*N mask ranks.
    pub mask: &'a Buffer,
    /// One u32 per visible pixel (zeros: the paper's method; else classify_pixels).
    pub classes: &'a Buffer,
    /// One f32 per visible pixel subtracted from the key (zeros: the raw key; else
    /// history_key's means, NaN for the class mean in the block).
    pub history: &'a Buffer,
    /// Two u32 the pass adds (skewed classes, classes counted) to when
    /// `SortParams::count_skew` is set; the caller zeroes them (`sort_seeds_cpu` returns the
    /// same counts).
    pub stats: &'a Buffer,
}

/// Pipelines of both permutation passes.
pub struct PermutePasses {
    classify: ComputePipeline,
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
                Binding::storage(3, "classes"),
                Binding::storage(4, "history"),
                Binding::storage(5, "stats"),
            ],
            std::mem::size_of::<SortParams>(),
        )?;
        let classify = pipeline(
            dev,
            "permute/classify_pixels",
            &[
                Binding::storage(0, "gbuffer"),
                Binding::storage(1, "classes"),
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
        Ok(Self {
            classify,
            sort,
            retarget,
        })
    }

    /// Records the sorting pass (in place on `seeds`).
    pub fn sort_seeds(
        &self,
        rec: &mut Recorder,
        p: &SortParams,
        input: &SortInput,
        seeds: &Buffer,
    ) -> Result<()> {
        rec.dispatch(
            &self.sort,
            &[
                input.estimate.into(),
                input.mask.into(),
                seeds.into(),
                input.classes.into(),
                input.history.into(),
                input.stats.into(),
            ],
            bytemuck::bytes_of(p),
            block_groups(p)?,
        )?;
        Ok(())
    }

    /// Records edge-aware grouping: per block, the surface class of every visible pixel from
    /// the G-buffer (`GBufferTexel` per visible pixel) into `classes`.
    pub fn classify_pixels(
        &self,
        rec: &mut Recorder,
        p: &SortParams,
        gbuffer: &Buffer,
        classes: &Buffer,
    ) -> Result<()> {
        rec.dispatch(
            &self.classify,
            &[gbuffer.into(), classes.into()],
            bytemuck::bytes_of(p),
            block_groups(p)?,
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

/// One invocation per block (64 per workgroup).
fn block_groups(p: &SortParams) -> Result<[u32; 3]> {
    if !(2..=8).contains(&p.block) {
        return Err(PermuteError::BlockSize(p.block));
    }
    let (bx, by) = crate::block_counts(p);
    let blocks = bx * by;
    Ok([blocks.div_ceil(64), 1, 1])
}
