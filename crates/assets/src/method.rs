//! The precomputed textures the methods need, loaded from `assets/`.
use crate::error::{AssetError, Result};
use crate::formats::{load_mask, load_retarget, load_stbn};
use blueshift_sampling::hbo19::KeyTable;
use std::path::{Path, PathBuf};

/// Where [`MethodAssets::load`] finds the FAST mask (`blueshift-tools fast` writes it).
pub const FAST_FILE: &str = "masks/fast64x32_s1_a0.1.r16";

/// Where [`MethodAssets::load`] finds the motion volume (`blueshift-tools mask --frames 32
/// --sigma-t 0.5` writes it).
pub const MOTION_FILE: &str = "masks/stbn64x32_t0.5.r16";

/// Mask tile, retarget table and spatio-temporal mask, flattened for upload.
#[derive(Debug, Clone)]
pub struct MethodAssets {
    /// Mask tile edge N.
    pub n: u32,
    /// N*N void-and-cluster ranks.
    pub mask: Vec<u32>,
    /// Retarget displacement per mask texel.
    pub table: Vec<[i32; 2]>,
    /// The integer shift s the table was optimised for.
    pub shift: (u32, u32),
    /// Spatio-temporal mask: edge, slices, ranks (slice-major).
    pub stbn_n: u32,
    pub stbn_frames: u32,
    pub stbn: Vec<u32>,
    /// The FAST mask (optimised for a Gaussian sigma 1 and an EMA alpha 0.1), the same size as
    /// the spatio-temporal mask; empty when the asset is missing (then `fast` is unavailable).
    pub fast: Vec<u32>,
    /// The motion volume: a spatio-temporal mask whose temporal energy reaches only the next
    /// slices (sigma_t 0.5), so each slice is as blue as a 2D mask while consecutive slices
    /// still differ; the same size as the spatio-temporal mask. `sort-cycle` draws a moving
    /// view's first vertex from it. Empty when the asset is missing.
    pub motion: Vec<u32>,
    /// HBO+19 key tables of one tile, one per sample count, ascending spp (may be empty:
    /// then the `hbo19` sampler is unavailable).
    pub keys: Vec<KeyTable>,
}

/// `BLUESHIFT_ASSETS`, else the workspace's `assets/` (the nearest one holding a MANIFEST,
/// [`crate::workspace_path`]).
pub fn default_assets_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("BLUESHIFT_ASSETS") {
        return PathBuf::from(d);
    }
    crate::workspace_path("assets", |d| d.join("MANIFEST").is_file())
}

impl MethodAssets {
    /// Loads the 64x64 mask, its retarget table, the 64x64xT spatio-temporal mask and the
    /// HBO+19 key tables `keys/hbo19_*.bin`.
    pub fn load(dir: &Path) -> Result<Self> {
        let a = Self::load_files(
            &dir.join("masks/bn64.r16"),
            &dir.join("retarget/bn64_s48_36_r6.bin"),
            &dir.join("masks/stbn64x32.r16"),
            64,
        )?;
        a.with_fast(&dir.join(FAST_FILE))?
            .with_motion(&dir.join(MOTION_FILE))?
            .with_keys_dir(&dir.join("keys"))
    }

    /// Adds the FAST volume at `path` if it exists; it must match the spatio-temporal mask's
    /// size.
    pub fn with_fast(mut self, path: &Path) -> Result<Self> {
        if let Some(v) = self.optional_volume(path, "FAST mask")? {
            self.fast = v;
        }
        Ok(self)
    }

    /// Adds the motion volume at `path` if it exists; it must match the spatio-temporal
    /// mask's size.
    pub fn with_motion(mut self, path: &Path) -> Result<Self> {
        if let Some(v) = self.optional_volume(path, "motion volume")? {
            self.motion = v;
        }
        Ok(self)
    }

    /// The volume at `path` (`what` names it in errors), `None` if there is no such file.
    fn optional_volume(&self, path: &Path, what: &str) -> Result<Option<Vec<u32>>> {
        if !path.is_file() {
            return Ok(None);
        }
        let v = load_stbn(path, self.stbn_n as usize)?;
        if v.t as u32 != self.stbn_frames {
            return Err(AssetError::Mismatch(format!(
                "{what} {} has {} slices, the spatio-temporal mask {}",
                path.display(),
                v.t,
                self.stbn_frames
            )));
        }
        Ok(Some(v.ranks.iter().map(|&r| r as u32).collect()))
    }

    /// Adds every `hbo19_*.bin` key table of `dir` (none if `dir` does not exist). The tables
    /// must share tile and pairs (the seed map depends on the tile) and differ in spp.
    pub fn with_keys_dir(mut self, dir: &Path) -> Result<Self> {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return Ok(self);
        };
        let mut paths: Vec<_> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("hbo19_") && n.ends_with(".bin"))
            })
            .collect();
        paths.sort();
        let mut keys = Vec::new();
        for p in &paths {
            keys.push(KeyTable::load(p)?);
        }
        self.set_keys(keys)?;
        Ok(self)
    }

    /// Replaces the key tables after checking they fit together.
    pub fn set_keys(&mut self, mut keys: Vec<KeyTable>) -> Result<()> {
        keys.sort_by_key(|k| k.spp);
        if let Some(first) = keys.first() {
            for k in &keys[1..] {
                if (k.tile, k.pairs) != (first.tile, first.pairs) {
                    return Err(AssetError::Mismatch(format!(
                        "HBO+19 key tables disagree: tile {} / {} pairs vs tile {} / {} pairs",
                        first.tile, first.pairs, k.tile, k.pairs
                    )));
                }
            }
            if keys.windows(2).any(|w| w[0].spp == w[1].spp) {
                return Err(AssetError::Mismatch(
                    "two HBO+19 key tables for the same spp".into(),
                ));
            }
        }
        self.keys = keys;
        Ok(())
    }

    /// The key table for `spp`: the largest spp not above it, else the smallest.
    pub fn keys_for(&self, spp: u32) -> Option<&KeyTable> {
        self.keys
            .iter()
            .rev()
            .find(|k| k.spp <= spp)
            .or(self.keys.first())
    }

    /// Loads explicit files; the table must be made for a mask of the same size.
    pub fn load_files(mask: &Path, table: &Path, stbn: &Path, stbn_n: usize) -> Result<Self> {
        // The loaders' errors already name the file.
        let m = load_mask(mask)?;
        let t = load_retarget(table)?;
        if t.n != m.n {
            return Err(AssetError::Mismatch(format!(
                "retarget table {} is for a {}x{} mask but mask {} is {}x{}",
                table.display(),
                t.n,
                t.n,
                mask.display(),
                m.n,
                m.n
            )));
        }
        let v = load_stbn(stbn, stbn_n)?;
        Ok(Self {
            n: m.n as u32,
            mask: m.ranks.iter().map(|&r| r as u32).collect(),
            table: t
                .offsets
                .iter()
                .map(|&(dx, dy)| [dx as i32, dy as i32])
                .collect(),
            shift: (t.shift.0 as u32, t.shift.1 as u32),
            stbn_n: v.n as u32,
            stbn_frames: v.t as u32,
            stbn: v.ranks.iter().map(|&r| r as u32).collect(),
            fast: Vec::new(),
            motion: Vec::new(),
            keys: Vec::new(),
        })
    }
}
