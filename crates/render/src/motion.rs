//! Our extensions of the paper's frame loop (docs/algorithm.md, "Extensions"):
//! G-buffer, edge-aware grouping (classes for the sorting pass) and bijective seed
//! reprojection, with the mask offset following the image's mean motion.
use crate::recipe::{FrameRecipe, SortGrid};
use crate::resources::FrameResources;
use crate::{GBufferPass, RenderError, Result, SceneBuffers, SceneImages};
use blueshift_device::{Buffer, Device, MemoryLocation, PassTime, Recorder};
use blueshift_layout::motion::{
    GBufferTexel, HISTORY_MAX_FRAMES, HISTORY_MIN_FRAMES, HistoryParams, MotionParams,
    REPROJECT_NONE,
};
use blueshift_layout::params::TraceParams;
use blueshift_permute::{
    ANCHOR_WRAP, FollowAnchors, HistoryKeys, PermutePasses, Reprojection, Screen, SortParams,
    follow_offset, mask_offset, mean_motion,
};

/// The surfaces on screen: G-buffers (this and the previous frame) and their classes, with the
/// reprojection between them, the history keys, and what the next frame needs to know about
/// this one.
pub(crate) struct Surfaces {
    pass: GBufferPass,
    gbuffers: [Buffer; 2],
    /// Index of the G-buffer the next frame writes.
    next_g: usize,
    /// Surface classes from classify_pixels.
    pub classes: Buffer,
    reprojection: Reprojection,
    /// The previous frame's camera (None after a reset: nothing to reproject from).
    prev: Option<TraceParams>,
    /// The mask offset the previous frame sorted against.
    prev_offset: Option<(u32, u32)>,
    /// The last reprojection's mean motion (pixels), for reports.
    pub last_motion: (i32, i32),
    /// Whether this frame's `src` maps to the previous frame (false on a sequence's first).
    reprojected: bool,
    /// History keys, created when a method first needs them.
    history: Option<HistoryKeys>,
    /// The anchored masks' pass, created when a method first needs it.
    anchors: Option<FollowAnchors>,
    /// The view each G-buffer was made for: a frame whose view a G-buffer already shows
    /// takes it instead of tracing it again.
    gviews: [Option<ViewInputs>; 2],
    /// What the current G-buffer and classes were made from, when no reprojection has
    /// written a G-buffer since: a frame with the same view and blocks reuses both.
    classified: Option<ClassInputs>,
    /// Whether `classes` holds one class per block (all zero), as a moving view leaves it.
    classes_blocks: bool,
    /// What the last reprojection was computed from, and once checked, whether its source
    /// map sends every pixel to itself or nowhere (a still view).
    reprojection_inputs: Option<(ReprojectionInputs, Option<bool>)>,
}

/// The inputs of the reprojection passes besides the seeds: the views of the previous and the
/// current G-buffer (the previous one's is the previous camera, which the passes also read).
/// Equal inputs give the same source map (the `src` buffer, which nothing else writes); if
/// that map sends each pixel to itself or nowhere, the seed permutation is the identity
/// (every pixel wins its own seed, and the holes and the unclaimed pixels are the same list),
/// so a still view skips both passes without changing a bit.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ReprojectionInputs {
    previous: Option<ViewInputs>,
    current: Option<ViewInputs>,
}

/// Everything the `gbuffer` pass reads besides the scene: the camera ray through each pixel
/// centre. Equal inputs give equal outputs (the passes are deterministic), so a still view
/// skips the G-buffer, and with the same block grid the classes, without changing a bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ViewInputs {
    camera: [glam::Vec3; 4],
    view: [glam::Vec2; 2],
}

impl ViewInputs {
    pub fn of(tp: &TraceParams) -> Self {
        Self {
            camera: [tp.cam_origin, tp.cam_forward, tp.cam_right, tp.cam_up],
            view: [tp.view_offset, tp.view_size],
        }
    }
}

