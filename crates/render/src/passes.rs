//! The pass functions a [`crate::recipe::FrameRecipe`] lists: each records one pass into the
//! frame slot's command buffer. What a pass reads and writes is what its shaders declare
//! (`readonly` bindings are read), from which the recorder places the barriers.
use crate::recipe::{FrameRecipe, MaskSource, Pass, SortGrid, SortPlan};
use crate::{Accumulation, RenderError, Renderer, Result, trace_params};
use blueshift_device::{Buffer, Device};
use blueshift_layout::params::{ImageParams, TraceParams};
use blueshift_permute::{
    CycleInput, SortInput, SortParams, add_mask_shift, grid_offset, mask_offset, pair_phase,
    sequence_mask_shift,
};

impl Renderer {
    /// Records `pass` of the frame `recipe` describes, traced with `tp`, sorting with `sort`'s
    /// plan and parameters.
    pub(crate) fn record_pass(
        &mut self,
        pass: Pass,
        recipe: &FrameRecipe,
        tp: &TraceParams,
        sort: Option<&(SortPlan, SortParams)>,
    ) -> Result<()> {
        let sort = || sort.ok_or_else(|| RenderError::Invalid("sort pass without params".into()));
        match pass {
            Pass::ClearStatus => Ok(self.slots[self.slot]
                .rec
                .fill_buffer(&self.trace_status, 0)?),
            Pass::FollowAnchors => self.record_anchors(tp),
            Pass::Trace => self.trace_pass(tp, recipe.trace.mask),
            Pass::HistoryKeys => self.record_history_keys(),
            Pass::Classify { gbuffer } => self.record_classes(tp, &sort()?.1, gbuffer),
            Pass::ClassesPerBlock => self.record_classes_per_block(),
            Pass::ClearSortStats if sort()?.1.count_skew != 0 => {
                Ok(self.slots[self.slot].rec.fill_buffer(&self.sort_stats, 0)?)
            }
            Pass::ClearSortStats => Ok(()),
            Pass::Sort => {
                let (plan, params) = sort()?;
                self.sort_pass(plan, params)
            }
            Pass::Accumulate if self.cfg.accumulation != Accumulation::Mean => {
                self.record_accumulation(tp)
            }
            Pass::Accumulate | Pass::Tonemap => self.image_pass(pass),
            Pass::Readback => self.record_readback(),
        }
    }

    fn trace_pass(&mut self, tp: &TraceParams, mask: MaskSource) -> Result<()> {
        let slot = self.slot;
        let rec = &mut self.slots[slot].rec;
        let mask = self.masks.get(mask)?;
        rec.begin_pass("trace")?;
        self.per_dispatch = self.trace.trace(
            rec,
            tp,
            &self.scene,
            &self.images,
            &self.seeds[self.current],
            mask,
            &self.masks.keys,
            &self.estimate,
            &self.primary_flags,
            &self.trace_status,
            self.dispatch_vertices,
            self.cfg.loop_stats,
        )?;
        Ok(())
    }

    /// The sorting pass's parameters for this frame: `offset` is the mask offset the frame
    /// sorts against (fixed grids). The sequence's mask shift comes on top
    /// (`sequence_mask_shift`).
    pub(crate) fn sort_params(&self, s: &SortPlan, offset: (u32, u32)) -> Result<SortParams> {
        let sp = self.sort_params_unshifted(s, offset)?;
        let shift = sequence_mask_shift(self.cfg.sequence);
        let (offset_x, offset_y) = add_mask_shift((sp.offset_x, sp.offset_y), shift, sp.mask_size);
        Ok(SortParams {
            offset_x,
            offset_y,
            ..sp
        })
    }

