//! Parameter structs of the passes, shared with GLSL. They live here, not in the pass crates,
//! so the header generator (crates/headers) never waits on the shader build.
use crate::gpu_struct;

gpu_struct! {
    /// Push constants of `permute/sort_seeds` (one workgroup per block).
    pub struct SortParams {
        /// Visible screen size; pixels outside it are never ranked.
        pub width: u32,
        pub height: u32,
        /// Row stride of the seed buffer (screen width padded to a multiple of the mask size).
        pub stride: u32,
        /// Rows of the seed buffer (screen height padded likewise): the sorting pass that also
        /// retargets moves the padded pixels too.
        pub padded_height: u32,
        /// Block edge B (2..=8).
        pub block: u32,
        /// Mask tile edge N.
        pub mask_size: u32,
        /// Mask offset of this frame: mask value at pixel p is M((p + offset) mod N).
        pub offset_x: u32,
        pub offset_y: u32,
        /// Block grid offset G (each < B): blocks start at (k * B - G), so a grid that moves
        /// between frames lets seeds cross last frame's block borders without retargeting.
        pub grid_x: u32,
        pub grid_y: u32,
        /// 1: classes at most 2 pixels wide or tall in the block rank against antithetic pairs
        /// on a checkerboard instead of the mask (whose restriction to a thin strip is not
        /// blue); 2: every class does; 0: the paper's ranking everywhere; SORT_PAIRS_FROM_GATE:
        /// 0 or 2 as the pairs gate's buffer says (variants that count skewed classes).
        pub pairs: u32,
        /// Checkerboard phase (0 or 1) of the pairs: alternated per frame so that no pixel
        /// always takes the lower half of its class's keys.
        pub phase: u32,
        /// 1: add (classes with skewed keys, classes counted) of every block to the stats
        /// buffer (`count_skewed_classes`), for `sort-grid-adaptive`'s choice of pairs.
        pub count_skew: u32,
        /// The point cycle of `sort-cycle`, for the sorting pass that runs it on the way in
        /// (`CycleParams` holds the meaning of each): the mask slice of the next frame, the
        /// phases, whether the next phase's slot is written, frames in the running mean,
        /// whether the seeds rank by their next light sample.
        pub mask_layer: u32,
        pub cycle_phase: u32,
        pub cycle_next_phase: u32,
        pub cycle_next_valid: u32,
        pub cycle_mean_count: u32,
        pub cycle_sample_keys: u32,
    }
}

gpu_struct! {
    /// The point cycle of `sort-cycle` for one frame (`SortParams::cycle_*` on the GPU).
    pub struct CycleParams {
        pub width: u32,
        pub height: u32,
        /// Row stride of the seed buffer.
        pub stride: u32,
        /// Phase of the frame just traced (frame mod CYCLE_FRAMES): its history slot.
        pub phase: u32,
        /// Phase of the next frame: the slot whose seeds and keys the sorting pass ranks.
        pub next_phase: u32,
        /// 1 once the next phase's slot has been written (a whole cycle has run); 0: the
        /// sorting pass ranks this frame's seeds and keys instead.
        pub next_valid: u32,
        /// Spatio-temporal mask: tile edge, and the slice the next frame sorts against.
        pub mask_size: u32,
        pub mask_layer: u32,
        /// Frames in the pixel's running mean (`accum`); above 0 the recorded key is the
        /// estimate's key minus that mean, an estimate of the seed's error rather than of the
        /// image, which carries over to the other pixels of the block.
        pub mean_count: u32,
        /// 1: rank the block's seeds by where their next light sample lands
        /// ([`sample_key_code`] of block-net dimensions [`SAMPLE_KEY_DIM`] and the next, at
        /// the next phase) instead of by their recorded keys. While the view moves the recorded
        /// keys belong to what the block showed a cycle ago; the sample's own position still
        /// spreads the block's net over the mask, so neighbours take distant light samples.
        /// The sorting pass runs a shader with or without them compiled in, as this asks.
        pub sample_keys: u32,
    }
}

