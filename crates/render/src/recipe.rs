//! The frame recipe: [`recipe`] turns a configuration's [`Method`] and the view state into
//! everything a frame does: the passes in order (each with its shader variant and the
//! resources it uses), the trace pass's flags and mask mode, and the sorting pass's rules.
//! It is the only place a frame's work reads the method; every rule that depends on whether
//! the view moves is in it. The renderer keeps one recipe per view state
//! ([`Recipes`]), made when the configuration changes.
//!
//! Barriers between the passes come from what each one's shaders declare they read and write
//! (`blueshift_device::Recorder::access`), so only dependent passes wait for each other.
use crate::method::{Grouping, Pairs};
use crate::{Method, RenderConfig};
use blueshift_layout::params::{
    MASK_MODE_2D, MASK_MODE_NONE, MASK_MODE_ROTATE, MASK_MODE_SPATIOTEMPORAL,
    TRACE_FLAG_ADVANCE_INDEX, TRACE_FLAG_DEMODULATE, TRACE_FLAG_MASK_ANCHORED,
    TRACE_FLAG_MASK_DIMS_SHIFT, TRACE_FLAG_NO_JITTER, TRACE_FLAG_SALT_FRAME,
};
use blueshift_permute::SortVariant;
use blueshift_sampling::Sampler;

/// Which mask buffer a pass reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MaskSource {
    /// The N*N blue-noise mask.
    Mask,
    /// The mask packed with the retarget table (`pack_mask_moves`).
    MaskMoves,
    /// The spatio-temporal volume (`stbn`, also sort-cycle's slices).
    Stbn,
    /// The FAST volume.
    Fast,
    /// The motion volume (a moving `sort-cycle`'s mask dimensions).
    Motion,
}

/// The block grid and mask frame the sorting pass ranks against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SortGrid {
    /// Fixed blocks against this frame's mask offset (followed along the motion when
    /// reprojecting).
    Fixed,
    /// The moving grid, against the next frame's mask and grid offsets.
    Moving,
    /// Fixed blocks against the next spatio-temporal slice, after the point cycle.
    Cycle,
}

/// The sorting pass of a recipe: its shader (`variant.shader()`) and its parameters' rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SortPlan {
    pub variant: SortVariant,
    pub mask: MaskSource,
    pub grid: SortGrid,
    pub block: u32,
    /// Which classes rank against antithetic pairs (`SortParams::pairs`).
    pub pairs: Pairs,
    /// The pairs' checkerboard phase is a hash bit of the frame (`permute::pair_phase`).
    pub hashed_phase: bool,
    /// The pass counts skewed classes for the pairs gate (`SortParams::count_skew`).
    pub count_skew: bool,
    /// The point cycle ranks by the seeds' next light sample (`SortParams::cycle_sample_keys`).
    pub sample_keys: bool,
    /// The spatio-temporal target moves with the image (`target=follow`).
    pub follow_target: bool,
}

/// The trace pass's method-dependent push constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TracePlan {
    /// `TRACE_FLAG_*` bits, the mask's dimensions among them.
    pub flags: u32,
    /// `MASK_MODE_*`: which mask and how it moves; the mode alone says which offsets.
    pub mask_mode: u32,
    /// The mask buffer bound.
    pub mask: MaskSource,
    /// The sampler's frame is the phase of the point cycle (the index repeats).
    pub cycle_phase: bool,
    /// The trace reads no seed ([`Method::reads_seeds`]): it runs the `white` sampler, the
    /// cheapest, whose bits the mask replaces as it would the method's own.
    pub no_seeds: bool,
}

/// One pass of the frame's main submission.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Zeroes the trace status words.
    ClearStatus,
    /// The G-buffer and `follow_anchors`: the seeds (anchors) move with their surfaces.
    FollowAnchors,
    /// The path tracer, writing the estimate from the seeds and the trace plan's mask.
    Trace,
    /// `history_key` on this frame's estimate (reads the reprojection's source map).
    HistoryKeys,
    /// Surface classes for the sort (with the G-buffer first unless the reprojection
    /// submission wrote it); a still view reuses the last ones.
    Classify {
        gbuffer: bool,
    },
    /// One class per block (zeroed classes, kept while they stay so): a moving view under
    /// `grouping=still-surfaces`, which traces no G-buffer.
    ClassesPerBlock,
    /// Zeroes the sorting statistics the adaptive pairs count into.
    ClearSortStats,
    /// The sorting pass.
    Sort,
    /// The adaptive pairs' gate: this frame's counts into the choice the next sort reads, on
    /// the GPU (the next frame need not wait for this one).
    PairsGate,
    Accumulate,
    Tonemap,
    /// Copies the status words (and the output frames, when asked) to the frame slot's
    /// readback buffers, read when the slot's fence is next waited for.
    Readback,
}

