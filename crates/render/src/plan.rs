//! The frame as a plan: a [`Method`] (with the block size) decoded once into the passes a
//! frame records, in order, with each pass's shader variant and the resources it uses. The
//! renderer executes the list; no pass works out from the buffers it is handed what to do.
//!
//! Barriers between the passes come from what each one's shaders declare they read and write
//! (`blueshift_device::Recorder::access`), so only dependent passes wait for each other.
use crate::Method;
use crate::method::Pairs;
use blueshift_permute::SortVariant;

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

/// The sorting pass of a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SortPlan {
    pub variant: SortVariant,
    pub mask: MaskSource,
    pub grid: SortGrid,
    pub block: u32,
}

/// One pass of the frame's main submission.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Zeroes the trace status words.
    ClearStatus,
    /// The G-buffer and `follow_anchors`: the seeds (anchors) move with their surfaces.
    FollowAnchors,
    /// The path tracer, writing the estimate from the seeds and `mask`.
    Trace {
        mask: MaskSource,
    },
    /// `history_key` on this frame's estimate (reads the reprojection's source map).
    HistoryKeys,
    /// Surface classes for the sort (with the G-buffer first unless the reprojection
    /// submission wrote it); a still view reuses the last ones. With `still_only`, a frame
    /// whose view moved since the previous one takes one class per block instead.
    Classify {
        gbuffer: bool,
        still_only: bool,
    },
    /// Zeroes the sorting statistics the adaptive pairs count into.
    ClearSortStats,
    /// The sorting pass.
    Sort(SortPlan),
    Accumulate,
    Tonemap,
    /// Copies the status words (and the output frames, when asked) to the frame slot's
    /// readback buffers, read when the slot's fence is next waited for.
    Readback,
}

/// What one frame does, decoded from the method once per configuration.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FramePlan {
    /// A submission of its own before the frame: the G-buffer and the seed reprojection
    /// (its mean motion, read back, sets the frame's mask offset).
    pub reproject: bool,
    /// The main submission's passes, in order.
    pub passes: Vec<Pass>,
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

impl FramePlan {
    /// Decodes `method` with the paper's block size `block`.
    pub fn new(method: Method, block: u32) -> Self {
        let m = method;
        let trace_mask = match m.mask_method() {
            Method::Stbn => MaskSource::Stbn,
            Method::Fast => MaskSource::Fast,
            _ => MaskSource::Mask,
        };
        let mut passes = vec![Pass::ClearStatus];
        if m.anchors_mask() {
            passes.push(Pass::FollowAnchors);
        }
        passes.push(Pass::Trace { mask: trace_mask });
        if m.sorts() {
            let block = m.block(block);
            let variant = SortVariant {
                classes: m.edge_aware(),
                history: m.history_keys(),
                pairs: m.permutation().is_some_and(|p| p.pairs != Pairs::Off),
                skew: m.adapts_pairs(),
                large: SortVariant::large_for(block),
                retarget: m.retargets(),
                cycle: m.cycles_points(),
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
            if m.edge_aware() {
                passes.push(Pass::Classify {
                    gbuffer: !m.reprojects(),
                    still_only: m.classifies_still_only(),
                });
            }
            if m.adapts_pairs() {
                passes.push(Pass::ClearSortStats);
            }
            passes.push(Pass::Sort(SortPlan {
                variant,
                mask,
                grid,
                block,
            }));
        }
        passes.extend([Pass::Accumulate, Pass::Tonemap, Pass::Readback]);
        Self {
            reproject: m.reprojects(),
            passes,
            surfaces: m.reprojects() || m.edge_aware() || m.anchors_mask(),
            cycle_history: m.cycles_points(),
            swap_seeds: m.retargets(),
            adapts_pairs: m.adapts_pairs(),
        }
    }

    /// The sorting pass, if the plan sorts.
    pub fn sort(&self) -> Option<SortPlan> {
        self.passes.iter().find_map(|p| match p {
            Pass::Sort(s) => Some(*s),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every preset decodes to a plan whose sort variant is a compiled shader, whose passes
    /// come in dependency order, and whose classes exist exactly when the sort reads them.
    #[test]
    fn every_preset_decodes_to_a_consistent_plan() {
        for (name, m) in Method::PRESETS {
            for block in [2, 4, 8] {
                let plan = FramePlan::new(m, block);
                let at = |p: fn(&Pass) -> bool| plan.passes.iter().position(p);
                let trace = at(|p| matches!(p, Pass::Trace { .. }));
                let tonemap = at(|p| *p == Pass::Tonemap);
                assert!(trace < tonemap, "{name}");
                match plan.sort() {
                    None => assert!(!m.sorts(), "{name}"),
                    Some(s) => {
                        assert!(SortVariant::all().contains(&s.variant), "{name}: {s:?}");
                        let sort = at(|p| matches!(p, Pass::Sort(_)));
                        let classify = at(|p| matches!(p, Pass::Classify { .. }));
                        assert_eq!(classify.is_some(), s.variant.classes, "{name}");
                        assert!(classify < sort && trace < sort, "{name}");
                        assert_eq!(s.variant.retarget, plan.swap_seeds, "{name}");
                        assert!(!s.variant.classes || plan.surfaces, "{name}");
                    }
                }
            }
        }
    }
}
