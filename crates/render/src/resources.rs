//! What the passes of a frame work with: the device buffers ([`FrameResources`]) and the
//! pipelines ([`Pipelines`]). Pass functions take them as arguments, so each one's inputs and
//! outputs are in its signature.
use crate::Result;
use crate::recipe::MaskSource;
use crate::trace_params;
use blueshift_device::{Buffer, Device};
use blueshift_permute::PermutePasses;
use blueshift_trace::{SceneBuffers, SceneImages, TracePass};

use crate::image::ImagePasses;

/// The buffers a frame's passes read and write (per-method state aside: G-buffers, classes,
/// histories live with the state that makes them).
pub(crate) struct FrameResources {
    pub scene: SceneBuffers,
    pub images: SceneImages,
    /// The two seed buffers: the sort retargets and the reprojection moves from one into the
    /// other.
    pub seeds: [Buffer; 2],
    /// Which of `seeds` holds the current seeds.
    pub current: usize,
    pub estimate: Buffer,
    /// `PRIMARY_*` bits of each pixel's latest primary hit (the trace pass's mask variants
    /// write them with `TRACE_FLAG_RECORD_PRIMARY` and read them with
    /// `TRACE_FLAG_SEED_JITTER_ON_TEXTURES`); zero after a reset.
    pub primary_flags: Buffer,
    pub trace_status: Buffer,
    pub accum: Buffer,
    pub ldr: Buffer,
    pub masks: Masks,
    /// (skewed classes, classes counted) of the last sorting pass (`SortInput::stats`).
    pub sort_stats: Buffer,
    /// The adaptive pairs' gate (`PairsGate::words`): the `pairs_gate` pass updates it after
    /// each sort, the next sort reads it; zero for a new sequence.
    pub pairs_gate: Buffer,
}

impl FrameResources {
    /// The current seed buffer.
    pub fn seeds(&self) -> &Buffer {
        &self.seeds[self.current]
    }

    /// The other seed buffer, which a pass that moves the seeds writes.
    pub fn other_seeds(&self) -> &Buffer {
        &self.seeds[1 - self.current]
    }

    /// Makes the other seed buffer the current one.
    pub fn swap_seeds(&mut self) {
        self.current = 1 - self.current;
    }
}

/// The pipelines of the passes every method may record.
pub(crate) struct Pipelines {
    pub trace: TracePass,
    pub image: ImagePasses,
    pub permute: PermutePasses,
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
    /// The motion volume, when the asset exists.
    pub motion: Option<Buffer>,
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
            motion: match assets.motion.is_empty() {
                true => None,
                false => Some(Buffer::upload(dev, "assets.motion", &assets.motion)?),
            },
            mask_moves: Buffer::upload(dev, "assets.mask_moves", &moves)?,
        })
    }

    /// Fails unless every mask the recipes read is here (an optional asset may be missing):
    /// at creation, not at the first frame that reads it.
    pub fn check(&self, recipes: &crate::recipe::Recipes) -> Result<()> {
        recipes.masks().try_for_each(|m| self.get(m).map(|_| ()))
    }

    /// The mask buffer `m` names.
    pub fn get(&self, m: MaskSource) -> Result<&Buffer> {
        Ok(match m {
            MaskSource::Mask => &self.mask,
            MaskSource::MaskMoves => &self.mask_moves,
            MaskSource::Stbn => &self.stbn,
            MaskSource::Fast => self.fast.as_ref().ok_or_else(trace_params::no_fast)?,
            MaskSource::Motion => self.motion.as_ref().ok_or_else(trace_params::no_motion)?,
        })
    }
}
