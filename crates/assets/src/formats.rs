//! Readers and writers of the precomputed assets (tools/README.md has the byte layouts).
//!
//! * **Mask** (`.r16`): `n * n` little-endian `u16` ranks, row-major (`y * n + x`), no header.
//!   `n` is inferred as `sqrt(len / 2)` and must be a power of two in `2..=256`; the ranks
//!   must be a permutation of `0..n*n`.
//! * **Spatio-temporal mask** (`.r16`): `t` slices of `n * n` ranks, slice-major
//!   (`(s * n + y) * n + x`), no header; `n` is given by the caller (file names carry it,
//!   e.g. `stbn64x32.r16`). Each slice is a permutation of `0..n*n`.
//! * **Retarget table** (`.bin`): a 16-byte header, then `n * n` pairs of `i8` `(dx, dy)`
//!   indexed by mask coordinate `u = (x, y)` at `y * n + x`; see [`RetargetTable`].

use std::path::Path;

use crate::error::{AssetError, Result, write_atomic};

/// Magic bytes of a retarget table file.
pub const RETARGET_MAGIC: [u8; 4] = *b"BSRT";
/// Current retarget table format version.
pub const RETARGET_VERSION: u16 = 1;
/// Size of the retarget header in bytes.
pub const RETARGET_HEADER_LEN: usize = 16;

/// The largest asset file read: the 64x64x32 volumes and retarget tables are a few MiB.
const MAX_ASSET_BYTES: u64 = 256 << 20;

fn read(path: &Path) -> Result<Vec<u8>> {
    crate::files::read_regular(path, MAX_ASSET_BYTES).map_err(|e| AssetError::io(path, e))
}

fn u16s(bytes: &[u8]) -> Vec<u16> {
    bytes
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect()
}

fn check_permutation(ranks: &[u16], what: &str) -> std::result::Result<(), String> {
    let mut seen = vec![false; ranks.len()];
    for (i, &r) in ranks.iter().enumerate() {
        let r = r as usize;
        if r >= ranks.len() {
            return Err(format!(
                "{what}: rank {r} at index {i} out of range 0..{}",
                ranks.len()
            ));
        }
        if std::mem::replace(&mut seen[r], true) {
            return Err(format!(
                "{what}: rank {r} appears twice (not a permutation)"
            ));
        }
    }
    Ok(())
}

fn check_side(n: usize) -> std::result::Result<(), String> {
    if !(2..=256).contains(&n) || !n.is_power_of_two() {
        return Err(format!("side {n} is not a power of two in 2..=256"));
    }
    Ok(())
}

/// A square dither mask of ranks: every value of `0..n*n` exactly once.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mask {
    /// Side (power of two, <= 256).
    pub n: usize,
    /// `n * n` ranks, row-major.
    pub ranks: Vec<u16>,
}

impl Mask {
    /// Validates side and permutation.
    pub fn new(n: usize, ranks: Vec<u16>) -> Result<Mask> {
        check_side(n).map_err(AssetError::Invalid)?;
        if ranks.len() != n * n {
            return Err(AssetError::Invalid(format!(
                "mask {n}x{n} with {} ranks",
                ranks.len()
            )));
        }
        check_permutation(&ranks, "mask").map_err(AssetError::Invalid)?;
        Ok(Mask { n, ranks })
    }

    /// Rank at `(x, y)`, wrapping toroidally.
    pub fn rank(&self, x: i64, y: i64) -> u16 {
        let n = self.n as i64;
        self.ranks[(y.rem_euclid(n) * n + x.rem_euclid(n)) as usize]
    }

    /// Dither threshold of a rank: `(rank + 0.5) / n^2`, uniform in (0, 1).
    pub fn threshold(&self, rank: u16) -> f32 {
        (f32::from(rank) + 0.5) / (self.n * self.n) as f32
    }

    /// The `.r16` bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        self.ranks.iter().flat_map(|r| r.to_le_bytes()).collect()
    }
}

/// Loads a 2D `.r16` mask (module docs), checking size and permutation.
pub fn load_mask(path: &Path) -> Result<Mask> {
    Mask::from_bytes(&read(path)?, path)
}

impl Mask {
    /// Parses and validates `.r16` bytes; `path` only names the source in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Mask> {
        mask_from_bytes(bytes, path)
    }
}

fn mask_from_bytes(bytes: &[u8], path: &Path) -> Result<Mask> {
    if bytes.len() % 2 != 0 {
        return Err(AssetError::format(
            path,
            format!("odd length {} for u16 data", bytes.len()),
        ));
    }
    let count = bytes.len() / 2;
    let n = (count as f64).sqrt().round() as usize;
    if n * n != count {
        return Err(AssetError::format(
            path,
            format!("{count} values is not a square mask"),
        ));
    }
    check_side(n).map_err(|r| AssetError::format(path, r))?;
    let ranks = u16s(bytes);
    check_permutation(&ranks, "mask").map_err(|r| AssetError::format(path, r))?;
    Ok(Mask { n, ranks })
}

