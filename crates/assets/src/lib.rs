//! The precomputed assets of Blueshift: readers and writers of their files and the loading of
//! the set a renderer needs.
//!
//! * [`Mask`], [`StbnVolume`], [`RetargetTable`] with [`load_mask`] / [`save_mask`],
//!   [`load_stbn`] / [`save_stbn`], [`load_retarget`] / [`save_retarget`]: the blue-noise
//!   masks (`.r16`), spatio-temporal masks and retarget tables (`.bin`); tools/README.md has
//!   the byte layouts. Writers are atomic ([`write_atomic`]).
//! * [`MethodAssets`]: the mask tile, retarget table, spatio-temporal mask and HBO+19 key
//!   tables of an `assets/` directory ([`default_assets_dir`]), flattened for upload.
//!
//! * [`workspace_path`]: a directory of this checkout, found at run time.
//!
//! Every error is an [`AssetError`] naming the file.
//!
//! ```no_run
//! use blueshift_assets::{MethodAssets, default_assets_dir, load_mask};
//! # fn main() -> Result<(), blueshift_assets::AssetError> {
//! let dir = default_assets_dir();
//! let mask = load_mask(&dir.join("masks/bn64.r16"))?;
//! let assets = MethodAssets::load(&dir)?;
//! assert_eq!(assets.n as usize, mask.n);
//! # Ok(()) }
//! ```

mod error;
mod formats;
mod method;
mod workspace;

pub use error::{AssetError, Result, write_atomic};
pub mod files;
pub use formats::{
    Mask, RETARGET_HEADER_LEN, RETARGET_MAGIC, RETARGET_VERSION, RetargetTable, StbnVolume,
    load_mask, load_retarget, load_stbn, save_mask, save_retarget, save_stbn,
};
pub use method::{FAST_FILE, MOTION_FILE, MethodAssets, default_assets_dir};
pub use workspace::workspace_path;