/// Whether the view moves, as far as a method cares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewState {
    /// The frame sees the scene from the view of the frame before (or is a sequence's first).
    Still,
    /// The frame sees the scene from another view than the frame before.
    Moving,
}

/// What one frame does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FrameRecipe {
    /// A submission of its own before the frame: the G-buffer and the seed reprojection
    /// (its mean motion, read back, sets the frame's mask offset).
    pub reproject: bool,
    /// The main submission's passes, in order.
    pub passes: Vec<Pass>,
    pub trace: TracePlan,
    pub sort: Option<SortPlan>,
    /// G-buffers and classes are needed ([`crate::motion::Surfaces`]).
    pub surfaces: bool,
    /// Sort-cycle's per-phase history is needed.
    pub cycle_history: bool,
    /// The sort writes the other seed buffer, which becomes the current one.
    pub swap_seeds: bool,
    /// The sorting statistics feed the pairs gate, which the next frame's sort reads: that
    /// frame is recorded only once this one is done.
    pub adapts_pairs: bool,
}

/// The recipes of a configuration, one per view state.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Recipes {
    still: FrameRecipe,
    moving: FrameRecipe,
}

impl Recipes {
    /// The recipes of `cfg` in a scene with textures or not (`textured`: whether any pixel
    /// can take the seeds' jitter, [`Method::reads_seeds`]).
    pub fn new(cfg: &RenderConfig, textured: bool) -> Self {
        Self {
            still: recipe(cfg, ViewState::Still, textured),
            moving: recipe(cfg, ViewState::Moving, textured),
        }
    }

    /// The recipe of any view state, for the fields that do not depend on it (state to
    /// make, seed swaps, the pairs gate).
    pub fn base(&self) -> &FrameRecipe {
        &self.still
    }

    /// Every mask buffer a frame of these recipes reads.
    pub fn masks(&self) -> impl Iterator<Item = MaskSource> + '_ {
        [&self.still, &self.moving]
            .into_iter()
            .flat_map(|r| std::iter::once(r.trace.mask).chain(r.sort.map(|s| s.mask)))
    }

    pub fn get(&self, view: ViewState) -> &FrameRecipe {
        match view {
            ViewState::Still => &self.still,
            ViewState::Moving => &self.moving,
        }
    }
}

/// The frame of configuration `cfg` for a view in state `view`, in a scene with textures or
/// not (`textured`).
pub(crate) fn recipe(cfg: &RenderConfig, view: ViewState, textured: bool) -> FrameRecipe {
    let m = cfg.method;
    let moving = view != ViewState::Still;
    let trace = trace_plan(cfg, view, textured);
    // No sort where the trace reads no seed. The point cycle's history then keeps the slots
    // of the last sorted frames: each holds the same seeds per block, so the first still
    // frame's sort permutes them as ever, ranked by older keys for one cycle.
    let reads_seeds = !trace.no_seeds;
    let mut passes = vec![Pass::ClearStatus];
    if m.anchors_mask() {
        passes.push(Pass::FollowAnchors);
    }
    passes.push(Pass::Trace);
    let sort = m.permutation().filter(|_| reads_seeds).map(|p| {
        let block = cfg.effective_block();
        // Under `grouping=still-surfaces` a moving view ranks whole blocks: the variant
        // without classes ranks one class per block exactly as zeroed classes would, and
        // skips a load per pixel.
        let blocks_only = moving && p.grouping == Grouping::StillSurfaces;
        let sample_keys = moving && m.ranks_by_sample_keys(cfg.effective_sampler());
        let variant = SortVariant {
            classes: m.edge_aware() && !blocks_only,
            history: m.history_keys(),
            pairs: p.pairs != Pairs::Off,
            skew: m.adapts_pairs(),
            large: SortVariant::large_for(block),
            retarget: m.retargets(),
            cycle: m.cycles_points(),
            sample_keys,
        };
        let (mask, grid) = if m.cycles_points() {
            (MaskSource::Stbn, SortGrid::Cycle)
        } else if m.retargets() {
            (MaskSource::MaskMoves, SortGrid::Fixed)
        } else if m.shifts_grid() {
            (MaskSource::Mask, SortGrid::Moving)
        } else {
            (MaskSource::Mask, SortGrid::Fixed)
        };
        if m.history_keys() {
            passes.push(Pass::HistoryKeys);
        }
        if blocks_only {
            passes.push(Pass::ClassesPerBlock);
        } else if m.edge_aware() {
            passes.push(Pass::Classify {
                gbuffer: !m.reprojects(),
            });
        }
        if m.adapts_pairs() {
            passes.push(Pass::ClearSortStats);
        }
        passes.push(Pass::Sort);
        if m.adapts_pairs() {
            passes.push(Pass::PairsGate);
        }
        SortPlan {
            variant,
            mask,
            grid,
            block,
            pairs: p.pairs,
            hashed_phase: m.hashes_pair_phase(),
            count_skew: m.adapts_pairs(),
            sample_keys,
            follow_target: m.follows_target(),
        }
    });
    passes.extend([Pass::Accumulate, Pass::Tonemap, Pass::Readback]);
    FrameRecipe {
        reproject: m.reprojects(),
        passes,
        trace,
        sort,
        surfaces: m.reprojects() || m.edge_aware() || m.anchors_mask(),
        cycle_history: m.cycles_points(),
        swap_seeds: m.retargets(),
        adapts_pairs: m.adapts_pairs(),
    }
}

