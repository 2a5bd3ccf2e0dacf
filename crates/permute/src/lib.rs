//! The seed-permutation passes of Heitz & Belcour 2019, on the GPU and as CPU twins.
//!
//! Seed buffer layout: one u32 per pixel of the *padded* screen, row stride
//! [`Screen::stride`]; the padded size is the screen rounded up to a multiple of the mask
//! tile N. Only visible pixels are traced and sorted; the retargeting permutation runs over the
//! whole padded screen as a torus, which makes it a bijection for any resolution (the tile
//! permutation repeats exactly over a padded screen). Seeds parked in the padding are never
//! lost: they come back into view like fresh seeds. The buffer is a permutation at all times.
//!
//! Frame t sorts against mask M_t(p) = M((p + o_t) mod N) with o_t = t*s mod N for the integer
//! shift s the retarget table was optimised for (never a rounded R2 value: docs/algorithm.md).
mod anchors;
mod cpu;
mod cycle;
mod edges;
mod gpu;
mod history;
mod pairs_gate;
mod reproject;
mod reproject_gpu;
mod similar;
mod skew;

pub use anchors::{
    ANCHOR_WRAP, FollowAnchors, anchor_at, anchor_pixel, follow_anchors_cpu, initial_anchors,
};
pub use blueshift_layout::motion::{GBufferTexel, MotionParams, REPROJECT_NONE};
pub use blueshift_layout::params::SortParams;
pub use cpu::{pack_mask_moves, retarget_seeds_cpu, sort_key, sort_seeds_cpu};
pub use cycle::{
    CYCLE_FRAMES, CycleOutput, CycleParams, cycle_history_bytes, cycle_keys_cpu, sample_key,
    with_cycle,
};
pub use edges::classify_pixels_cpu;
pub use gpu::{CycleInput, PermutePasses, SortInput, SortVariant};
pub use history::{HistoryKeys, history_key_cpu};
pub use pairs_gate::{PAIRS_MAX_SKEWED_SHARE, PairsGate, SKEWED_SHARE_ALPHA};
pub use reproject::{
    Reprojected, mean_motion, project_previous, reproject_motion_cpu, reproject_seeds_cpu,
};
pub use reproject_gpu::Reprojection;
pub use similar::similar;

/// Errors of the permutation passes.
#[derive(Debug, thiserror::Error)]
pub enum PermuteError {
    #[error(transparent)]
    Device(#[from] blueshift_device::DeviceError),
    #[error("block size {0} is outside 2..=8")]
    BlockSize(u32),
    #[error("{0}")]
    Invalid(String),
}

pub type Result<T, E = PermuteError> = std::result::Result<T, E>;

/// Screen geometry shared by the passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Screen {
    pub width: u32,
    pub height: u32,
    /// Mask tile edge N.
    pub tile: u32,
}

impl Screen {
    pub fn new(width: u32, height: u32, tile: u32) -> Result<Self> {
        if width == 0 || height == 0 || tile == 0 {
            return Err(PermuteError::Invalid(format!(
                "screen {width}x{height} with mask tile {tile}: all must be positive"
            )));
        }
        Ok(Self {
            width,
            height,
            tile,
        })
    }
    /// Row stride of the seed buffer (width padded to a multiple of the tile).
    pub fn stride(&self) -> u32 {
        self.width.div_ceil(self.tile) * self.tile
    }
    pub fn padded_height(&self) -> u32 {
        self.height.div_ceil(self.tile) * self.tile
    }
    /// Seeds in the padded buffer.
    pub fn seed_count(&self) -> usize {
        self.stride() as usize * self.padded_height() as usize
    }
    /// Push constants for sorting frame `frame`.
    pub fn sort_params(&self, block: u32, offset: (u32, u32)) -> Result<SortParams> {
        self.sort_params_on_grid(block, offset, (0, 0))
    }
    /// Push constants for sorting on a block grid offset by `grid` (each < `block`).
    pub fn sort_params_on_grid(
        &self,
        block: u32,
        offset: (u32, u32),
        grid: (u32, u32),
    ) -> Result<SortParams> {
        if !(2..=8).contains(&block) {
            return Err(PermuteError::BlockSize(block));
        }
        if grid.0 >= block || grid.1 >= block {
            return Err(PermuteError::Invalid(format!(
                "block grid offset {grid:?} must be below the block size {block}"
            )));
        }
        Ok(SortParams {
            width: self.width,
            height: self.height,
            stride: self.stride(),
            padded_height: self.padded_height(),
            block,
            mask_size: self.tile,
            offset_x: offset.0,
            offset_y: offset.1,
            grid_x: grid.0,
            grid_y: grid.1,
            pairs: 0,
            phase: 0,
            count_skew: 0,
            mask_layer: 0,
            cycle_phase: 0,
            cycle_next_phase: 0,
            cycle_next_valid: 0,
            cycle_mean_count: 0,
            cycle_sample_keys: 0,
        })
    }
}