/// The inputs of `classify_pixels`: the G-buffer's view and the block grid.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ClassInputs {
    view: ViewInputs,
    /// width, height, block, grid x, grid y
    blocks: [u32; 5],
}

impl ClassInputs {
    fn of(tp: &TraceParams, sort: &SortParams) -> Self {
        Self {
            view: ViewInputs::of(tp),
            blocks: [
                sort.width,
                sort.height,
                sort.block,
                sort.grid_x,
                sort.grid_y,
            ],
        }
    }
}

impl Surfaces {
    pub fn new(dev: &Device, screen: &Screen) -> Result<Self> {
        let pixels = screen.width as u64 * screen.height as u64;
        let g = pixels * size_of::<GBufferTexel>() as u64;
        let gpu = MemoryLocation::GpuOnly;
        Ok(Self {
            pass: GBufferPass::new(dev)?,
            gbuffers: [
                Buffer::new(dev, "frame.gbuffer.a", g, gpu)?,
                Buffer::new(dev, "frame.gbuffer.b", g, gpu)?,
            ],
            next_g: 0,
            classes: Buffer::new(dev, "frame.classes", pixels * 4, gpu)?,
            reprojection: Reprojection::new(dev, screen)?,
            prev: None,
            prev_offset: None,
            last_motion: (0, 0),
            reprojected: false,
            history: None,
            anchors: None,
            gviews: [None; 2],
            classified: None,
            classes_blocks: false,
            reprojection_inputs: None,
        })
    }

    /// Forget the previous frame (sequence restart).
    pub fn reset(&mut self) {
        self.prev = None;
        self.prev_offset = None;
        self.last_motion = (0, 0);
        self.classified = None;
    }

    /// The history means the sorting pass ranks against (history-key methods).
    pub fn history_mean(&self) -> Option<&Buffer> {
        self.history.as_ref().map(|h| &h.mean)
    }

    /// The history keys, once a frame has made them.
    pub fn history_keys(&self) -> Option<&HistoryKeys> {
        self.history.as_ref()
    }

    /// The G-buffer written by the last frame.
    pub fn current_gbuffer(&self) -> &Buffer {
        &self.gbuffers[1 - self.next_g]
    }

    /// The G-buffer of the frame before (the reprojection source).
    pub fn previous_gbuffer(&self) -> &Buffer {
        &self.gbuffers[self.next_g]
    }

    /// The view the previous G-buffer shows, if any.
    pub fn previous_view(&self) -> Option<ViewInputs> {
        self.gviews[self.next_g]
    }

    /// The view the current G-buffer shows, if any.
    pub fn current_view(&self) -> Option<ViewInputs> {
        self.gviews[1 - self.next_g]
    }

    /// Records the `gbuffer` pass for camera `tp` into the next G-buffer, which becomes the
    /// current one; nothing to record when it already shows that view (a still camera).
    pub fn record_gbuffer(
        &mut self,
        rec: &mut Recorder,
        tp: &TraceParams,
        scene: &SceneBuffers,
        images: &SceneImages,
    ) -> Result<()> {
        let (slot, view) = (self.next_g, ViewInputs::of(tp));
        if self.gviews[slot] != Some(view) {
            rec.begin_pass("gbuffer")?;
            self.pass
                .gbuffer(rec, tp, scene, images, &self.gbuffers[slot])?;
            self.gviews[slot] = Some(view);
        }
        self.next_g = 1 - slot;
        self.classified = None;
        Ok(())
    }

    /// Whether the reprojection into the current G-buffer would repeat the last one and that
    /// one moved no seed (see [`ReprojectionInputs`]); otherwise records the inputs of the one
    /// about to run.
    fn reprojection_unchanged(&mut self) -> Result<bool> {
        let inputs = ReprojectionInputs {
            previous: self.gviews[self.next_g],
            current: self.gviews[1 - self.next_g],
        };
        match self.reprojection_inputs {
            Some((last, Some(identity))) if last == inputs => Ok(identity),
            Some((last, None)) if last == inputs => {
                // Read once per still view: the last run's map is still in `src`.
                let src = self.reprojection.src.read::<u32>()?;
                let identity = src
                    .iter()
                    .enumerate()
                    .all(|(q, &s)| s == REPROJECT_NONE || s as usize == q);
                self.reprojection_inputs = Some((inputs, Some(identity)));
                Ok(identity)
            }
            _ => {
                self.reprojection_inputs = Some((inputs, None));
                Ok(false)
            }
        }
    }
}