/// Writes a 2D mask as `.r16`, atomically.
pub fn save_mask(mask: &Mask, path: &Path) -> Result<()> {
    write_atomic(path, &mask.to_bytes())
}

/// A spatio-temporal mask: `t` slices of `n x n`, each a permutation of `0..n*n`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StbnVolume {
    /// Side of each slice.
    pub n: usize,
    /// Number of slices (frames).
    pub t: usize,
    /// `t * n * n` ranks, slice-major.
    pub ranks: Vec<u16>,
}

impl StbnVolume {
    /// Validates side, slice count and every slice's permutation.
    pub fn new(n: usize, t: usize, ranks: Vec<u16>) -> Result<StbnVolume> {
        check_volume(n, t, &ranks).map_err(AssetError::Invalid)?;
        Ok(StbnVolume { n, t, ranks })
    }

    /// Slice `s` as a 2D mask.
    pub fn slice(&self, s: usize) -> Result<Mask> {
        let a = self.n * self.n;
        let r = self
            .ranks
            .get(s * a..(s + 1) * a)
            .ok_or_else(|| AssetError::Invalid(format!("slice {s} of {}", self.t)))?;
        Mask::new(self.n, r.to_vec())
    }

    /// The `.r16` bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        self.ranks.iter().flat_map(|r| r.to_le_bytes()).collect()
    }
}

fn check_volume(n: usize, t: usize, ranks: &[u16]) -> std::result::Result<(), String> {
    check_side(n)?;
    let a = n * n;
    if t == 0 || ranks.len() != a * t {
        return Err(format!(
            "{} values is not {t} slices of {n}x{n}",
            ranks.len()
        ));
    }
    for (s, slice) in ranks.chunks_exact(a).enumerate() {
        check_permutation(slice, &format!("slice {s}"))?;
    }
    Ok(())
}

/// Loads a spatio-temporal `.r16` of side `n`; the slice count is inferred from the length.
pub fn load_stbn(path: &Path, n: usize) -> Result<StbnVolume> {
    StbnVolume::from_bytes(&read(path)?, n, path)
}

impl StbnVolume {
    /// Parses and validates spatio-temporal `.r16` bytes of side `n`; `path` only names the
    /// source in errors.
    pub fn from_bytes(bytes: &[u8], n: usize, path: &Path) -> Result<StbnVolume> {
        stbn_from_bytes(bytes, n, path)
    }
}

fn stbn_from_bytes(bytes: &[u8], n: usize, path: &Path) -> Result<StbnVolume> {
    let a = n.checked_mul(n).and_then(|a| a.checked_mul(2)).unwrap_or(0);
    if a == 0 || bytes.len() % a != 0 || bytes.is_empty() {
        return Err(AssetError::format(
            path,
            format!(
                "length {} is not a whole number of {n}x{n} u16 slices",
                bytes.len()
            ),
        ));
    }
    let t = bytes.len() / a;
    let ranks = u16s(bytes);
    check_volume(n, t, &ranks).map_err(|r| AssetError::format(path, r))?;
    Ok(StbnVolume { n, t, ranks })
}

/// Writes a spatio-temporal mask as `.r16`, atomically.
pub fn save_stbn(v: &StbnVolume, path: &Path) -> Result<()> {
    write_atomic(path, &v.to_bytes())
}

/// A retargeting permutation of the mask tile (docs/algorithm.md).
///
/// **Semantics.** Frame `t` uses the mask `M_t(x) = M(x + o_t)`, `o_t = t * s mod n`, so a
/// screen pixel `x` sees mask coordinate `u = x + o_t`. After sorting, the seed at `x` suits
/// the value `M(u)`. The runtime reads `d = offsets[u]` and moves that seed to pixel `x + d`,
/// i.e. to mask coordinate `u + d` of frame `t`'s mask. In frame `t + 1` that pixel sees
/// `M_{t+1}(x + d) = M(u + d + s)`, and the table was optimised so that
/// `M(u + d(u) + s) ~= M(u)`: writing `pi(u) = u + d(u)`, it minimises
/// `sum_u |M(u) - M(pi(u) + s)|` over permutations `pi` of the torus with
/// `|d(u)|^2 <= radius^2` (Euclidean disc). Because `pi` is a permutation,
/// `x -> x + d(x + o_t)` is a bijection of any screen that is a multiple of `n` and wraps at
/// its edges. The table does not depend on `t`; `o_t` only selects where it is read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RetargetTable {
    /// Mask side.
    pub n: usize,
    /// The per-frame mask shift `s` the table was optimised for.
    pub shift: (u32, u32),
    /// Maximum Euclidean displacement.
    pub radius: u32,
    /// `(dx, dy)` per mask coordinate, row-major.
    pub offsets: Vec<(i8, i8)>,
}