/// Blocks per row and column of the sorting grid: blocks start at (k * B - G), so with a grid
/// offset G the first and last blocks of a row or column may be partial.
pub fn block_counts(p: &SortParams) -> (u32, u32) {
    (
        (p.width + p.grid_x).div_ceil(p.block),
        (p.height + p.grid_y).div_ceil(p.block),
    )
}

/// The visible pixels of block `index` (row-major over `block_counts`), in row-major in-block
/// order, each with its in-block index `ty * B + tx`.
pub fn block_pixels(p: &SortParams, index: u32) -> Vec<(u32, u32, usize)> {
    let (bx, b) = (block_counts(p).0, p.block as i64);
    let ox = (index % bx) as i64 * b - p.grid_x as i64;
    let oy = (index / bx) as i64 * b - p.grid_y as i64;
    let mut v = Vec::with_capacity((b * b) as usize);
    for ty in 0..b {
        for tx in 0..b {
            let (x, y) = (ox + tx, oy + ty);
            if x >= 0 && y >= 0 && x < p.width as i64 && y < p.height as i64 {
                v.push((x as u32, y as u32, (ty * b + tx) as usize));
            }
        }
    }
    v
}

/// Grid offset of frame `frame` for the shifted-grid methods: a 4-frame cycle (0, 0),
/// (B/2, B/2), (B/4, 3B/4), (3B/4, B/4), so every block border of one frame lies inside a block
/// of the next, and seeds of a still image mix over more than two partitions. The offsets are
/// even for B = 8: odd ones measured worse with the thin-class pairs, whose checkerboard is
/// fixed to the screen (docs/algorithm.md, "Extensions").
pub fn grid_offset(frame: u64, block: u32) -> (u32, u32) {
    let (h, q) = (block / 2, block / 4);
    [(0, 0), (h, h), (q, q + h), (q + h, q)][(frame % 4) as usize]
}

/// Checkerboard phase of the antithetic pairs in `frame`: alternating, or with `hashed` a hash
/// bit of the frame. History keys need the hash: a pan by an odd number of pixels per frame
/// cancels the alternation, so a surface point would always take the lower (or upper) half of
/// its class's keys; its history mean then carries that bias back into its keys (edges scene,
/// pan 1, 4 spp: P1 0.813 alternating, 0.751 hashed). The other grid methods keep the
/// alternation their reports were measured with (hashed changes them within noise).
pub fn pair_phase(frame: u64, hashed: bool) -> u32 {
    if hashed {
        blueshift_sampling::rng::pcg_hash(frame as u32 ^ (frame >> 32) as u32) & 1
    } else {
        (frame % 2) as u32
    }
}

/// The next mask offset when the image moved by `motion` pixels: the mask moves with the
/// image, so a seed reprojected with its surface meets the mask value the retarget table
/// prepared it for: o' = o + s - motion (mod n).
pub fn follow_offset(
    offset: (u32, u32),
    shift: (u32, u32),
    motion: (i32, i32),
    n: u32,
) -> (u32, u32) {
    let step =
        |o: u32, s: u32, m: i32| ((o as i64 + s as i64 - m as i64).rem_euclid(n as i64)) as u32;
    (
        step(offset.0, shift.0, motion.0),
        step(offset.1, shift.1, motion.1),
    )
}

/// Where sequence `sequence` lays every blue-noise mask over the screen: a toroidal shift
/// (pixels, to be taken modulo the mask's side) added to every mask read, so that independent
/// sequences also draw independent windows of the masks. A mask window is a draw too: on one
/// scene and path, five shifts of the same method spread by 0.01 per frame and 0.05 after TAA
/// (docs/experiments.md), so sequences that share it understate the error of a mean.
/// Sequence 0 (what `render` and `view` show) keeps the masks where they are.
pub fn sequence_mask_shift(sequence: u32) -> (u32, u32) {
    if sequence == 0 {
        return (0, 0);
    }
    // One hash per axis, the second chained on the first.
    use blueshift_sampling::rng::lowbias32;
    let h = lowbias32(sequence);
    (h, lowbias32(h ^ 0x9e37_79b9))
}