/// Parameters of the reprojection passes: the camera of the previous frame (`prev`, the
/// push constants it was traced with) and the screen.
pub fn motion_params(prev: &TraceParams, screen: &Screen) -> MotionParams {
    MotionParams {
        cam_origin: prev.cam_origin,
        cam_forward: prev.cam_forward,
        cam_right: prev.cam_right,
        cam_up: prev.cam_up,
        view_offset: prev.view_offset,
        view_size: prev.view_size,
        width: screen.width,
        height: screen.height,
        padded_width: screen.stride(),
        padded_height: screen.padded_height(),
    }
}

/// The renderer's surfaces, which `make_state` made for the recipe.
pub(crate) fn state(slot: &mut Option<Surfaces>) -> Result<&mut Surfaces> {
    slot.as_mut()
        .ok_or_else(|| RenderError::Invalid("the recipe needs surfaces".into()))
}

impl Surfaces {
    /// Records a reprojecting frame's first passes into its open command buffer `rec`: the
    /// G-buffer of camera `tp`, and the seeds of `res` moved along the motion since the
    /// previous frame (into the other seed buffer, which becomes the current one). Returns the
    /// mask offset frame `frame` sorts against on `recipe`'s grid, and the times of the part
    /// of the frame submitted early: a fixed block grid follows the image's mean motion,
    /// which is read back, so there the passes so far run (and are waited for) before the
    /// frame goes on recording. The moving grid needs no read-back, so such a frame is one
    /// submission and the next one is recorded while it runs.
    #[allow(clippy::too_many_arguments)]
    pub fn reproject(
        &mut self,
        rec: &mut Recorder,
        recipe: &FrameRecipe,
        tp: &TraceParams,
        res: &mut FrameResources,
        screen: &Screen,
        (shift, n): ((u32, u32), u32),
        frame: u64,
    ) -> Result<((u32, u32), Vec<PassTime>)> {
        self.record_gbuffer(rec, tp, &res.scene, &res.images)?;
        let reproject = self.prev.is_some();
        // A still view's repeat of an identity reprojection is skipped: the seeds stay where
        // they are, `src` and the motion sums keep the last run's (equal) values.
        let prev = self.prev;
        let run = match prev {
            Some(prev) if !self.reprojection_unchanged()? => Some(prev),
            _ => None,
        };
        if let Some(prev) = &run {
            let mp = motion_params(prev, screen);
            rec.begin_pass("reproject_motion")?;
            let r = &self.reprojection;
            r.reproject_motion(rec, &mp, self.previous_gbuffer(), self.current_gbuffer())?;
            rec.begin_pass("reproject_seeds")?;
            r.reproject_seeds(rec, &mp, res.seeds(), res.other_seeds())?;
            res.swap_seeds();
        }
        self.prev = Some(*tp);
        self.reprojected = reproject;
        if recipe.sort.is_some_and(|s| s.grid == SortGrid::Moving) {
            // The moving grid sorts against the next frame's own mask offset: nothing to follow.
            return Ok((mask_offset(frame, shift, n), Vec::new()));
        }
        let (offset, times) = match self.prev_offset {
            None => ((0, 0), Vec::new()),
            Some(o) => {
                let (motion, times) = if reproject {
                    let times = rec.submit_and_wait()?;
                    rec.begin()?;
                    (mean_motion(self.reprojection.read_motion()?), times)
                } else {
                    ((0, 0), Vec::new())
                };
                self.last_motion = motion;
                (follow_offset(o, shift, motion, n), times)
            }
        };
        self.prev_offset = Some(offset);
        Ok((offset, times))
    }

