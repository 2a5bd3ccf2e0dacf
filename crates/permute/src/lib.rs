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
//! shift s the retarget table was optimised for (never a rounded R2 value: algorithm.md).
mod cpu;
mod edges;
mod gpu;
mod reproject;
mod reproject_gpu;
mod similar;

pub use blueshift_layout::motion::{GBufferTexel, MotionParams, REPROJECT_NONE};
pub use blueshift_layout::params::{RetargetParams, SortParams};
pub use cpu::{retarget_seeds_cpu, sort_key, sort_seeds_cpu};
pub use edges::classify_pixels_cpu;
pub use gpu::PermutePasses;
pub use reproject::{Reprojected, mean_motion, reproject_motion_cpu, reproject_seeds_cpu};
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
        if !(2..=8).contains(&block) {
            return Err(PermuteError::BlockSize(block));
        }
        Ok(SortParams {
            width: self.width,
            height: self.height,
            stride: self.stride(),
            block,
            mask_size: self.tile,
            offset_x: offset.0,
            offset_y: offset.1,
        })
    }
    pub fn retarget_params(&self, offset: (u32, u32)) -> RetargetParams {
        RetargetParams {
            padded_width: self.stride(),
            padded_height: self.padded_height(),
            mask_size: self.tile,
            offset_x: offset.0,
            offset_y: offset.1,
        }
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
