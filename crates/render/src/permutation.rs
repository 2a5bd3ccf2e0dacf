//! The fields of a seed-permutation method ([`Permutation`]): each gates its own passes and
//! shader code; `crate::method_spec` spells them out and checks their combinations.
/// What the sorting pass ranks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Key {
    /// Luminance of the raw estimate (the paper).
    Raw,
    /// Luminance over the primary hit's base colour: the light a seed gathered, not its
    /// product with the texture, so textures do not scramble the ranks.
    Demodulated,
    /// The demodulated key minus its surface's mean over earlier frames (`permute/history_key`):
    /// an estimate of the seed's error rather than of the image.
    History,
}

/// Which pixels of a block rank together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Grouping {
    /// The whole block (the paper).
    Blocks,
    /// Each surface of the block (G-buffer classes, `permute/classify_pixels`).
    Surfaces,
    /// Surfaces while the view stands still, the whole block while it moves: the classes need
    /// a pixel-centre G-buffer, which a still view traces once but a moving one every frame
    /// (most of the passes' cost under motion), and under motion they gain little.
    StillSurfaces,
}

/// How seeds reach the next frame's mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Transport {
    /// They do not: the sorting pass alone.
    None,
    /// The precomputed retarget table carries mask frame t onto t + 1 (the paper).
    Retarget,
    /// No table: each frame sorts [`crate::GRID_BLOCK`]-sized blocks against the next frame's mask, on
    /// a block grid that moves every frame (`permute::grid_offset`).
    Grid,
}

/// Whether seeds follow the image between frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Seeds stay on the screen (the paper).
    None,
    /// Seeds follow their surface: a bijective reprojection along the G-buffer's motion.
    Reproject,
}

/// Which classes rank against antithetic pairs instead of the mask (`SortParams::pairs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pairs {
    Off,
    /// Classes at most 2 px wide or tall, where the mask restricted to a strip is not blue.
    Thin,
    /// Every class while the sorting keys are about symmetric, none while many classes are
    /// heavy-tailed ([`crate::PairsGate`], from the sorting pass's counts).
    Adaptive,
    /// Every class, always (experiments: the error becomes a checkerboard with mask-ordered
    /// magnitudes where keys are heavy-tailed).
    All,
}

/// Which sample points a seed stands for over frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Points {
    /// The same point every frame (the paper): the estimate a seed gave predicts its next one
    /// exactly, but a neighbourhood keeps the same population of errors, which neither a blur
    /// nor an accumulation removes.
    Fixed,
    /// Block-net points (`Sampler::BlockNet`: a block's seeds share one scrambled Sobol
    /// sequence, so at every index they hold a 64-point net) with the index cycling through
    /// `CYCLE_FRAMES` values (the sorting pass's point cycle); seeds stay in their
    /// [`crate::GRID_BLOCK`]-sized block and rank by the key they gave one cycle earlier, against
    /// spatio-temporal mask slices. The block's mean error is small in every frame, its
    /// arrangement is blue, and the arrangement changes every frame, so a temporal filter
    /// averages it out.
    Cycle,
}

/// Which sample dimensions the void-and-cluster mask drives instead of the seed's sampler
/// (the rest stay the seed's, so the sort still arranges them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MaskDims {
    /// None: the seeds carry every dimension.
    None,
    /// The camera jitter: a seed's coverage of an edge is a property of the pixel it lands on,
    /// not of the seed, so no key predicts it; the mask makes it blue instead. While the view
    /// stands still its values turn along a Sobol (0,2)-sequence on untextured pixels
    /// (`TRACE_FLAG_SOBOL_JITTER`) and along R2 on textured ones, so each pixel's jitter
    /// converges; while it moves they are shifted by R2 (`MASK_MODE_2D`: a per-pixel sequence
    /// means nothing to a filter that follows the surface).
    Jitter,
    /// [`MaskDims::Jitter`], and while the view moves also the first vertex's BSDF sample:
    /// keys recorded a cycle ago at another place no longer predict it, and the mask's blue
    /// first bounce beats stale keys (with a still view the sort keeps it, and wins at depth).
    Motion,
    /// [`MaskDims::Motion`], and while the view moves also the first vertex's light sample,
    /// so every dimension of the camera ray and the first vertex is the mask's (what `mask-r2`
    /// draws there); deeper vertices stay the sorted seeds' where the frame sorts (textures;
    /// without them a moving frame reads no seed, [`Without::WhiteDepth`]). The sample keys,
    /// kept while the view moves, then rank by a light sample no pixel takes. `sort-cycle`'s:
    /// ahead of [`MaskDims::Motion`] in every moving configuration of the motion tables, per
    /// frame and after TAA (docs/results.md).
    Vertex,
}

/// What the sorting pass ranks against while the view moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Target {
    /// The mask stays on the screen.
    Screen,
    /// The spatio-temporal mask moves with the image (the scene centre's image motion), so a
    /// filter that follows the motion meets a surface point at one texel's temporally blue
    /// values (only with [`Points::Cycle`]; `follow.rs`). `sort-cycle`'s: where a moving frame
    /// sorts (textures) ahead after TAA at 8 bounces (docs/results.md), level per frame.
    Follow,
}

/// One of `sort-cycle`'s rules that depend on the view state, switched off for an ablation
/// row (the rule's own comparison in the tables): the method without it is otherwise the same.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Without {
    /// Every rule kept.
    Nothing,
    /// A moving view ranks by the keys recorded a cycle ago instead of the seeds' next light
    /// sample (`SortParams::cycle_sample_keys`).
    SampleKeys,
    /// A moving view keeps the mask's jitter on textured pixels too
    /// (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES` off).
    TextureJitter,
    /// A still view walks the mask's jitter along R2 on every pixel, not along Sobol's
    /// (0,2)-sequence on untextured ones (`TRACE_FLAG_SOBOL_JITTER` off).
    SobolJitter,
    /// A still view in direct light on a scene without textures keeps the sorted seeds (the
    /// rules above) instead of taking the jitter and the first vertex from the
    /// spatio-temporal volume ([`crate::Method::volume_vertex`]).
    StillVolume,
    /// A moving view takes its mask dimensions from the 2D mask shifted along R2 every frame
    /// (`mask-r2`'s), instead of the motion volume ([`crate::Method::motion_volume`]).
    MotionVolume,
    /// A moving view at depth on a scene without textures keeps the sorted seeds for the
    /// vertices past the first, instead of fresh white noise and no sort
    /// ([`crate::Method::reads_seeds`]).
    WhiteDepth,
}

/// A seed-permutation method: each field gates its own passes and shader code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Permutation {
    pub key: Key,
    pub grouping: Grouping,
    pub transport: Transport,
    pub motion: Motion,
    pub pairs: Pairs,
    pub points: Points,
    pub mask: MaskDims,
    pub target: Target,
    pub without: Without,
}
