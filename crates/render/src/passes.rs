//! The pass functions a [`crate::recipe::FrameRecipe`] lists. Each records one pass into
//! `rec`; what it reads and writes is in its signature, and what its shaders declare
//! (`readonly` bindings are read) places the barriers.
use crate::cycle::CycleHistory;
use crate::follow::FollowShift;
use crate::image::ImagePasses;
use crate::motion::Surfaces;
use crate::recipe::{MaskSource, SortGrid, SortPlan};
use crate::resources::FrameResources;
use crate::{MethodAssets, Pairs, RenderError, Result};
use blueshift_device::Recorder;
use blueshift_layout::params::{ImageParams, SORT_PAIRS_FROM_GATE, TraceParams};
use blueshift_permute::{
    CycleInput, PermutePasses, Screen, SortInput, SortParams, add_mask_shift, grid_offset,
    mask_offset, pair_phase, sequence_mask_shift,
};
use blueshift_trace::TracePass;

/// Records the path tracer: the current seeds and mask `mask` into the estimate, the primary
/// flags and the status words. Returns the samples per dispatch it ran.
#[allow(clippy::too_many_arguments)]
pub(crate) fn trace(
    rec: &mut Recorder,
    pass: &mut TracePass,
    res: &FrameResources,
    tp: &TraceParams,
    mask: MaskSource,
    dispatch_vertices: u32,
    loop_stats: bool,
) -> Result<u32> {
    let mask = res.masks.get(mask)?;
    rec.begin_pass("trace")?;
    Ok(pass.trace(
        rec,
        tp,
        &res.scene,
        &res.images,
        res.seeds(),
        mask,
        &res.masks.keys,
        &res.estimate,
        &res.primary_flags,
        &res.trace_status,
        dispatch_vertices,
        loop_stats,
    )?)
}

/// What the sorting pass's parameters depend on besides its plan.
pub(crate) struct SortContext<'a> {
    pub screen: &'a Screen,
    pub assets: &'a MethodAssets,
    /// The frame being recorded.
    pub frame: u64,
    /// Frames in the running mean before this one (the point cycle's keys).
    pub accumulated: u32,
    pub follow: &'a FollowShift,
    /// The sequence, whose mask shift comes on top.
    pub sequence: u32,
}

/// The sorting pass's parameters for this frame: `offset` is the mask offset the frame sorts
/// against (fixed grids); the sequence's mask shift comes on top (`sequence_mask_shift`).
pub(crate) fn sort_params(s: &SortPlan, offset: (u32, u32), c: &SortContext) -> Result<SortParams> {
    let sp = match s.grid {
        SortGrid::Moving => {
            // Sorted for the frame they will be rendered in: the next mask, the next grid.
            let (shift, n) = (c.assets.shift, c.assets.n);
            let next = mask_offset(c.frame + 1, shift, n);
            let grid = grid_offset(c.frame + 1, s.block);
            SortParams {
                pairs: pairs_of(s.pairs),
                phase: pair_phase(c.frame + 1, s.hashed_phase),
                count_skew: u32::from(s.count_skew),
                ..c.screen.sort_params_on_grid(s.block, next, grid)?
            }
        }
        SortGrid::Cycle => {
            // Fixed blocks against the next spatio-temporal slice, the point cycle first.
            let (n, t) = (c.assets.stbn_n, c.assets.stbn_frames);
            let cp = c
                .screen
                .cycle_params(c.frame, n, t, c.accumulated, s.sample_keys);
            // `target=follow`: the volume moves with the image (one frame behind it: a
            // constant lag, which does not matter to a pattern that only has to move along).
            let offset = if s.follow_target {
                c.follow.offset(n)
            } else {
                (0, 0)
            };
            let sp = SortParams {
                mask_size: n,
                ..c.screen.sort_params(s.block, offset)?
            };
            blueshift_permute::with_cycle(sp, &cp)
        }
        SortGrid::Fixed => c.screen.sort_params(s.block, offset)?,
    };
    let shift = sequence_mask_shift(c.sequence);
    let (offset_x, offset_y) = add_mask_shift((sp.offset_x, sp.offset_y), shift, sp.mask_size);
    Ok(SortParams {
        offset_x,
        offset_y,
        ..sp
    })
}

/// `SortParams::pairs` of a sort whose rule is `rule`: 0 none, 1 thin classes, 2 every
/// class; adaptive pairs take what the pairs gate chose from the counts so far, on the GPU.
fn pairs_of(rule: Pairs) -> u32 {
    match rule {
        Pairs::Off => 0,
        Pairs::Thin => 1,
        Pairs::Adaptive => SORT_PAIRS_FROM_GATE,
        Pairs::All => 2,
    }
}

/// Records the sorting pass of plan `s` with parameters `sp` on the current seeds (in place,
/// or retargeted into the other buffer), reading the estimate, the plan's mask and the state
/// its variant binds: the classes and history means of `surfaces`, the point cycle's
/// `cycle` history with the running mean.
pub(crate) fn sort_seeds(
    rec: &mut Recorder,
    permute: &mut PermutePasses,
    res: &FrameResources,
    s: &SortPlan,
    sp: &SortParams,
    surfaces: Option<&Surfaces>,
    cycle: Option<&CycleHistory>,
) -> Result<()> {
    let v = s.variant;
    let missing = |what: &str| RenderError::Invalid(format!("{} without {what}", v.shader()));
    let cycle = match (v.cycle, cycle) {
        (false, _) => None,
        (true, Some(c)) => Some(CycleInput {
            history: &c.history,
            accum: &res.accum,
        }),
        (true, None) => return Err(missing("a cycle history")),
    };
    let input = SortInput {
        classes: v
            .classes
            .then(|| {
                surfaces
                    .map(|st| &st.classes)
                    .ok_or_else(|| missing("classes"))
            })
            .transpose()?,
        history: v
            .history
            .then(|| surfaces.and_then(|st| st.history_mean()))
            .map(|h| h.ok_or_else(|| missing("history keys")))
            .transpose()?,
        stats: v.skew.then_some(&res.sort_stats),
        gate: (v.skew && v.pairs).then_some(&res.pairs_gate),
        retarget: v.retarget.then_some(res.other_seeds()),
        cycle,
        ..SortInput::new(&res.estimate, res.masks.get(s.mask)?)
    };
    rec.begin_pass("sort_seeds")?;
    permute.sort_seeds(rec, sp, v, &input, res.seeds())?;
    Ok(())
}

/// Records the adaptive pairs' gate: the sort's counts into the choice of the next sort.
pub(crate) fn pairs_gate(
    rec: &mut Recorder,
    permute: &PermutePasses,
    res: &FrameResources,
) -> Result<()> {
    rec.begin_pass("pairs_gate")?;
    Ok(permute.pairs_gate(rec, &res.sort_stats, &res.pairs_gate)?)
}

/// Records one step of the running mean: the estimate into the accumulation.
pub(crate) fn accumulate(
    rec: &mut Recorder,
    image: &ImagePasses,
    res: &FrameResources,
    p: &ImageParams,
) -> Result<()> {
    rec.begin_pass("accumulate")?;
    image.accumulate(rec, p, &res.estimate, &res.accum)
}

/// Records the tonemap of the accumulation into the LDR output.
pub(crate) fn tonemap(
    rec: &mut Recorder,
    image: &ImagePasses,
    res: &FrameResources,
    p: &ImageParams,
) -> Result<()> {
    rec.begin_pass("tonemap")?;
    image.tonemap(rec, p, &res.accum, &res.ldr)
}
