//! The methods Blueshift compares: baselines, and the seed-permutation methods as one
//! specification ([`Permutation`]) with named presets.
use crate::recipe::ViewState;
use blueshift_sampling::Sampler;

pub use crate::permutation::{
    Grouping, Key, MaskDims, Motion, Pairs, Permutation, Points, Target, Transport, Without,
};

/// A way of choosing per-pixel randomness over frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Fresh decorrelated randomness every frame: seed = hash(pixel seed, frame).
    White,
    /// Owen-scrambled Sobol, fixed per-pixel scramble seeds, sample index advancing per frame.
    Sobol,
    /// HBO+19: Owen-Sobol with per-pixel keys optimised offline so that frame 0's error is
    /// already blue; fixed tile-position seeds, sample index advancing per frame.
    Hbo19,
    /// Blue-noise mask (void-and-cluster) offsets the first dimensions, shifted by R2 per frame.
    MaskR2,
    /// Spatio-temporal blue-noise mask slices in the same role.
    Stbn,
    /// FAST mask slices (optimised for a Gaussian blur and an EMA) in the same role.
    Fast,
    /// The blue-noise mask, not shifted, its values rotated by R2 every frame
    /// (`MASK_MODE_ROTATE`): blue in every frame, and per pixel an R2 sequence over frames,
    /// which an accumulation averages like a low-discrepancy sequence.
    MaskRot,
    /// [`Method::MaskRot`] with the mask anchored to the image: each pixel reads it at an
    /// anchor that follows its surface (`permute::follow_anchors`), so under motion a temporal
    /// filter that follows the surface averages that surface point's own R2 sequence.
    MaskRotFollow,
    /// Block nets without any sorting (`sobol` with the `blocknet` sampler): each 8x8 block's
    /// seeds share one scrambled Sobol sequence, index advancing per frame. The ablation of
    /// `sort-cycle`: what its sampler gives before the sort.
    BlockNet,
    /// Per-pixel seeds permuted between frames.
    Permute(Permutation),
}

/// Block edge of the moving grid, whatever the paper's block size: without retargeting, the
/// blocks alone carry seeds across the screen, and 8 (the largest the sorting pass allows)
/// measured best on the bundled scenes (docs/experiments.md).
pub const GRID_BLOCK: u32 = 8;

/// The sorting block edge of the methods that take `--block` unless told (the paper's 4).
pub const PAPER_BLOCK: u32 = 4;

/// The camera jitter's sample dimensions (0 and 1), as a `Method::mask_dims` bit set.
const JITTER_DIMS: u32 = 0b11;

const PAPER: Permutation = Permutation {
    key: Key::Raw,
    grouping: Grouping::Blocks,
    transport: Transport::Retarget,
    motion: Motion::None,
    pairs: Pairs::Off,
    points: Points::Fixed,
    mask: MaskDims::None,
    target: Target::Screen,
    without: Without::Nothing,
};

const SORT: Permutation = Permutation {
    transport: Transport::None,
    ..PAPER
};

const HISTORY: Permutation = Permutation {
    key: Key::History,
    grouping: Grouping::Surfaces,
    transport: Transport::Grid,
    motion: Motion::Reproject,
    pairs: Pairs::Thin,
    points: Points::Fixed,
    mask: MaskDims::None,
    target: Target::Screen,
    without: Without::Nothing,
};

const CYCLE: Permutation = Permutation {
    grouping: Grouping::StillSurfaces,
    transport: Transport::None,
    points: Points::Cycle,
    mask: MaskDims::Vertex,
    target: Target::Follow,
    ..PAPER
};

