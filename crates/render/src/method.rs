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
    /// Ours: no retargeting; each frame sorts GRID_BLOCK-sized blocks against the next
    /// frame's mask on a block grid that moves every frame (`permute::grid_offset`), so seeds
    /// cross block borders but never move more than GRID_BLOCK - 1 pixels per frame. Classes
    /// at most 2 px wide or tall in a block rank against antithetic pairs on a checkerboard
    /// (`SortParams::pairs`), since the mask restricted to a thin strip is not blue.
    SortGrid,
    /// Ours: `SortGrid` ranking only within surfaces (G-buffer classes): seeds never leave
    /// their surface.
    SortGridEdges,
    /// Ours: `SortGridEdges` with reprojection and the demodulated key.
    SortGridPlus,
    /// Ours: `SortGridPlus` with antithetic pairs in every class, not only thin ones: lower P1,
    /// but the error becomes a checkerboard with mask-ordered magnitudes, not blue noise.
    SortGridPairs,
    /// Ours: `SortGridPlus` ranking history keys (`permute/history_key`): each pixel's key
    /// minus its surface's mean key over earlier frames, an estimate of the seed's error.
    SortGridHistory,
    /// Ours: `SortGridHistory` with antithetic pairs in every class while the sorting keys are
    /// about symmetric, and in none (the mask everywhere) while many classes have heavy-tailed
    /// keys (counted by the sorting pass; `PairsGate`).
    SortGridAdaptive,
    /// Evaluation only: `SortGridHistory`'s passes, but the sorting pass ranks each pixel's
    /// exact luminance error against the frame's reference (`permute/oracle_key`). No
    /// renderer has that reference; the method measures the ceiling of any sorting key.
    SortGridOracle,
}

/// Block edge of the moving-grid methods, whatever the paper's block size: without
/// retargeting, the blocks alone carry seeds across the screen, and 8 (the largest the
/// sorting pass allows) measured best on the bundled scenes (README, "Beyond the paper").
pub const GRID_BLOCK: u32 = 8;

impl Method {
    pub const ALL: [Method; 19] = [
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
        Method::SortGrid,
        Method::SortGridEdges,
        Method::SortGridPlus,
        Method::SortGridPairs,
        Method::SortGridHistory,
        Method::SortGridAdaptive,
        Method::SortGridOracle,
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
            Method::SortGrid => "sort-grid",
            Method::SortGridEdges => "sort-grid-edges",
            Method::SortGridPlus => "sort-grid-plus",
            Method::SortGridPairs => "sort-grid-pairs",
            Method::SortGridHistory => "sort-grid-history",
            Method::SortGridAdaptive => "sort-grid-adaptive",
            Method::SortGridOracle => "sort-grid-oracle",
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
        self == Method::Sort || self.shifts_grid() || self.retargets()
    }

    /// Whether sorting runs on a moving block grid against the next frame's mask (instead of
    /// retargeting).
    pub fn shifts_grid(self) -> bool {
        matches!(
            self,
            Method::SortGrid
                | Method::SortGridEdges
                | Method::SortGridPlus
                | Method::SortGridPairs
                | Method::SortGridHistory
                | Method::SortGridAdaptive
                | Method::SortGridOracle
        )
    }

    /// The sorting block edge: `requested` (the paper's B) or GRID_BLOCK for the moving grid.
    pub fn block(self, requested: u32) -> u32 {
        if self.shifts_grid() {
            GRID_BLOCK
        } else {
            requested
        }
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
            Method::SortRetargetReproject
                | Method::SortRetargetPlus
                | Method::SortGridPlus
                | Method::SortGridPairs
                | Method::SortGridHistory
                | Method::SortGridAdaptive
                | Method::SortGridOracle
        )
    }

    /// Whether the sorting key is demodulated by the primary hit's base colour.
    pub fn demodulates(self) -> bool {
        matches!(
            self,
            Method::SortRetargetDemod
                | Method::SortRetargetPlus
                | Method::SortGridPlus
                | Method::SortGridPairs
                | Method::SortGridHistory
                | Method::SortGridAdaptive
        )
    }

    /// Whether sorting ranks within G-buffer surface classes.
    pub fn edge_aware(self) -> bool {
        matches!(
            self,
            Method::SortRetargetEdges
                | Method::SortRetargetPlus
                | Method::SortGridEdges
                | Method::SortGridPlus
                | Method::SortGridPairs
                | Method::SortGridHistory
                | Method::SortGridAdaptive
                | Method::SortGridOracle
        )
    }

    /// Whether the sorting pass ranks history keys (`permute/history_key`).
    pub fn history_keys(self) -> bool {
        matches!(self, Method::SortGridHistory | Method::SortGridAdaptive)
    }

    /// Whether the sorting pass ranks exact errors (`permute/oracle_key`), so that every frame
    /// needs `Renderer::set_reference_luminance` first (only `blueshift eval` has references).
    pub fn needs_reference(self) -> bool {
        self == Method::SortGridOracle
    }

    /// Whether the pairs' checkerboard phase is a hash bit of the frame rather than its parity
    /// (`permute::pair_phase`): the methods that rank errors, where an alternating phase that a
    /// 1 px/frame pan cancels fed a bias back through the history means.
    pub fn hashes_pair_phase(self) -> bool {
        self.history_keys() || self.needs_reference()
    }

    /// Whether the sorting pass counts skewed classes and `PairsGate` chooses the pairs.
    pub fn adapts_pairs(self) -> bool {
        self == Method::SortGridAdaptive
    }

    /// Which classes rank against antithetic pairs (`SortParams::pairs`): thin ones for the
    /// moving grid, every one for `SortGridPairs`, what `gate` chose from the sequence's
    /// counts so far for `SortGridAdaptive`, none otherwise.
    pub fn pairs(self, gate: &crate::PairsGate) -> u32 {
        match self {
            Method::SortGridAdaptive => gate.pairs(),
            Method::SortGridPairs => 2,
            m if m.shifts_grid() => 1,
            _ => 0,
        }
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