/// The trace pass's flags, mask mode and mask for configuration `cfg`, view state `view` and
/// a scene with textures or not.
fn trace_plan(cfg: &RenderConfig, view: ViewState, textured: bool) -> TracePlan {
    let m = cfg.method;
    let moving = view != ViewState::Still;
    let no_seeds = !m.reads_seeds(view, cfg.bounces, textured);
    if m.volume_vertex(view, cfg.bounces, textured) {
        use blueshift_layout::params::{MASK_DIMS, TRACE_FLAG_RECORD_PRIMARY};
        return TracePlan {
            flags: method_flags(cfg)
                | ((1 << MASK_DIMS) - 1) << TRACE_FLAG_MASK_DIMS_SHIFT
                | TRACE_FLAG_RECORD_PRIMARY,
            mask_mode: MASK_MODE_SPATIOTEMPORAL,
            mask: MaskSource::Stbn,
            cycle_phase: m.cycles_points(),
            no_seeds,
        };
    }
    let dims = m.mask_dims(moving);
    let motion_volume = m.motion_volume(view, cfg.bounces, textured);
    let mask_mode = if motion_volume {
        MASK_MODE_SPATIOTEMPORAL
    } else if dims != 0 {
        // Shifted while moving, rotated while still: see `MaskDims::Jitter`.
        if moving {
            MASK_MODE_2D
        } else {
            MASK_MODE_ROTATE
        }
    } else {
        match m.mask_method() {
            Method::MaskR2 => MASK_MODE_2D,
            Method::MaskRot => MASK_MODE_ROTATE,
            Method::Stbn | Method::Fast => MASK_MODE_SPATIOTEMPORAL,
            _ => MASK_MODE_NONE,
        }
    };
    let mask = match m.mask_method() {
        _ if motion_volume => MaskSource::Motion,
        Method::Stbn => MaskSource::Stbn,
        Method::Fast => MaskSource::Fast,
        _ => MaskSource::Mask,
    };
    // Without seeds the deeper vertices take the white sampler's bits, salted by the frame
    // (the cycle's index repeats).
    let salt = if no_seeds { TRACE_FLAG_SALT_FRAME } else { 0 };
    TracePlan {
        flags: method_flags(cfg)
            | dims << TRACE_FLAG_MASK_DIMS_SHIFT
            | m.jitter_flags(moving)
            | salt,
        mask_mode,
        mask,
        cycle_phase: m.cycles_points(),
        no_seeds,
    }
}

/// The trace pass's flags that do not depend on the view.
fn method_flags(c: &RenderConfig) -> u32 {
    let m = c.method;
    let mut flags = 0;
    // The mask methods drive only the first MASK_DIMS dimensions: the rest are fresh white
    // noise every frame, as `white`'s (unsalted, a pixel would repeat its deeper bounces'
    // directions every frame, and its average would never converge). Behind `mask-rot`'s
    // rotating mask a progressive sampler (Sobol, its default) runs on instead, index advancing
    // per frame, keyed by the pixel (anchored: by the anchor's cell), so a pixel's (a surface
    // point's) deeper dimensions converge like its mask dimensions.
    let sequence_rest =
        m.mask_method() == Method::MaskRot && c.effective_sampler() == Sampler::Sobol;
    let white_rest = matches!(
        m.mask_method(),
        Method::White | Method::MaskR2 | Method::MaskRot | Method::Stbn | Method::Fast
    ) && !sequence_rest;
    if white_rest || c.frame_salt {
        flags |= TRACE_FLAG_SALT_FRAME;
    }
    if m.advances_index() || sequence_rest {
        flags |= TRACE_FLAG_ADVANCE_INDEX;
    }
    if c.no_jitter {
        flags |= TRACE_FLAG_NO_JITTER;
    }
    if m.demodulates() {
        flags |= TRACE_FLAG_DEMODULATE;
    }
    if m.anchors_mask() {
        flags |= TRACE_FLAG_MASK_ANCHORED;
    }
    flags
}

#[cfg(test)]
#[path = "recipe_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "recipe_volume_tests.rs"]
mod volume_tests;
