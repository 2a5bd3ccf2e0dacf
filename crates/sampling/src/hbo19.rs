//! Screen-space blue-noise sampler in the manner of Heitz, Belcour, Ostromoukhov, Coeurjolly &
//! Iehl 2019 (HBO+19): every pixel runs the same Owen-scrambled Sobol sequence, but with its
//! own keys, and the keys are arranged over a tile (by `blueshift-tools keys`) so that the
//! errors of neighbouring pixels differ, i.e. the error is blue noise already in frame 0.
//!
//! Dimensions come in pairs (2p, 2p+1) = Sobol dimensions (0, 1), a (0,m,2)-net, because the
//! path tracer consumes them in pairs (camera jitter, light point, light choice + lobe, BSDF
//! direction). Each (pixel, pair) has a key `[scramble, rank]`:
//! * the sample index is XORed with `rank` (< spp: reorders the pixel's spp samples so that
//!   prefixes are blue too; always 0 at 1 spp, as in the paper),
//! * then shuffled by a nested uniform scramble seeded with `scramble` (Burley's "padding": it
//!   decorrelates the pairs of one pixel and maps aligned blocks of indices onto aligned blocks,
//!   so the first 2^m points stay a (0,m,2)-net),
//! * and each coordinate is Owen-scrambled with a seed derived from `scramble`.
//!
//! The "seed" of a pixel is a tile position `y * tile + x` (wrapped modulo tile^2); dimensions
//! past the table's pairs fall back to plain Owen-Sobol with that seed.
//!
//! File format (`.bin`, little endian): magic `BSKY`, version `u16`, tile `u16`, spp `u16`,
//! pairs `u16`, 6 zero bytes; then `tile * tile * pairs` keys `[scramble: u32, rank: u32]`
//! at `(y * tile + x) * pairs + pair`.

use std::path::Path;

use crate::sobol::{hash_combine, nested_uniform_scramble, owen_sobol_bits, sobol};

/// Magic bytes of a key table file.
pub const KEYS_MAGIC: [u8; 4] = *b"BSKY";
/// Current key table format version.
pub const KEYS_VERSION: u16 = 1;
/// Header size in bytes.
pub const KEYS_HEADER_LEN: usize = 16;
/// Most dimension pairs a table may hold.
pub const MAX_PAIRS: u32 = 16;

/// Why a key table was rejected.
#[derive(Debug, thiserror::Error)]
pub enum KeysError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}: {msg}")]
    Invalid { path: String, msg: String },
}

/// Per-pixel keys of one tile, for one sample count.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyTable {
    /// Tile edge (power of two, 1..=256).
    pub tile: u32,
    /// Samples per pixel the keys were optimised for (power of two, 1..=4096).
    pub spp: u32,
    /// Optimised dimension pairs (dimensions `0 .. 2 * pairs`).
    pub pairs: u32,
    /// `[scramble, rank]` at `(y * tile + x) * pairs + pair`.
    pub keys: Vec<[u32; 2]>,
}

/// The sample bits of dimension `dim` given the key of its pair (`pairs` pairs optimised).
pub fn hbo19_bits(
    key: [u32; 2],
    pairs: u32,
    seed: u32,
    index: u32,
    dim: u32,
    dirs: &[[u32; 32]; 4],
) -> u32 {
    if dim >= 2 * pairs {
        return owen_sobol_bits(seed, index, dim, dirs);
    }
    let d = dim % 2;
    let shuffled = nested_uniform_scramble(index ^ key[1], key[0]);
    nested_uniform_scramble(sobol(shuffled, d, dirs), hash_combine(key[0], d + 1))
}