impl RetargetTable {
    /// Validates side, shift, radius, displacement bound and bijectivity.
    pub fn new(n: usize, shift: (u32, u32), radius: u32, offsets: Vec<(i8, i8)>) -> Result<Self> {
        let t = RetargetTable {
            n,
            shift,
            radius,
            offsets,
        };
        t.check().map_err(AssetError::Invalid)?;
        Ok(t)
    }

    /// Destination mask coordinate index `pi(u)` of mask coordinate `(x, y)`.
    pub fn target(&self, x: usize, y: usize) -> usize {
        let n = self.n as i64;
        let (dx, dy) = self.offsets[y * self.n + x];
        let tx = (x as i64 + i64::from(dx)).rem_euclid(n);
        let ty = (y as i64 + i64::from(dy)).rem_euclid(n);
        (ty * n + tx) as usize
    }

    fn check(&self) -> std::result::Result<(), String> {
        let n = self.n;
        if !(2..=4096).contains(&n) || !n.is_power_of_two() {
            return Err(format!("side {n} is not a power of two in 2..=4096"));
        }
        if self.shift.0 as usize >= n || self.shift.1 as usize >= n {
            return Err(format!("shift {:?} not below side {n}", self.shift));
        }
        if self.radius > 127 {
            return Err(format!("radius {} does not fit i8 offsets", self.radius));
        }
        if self.offsets.len() != n * n {
            return Err(format!("{} offsets for a {n}x{n} tile", self.offsets.len()));
        }
        let r2 = i64::from(self.radius).pow(2);
        let mut hit = vec![false; n * n];
        for y in 0..n {
            for x in 0..n {
                let (dx, dy) = self.offsets[y * n + x];
                if i64::from(dx).pow(2) + i64::from(dy).pow(2) > r2 {
                    return Err(format!(
                        "displacement ({dx}, {dy}) at ({x}, {y}) exceeds radius {}",
                        self.radius
                    ));
                }
                if std::mem::replace(&mut hit[self.target(x, y)], true) {
                    return Err(format!("not a bijection: ({x}, {y}) hits a taken target"));
                }
            }
        }
        Ok(())
    }

    /// The `.bin` bytes (header + offsets).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(RETARGET_HEADER_LEN + 2 * self.offsets.len());
        b.extend_from_slice(&RETARGET_MAGIC);
        for v in [
            RETARGET_VERSION,
            self.n as u16,
            self.shift.0 as u16,
            self.shift.1 as u16,
            self.radius as u16,
            0,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for &(dx, dy) in &self.offsets {
            b.extend_from_slice(&[dx as u8, dy as u8]);
        }
        b
    }

    /// Parses and validates `.bin` bytes; `path` only names the source in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Self> {
        if bytes.len() < RETARGET_HEADER_LEN || bytes[..4] != RETARGET_MAGIC {
            return Err(AssetError::format(
                path,
                "not a retarget table (magic \"BSRT\" missing)",
            ));
        }
        let h = u16s(&bytes[4..RETARGET_HEADER_LEN]);
        if h[0] != RETARGET_VERSION {
            return Err(AssetError::format(
                path,
                format!("unsupported version {}", h[0]),
            ));
        }
        if h[5] != 0 {
            return Err(AssetError::format(
                path,
                format!("reserved header field is {}, must be 0", h[5]),
            ));
        }
        let n = usize::from(h[1]);
        let body = &bytes[RETARGET_HEADER_LEN..];
        if body.len() != 2 * n * n {
            return Err(AssetError::format(
                path,
                format!(
                    "{} offset bytes for a {n}x{n} table (need {})",
                    body.len(),
                    2 * n * n
                ),
            ));
        }
        let offsets = body
            .chunks_exact(2)
            .map(|c| (c[0] as i8, c[1] as i8))
            .collect();
        let t = RetargetTable {
            n,
            shift: (u32::from(h[2]), u32::from(h[3])),
            radius: u32::from(h[4]),
            offsets,
        };
        t.check().map_err(|r| AssetError::format(path, r))?;
        Ok(t)
    }
}

/// Loads and validates a retarget table `.bin`.
pub fn load_retarget(path: &Path) -> Result<RetargetTable> {
    RetargetTable::from_bytes(&read(path)?, path)
}

/// Writes a retarget table `.bin`, atomically.
pub fn save_retarget(t: &RetargetTable, path: &Path) -> Result<()> {
    write_atomic(path, &t.to_bytes())
}

#[cfg(test)]
#[path = "formats_tests.rs"]
mod tests;