impl Method {
    /// The sorting pass only (Heitz & Belcour 2019, without retargeting): the spelled-out
    /// form `sort-retarget:transport=none`, for the paper's analysis.
    pub const SORT: Method = Method::Permute(SORT);
    /// Sorting + retargeting (Heitz & Belcour 2019): the paper.
    pub const SORT_RETARGET: Method = Method::Permute(PAPER);
    /// Moving grid, reprojection, surfaces, history keys, thin-class pairs
    /// (`sort-grid-adaptive:pairs=thin`).
    pub const SORT_GRID_HISTORY: Method = Method::Permute(HISTORY);
    /// [`Method::SORT_GRID_HISTORY`] with adaptive pairs.
    pub const SORT_GRID_ADAPTIVE: Method = Method::Permute(Permutation {
        pairs: Pairs::Adaptive,
        ..HISTORY
    });
    /// Sorting within the surfaces of fixed blocks over a cycle of block-net points per seed,
    /// against spatio-temporal mask slices ([`Points::Cycle`]) that move with the image
    /// ([`Target::Follow`]); while the view moves the camera ray and the first vertex draw
    /// from the mask ([`MaskDims::Vertex`]).
    pub const SORT_CYCLE: Method = Method::Permute(CYCLE);
    /// The default of the library and of every command.
    pub const DEFAULT: Method = Method::SORT_CYCLE;