    /// For history-key methods: records `history_key` on this frame's `estimate` (after the
    /// trace pass, before sorting), against the reprojection's source map.
    pub fn record_history_keys(
        &mut self,
        rec: &mut Recorder,
        dev: &Device,
        screen: &Screen,
        estimate: &Buffer,
    ) -> Result<()> {
        let p = HistoryParams {
            width: screen.width,
            height: screen.height,
            padded_width: screen.stride(),
            has_history: self.reprojected as u32,
            min_frames: HISTORY_MIN_FRAMES,
            max_frames: HISTORY_MAX_FRAMES,
        };
        let h = match &mut self.history {
            Some(h) => h,
            slot @ None => slot.insert(HistoryKeys::new(dev, screen)?),
        };
        rec.begin_pass("history_key")?;
        // This frame's G-buffer (`current_gbuffer`, borrowed field by field): history methods
        // reproject, so `reproject` has written it.
        let gbuffer = &self.gbuffers[1 - self.next_g];
        h.history_key(rec, &p, estimate, &self.reprojection.src, gbuffer)?;
        Ok(())
    }

    /// For edge-aware methods: records the G-buffer of camera `tp` (with `gbuffer`: when the
    /// reprojection did not write it) and the classes the sorting pass with `sort` then reads.
    pub fn classify(
        &mut self,
        rec: &mut Recorder,
        permute: &PermutePasses,
        tp: &TraceParams,
        sort: &SortParams,
        gbuffer: bool,
        res: &FrameResources,
    ) -> Result<()> {
        let inputs = ClassInputs::of(tp, sort);
        if gbuffer {
            if self.classified == Some(inputs) {
                return Ok(()); // a still view: last frame's G-buffer and classes stand
            }
            self.record_gbuffer(rec, tp, &res.scene, &res.images)?;
        }
        rec.begin_pass("classify_pixels")?;
        permute.classify_pixels(rec, sort, self.current_gbuffer(), &self.classes)?;
        self.classes_blocks = false;
        self.classified = gbuffer.then_some(inputs);
        Ok(())
    }

    /// For `grouping=still-surfaces` while the view moves: one class per block (zeroed
    /// classes, written once while they stay so; the sort ranks as `grouping=blocks`) and no
    /// G-buffer.
    pub fn classes_per_block(&mut self, rec: &mut Recorder) -> Result<()> {
        if !self.classes_blocks {
            rec.fill_buffer(&self.classes, 0)?;
            self.classes_blocks = true;
        }
        self.classified = None;
        Ok(())
    }

    /// For anchored masks: records this frame's G-buffer (camera `tp`) and, when the view
    /// changed since the previous frame, `follow_anchors` into the other seed buffer of `res`,
    /// which becomes the current one (the trace reads it).
    pub fn follow_anchors(
        &mut self,
        rec: &mut Recorder,
        dev: &Device,
        tp: &TraceParams,
        screen: &Screen,
        res: &mut FrameResources,
    ) -> Result<()> {
        if ANCHOR_WRAP % tp.mask_size != 0 {
            return Err(RenderError::Invalid(format!(
                "an anchored mask's tile ({}) must divide {ANCHOR_WRAP}",
                tp.mask_size
            )));
        }
        self.record_gbuffer(rec, tp, &res.scene, &res.images)?;
        let moved = self
            .prev
            .filter(|p| ViewInputs::of(p) != ViewInputs::of(tp));
        if let Some(prev) = moved {
            let pass = match &mut self.anchors {
                Some(a) => a,
                slot @ None => slot.insert(FollowAnchors::new(dev)?),
            };
            let mp = motion_params(&prev, screen);
            rec.begin_pass("follow_anchors")?;
            let (prev_g, cur_g) = (&self.gbuffers[self.next_g], &self.gbuffers[1 - self.next_g]);
            pass.follow_anchors(rec, &mp, prev_g, cur_g, res.seeds(), res.other_seeds())?;
            res.swap_seeds();
        }
        self.prev = Some(*tp);
        Ok(())
    }
}