/// Frames in the point cycle of `sort-cycle`: each seed revisits the same CYCLE_FRAMES points
/// of its Owen-scrambled Sobol sequence (indices 0..CYCLE_FRAMES, a (0,4,2)-net), so the
/// estimate it gave CYCLE_FRAMES frames ago predicts the next one (docs/algorithm.md).
pub const CYCLE_FRAMES: u32 = 16;

/// The first dimension of the first vertex's light sample (after the two jitter dimensions):
/// with the next, one pair of the block net, whose position ranks the seeds under motion
/// (`CycleParams::sample_keys`).
pub const SAMPLE_KEY_DIM: u32 = 2;
// The sorting pass draws the two as one sampler pair (sort_seeds.glsl).
const _: () = assert!(SAMPLE_KEY_DIM % 2 == 0);

/// Bits per coordinate of the sample key's grid. A block's 64 points at one phase are a
/// (0,6,2)-net in the key's pair, one point in each cell of the 8 x 8 grid, so the order along
/// the Hilbert curve of that grid is already the order along any finer one, without ties.
pub const SAMPLE_KEY_BITS: u32 = 3;

/// The sample key of a 2D point from its two 32-bit fractions: the index of its cell of the
/// 2^SAMPLE_KEY_BITS grid along a Hilbert curve. Cells close on the curve are neighbours in
/// the square, and every aligned 2^k x 2^k square of cells is one run of keys, so points close
/// in the square mostly get close keys (the GLSL `sample_key_code`). A Morton order, which
/// jumps at every square's border, ranked worse (docs/experiments.md).
pub fn sample_key_code(x: u32, y: u32) -> u32 {
    const N: u32 = 1 << SAMPLE_KEY_BITS;
    let (mut x, mut y) = (x >> (32 - SAMPLE_KEY_BITS), y >> (32 - SAMPLE_KEY_BITS));
    let mut d = 0;
    let mut s = N / 2;
    while s > 0 {
        let rx = u32::from(x & s != 0);
        let ry = u32::from(y & s != 0);
        d += s * s * ((3 * rx) ^ ry);
        // Into the sub-square's own frame: reflected in the last quadrant, transposed.
        if ry == 0 {
            if rx == 1 {
                x = N - 1 - x;
                y = N - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}

/// The sorting pass counts the classes of at least SKEW_MIN_PIXELS pixels in a block, and
/// those among them whose keys have a sample skewness |g| > SKEW_LIMIT: antithetic pairs
/// cannot cancel a heavy tail (docs/algorithm.md, "pairs=adaptive").
pub const SKEW_MIN_PIXELS: u32 = 8;
pub const SKEW_LIMIT: f32 = 2.0;

/// `SortParams::pairs` of `sort-grid-adaptive`: the pairs the `pairs_gate` pass chose from
/// the counts of the frames before (0 or 2), read from the gate's buffer on the GPU, so that
/// the frame need not wait for the one before it.
pub const SORT_PAIRS_FROM_GATE: u32 = 3;
/// The pairs gate keeps its smoothed share of skewed classes in fixed point, units of
/// 1 / PAIRS_GATE_ONE: integer arithmetic, so that the pass and its CPU twin agree exactly.
pub const PAIRS_GATE_ONE: u32 = 1 << 24;
/// Pairs go to every class while the smoothed share is below this: 0.1 (rounded up to the
/// next unit), from the shares measured on the bundled scenes (`PairsGate`).
pub const PAIRS_GATE_LIMIT: u32 = PAIRS_GATE_ONE / 10 + 1;

gpu_struct! {
    /// Push constants of `trace/trace` (124 bytes: fits the 128-byte minimum limit).
    pub struct TraceParams {
        pub cam_origin: glam::Vec3,
        pub cam_forward: glam::Vec3,
        /// Right and up vectors scaled so that pixel NDC (-1..1) maps onto the image plane.
        pub cam_right: glam::Vec3,
        pub cam_up: glam::Vec3,
        pub width: u32,
        pub height: u32,
        /// Row stride of the (padded) seed buffer.
        pub stride: u32,
        pub frame: u32,
        pub spp: u32,
        /// The first sample of this dispatch (0..spp). A frame takes several dispatches of
        /// `sample_count` samples each, so that every invocation stays far below llvmpipe's
        /// limit of 65535 loop iterations per shader invocation (shared by all loops; past it
        /// loops silently exit), which many samples in one dispatch exceed.
        pub sample_index: u32,
        /// Samples of this dispatch (`sample_index .. sample_index + sample_count`): at most
        /// a bounded number of path vertices per invocation (at least one sample; the
        /// renderer's `trace` pass chooses).
        pub sample_count: u32,
        /// Maximum path vertices after the camera (1 = direct light only).
        pub max_bounces: u32,
        /// `SAMPLER_*` constant of sampling.glsl.
        pub sampler_kind: u32,
        /// `TRACE_FLAG_*` bits.
        pub flags: u32,
        /// `MASK_MODE_*`: whether the first dimensions come from a blue-noise mask.
        pub mask_mode: u32,
        pub mask_size: u32,
        /// The mask's state in this frame: the slice of a spatio-temporal mask, or the
        /// number of R2 steps a rotating mask's values have turned (0 for a shifted 2D mask).
        /// It counts frames, not `frame`, which repeats with a point cycle: a rotating mask's
        /// pixel then runs on through new jitter points instead of repeating 16.
        pub mask_step: u32,
        pub mask_offset_x: u32,
        pub mask_offset_y: u32,
        /// Sensor shift in pixels: pixel p samples the view at p + view_offset.
        pub view_offset: glam::Vec2,
        /// Nominal view size in pixels that maps onto NDC -1..1 (the image may be wider, e.g.
        /// a reference covering a whole pan).
        pub view_size: glam::Vec2,
    }
}

/// `TraceParams::flags`: hash the frame index into the seed (fresh randomness every frame).
pub const TRACE_FLAG_SALT_FRAME: u32 = 1;
/// `TraceParams::flags`: sample index = frame * spp + s (a progressive sequence per pixel).
pub const TRACE_FLAG_ADVANCE_INDEX: u32 = 2;
/// `TraceParams::flags`: primary rays through pixel centres (no anti-aliasing jitter), so the
/// error is the light-transport integrand's alone; edges of visible emitters otherwise
/// dominate every error metric.
pub const TRACE_FLAG_NO_JITTER: u32 = 4;
/// `TraceParams::flags`: the sorting key (`estimate.w`) is the luminance of the estimate
/// divided by the base colour at the primary hit (floored at `DEMODULATE_MIN_ALBEDO`): the
/// lighting a seed produced rather than its product with the texture, so a seed's rank carries
/// over across albedo edges. The image (`estimate.rgb`) is unchanged.
pub const TRACE_FLAG_DEMODULATE: u32 = 8;
/// `TraceParams::flags`: the mask dimensions read the mask at the seed's anchor (a fixed-point
/// screen position that follows the pixel's surface, `permute/follow_anchors`) instead of at
/// the pixel, so a surface keeps its mask values while the image moves.
pub const TRACE_FLAG_MASK_ANCHORED: u32 = 16;
/// `TraceParams::flags` (mask variants): each pixel records `PRIMARY_*` bits of its primary
/// hit in `primary_flags`, for the next frame's `TRACE_FLAG_SEED_JITTER_ON_TEXTURES`.
pub const TRACE_FLAG_RECORD_PRIMARY: u32 = 32;
/// `TraceParams::flags` (mask variants): a pixel whose recorded primary hit (the previous
/// frame's) was on a textured material takes its anti-aliasing jitter from its seed even
/// where the mask drives the jitter. At a texture's detail the jitter's error follows the
/// texture's gradient, which changes sign from texel to texel: that modulation moves a blue
/// mask's high-frequency error down to low frequencies, while the seeds' block nets and the
/// sort act on the error itself. At a depth edge the gradient keeps its sign and the mask's
/// jitter stays blue.
pub const TRACE_FLAG_SEED_JITTER_ON_TEXTURES: u32 = 64;
/// `TraceParams::flags`: a rotating mask's jitter dimensions (0 and 1) walk the first two
/// dimensions of a Sobol sequence, shifted by the mask's values (a Cranley-Patterson
/// rotation, so each frame is the mask moved by one constant), instead of R2, on pixels whose
/// previous primary hit was untextured (`primary_flags`): each such pixel's jitter is a
/// (0,2)-sequence over frames, whose 1D projections stratify a pixel that an edge crosses
/// better than R2's (R2's x step is close to 3/4, so its x values cluster in fours). Textured
/// pixels keep R2. Only the jitter: every pair of dimensions would walk the same two.
pub const TRACE_FLAG_SOBOL_JITTER: u32 = 128;
/// Mask dimension `dim` reads the mask at the pixel moved by `dim` times this offset, so
/// the dimensions a mask drives see different, uncorrelated parts of one mask.
pub const MASK_DIM_OFFSET_X: u32 = 37;
pub const MASK_DIM_OFFSET_Y: u32 = 71;
/// `primary_flags` bit: the primary hit's material has a texture.
pub const PRIMARY_TEXTURED: u32 = 1;
/// `TraceParams::flags`: bits from this one up select which of the first `MASK_DIMS`
/// dimensions a mask mode drives (bit d: dimension d); none set: all of them.
pub const TRACE_FLAG_MASK_DIMS_SHIFT: u32 = 16;
const _: () = assert!(TRACE_FLAG_MASK_DIMS_SHIFT + MASK_DIMS <= 32);
/// Fraction bits of an anchor coordinate: a seed packs x and y, each 16-bit fixed point
/// (8.8), so anchors wrap at 256 px and a mask tile must divide 256.
pub const ANCHOR_FRAC_BITS: u32 = 8;
/// Smallest albedo per channel the demodulated key divides by.
pub const DEMODULATE_MIN_ALBEDO: f32 = 0.02;
/// Workgroup size of the trace pass (invocations = pixels; llvmpipe runs them in SIMD batches
/// of 8 consecutive invocations, which trace_body.glsl maps to 4x2 pixel blocks: X must stay
/// a multiple of 4 and Y of 2).
pub const TRACE_GROUP_X: u32 = 8;
pub const TRACE_GROUP_Y: u32 = 8;
const _: () = assert!(TRACE_GROUP_X % 4 == 0 && TRACE_GROUP_Y % 2 == 0);
/// `TraceParams::mask_mode` values.
pub const MASK_MODE_NONE: u32 = 0;
pub const MASK_MODE_2D: u32 = 1;
pub const MASK_MODE_SPATIOTEMPORAL: u32 = 2;
/// One 2D mask, not shifted: each dimension's value is rotated by frame * alpha (mod 1), alpha
/// R2's 1/g or 1/g^2 by the dimension's parity. A pixel's values over frames are then an R2
/// sequence per pair of dimensions (low discrepancy in time), and each frame is the mask's
/// blue pattern, rotated.
pub const MASK_MODE_ROTATE: u32 = 3;
/// Sample dimensions driven by the mask in the mask modes: camera jitter and the first vertex.
pub const MASK_DIMS: u32 = 9;
/// Sample dimensions: 0-1 camera jitter; then per path vertex b, base 2 + 7b: light point (2),
/// light choice, lobe choice, BSDF direction (2), Russian roulette.
pub const DIMS_PER_BOUNCE: u32 = 7;
// The trace draws a vertex's dimensions as the four sampler pairs that hold them
// (path.glsl vertex_bits), which is written for seven.
const _: () = assert!(DIMS_PER_BOUNCE == 7);

gpu_struct! {
    /// Push constants of `trace/accumulate` and `trace/tonemap`.
    pub struct ImageParams {
        pub width: u32,
        pub height: u32,
        /// accumulate: frames already in the running mean (0 resets it).
        pub count: u32,
        /// tonemap: exposure multiplier applied before the sRGB curve.
        pub exposure: f32,
    }
}

gpu_struct! {
    /// Push constants of `view/present`: composes the renderers' outputs into the window's
    /// packed 8-bit pixels (one invocation per window pixel).
    pub struct PresentParams {
        /// Window (swapchain) size in pixels.
        pub out_width: u32,
        pub out_height: u32,
        /// Render size of every source (nearest upscaling to the window).
        pub src_width: u32,
        pub src_height: u32,
        /// Window column where the right-hand source starts (split-screen only).
        pub split_x: u32,
        /// `PRESENT_FLAG_*` bits.
        pub flags: u32,
        /// Error view: |accum - reference| * error_scale, then the sRGB curve.
        pub error_scale: f32,
    }
}

/// `PresentParams::flags`: left half from source A, right half from source B, with a divider.
pub const PRESENT_FLAG_SPLIT: u32 = 1;
/// `PresentParams::flags`: show the scaled absolute error against the reference instead.
pub const PRESENT_FLAG_ERROR: u32 = 2;
/// `PresentParams::flags`: the window's bytes are B, G, R, A (else R, G, B, A).
pub const PRESENT_FLAG_BGRA: u32 = 4;
/// Divider width in window pixels (split-screen).
pub const PRESENT_DIVIDER_WIDTH: u32 = 2;

/// The loops of the trace shader that its loop-statistics variant (`trace/trace_loop_stats`)
/// counts, as `TRACE_LOOP_<NAME>` in the params header. llvmpipe runs a loop for a whole SIMD
/// batch while any lane is still in it, so per loop the iterations the batches ran and the
/// lanes busy in them show where divergence costs time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum TraceLoop {
    /// One path vertex (trace_paths).
    PathVertex,
    /// The binary search of the light CDF (sample_light).
    LightChoice,
    /// Closest hit: one descent, its leaf, one pop (the outer loop).
    ClosestHit,
    /// Closest hit: one interior node (both children tested).
    ClosestDescend,
    /// Closest hit: one triangle of a leaf.
    ClosestLeaf,
    /// Closest hit: one stack entry popped.
    ClosestPop,
    /// Occlusion: one walk to a leaf and its triangles (the outer loop).
    Occlusion,
    /// Occlusion: one node of the skip-link walk.
    OcclusionWalk,
    /// Occlusion: one triangle of a leaf.
    OcclusionLeaf,
}

impl TraceLoop {
    pub const ALL: [Self; 9] = [
        Self::PathVertex,
        Self::LightChoice,
        Self::ClosestHit,
        Self::ClosestDescend,
        Self::ClosestLeaf,
        Self::ClosestPop,
        Self::Occlusion,
        Self::OcclusionWalk,
        Self::OcclusionLeaf,
    ];

    /// Lower-case name (tables, CLI output).
    pub fn name(self) -> &'static str {
        match self {
            Self::PathVertex => "path vertex",
            Self::LightChoice => "light choice",
            Self::ClosestHit => "closest hit",
            Self::ClosestDescend => "descend",
            Self::ClosestLeaf | Self::OcclusionLeaf => "leaf triangle",
            Self::ClosestPop => "pop",
            Self::Occlusion => "occlusion",
            Self::OcclusionWalk => "walk node",
        }
    }

    /// Whether the loop runs inside the closest-hit or occlusion loop listed before it.
    pub fn nested(self) -> bool {
        !matches!(
            self,
            Self::PathVertex | Self::LightChoice | Self::ClosestHit | Self::Occlusion
        )
    }

    /// The header constant, `TRACE_LOOP_<NAME>`.
    pub fn glsl_name(self) -> &'static str {
        match self {
            Self::PathVertex => "TRACE_LOOP_PATH_VERTEX",
            Self::LightChoice => "TRACE_LOOP_LIGHT_CHOICE",
            Self::ClosestHit => "TRACE_LOOP_CLOSEST_HIT",
            Self::ClosestDescend => "TRACE_LOOP_CLOSEST_DESCEND",
            Self::ClosestLeaf => "TRACE_LOOP_CLOSEST_LEAF",
            Self::ClosestPop => "TRACE_LOOP_CLOSEST_POP",
            Self::Occlusion => "TRACE_LOOP_OCCLUSION",
            Self::OcclusionWalk => "TRACE_LOOP_OCCLUSION_WALK",
            Self::OcclusionLeaf => "TRACE_LOOP_OCCLUSION_LEAF",
        }
    }
}

