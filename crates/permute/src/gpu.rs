//! The GPU passes: `permute/classify_pixels`, `permute/sort_seeds`, which also retargets, and
//! `permute/pairs_gate` (seed reprojection: reproject_gpu.rs).
use crate::{PermuteError, Result, SortParams};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, PipelineCache, Recorder, Res};
use blueshift_layout::params::SORT_PAIRS_FROM_GATE;
pub use blueshift_layout::variants::SortVariant;

/// The buffers the sorting pass reads and writes. Which of the optional ones it binds is the
/// caller's [`SortVariant`] (passed beside this), never guessed from which are given: each
/// must be present exactly when the variant's extension is on.
#[derive(Debug, Clone, Copy)]
pub struct SortInput<'a> {
    /// vec4 (rgb, sorting key) per visible pixel.
    pub estimate: &'a Buffer,
    /// The N*N mask ranks; when retargeting, packed with the displacements
    /// (`pack_mask_moves`).
    pub mask: &'a Buffer,
    /// `SortVariant::classes`: one u32 per visible pixel from classify_pixels (below 2^26).
    pub classes: Option<&'a Buffer>,
    /// `SortVariant::history`: one f32 per visible pixel subtracted from the key
    /// (history_key's means, NaN for the class mean in the block).
    pub history: Option<&'a Buffer>,
    /// `SortVariant::skew`: two u32 the pass adds (skewed classes, classes counted) to when
    /// `SortParams::count_skew` is set; the caller zeroes them (`sort_seeds_cpu` returns the
    /// same counts).
    pub stats: Option<&'a Buffer>,
    /// `SortVariant::skew` with `pairs`: the pairs gate's two words (`PairsGate::words`),
    /// read where `SortParams::pairs` is `SORT_PAIRS_FROM_GATE` (the `pairs_gate` pass
    /// updates them from `stats` after the sort).
    pub gate: Option<&'a Buffer>,
    /// `SortVariant::retarget`: the buffer the seeds are retargeted into (padded like the
    /// seeds; every seed is written).
    pub retarget: Option<&'a Buffer>,
    /// `SortVariant::cycle`: sort-cycle's point cycle runs first (`SortParams::cycle_*`,
    /// `mask` then holds the spatio-temporal volume and `mask_layer` picks the slice).
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

impl<'a> SortInput<'a> {
    /// The paper's inputs: keys and mask, no extension buffers.
    pub fn new(estimate: &'a Buffer, mask: &'a Buffer) -> Self {
        Self {
            estimate,
            mask,
            classes: None,
            history: None,
            stats: None,
            gate: None,
            retarget: None,
            cycle: None,
        }
    }

    /// The optional buffers in `SORT_OPTIONAL`'s order.
    fn optional(&self) -> [Option<&'a Buffer>; 7] {
        [
            self.classes,
            self.history,
            self.stats,
            self.gate,
            self.retarget,
            self.cycle.map(|c| c.history),
            self.cycle.map(|c| c.accum),
        ]
    }

    /// Checks that `v` is a compiled variant for blocks of edge `block` and that the optional
    /// buffers are exactly those it binds.
    fn check(&self, v: SortVariant, block: u32) -> Result<()> {
        let invalid = |what: String| Err(PermuteError::Invalid(format!("sorting pass: {what}")));
        if SortVariant::large_for(block) && !v.large {
            return invalid(format!("blocks of {block} need the 64-slot variant"));
        }
        if !SortVariant::all().contains(&v) {
            return invalid(format!("no shader for {v:?}"));
        }
        for ((b, on), given) in SORT_OPTIONAL
            .iter()
            .zip(optional_flags(v))
            .zip(self.optional())
        {
            match (on, given.is_some()) {
                (true, false) => return invalid(format!("{} needs '{}'", v.shader(), b.name)),
                (false, true) => return invalid(format!("{} binds no '{}'", v.shader(), b.name)),
                _ => {}
            }
        }
        Ok(())
    }
}