    /// The named presets `--method` offers, in the order of the documentation: the baseline,
    /// a progressive sequence, a mask, the paper, the best single frames at depth under
    /// motion, the default.
    pub const PRESETS: [(&'static str, Method); 6] = [
        ("white", Method::White),
        ("sobol", Method::Sobol),
        ("mask-r2", Method::MaskR2),
        ("sort-retarget", Method::SORT_RETARGET),
        ("sort-grid-adaptive", Method::SORT_GRID_ADAPTIVE),
        ("sort-cycle", Method::SORT_CYCLE),
    ];

    /// Baselines kept for comparisons only: `eval` and `bench` take these names
    /// ([`Method::parse_comparison`]); `--method` of the other commands does not.
    pub const COMPARISONS: [(&'static str, Method); 6] = [
        ("hbo19", Method::Hbo19),
        ("stbn", Method::Stbn),
        ("fast", Method::Fast),
        ("mask-rot", Method::MaskRot),
        ("mask-rot-follow", Method::MaskRotFollow),
        ("blocknet", Method::BlockNet),
    ];

    /// The preset's or comparison's name, or the spelled-out form `PRESET:field=value,...`
    /// relative to the permutation preset it differs from in the fewest fields (the first
    /// such preset), so an ablation reads as the method it changes (`sort-cycle:mask=none`).
    pub fn name(self) -> String {
        let named = Self::PRESETS.iter().chain(&Self::COMPARISONS);
        if let Some((name, _)) = named.clone().find(|(_, m)| *m == self) {
            return (*name).to_string();
        }
        let Method::Permute(p) = self else {
            return format!("{self:?}"); // every baseline is named
        };
        let own = crate::method_spec::fields(&p);
        let differing = |q: &Permutation| -> Vec<String> {
            own.iter()
                .zip(crate::method_spec::fields(q))
                .filter(|(a, b)| **a != *b)
                .map(|((field, value), _)| format!("{field}={value}"))
                .collect()
        };
        let (base, fields) = Self::PRESETS
            .iter()
            .filter_map(|(n, m)| m.permutation().map(|q| (*n, differing(&q))))
            .min_by_key(|(_, f)| f.len())
            .expect("sort-retarget is a permutation preset");
        format!("{base}:{}", fields.join(","))
    }

    /// Every named method: the presets, then the comparison baselines.
    pub fn named() -> impl Iterator<Item = (&'static str, Method)> {
        Self::PRESETS.into_iter().chain(Self::COMPARISONS)
    }

    /// Every spelled-out permutation the passes can run (the presets' among them).
    pub fn all_permutations() -> Vec<Method> {
        crate::method_spec::all_valid()
            .into_iter()
            .map(Method::Permute)
            .collect()
    }

    /// A preset, a comparison baseline or a spelled-out form: what `eval` and `bench` take.
    pub fn parse_comparison(s: &str) -> Result<Method, String> {
        match Self::COMPARISONS.iter().find(|(n, _)| *n == s) {
            Some((_, m)) => Ok(*m),
            None => s.parse().map_err(|e: String| {
                format!(
                    "{e}; for comparisons also: {}",
                    Self::COMPARISONS.map(|(n, _)| n).join(", ")
                )
            }),
        }
    }

    /// All preset names, for error messages and `--help`.
    pub fn names() -> String {
        Self::PRESETS.map(|(n, _)| n).join(", ")
    }

    /// The fields of the spelled-out form `PRESET:field=value,...` with their values
    /// (`key=raw|demod|history, ...`), for `--help`.
    pub fn fields_syntax() -> String {
        crate::method_spec::syntax()
    }

    /// The permutation spec, for the seed-permutation methods.
    pub fn permutation(self) -> Option<Permutation> {
        match self {
            Method::Permute(p) => Some(p),
            _ => None,
        }
    }

    /// The seeded sampler this method uses unless overridden.
    pub fn default_sampler(self) -> Sampler {
        match self {
            Method::Sobol => Sampler::Sobol,
            Method::Hbo19 => Sampler::Hbo19,
            Method::BlockNet => Sampler::BlockNet,
            // Behind the rotating mask: its deeper dimensions converge along the pixel (or
            // the anchor) too.
            Method::MaskRot | Method::MaskRotFollow => Sampler::Sobol,
            m if m.cycles_points() => Sampler::BlockNet,
            _ => Sampler::White,
        }
    }

    /// Whether the sorting pass runs.
    pub fn sorts(self) -> bool {
        self.permutation().is_some()
    }

    fn has(self, f: impl Fn(Permutation) -> bool) -> bool {
        self.permutation().is_some_and(f)
    }

    /// Whether a view-state rule is left on (only the `without=` ablations drop one).
    pub(crate) fn keeps(self, rule: Without) -> bool {
        !self.has(|p| p.without == rule)
    }

    /// Whether sorting runs on a moving block grid against the next frame's mask (instead of
    /// retargeting).
    pub fn shifts_grid(self) -> bool {
        self.has(|p| p.transport == Transport::Grid)
    }

    /// The block edge this method sorts with whatever is asked ([`GRID_BLOCK`] for the moving
    /// grid and the point cycle); `None` where `--block` chooses it.
    pub fn fixed_block(self) -> Option<u32> {
        (self.shifts_grid() || self.cycles_points()).then_some(GRID_BLOCK)
    }

    /// The sorting block edge: the method's own, else `requested` (the paper's B), else
    /// [`PAPER_BLOCK`].
    pub fn block(self, requested: Option<u32>) -> u32 {
        self.fixed_block()
            .unwrap_or(requested.unwrap_or(PAPER_BLOCK))
    }

    /// Whether the sample index advances with the frame (a progressive sequence per pixel).
    pub fn advances_index(self) -> bool {
        matches!(self, Method::Sobol | Method::Hbo19 | Method::BlockNet) || self.cycles_points()
    }

    /// Whether seeds cycle through a fixed set of points (the sorting pass's point cycle): the
    /// sample index is the frame's phase in the cycle.
    pub fn cycles_points(self) -> bool {
        self.has(|p| p.points == Points::Cycle)
    }

    /// Whether the mask is read at anchors that follow the surfaces (`follow_anchors`).
    pub fn anchors_mask(self) -> bool {
        self == Method::MaskRotFollow
    }

    /// The screen-fixed mask method an anchored one reads its mask like (itself otherwise).
    pub fn mask_method(self) -> Method {
        match self {
            Method::MaskRotFollow => Method::MaskRot,
            m => m,
        }
    }

    /// Whether the retargeting pass runs.
    pub fn retargets(self) -> bool {
        self.has(|p| p.transport == Transport::Retarget)
    }

    /// Whether seeds are reprojected along the motion between frames.
    pub fn reprojects(self) -> bool {
        self.has(|p| p.motion == Motion::Reproject)
    }

    /// Whether the sorting key is demodulated by the primary hit's base colour (history keys
    /// are demodulated too).
    pub fn demodulates(self) -> bool {
        self.has(|p| p.key != Key::Raw)
    }

    /// Whether sorting ranks within G-buffer surface classes (at least while the view is still).
    pub fn edge_aware(self) -> bool {
        self.has(|p| p.grouping != Grouping::Blocks)
    }

    /// Whether the classes are made only while the view is still (one class per block while it
    /// moves).
    pub fn classifies_still_only(self) -> bool {
        self.has(|p| p.grouping == Grouping::StillSurfaces)
    }

    /// Whether the sorting target moves with the image ([`Target::Follow`]).
    pub fn follows_target(self) -> bool {
        self.has(|p| p.target == Target::Follow)
    }

    /// Whether the sorting pass ranks history keys (`permute/history_key`).
    pub fn history_keys(self) -> bool {
        self.has(|p| p.key == Key::History)
    }

    /// The sample dimensions the mask drives (bit d: dimension d) instead of the seed's
    /// sampler, for a view that `moving` or stands still; 0: none (the mask methods drive
    /// all of the first `MASK_DIMS`, and say so with their own mask mode).
    pub fn mask_dims(self, moving: bool) -> u32 {
        use blueshift_layout::params::{DIMS_PER_BOUNCE, MASK_DIMS};
        let jitter = JITTER_DIMS;
        // Vertex 0's BSDF sample: lobe choice, direction (2) and Russian roulette, after its
        // three light dimensions (see `DIMS_PER_BOUNCE`).
        let bsdf = ((1 << (DIMS_PER_BOUNCE - 3)) - 1) << (2 + 3);
        match self.permutation().map(|p| p.mask) {
            Some(MaskDims::Jitter) => jitter,
            Some(MaskDims::Motion) if moving => jitter | bsdf,
            Some(MaskDims::Vertex) if moving => (1 << MASK_DIMS) - 1,
            Some(MaskDims::Motion | MaskDims::Vertex) => jitter,
            _ => 0,
        }
    }

    /// The trace pass's flags for a jitter taken from the mask: such a method records which
    /// pixels show a textured surface (`TRACE_FLAG_RECORD_PRIMARY`), and while the view moves
    /// those pixels take the seed's jitter instead (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES`: on
    /// textures the mask's shifted jitter is worse than the seeds' sorted block nets). With a
    /// still view the mask's rotated jitter stays everywhere: it walks a (0,2)-sequence per
    /// pixel where the previous primary hit was untextured (`TRACE_FLAG_SOBOL_JITTER`), R2
    /// on textured pixels.
    pub fn jitter_flags(self, moving: bool) -> u32 {
        use blueshift_layout::params::{
            TRACE_FLAG_RECORD_PRIMARY, TRACE_FLAG_SEED_JITTER_ON_TEXTURES, TRACE_FLAG_SOBOL_JITTER,
        };
        let flag = |on: bool, f: u32| if on { f } else { 0 };
        if self.mask_dims(moving) & JITTER_DIMS == 0 {
            0
        } else if moving {
            TRACE_FLAG_RECORD_PRIMARY
                | flag(
                    self.keeps(Without::TextureJitter),
                    TRACE_FLAG_SEED_JITTER_ON_TEXTURES,
                )
        } else {
            TRACE_FLAG_RECORD_PRIMARY
                | flag(self.keeps(Without::SobolJitter), TRACE_FLAG_SOBOL_JITTER)
        }
    }

    /// Whether the trace reads the seeds in view state `view`, at `bounces`, in a scene with
    /// textures or not. Not where the mask drives the first vertex (`mask=vertex` moving, or
    /// the volume) and no pixel takes the seeds' jitter (no textures), in direct light or while
    /// the view moves: a sort there would rank seeds no path uses, or at depth under motion
    /// gain nothing it costs (the moving view's vertices past the first then take fresh white
    /// noise, as the masks' do; docs/experiments.md), so the frame skips it and costs what the
    /// mask's frame costs.
    pub fn reads_seeds(self, view: ViewState, bounces: u32, textured: bool) -> bool {
        use blueshift_layout::params::{MASK_DIMS, TRACE_FLAG_SEED_JITTER_ON_TEXTURES};
        let moving = view != ViewState::Still;
        let whole_vertex = self.mask_dims(moving) == (1 << MASK_DIMS) - 1;
        let seed_jitter =
            textured && self.jitter_flags(moving) & TRACE_FLAG_SEED_JITTER_ON_TEXTURES != 0;
        let white_depth = moving && self.keeps(Without::WhiteDepth);
        (!whole_vertex || (bounces > 1 && !white_depth) || seed_jitter)
            && !self.volume_vertex(view, bounces, textured)
    }

    /// Whether the frame in view state `view`, at `bounces`, in a scene with textures or not,
    /// takes the camera jitter and the whole first vertex from the spatio-temporal volume
    /// (`MASK_MODE_SPATIOTEMPORAL`, the slices the point cycle sorts against): a `mask=vertex`
    /// point cycle in direct light without textures, with a still view. A path draws nothing
    /// else there, and the volume is blue in each frame and along each pixel's frames: it
    /// beats the sorted seeds on both axes (docs/results.md), so the trace reads no seed and
    /// the frame skips the sort. With textures the seeds' sorted light sample and the mask's
    /// Sobol walk accumulate better than the volume.
    pub fn volume_vertex(self, view: ViewState, bounces: u32, textured: bool) -> bool {
        view == ViewState::Still
            && bounces <= 1
            && !textured
            && self.has(|p| p.points == Points::Cycle && p.mask == MaskDims::Vertex)
            && self.keeps(Without::StillVolume)
    }

    /// Whether a moving view at `bounces`, in a scene with textures or not, takes the
    /// dimensions the mask drives ([`Self::mask_dims`]) from the motion volume
    /// (`MASK_MODE_SPATIOTEMPORAL` on `MethodAssets::motion`) rather than from the 2D mask
    /// shifted along R2: a point cycle with a mask, in direct light or where the frame reads no
    /// seed. The motion volume's slices are as blue as the 2D mask, and a pixel's values in
    /// consecutive frames still differ, which a TAA's history averages: ahead of the 2D mask
    /// after TAA at every speed, and of the still volume on both axes but one
    /// (docs/experiments.md). Behind the sorted seeds at depth it lost the box's TAA.
    pub fn motion_volume(self, view: ViewState, bounces: u32, textured: bool) -> bool {
        view == ViewState::Moving
            && (bounces <= 1 || !self.reads_seeds(view, bounces, textured))
            && self.cycles_points()
            && self.mask_dims(true) != 0
            && self.keeps(Without::MotionVolume)
    }

    /// Whether a moving view's point cycle ranks the seeds by their next light sample
    /// (`SortParams::cycle_sample_keys`; the sampler must be the block nets the keys index).
    pub fn ranks_by_sample_keys(self, sampler: Sampler) -> bool {
        self.cycles_points() && sampler == Sampler::BlockNet && self.keeps(Without::SampleKeys)
    }

    /// Whether the pairs' checkerboard phase is a hash bit of the frame rather than its parity
    /// (`permute::pair_phase`): with history keys an alternating phase that a 1 px/frame pan
    /// cancels feeds a bias back through the history means.
    pub fn hashes_pair_phase(self) -> bool {
        self.history_keys()
    }

    /// Whether the sorting pass counts skewed classes and `PairsGate` chooses the pairs.
    pub fn adapts_pairs(self) -> bool {
        self.has(|p| p.pairs == Pairs::Adaptive)
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        crate::method_spec::parse(s)
    }
}