/// Number of [`TraceLoop`]s.
pub const TRACE_LOOP_COUNT: u32 = TraceLoop::ALL.len() as u32;
/// The trace pass's status buffer (binding 11): word 0 the most loop iterations of one batch
/// (the loop-limit guard); from word TRACE_STATUS_LOOPS, four words per [`TraceLoop`] (loop
/// statistics variant only): lane iterations (low, high word), batch iterations (low, high).
pub const TRACE_STATUS_LOOPS: u32 = 4;
pub const TRACE_STATUS_WORDS: u32 = TRACE_STATUS_LOOPS + 4 * TRACE_LOOP_COUNT;

#[cfg(test)]
mod tests {
    use super::*;

    /// The shader indexes its counters by discriminant and the host reads them in `ALL` order.
    #[test]
    fn trace_loops_are_listed_in_discriminant_order() {
        for (i, l) in TraceLoop::ALL.into_iter().enumerate() {
            assert_eq!(l as usize, i, "{l:?}");
            assert!(l.glsl_name().starts_with("TRACE_LOOP_"));
        }
        let names: std::collections::HashSet<_> =
            TraceLoop::ALL.iter().map(|l| l.glsl_name()).collect();
        assert_eq!(names.len(), TraceLoop::ALL.len());
    }

    /// The sample key walks a Hilbert curve through the grid: a bijection onto its cells,
    /// consecutive keys are 4-neighbours, every aligned 2^k x 2^k square of cells takes one
    /// aligned run of 4^k keys, and the bits below the grid are ignored.
    #[test]
    fn sample_key_is_a_hilbert_curve_on_its_grid() {
        let n = 1u32 << SAMPLE_KEY_BITS;
        let shift = 32 - SAMPLE_KEY_BITS;
        let mut at = vec![None; (n * n) as usize];
        for y in 0..n {
            for x in 0..n {
                let low = x.wrapping_mul(0x9E37_79B9) >> SAMPLE_KEY_BITS;
                let c = sample_key_code(x << shift | low, y << shift | low >> 1);
                assert!(c < n * n);
                assert_eq!(at[c as usize], None, "({x}, {y}) repeats {c}");
                at[c as usize] = Some((x, y));
            }
        }
        let at: Vec<(u32, u32)> = at.into_iter().map(Option::unwrap).collect();
        for w in at.windows(2) {
            let (a, b) = (w[0], w[1]);
            assert_eq!(a.0.abs_diff(b.0) + a.1.abs_diff(b.1), 1, "{a:?} -> {b:?}");
        }
        for k in 0..=SAMPLE_KEY_BITS {
            let side = 1u32 << k;
            for qy in (0..n).step_by(side as usize) {
                for qx in (0..n).step_by(side as usize) {
                    let codes = (qy..qy + side)
                        .flat_map(|y| (qx..qx + side).map(move |x| (x, y)))
                        .map(|(x, y)| sample_key_code(x << shift, y << shift));
                    let (lo, hi) = codes.fold((u32::MAX, 0), |(l, h), c| (l.min(c), h.max(c)));
                    assert_eq!(hi - lo + 1, side * side, "square {side} at ({qx}, {qy})");
                    assert_eq!(lo % (side * side), 0, "square {side} at ({qx}, {qy})");
                }
            }
        }
    }
}
