//! The methods Blueshift compares, and what each means for the passes.
use blueshift_sampling::Sampler;

/// A way of choosing per-pixel randomness over frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Fresh decorrelated randomness every frame: seed = hash(pixel seed, frame).
    White,
    /// Decorrelated seeds fixed for the whole sequence (the permutation methods' starting point).
    WhiteFixed,
    /// Owen-scrambled Sobol, fixed per-pixel scramble seeds, sample index advancing per frame.
    Sobol,
    /// HBO+19: Owen-Sobol with per-pixel keys optimised offline so that frame 0's error is
    /// already blue; fixed tile-position seeds, sample index advancing per frame.
    Hbo19,
    /// Blue-noise mask (void-and-cluster) offsets the first dimensions, shifted by R2 per frame.
    MaskR2,
    /// Spatio-temporal blue-noise mask slices in the same role.
    Stbn,
    /// Sorting pass only.
    Sort,
    /// Sorting + retargeting (Heitz & Belcour 2019): the default.
    SortRetarget,
    /// Ours: sorting + retargeting, and seeds follow their surface between frames (a
    /// bijective reprojection along the G-buffer's motion; the mask moves with the image).
    SortRetargetReproject,
    /// Ours: sorting ranks only pixels of one surface (G-buffer classes) within a block.
    SortRetargetEdges,
    /// Ours: reprojection, edge-aware grouping and the demodulated key together.
    SortRetargetPlus,
    /// Ours: sorting + retargeting on a demodulated key (the estimate over the primary hit's
    /// base colour), so textures do not scramble the ranks.
    SortRetargetDemod,
}

impl Method {
    pub const ALL: [Method; 12] = [
        Method::White,
        Method::WhiteFixed,
        Method::Sobol,
        Method::Hbo19,
        Method::MaskR2,
        Method::Stbn,
        Method::Sort,
        Method::SortRetarget,
        Method::SortRetargetReproject,
        Method::SortRetargetEdges,
        Method::SortRetargetPlus,
        Method::SortRetargetDemod,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Method::White => "white",
            Method::WhiteFixed => "white-fixed",
            Method::Sobol => "sobol",
            Method::Hbo19 => "hbo19",
            Method::MaskR2 => "mask-r2",
            Method::Stbn => "stbn",
            Method::Sort => "sort",
            Method::SortRetarget => "sort-retarget",
            Method::SortRetargetReproject => "sort-retarget-reproject",
            Method::SortRetargetEdges => "sort-retarget-edges",
            Method::SortRetargetPlus => "sort-retarget-plus",
            Method::SortRetargetDemod => "sort-retarget-demod",
        }
    }

    pub fn from_name(name: &str) -> Option<Method> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// All names, for error messages and `--help`.
    pub fn names() -> String {
        Self::ALL.map(|m| m.name()).join(", ")
    }

    /// The seeded sampler this method uses unless overridden.
    pub fn default_sampler(self) -> Sampler {
        match self {
            Method::Sobol => Sampler::Sobol,
            Method::Hbo19 => Sampler::Hbo19,
            _ => Sampler::White,
        }
    }

    /// Whether the sorting pass runs.
    pub fn sorts(self) -> bool {
        self == Method::Sort || self.retargets()
    }

    /// Whether the sample index advances with the frame (a progressive sequence per pixel).
    pub fn advances_index(self) -> bool {
        matches!(self, Method::Sobol | Method::Hbo19)
    }

    /// Whether the retargeting pass runs.
    pub fn retargets(self) -> bool {
        matches!(
            self,
            Method::SortRetarget
                | Method::SortRetargetReproject
                | Method::SortRetargetEdges
                | Method::SortRetargetPlus
                | Method::SortRetargetDemod
        )
    }

    /// Whether seeds are reprojected along the motion between frames.
    pub fn reprojects(self) -> bool {
        matches!(
            self,
            Method::SortRetargetReproject | Method::SortRetargetPlus
        )
    }

    /// Whether the sorting key is demodulated by the primary hit's base colour.
    pub fn demodulates(self) -> bool {
        matches!(self, Method::SortRetargetDemod | Method::SortRetargetPlus)
    }

    /// Whether sorting ranks within G-buffer surface classes.
    pub fn edge_aware(self) -> bool {
        matches!(self, Method::SortRetargetEdges | Method::SortRetargetPlus)
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::from_name(s)
            .ok_or_else(|| format!("unknown method '{s}' (known: {})", Method::names()))
    }
}
