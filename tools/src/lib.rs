//! `blueshift-tools`: blue-noise masks (void-and-cluster, 2D and spatio-temporal), FAST
//! filter-adapted spatio-temporal textures, Bayer and white-noise masks, retargeting
//! permutations, HBO+19 sampler keys, spectra, dithering, figures and the asset manifest.
//! The binary in `main.rs` is a thin clap front end over [`cli::run`].

pub mod cli;
pub mod commands;
pub mod dither;
pub mod fast;
pub mod keys;
pub mod manifest;
pub mod quality;
pub mod retarget;
pub mod rng;
pub mod voidcluster;
