//! Command-line interface (clap derive): the subcommands, each with its flags beside its code in
//! [`crate::commands`]. Every subcommand is deterministic given its flags.

use std::path::Path;

use anyhow::{Context, bail};
use clap::{Parser, Subcommand};

use crate::commands;
use crate::commands::assets::{AssetsArgs, ManifestArgs};
use crate::commands::dither::DitherArgs;
use crate::commands::fast::{FastArgs, FastBenchArgs};
use crate::commands::figures::FiguresArgs;
use crate::commands::keys::KeysArgs;
use crate::commands::masks::{BayerArgs, MaskArgs, WhiteArgs};
use crate::commands::retarget::RetargetArgs;
use crate::commands::scene::SceneArgs;
use crate::commands::sky::SkyArgs;
use crate::commands::spectrum::SpectrumArgs;

/// Precompute masks, retarget tables, spectra and figures for Blueshift.
#[derive(Debug, Parser)]
#[command(name = "blueshift-tools", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Void-and-cluster blue-noise mask (2D, or spatio-temporal with --frames > 1).
    Mask(MaskArgs),
    /// Bayer (ordered dither) mask.
    Bayer(BayerArgs),
    /// White-noise mask (random permutation of ranks).
    White(WhiteArgs),
    /// FAST texture: spatio-temporal values optimised for a spatial Gaussian x EMA filter.
    Fast(FastArgs),
    /// FAST's unit benchmark: filtered RMSE of step integrands, FAST vs STBN vs white noise.
    FastBench(FastBenchArgs),
    /// Power spectra, radial profiles and LF of images and masks.
    Spectrum(SpectrumArgs),
    /// Threshold-dither an image against a tiled mask.
    Dither(DitherArgs),
    /// Retargeting permutation of a mask for a per-frame shift.
    Retarget(RetargetArgs),
    /// HBO+19 per-pixel sampler keys, optimised so that errors are blue in screen space.
    Keys(KeysArgs),
    /// Figures: white / blue / Bayer textures, spectra, radial profiles, dithered gradient.
    Figures(FiguresArgs),
    /// Regenerate every committed asset and write the MANIFEST.
    Assets(AssetsArgs),
    /// Check the SHA-256 hashes listed in a MANIFEST.
    Manifest(ManifestArgs),
    /// Write the bundled glTF scenes (cornell-box, textured, edges).
    Scene(SceneArgs),
    /// Procedural sky as an equirectangular Radiance `.hdr` (the bundled environment map).
    Sky(SkyArgs),
}

/// Runs one parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Mask(a) => commands::masks::mask(&a),
        Command::Bayer(a) => commands::masks::bayer(&a),
        Command::White(a) => commands::masks::white(&a),
        Command::Fast(a) => commands::fast::fast(&a),
        Command::FastBench(a) => commands::fast::fast_bench(&a),
        Command::Spectrum(a) => commands::spectrum::spectrum(&a),
        Command::Dither(a) => commands::dither::dither(&a),
        Command::Retarget(a) => commands::retarget::retarget(&a),
        Command::Keys(a) => commands::keys::keys(&a),
        Command::Figures(a) => commands::figures::figures(&a),
        Command::Assets(a) => commands::assets::assets(&a, run_args),
        Command::Manifest(a) => commands::assets::manifest(&a),
        Command::Scene(a) => commands::scene::scene(&a),
        Command::Sky(a) => commands::sky::sky(&a),
    }
}

/// Parses `args` (without the program name) and runs them.
pub fn run_args<I, S>(args: I) -> anyhow::Result<()>
where
    I: IntoIterator<Item = S>,
    S: Into<std::ffi::OsString> + Clone,
{
    let argv = std::iter::once(std::ffi::OsString::from("blueshift-tools"))
        .chain(args.into_iter().map(Into::into));
    run(Cli::try_parse_from(argv)?)
}

/// Runs every job of the `assets` command whose outputs include `rel`, with the asset root
/// replaced by `root`.
pub fn regenerate(rel: &str, root: &Path) -> anyhow::Result<()> {
    let r = root.to_str().context("root must be UTF-8")?;
    for j in commands::assets::jobs(r) {
        if j.outputs.iter().any(|o| o == rel) {
            return run_args(j.args);
        }
    }
    bail!("no job writes {rel}")
}