/// `offset` moved by `shift` on a mask of side `n`.
pub fn add_mask_shift(offset: (u32, u32), shift: (u32, u32), n: u32) -> (u32, u32) {
    let n = n.max(1);
    (
        ((offset.0 % n) + shift.0 % n) % n,
        ((offset.1 % n) + shift.1 % n) % n,
    )
}

/// Mask offset of frame `frame`: exactly `frame * shift mod n` per axis.
pub fn mask_offset(frame: u64, shift: (u32, u32), n: u32) -> (u32, u32) {
    let n = n as u64;
    (
        ((frame % n) * shift.0 as u64 % n) as u32,
        ((frame % n) * shift.1 as u64 % n) as u32,
    )
}

/// Whether `seeds` is a permutation of `initial` (same multiset; seeds are distinct).
pub fn is_permutation_of(seeds: &[u32], initial: &[u32]) -> bool {
    let (mut a, mut b) = (seeds.to_vec(), initial.to_vec());
    a.sort_unstable();
    b.sort_unstable();
    a == b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Under a pan of one pixel per frame, a surface point's checkerboard colour is (its
    /// screen x, which drops by one per frame, plus the phase) mod 2: constant with the
    /// alternating phase, but both colours about equally often with the hashed one.
    #[test]
    fn hashed_pair_phase_does_not_lock_to_an_odd_pan() {
        let colour = |hashed: bool, t: u64| (pair_phase(t, hashed) as u64 + 1000 - t) % 2;
        let frames = 1..=256u64;
        let alternating: Vec<u64> = frames.clone().map(|t| colour(false, t)).collect();
        assert!(alternating.iter().all(|&c| c == alternating[0]));
        let lower = frames.filter(|&t| colour(true, t) == 0).count();
        assert!(
            (96..=160).contains(&lower),
            "{lower} of 256 frames in one colour"
        );
    }

    /// Both block borders move every frame (a border of one frame lies inside a block of the
    /// next), the offsets stay below B, and a still image sees four partitions.
    #[test]
    fn grid_offsets_move_every_border_each_frame() {
        for b in [4, 8] {
            let g: Vec<(u32, u32)> = (0..9).map(|f| grid_offset(f, b)).collect();
            for w in g.windows(2) {
                assert!(w[0].0 != w[1].0 && w[0].1 != w[1].1, "B={b}: {g:?}");
            }
            assert!(g.iter().all(|&(x, y)| x < b && y < b), "B={b}: {g:?}");
            let mut distinct = g.clone();
            distinct.sort_unstable();
            distinct.dedup();
            assert_eq!(distinct.len(), 4, "B={b}: {g:?}");
        }
    }

    /// Every visible pixel lies in exactly one block, at its in-block index, for every grid
    /// offset, on screens that are multiples of neither the block nor the tile.
    #[test]
    fn blocks_partition_the_screen_on_every_grid() {
        for (w, h, b) in [(13, 7, 2), (37, 23, 3), (64, 48, 4), (99, 61, 8)] {
            let sc = Screen::new(w, h, 16).unwrap();
            for gx in 0..b {
                for gy in 0..b {
                    let p = sc.sort_params_on_grid(b, (0, 0), (gx, gy)).unwrap();
                    let (bx, by) = block_counts(&p);
                    let mut hits = vec![0u32; (w * h) as usize];
                    for k in 0..bx * by {
                        let px = block_pixels(&p, k);
                        assert!(px.len() <= (b * b) as usize);
                        for (x, y, i) in px {
                            let (ox, oy) = ((k % bx) * b, (k / bx) * b);
                            assert_eq!(((x + gx - ox) + (y + gy - oy) * b) as usize, i);
                            hits[(y * w + x) as usize] += 1;
                        }
                    }
                    assert!(
                        hits.iter().all(|&c| c == 1),
                        "{w}x{h} B={b} grid ({gx}, {gy})"
                    );
                }
            }
            assert!(sc.sort_params_on_grid(b, (0, 0), (b, 0)).is_err());
        }
    }
}
