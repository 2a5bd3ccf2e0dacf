//! Recording a frame: the recipe of the frame's view state walked pass by pass, each pass a
//! function ([`crate::passes`], the state types' own) handed the resources it works on.
use crate::motion::{Surfaces, motion_params, state};
use crate::passes::{self, SortContext};
use crate::recipe::{FrameRecipe, Pass, SortPlan, ViewState};
use crate::taa_pass::{MEAN_FRAMES_AFTER_TAA, Step, TaaPass};
use crate::trace_params::TraceInputs;
use crate::{Accumulation, Completed, FRAMES_IN_FLIGHT, RenderError, Renderer, Result, cycle};
use blueshift_device::PassTime;
use blueshift_layout::params::{ImageParams, TraceParams};
use blueshift_permute::{SortParams, mask_offset};

impl Renderer {
    /// The path tracer's push constants for the next frame (camera, view window, method).
    pub fn trace_params(&self) -> TraceParams {
        crate::trace_params::trace_params(
            &self.recipes.get(self.view_state()).trace,
            &self.trace_inputs(),
        )
    }

    fn trace_inputs(&self) -> TraceInputs<'_> {
        TraceInputs {
            cfg: &self.cfg,
            screen: &self.screen,
            assets: &self.assets,
            camera: &self.camera,
            view_offset: self.view_offset,
            frame: self.frame,
        }
    }

    /// The view state of the next frame.
    pub(crate) fn view_state(&self) -> ViewState {
        if self.moving() {
            ViewState::Moving
        } else {
            ViewState::Still
        }
    }

    /// Records the next frame as its recipe says and submits it without waiting; returns the
    /// frames that had to be finished first (the one whose slot it takes, and the one before
    /// it when this frame depends on what that one read back).
    pub fn submit_frame(&mut self) -> Result<Vec<Completed>> {
        let mut done: Vec<Completed> = self.complete_slot(self.slot)?.into_iter().collect();
        if self.needs_previous() {
            let previous = (self.slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
            done.extend(self.complete_slot(previous)?);
        }
        self.make_state()?;
        let recipe = self.recipes.get(self.view_state()).clone();
        let tp = crate::trace_params::trace_params(&recipe.trace, &self.trace_inputs());
        if recipe.sort.is_some_and(|s| s.follow_target) {
            self.follow.update(&motion_params(&tp, &self.screen));
        }
        self.view_changed = false;
        self.slots[self.slot].rec.begin()?;
        let (offset, times) = self.reproject(&recipe, &tp)?;
        let sort = match &recipe.sort {
            Some(s) => {
                let context = SortContext {
                    screen: &self.screen,
                    assets: &self.assets,
                    frame: self.frame,
                    accumulated: self.accumulated,
                    follow: &self.follow,
                    sequence: self.cfg.sequence,
                };
                Some((*s, passes::sort_params(s, offset, &context)?))
            }
            None => None,
        };
        for pass in &recipe.passes {
            self.record_pass(*pass, &recipe, &tp, sort.as_ref())?;
        }
        self.submit_slot(self.frame, times)?;
        if recipe.swap_seeds {
            self.res.swap_seeds();
        }
        self.frame += 1;
        self.accumulated = self.accumulated.saturating_add(1);
        Ok(done)
    }

    /// Makes the state the recipes need and no earlier frame made: G-buffers and classes,
    /// the point cycle's history, and the `taa` pass when the accumulation follows the motion.
    fn make_state(&mut self) -> Result<()> {
        let r = self.recipes.base();
        let taa = self.cfg.accumulation != Accumulation::Mean;
        if (r.surfaces || taa) && self.surfaces.is_none() {
            self.surfaces = Some(Surfaces::new(&self.dev, &self.screen)?);
        }
        if r.cycle_history && self.cycle.is_none() {
            self.cycle = Some(cycle::CycleHistory::new(&self.dev, &self.screen)?);
        }
        if taa && self.taa.is_none() {
            let pixels = self.cfg.width as u64 * self.cfg.height as u64;
            self.taa = Some(TaaPass::new(&self.dev, pixels)?);
        }
        Ok(())
    }

    /// The mask offset the frame sorts against, after the reprojection a reprojecting recipe
    /// records first (with the times of a part of the frame submitted early).
    fn reproject(
        &mut self,
        recipe: &FrameRecipe,
        tp: &TraceParams,
    ) -> Result<((u32, u32), Vec<PassTime>)> {
        let (shift, n) = (self.assets.shift, self.assets.n);
        if !recipe.reproject {
            return Ok((mask_offset(self.frame, shift, n), Vec::new()));
        }
        let rec = &mut self.slots[self.slot].rec;
        state(&mut self.surfaces)?.reproject(
            rec,
            recipe,
            tp,
            &mut self.res,
            &self.screen,
            (shift, n),
            self.frame,
        )
    }

    /// Records `pass` of the frame `recipe` describes, traced with `tp`, sorting with `sort`'s
    /// plan and parameters.
    fn record_pass(
        &mut self,
        pass: Pass,
        recipe: &FrameRecipe,
        tp: &TraceParams,
        sort: Option<&(SortPlan, SortParams)>,
    ) -> Result<()> {
        let sort = || sort.ok_or_else(|| RenderError::Invalid("sort pass without params".into()));
        let image = |count: u32| ImageParams {
            width: self.cfg.width,
            height: self.cfg.height,
            count,
            exposure: self.cfg.exposure,
        };
        let rec = &mut self.slots[self.slot].rec;
        let res = &mut self.res;
        match pass {
            Pass::ClearStatus => rec.fill_buffer(&res.trace_status, 0)?,
            Pass::FollowAnchors => {
                state(&mut self.surfaces)?.follow_anchors(rec, &self.dev, tp, &self.screen, res)?
            }
            Pass::Trace => {
                self.per_dispatch = passes::trace(
                    rec,
                    &mut self.passes.trace,
                    res,
                    tp,
                    recipe.trace.mask,
                    self.dispatch_vertices,
                    self.cfg.loop_stats,
                )?
            }
            Pass::HistoryKeys => state(&mut self.surfaces)?.record_history_keys(
                rec,
                &self.dev,
                &self.screen,
                &res.estimate,
            )?,
            Pass::Classify { gbuffer } => state(&mut self.surfaces)?.classify(
                rec,
                &self.passes.permute,
                tp,
                &sort()?.1,
                gbuffer,
                res,
            )?,
            Pass::ClassesPerBlock => state(&mut self.surfaces)?.classes_per_block(rec)?,
            Pass::ClearSortStats if sort()?.1.count_skew != 0 => {
                rec.fill_buffer(&res.sort_stats, 0)?
            }
            Pass::ClearSortStats => {}
            Pass::Sort => {
                let (plan, params) = sort()?;
                passes::sort_seeds(
                    rec,
                    &mut self.passes.permute,
                    res,
                    plan,
                    params,
                    self.surfaces.as_ref(),
                    self.cycle.as_ref(),
                )?
            }
            Pass::PairsGate => passes::pairs_gate(rec, &self.passes.permute, res)?,
            Pass::Accumulate if self.cfg.accumulation != Accumulation::Mean => {
                let missing = || RenderError::Invalid("taa pass without its state".into());
                let st = self.surfaces.as_mut().ok_or_else(missing)?;
                let taa = self.taa.as_mut().ok_or_else(missing)?;
                let mode = self.cfg.accumulation;
                match taa.step(rec, st, res, tp, self.accumulated, mode)? {
                    Step::Restart => {
                        self.accumulated = 0;
                        passes::accumulate(rec, &self.passes.image, res, &image(0))?
                    }
                    Step::Mean => {
                        passes::accumulate(rec, &self.passes.image, res, &image(self.accumulated))?
                    }
                    Step::Taa { camera, still } => {
                        taa.record(rec, st, res, &self.screen, &camera, still)?;
                        // submit_frame counts this frame after its passes.
                        self.accumulated = MEAN_FRAMES_AFTER_TAA - 1;
                    }
                }
            }
            Pass::Accumulate => {
                passes::accumulate(rec, &self.passes.image, res, &image(self.accumulated))?
            }
            Pass::Tonemap => {
                passes::tonemap(rec, &self.passes.image, res, &image(self.accumulated))?
            }
            Pass::Readback => self.record_readback()?,
        }
        Ok(())
    }
}