impl KeyTable {
    /// Validates the shape and the ranks (each below spp).
    pub fn new(tile: u32, spp: u32, pairs: u32, keys: Vec<[u32; 2]>) -> Result<Self, String> {
        if !(1..=256).contains(&tile) || !tile.is_power_of_two() {
            return Err(format!("tile {tile} is not a power of two in 1..=256"));
        }
        if !(1..=4096).contains(&spp) || !spp.is_power_of_two() {
            return Err(format!("spp {spp} is not a power of two in 1..=4096"));
        }
        if !(1..=MAX_PAIRS).contains(&pairs) {
            return Err(format!("{pairs} dimension pairs, expected 1..={MAX_PAIRS}"));
        }
        let want = (tile * tile * pairs) as usize;
        if keys.len() != want {
            return Err(format!(
                "{} keys, a {tile}x{tile} tile with {pairs} pairs needs {want}",
                keys.len()
            ));
        }
        if let Some(i) = keys.iter().position(|k| k[1] >= spp) {
            return Err(format!(
                "rank {} of key {i} is not below spp {spp}",
                keys[i][1]
            ));
        }
        Ok(Self {
            tile,
            spp,
            pairs,
            keys,
        })
    }

    /// The key of the pair holding `dim` for the pixel whose seed is `seed`.
    pub fn key(&self, seed: u32, dim: u32) -> [u32; 2] {
        let pixel = seed % (self.tile * self.tile);
        let pair = (dim / 2).min(self.pairs - 1);
        self.keys[(pixel * self.pairs + pair) as usize]
    }

    /// The sample bits (GLSL `hbo19_lookup_bits`).
    pub fn bits(&self, seed: u32, index: u32, dim: u32, dirs: &[[u32; 32]; 4]) -> u32 {
        hbo19_bits(self.key(seed, dim), self.pairs, seed, index, dim, dirs)
    }

    /// The GPU buffer: element 0 is `(tile, pairs)`, then the keys.
    pub fn gpu_words(&self) -> Vec<[u32; 2]> {
        std::iter::once([self.tile, self.pairs])
            .chain(self.keys.iter().copied())
            .collect()
    }

    /// The file bytes (module docs).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(KEYS_HEADER_LEN + self.keys.len() * 8);
        b.extend_from_slice(&KEYS_MAGIC);
        for v in [
            KEYS_VERSION,
            self.tile as u16,
            self.spp as u16,
            self.pairs as u16,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.resize(KEYS_HEADER_LEN, 0);
        for k in &self.keys {
            b.extend_from_slice(&k[0].to_le_bytes());
            b.extend_from_slice(&k[1].to_le_bytes());
        }
        b
    }

    /// Parses and validates file bytes; `path` only names the source in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Self, KeysError> {
        let bad = |msg: String| KeysError::Invalid {
            path: path.display().to_string(),
            msg,
        };
        if bytes.len() < KEYS_HEADER_LEN {
            return Err(bad(format!(
                "{} bytes, shorter than the {KEYS_HEADER_LEN}-byte header",
                bytes.len()
            )));
        }
        if bytes[..4] != KEYS_MAGIC {
            return Err(bad("not a key table (magic is not BSKY)".into()));
        }
        let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]);
        let version = u16_at(4);
        if version != KEYS_VERSION {
            return Err(bad(format!(
                "format version {version}, this build reads {KEYS_VERSION}"
            )));
        }
        let (tile, spp, pairs) = (
            u32::from(u16_at(6)),
            u32::from(u16_at(8)),
            u32::from(u16_at(10)),
        );
        let body = &bytes[KEYS_HEADER_LEN..];
        let want = tile as usize * tile as usize * pairs as usize * 8;
        if body.len() != want {
            return Err(bad(format!(
                "{} bytes of keys, the header ({tile}x{tile} tile, {pairs} pairs) needs {want}",
                body.len()
            )));
        }
        let word = |c: &[u8]| u32::from_le_bytes([c[0], c[1], c[2], c[3]]);
        let keys = body
            .chunks_exact(8)
            .map(|c| [word(&c[..4]), word(&c[4..])])
            .collect();
        Self::new(tile, spp, pairs, keys).map_err(bad)
    }

    /// Loads and validates a key table file.
    pub fn load(path: &Path) -> Result<Self, KeysError> {
        let bytes = std::fs::read(path).map_err(|source| KeysError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Self::from_bytes(&bytes, path)
    }
}

#[cfg(test)]
#[path = "hbo19_tests.rs"]
mod tests;