    fn sort_params_unshifted(&self, s: &SortPlan, offset: (u32, u32)) -> Result<SortParams> {
        Ok(match s.grid {
            SortGrid::Moving => {
                // Sorted for the frame they will be rendered in: the next mask, the next grid.
                let (shift, n) = (self.assets.shift, self.assets.n);
                let next = mask_offset(self.frame + 1, shift, n);
                let grid = grid_offset(self.frame + 1, s.block);
                SortParams {
                    pairs: self.pairs_gate.pairs_of(s.pairs),
                    phase: pair_phase(self.frame + 1, s.hashed_phase),
                    count_skew: u32::from(s.count_skew),
                    ..self.screen.sort_params_on_grid(s.block, next, grid)?
                }
            }
            SortGrid::Cycle => {
                // Fixed blocks against the next spatio-temporal slice, the point cycle first.
                let (n, t) = (self.assets.stbn_n, self.assets.stbn_frames);
                let cp =
                    self.screen
                        .cycle_params(self.frame, n, t, self.accumulated, s.sample_keys);
                // `target=follow`: the volume moves with the image (one frame behind it: a
                // constant lag, which does not matter to a pattern that only has to move along).
                let offset = if s.follow_target {
                    self.follow.offset(n)
                } else {
                    (0, 0)
                };
                let sp = SortParams {
                    mask_size: n,
                    cycle_shade_edges: u32::from(s.shade_edges),
                    ..self.screen.sort_params(s.block, offset)?
                };
                blueshift_permute::with_cycle(sp, &cp)
            }
            SortGrid::Fixed => self.screen.sort_params(s.block, offset)?,
        })
    }

    fn sort_pass(&mut self, s: &SortPlan, sp: &SortParams) -> Result<()> {
        let surfaces = self.surfaces.as_ref();
        let v = s.variant;
        let missing = |what: &str| RenderError::Invalid(format!("{} without {what}", v.shader()));
        let cycle = match (v.cycle, &self.cycle) {
            (false, _) => None,
            (true, Some(c)) => Some(CycleInput {
                history: &c.history,
                accum: &self.accum,
                flags: &self.primary_flags,
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
            stats: v.skew.then_some(&self.sort_stats),
            retarget: v.retarget.then_some(&self.seeds[1 - self.current]),
            cycle,
            ..SortInput::new(&self.estimate, self.masks.get(s.mask)?)
        };
        let rec = &mut self.slots[self.slot].rec;
        rec.begin_pass("sort_seeds")?;
        let seeds = &self.seeds[self.current];
        self.permute.sort_seeds(rec, sp, v, &input, seeds)?;
        Ok(())
    }

    pub(crate) fn image_pass(&mut self, pass: Pass) -> Result<()> {
        let img = ImageParams {
            width: self.cfg.width,
            height: self.cfg.height,
            count: self.accumulated,
            exposure: self.cfg.exposure,
        };
        let rec = &mut self.slots[self.slot].rec;
        if pass == Pass::Accumulate {
            rec.begin_pass("accumulate")?;
            self.image
                .accumulate(rec, &img, &self.estimate, &self.accum)
        } else {
            rec.begin_pass("tonemap")?;
            self.image.tonemap(rec, &img, &self.accum, &self.ldr)
        }
    }
}

/// The method's read-only inputs on the device: masks, volumes and key tables.
pub(crate) struct Masks {
    pub mask: Buffer,
    /// The HBO+19 key table for the current spp (GPU layout of `KeyTable::gpu_words`).
    pub keys: Buffer,
    pub keys_spp: Option<u32>,
    pub stbn: Buffer,
    /// The FAST mask, when the asset exists.
    pub fast: Option<Buffer>,
    /// The mask packed with the retarget table (`pack_mask_moves`), for sorting that
    /// retargets.
    pub mask_moves: Buffer,
}

impl Masks {
    /// Uploads the assets' masks and the key table `keys` (for `keys_spp`).
    pub fn new(
        dev: &Device,
        assets: &crate::MethodAssets,
        keys: &[[u32; 2]],
        keys_spp: Option<u32>,
    ) -> Result<Self> {
        let moves = blueshift_permute::pack_mask_moves(&assets.mask, &assets.table)?;
        Ok(Self {
            mask: Buffer::upload(dev, "assets.mask", &assets.mask)?,
            keys: Buffer::upload(dev, "assets.hbo19_keys", keys)?,
            keys_spp,
            stbn: Buffer::upload(dev, "assets.stbn", &assets.stbn)?,
            fast: match assets.fast.is_empty() {
                true => None,
                false => Some(Buffer::upload(dev, "assets.fast", &assets.fast)?),
            },
            mask_moves: Buffer::upload(dev, "assets.mask_moves", &moves)?,
        })
    }

    /// The mask buffer `m` names.
    pub fn get(&self, m: MaskSource) -> Result<&Buffer> {
        Ok(match m {
            MaskSource::Mask => &self.mask,
            MaskSource::MaskMoves => &self.mask_moves,
            MaskSource::Stbn => &self.stbn,
            MaskSource::Fast => self.fast.as_ref().ok_or_else(trace_params::no_fast)?,
        })
    }
}