/// Whether `v` binds each of `SORT_OPTIONAL`.
fn optional_flags(v: SortVariant) -> [bool; 7] {
    let gate = v.skew && v.pairs;
    [
        v.classes, v.history, v.skew, gate, v.retarget, v.cycle, v.cycle,
    ]
}

/// Bindings of every sorting variant.
const SORT_BINDINGS: [Binding; 3] = [
    Binding::storage(0, "estimate"),
    Binding::storage(1, "mask"),
    Binding::storage(2, "seeds"),
];
/// Bindings of the extensions, in the order of `SortInput`'s classes, history, stats, gate,
/// retarget and cycle (two buffers).
const SORT_OPTIONAL: [Binding; 7] = [
    Binding::storage(3, "classes"),
    Binding::storage(4, "hist_mean"),
    Binding::storage(5, "sort_stats"),
    Binding::storage(10, "pairs_gate"),
    Binding::storage(6, "seeds_out"),
    Binding::storage(7, "cycle_history"),
    Binding::storage(8, "accum"),
];

/// Pipelines of the permutation passes.
pub struct PermutePasses {
    dev: Device,
    classify: ComputePipeline,
    gate: ComputePipeline,
    /// Sorting-pass shaders created so far, by variant.
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
        let gate = pipeline(
            dev,
            "permute/pairs_gate",
            &[
                Binding::storage(0, "sort_stats"),
                Binding::storage(1, "pairs_gate"),
            ],
            0,
        )?;
        Ok(Self {
            dev: dev.clone(),
            classify,
            gate,
            sort: PipelineCache::default(),
        })
    }

    /// Records the sorting pass in variant `v` (in place on `seeds`, or retargeted into
    /// `input.retarget`); `input` must hold exactly the buffers `v` binds.
    pub fn sort_seeds(
        &mut self,
        rec: &mut Recorder,
        p: &SortParams,
        v: SortVariant,
        input: &SortInput,
        seeds: &Buffer,
    ) -> Result<()> {
        input.check(v, p.block)?;
        if p.pairs == SORT_PAIRS_FROM_GATE && !(v.pairs && v.skew) {
            return Err(PermuteError::Invalid(format!(
                "sorting pass: {} has no pairs gate to take the pairs from",
                v.shader()
            )));
        }
        if v.cycle && v.sample_keys != (p.cycle_sample_keys != 0) {
            return Err(PermuteError::Invalid(format!(
                "sorting pass: {} with cycle_sample_keys = {}",
                v.shader(),
                p.cycle_sample_keys
            )));
        }
        let mut resources: Vec<(&str, Res)> = vec![
            ("estimate", input.estimate.into()),
            ("mask", input.mask.into()),
            ("seeds", seeds.into()),
        ];
        for ((b, buffer), on) in SORT_OPTIONAL
            .iter()
            .zip(input.optional())
            .zip(optional_flags(v))
        {
            resources.extend(buffer.filter(|_| on).map(|buf| (b.name, buf.into())));
        }
        let area = match v.retarget {
            true => (p.stride, p.padded_height),
            false => (p.width, p.height),
        };
        let groups = block_groups(p, area)?;
        let dev = &self.dev;
        let pipeline = self.sort.get_or_create(v, |v| {
            let optional = SORT_OPTIONAL
                .iter()
                .zip(optional_flags(v))
                .filter(|(_, on)| *on);
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

    /// Records the pairs gate: folds the sort's (skewed, counted) `stats` into the smoothed
    /// share the next frame's sort reads from `gate` (`PairsGate::update` is its twin).
    pub fn pairs_gate(&self, rec: &mut Recorder, stats: &Buffer, gate: &Buffer) -> Result<()> {
        rec.dispatch(
            &self.gate,
            &[("sort_stats", stats.into()), ("pairs_gate", gate.into())],
            &[],
            [1, 1, 1],
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
