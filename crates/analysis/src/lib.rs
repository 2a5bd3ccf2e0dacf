//! Error metrics of docs/results.md: error power spectra, radial profiles, the low-frequency
//! fraction `LF`, anisotropy, blurred RMSE `P_s`, plots. The readers and writers of the
//! precomputed assets live in `blueshift-assets` (re-exported as [`assets`]); a mask becomes
//! an image with `Gray::from(&mask)`.
//!
//! ```no_run
//! use blueshift_analysis::{Gray, SpectrumAccumulator, Window, low_frequency_fraction};
//! # fn main() -> blueshift_analysis::Result<()> {
//! let error = Gray::new(256, 256, vec![0.0; 256 * 256])?;
//! let mut acc = SpectrumAccumulator::new(64, Window::Hann)?;
//! acc.add_image(&error)?;
//! let lf = low_frequency_fraction(&acc.mean()?, 0.125);
//! # let _ = lf; Ok(()) }
//! ```

mod blur;
mod error;
mod gray;
mod plot;
mod radial;
mod spectrum;

/// The asset readers and writers, from `blueshift-assets` (the old path keeps working).
pub use blueshift_assets as assets;
pub use blur::{Boundary, blurred_rmse, gaussian_blur, gaussian_kernel, rmse};
pub use error::{Error, Result};
pub use gray::{Gray, luminance};
pub use plot::{RadialSeries, plot_radial_profiles, save_spectrum_png, spectrum_to_image};
pub use radial::{LF_CUTOFF, RadialProfile, low_frequency_fraction, radial_profile};
pub use spectrum::{Spectrum, SpectrumAccumulator, Window, periodogram, power_spectrum};
