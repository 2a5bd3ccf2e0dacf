//! The GPU passes: `permute/classify_pixels` and `permute/sort_seeds`, which also retargets
//! (seed reprojection: reproject_gpu.rs).
use crate::{PermuteError, Result, SortParams};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, PipelineCache, Recorder, Res};
pub use blueshift_layout::variants::SortVariant;

/// What the sorting pass ranks, and where it counts skewed classes. The optional inputs
/// select the pass's variant: the paper's sorting has none of them.
#[derive(Debug, Clone, Copy)]
pub struct SortInput<'a> {
    /// vec4 (rgb, sorting key) per visible pixel.
    pub estimate: &'a Buffer,
    /// The N*N mask ranks; when retargeting, packed with the displacements
    /// (`pack_mask_moves`).
    pub mask: &'a Buffer,
    /// One u32 per visible pixel from classify_pixels (below 2^26); `None`: one class per
    /// block.
    pub classes: Option<&'a Buffer>,
    /// One f32 per visible pixel subtracted from the key (history_key's means, NaN for the
    /// class mean in the block); `None`: the raw key.
    pub history: Option<&'a Buffer>,
    /// Whether `SortParams::pairs` may ask for antithetic pairs.
    pub pairs: bool,
    /// Two u32 the pass adds (skewed classes, classes counted) to when
    /// `SortParams::count_skew` is set; the caller zeroes them (`sort_seeds_cpu` returns the
    /// same counts). `None`: no counting.
    pub stats: Option<&'a Buffer>,
    /// Retarget as well, into this buffer (padded like the seeds; every seed is written);
    /// `None`: sort in place.
    pub retarget: Option<&'a Buffer>,
    /// Run sort-cycle's point cycle first (`SortParams::cycle_*`, `mask` then holds the
    /// spatio-temporal volume and `mask_layer` picks the slice); `None`: rank this frame's
    /// keys and seeds.
    pub cycle: Option<CycleInput<'a>>,
}

/// The point cycle's buffers (`cycle_keys_cpu` is the twin of what the pass does with them).
#[derive(Debug, Clone, Copy)]
pub struct CycleInput<'a> {
    /// (seed, key bits) per phase slot and visible pixel (`cycle_history_bytes`).
    pub history: &'a Buffer,
    /// vec4 per visible pixel: the running mean of the earlier frames.
    pub accum: &'a Buffer,
}

impl SortInput<'_> {
    /// The sorting pass's variant for this input and block edge.
    pub fn variant(&self, block: u32) -> SortVariant {
        SortVariant {
            classes: self.classes.is_some(),
            history: self.history.is_some(),
            pairs: self.pairs,
            skew: self.stats.is_some(),
            large: SortVariant::large_for(block),
            retarget: self.retarget.is_some(),
            cycle: self.cycle.is_some(),
        }
    }
}

/// Bindings of every sorting variant.
const SORT_BINDINGS: [Binding; 3] = [
    Binding::storage(0, "estimate"),
    Binding::storage(1, "mask"),
    Binding::storage(2, "seeds"),
];
/// Bindings of the extensions, in the order of `SortInput`'s classes, history, stats,
/// retarget and cycle (two buffers).
const SORT_OPTIONAL: [Binding; 6] = [
    Binding::storage(3, "classes"),
    Binding::storage(4, "hist_mean"),
    Binding::storage(5, "sort_stats"),
    Binding::storage(6, "seeds_out"),
    Binding::storage(7, "cycle_history"),
    Binding::storage(8, "accum"),
];

/// Pipelines of the permutation passes.
pub struct PermutePasses {
    dev: Device,
    classify: ComputePipeline,
    /// Sorting-pass variants created so far.
    sort: PipelineCache<SortVariant>,
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
        let classify = pipeline(
            dev,
            "permute/classify_pixels",
            &[
                Binding::storage(0, "gbuffer"),
                Binding::storage(1, "classes"),
            ],
            std::mem::size_of::<SortParams>(),
        )?;
        Ok(Self {
            dev: dev.clone(),
            classify,
            sort: PipelineCache::default(),
        })
    }

    /// Records the sorting pass (in place on `seeds`, or retargeted into `input.retarget`),
    /// in the variant `input` asks for.
    pub fn sort_seeds(
        &mut self,
        rec: &mut Recorder,
        p: &SortParams,
        input: &SortInput,
        seeds: &Buffer,
    ) -> Result<()> {
        let mut resources: Vec<(&str, Res)> = vec![
            ("estimate", input.estimate.into()),
            ("mask", input.mask.into()),
            ("seeds", seeds.into()),
        ];
        let optional = [
            input.classes,
            input.history,
            input.stats,
            input.retarget,
            input.cycle.map(|c| c.history),
            input.cycle.map(|c| c.accum),
        ];
        for (b, buffer) in SORT_OPTIONAL.iter().zip(optional) {
            resources.extend(buffer.map(|buf| (b.name, buf.into())));
        }
        let area = match input.retarget {
            Some(_) => (p.stride, p.padded_height),
            None => (p.width, p.height),
        };
        let groups = block_groups(p, area)?;
        let dev = &self.dev;
        let pipeline = self.sort.get_or_create(input.variant(p.block), |v| {
            let on = [v.classes, v.history, v.skew, v.retarget, v.cycle, v.cycle];
            let optional = SORT_OPTIONAL.iter().zip(on).filter(|(_, on)| *on);
            let bindings: Vec<Binding> = SORT_BINDINGS
                .into_iter()
                .chain(optional.map(|(b, _)| *b))
                .collect();
            pipeline(
                dev,
                &v.shader(),
                &bindings,
                std::mem::size_of::<SortParams>(),
            )
        })?;
        rec.dispatch(pipeline, &resources, bytemuck::bytes_of(p), groups)?;
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
            &[("gbuffer", gbuffer.into()), ("classes", classes.into())],
            bytemuck::bytes_of(p),
            block_groups(p, (p.width, p.height))?,
        )?;
        Ok(())
    }
}

/// One invocation per block (64 per workgroup) over `area` (the screen or the padded screen).
fn block_groups(p: &SortParams, area: (u32, u32)) -> Result<[u32; 3]> {
    if !(2..=8).contains(&p.block) {
        return Err(PermuteError::BlockSize(p.block));
    }
    let (bx, by) = crate::block_counts(&SortParams {
        width: area.0,
        height: area.1,
        ..*p
    });
    let blocks = bx * by;
    Ok([blocks.div_ceil(64), 1, 1])
}
