//! Command-line interface (clap derive). Every subcommand is deterministic given its flags.

use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};

use crate::commands;

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

/// `sky` flags.
#[derive(Debug, clap::Args)]
pub struct SkyArgs {
    /// Map width in texels (height is half of it).
    #[arg(long, default_value_t = 256)]
    pub width: u32,
    /// Sun elevation above the horizon, degrees.
    #[arg(long, default_value_t = 35.0, allow_negative_numbers = true)]
    pub sun_elevation: f32,
    /// Sun azimuth from -Z towards +X, degrees.
    #[arg(long, default_value_t = 150.0, allow_negative_numbers = true)]
    pub sun_azimuth: f32,
    /// Radiance of the sun disc (1.5 degrees in radius).
    #[arg(long, default_value_t = 1500.0)]
    pub sun_radiance: f32,
    /// Output `.hdr`.
    #[arg(long)]
    pub out: PathBuf,
}

/// `scene` flags.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Preset name, or `all`.
    #[arg(long, default_value = "all")]
    pub name: String,
    /// Output directory.
    #[arg(long, default_value = "assets/scenes")]
    pub out: std::path::PathBuf,
}

/// `mask` flags.
#[derive(Debug, clap::Args)]
pub struct MaskArgs {
    /// Side of the mask (power of two, 4..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Gaussian energy sigma in pixels.
    #[arg(long, default_value_t = 1.9)]
    pub sigma: f64,
    /// Initial density of the binary pattern.
    #[arg(long, default_value_t = 0.1)]
    pub density: f64,
    /// Number of slices; > 1 makes a spatio-temporal mask.
    #[arg(long, default_value_t = 1)]
    pub frames: usize,
    /// Temporal energy sigma in frames (spatio-temporal only).
    #[arg(long, default_value_t = 1.9)]
    pub sigma_t: f64,
    /// PRNG seed of the initial pattern.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output `.r16`; a 16-bit PNG preview is written beside it (`.png`).
    #[arg(long)]
    pub out: PathBuf,
}

/// `bayer` flags.
#[derive(Debug, clap::Args)]
pub struct BayerArgs {
    /// Side (power of two, 2..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Output `.r16` (plus `.png` preview).
    #[arg(long)]
    pub out: PathBuf,
}

/// `white` flags.
#[derive(Debug, clap::Args)]
pub struct WhiteArgs {
    /// Side (power of two, 2..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// PRNG seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output `.r16` (plus `.png` preview).
    #[arg(long)]
    pub out: PathBuf,
}

/// Temporal filter kinds (`fast`, `fast-bench`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TemporalKind {
    /// Exponential moving average (TAA), `--alpha`.
    Ema,
    /// Gaussian over frames, `--sigma-t`.
    Gauss,
}

/// The filter a FAST texture is optimised for / measured with.
#[derive(Debug, clap::Args)]
pub struct FilterArgs {
    /// Spatial Gaussian sigma in pixels (> 0).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub sigma: f64,
    /// Temporal filter.
    #[arg(long, value_enum, default_value_t = TemporalKind::Ema)]
    pub temporal: TemporalKind,
    /// EMA blend factor in (0, 1].
    #[arg(long, default_value_t = 0.1, allow_negative_numbers = true)]
    pub alpha: f64,
    /// Temporal Gaussian sigma in frames (> 0; `--temporal gauss`).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub sigma_t: f64,
}

/// `fast` flags.
#[derive(Debug, clap::Args)]
pub struct FastArgs {
    /// Side of each slice (power of two, 4..=256).
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Slices (power of two, <= 256 and <= size^2).
    #[arg(long, default_value_t = 32)]
    pub frames: usize,
    /// 1: scalar values; 2: 2D vectors (rank r = centre of cell (r mod N, r div N)).
    #[arg(long, default_value_t = 1)]
    pub dims: usize,
    #[command(flatten)]
    pub filter: FilterArgs,
    /// Integrands the loss models: `shared` (the paper: one step integrand for every voxel)
    /// or `pixel` (an independent one per pixel: filtered texture energy between pixels).
    #[arg(long, value_enum, default_value_t = crate::fast::Model::Shared)]
    pub model: crate::fast::Model,
    /// Swap proposals per voxel over the whole run (1024: about 2 min for 64x64x32 on two
    /// free cores).
    #[arg(long, default_value_t = 1024)]
    pub iterations: u32,
    /// Annealing rounds (temperature steps).
    #[arg(long, default_value_t = 64)]
    pub rounds: u32,
    /// PRNG seed (initial texture and proposals).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output `.r16` (slices of ranks, as `stbn64x32.r16`) plus a `.png` preview.
    #[arg(long)]
    pub out: PathBuf,
}

/// `fast-bench` flags.
#[derive(Debug, clap::Args)]
pub struct FastBenchArgs {
    /// FAST textures `.r16` (comma-separated; rows named by file name).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "assets/masks/fast64x32_s1_a0.1.r16"
    )]
    pub fast: Vec<PathBuf>,
    /// STBN texture `.r16` to compare with (scalar only).
    #[arg(long, default_value = "assets/masks/stbn64x32.r16")]
    pub stbn: PathBuf,
    /// Side of both textures.
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Values per pixel of the FAST texture (1 or 2; with 2, STBN is skipped).
    #[arg(long, default_value_t = 1)]
    pub dims: usize,
    #[command(flatten)]
    pub filter: FilterArgs,
    /// Random integrands per kind.
    #[arg(long, default_value_t = 256)]
    pub trials: u32,
    /// Integrand kinds (default: all).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub integrand: Vec<crate::fast::bench::Integrand>,
    /// Seed of the integrands, the white-noise texture and the stratified start.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `spectrum` flags.
#[derive(Debug, clap::Args)]
pub struct SpectrumArgs {
    /// PNG/EXR images or `.r16` masks.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Tile side for images (Hann-windowed tiles, docs/results.md).
    #[arg(long, default_value_t = 64)]
    pub tile: usize,
    /// Treat square images as periodic tiles: unwindowed periodogram of the whole image.
    #[arg(long)]
    pub periodic: bool,
    /// Read `.r16` inputs as spatio-temporal volumes with this slice side (averages the
    /// slices' periodograms).
    #[arg(long)]
    pub stbn_size: Option<usize>,
}

/// How image values map to the thesis' gray level `p` (probability of black).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GrayIs {
    /// Pixel value is brightness: `p = 1 - value` (output looks like the input).
    Brightness,
    /// Pixel value is `p` itself (black where mask <= value).
    Darkness,
}

/// `dither` flags.
#[derive(Debug, clap::Args)]
pub struct DitherArgs {
    /// Grayscale or RGB image (RGB is reduced to luminance).
    pub image: PathBuf,
    /// Mask `.r16`.
    #[arg(long)]
    pub mask: PathBuf,
    /// Output PNG.
    #[arg(long)]
    pub out: PathBuf,
    /// Meaning of pixel values.
    #[arg(long, value_enum, default_value_t = GrayIs::Brightness)]
    pub gray_is: GrayIs,
    /// Write the mask's result, a Bayer and a white-noise mask of the same side, side by side.
    #[arg(long)]
    pub compare: bool,
    /// Seed of the white-noise mask for --compare.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Retarget solvers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Solver {
    /// Min-cost bipartite matching (optimal).
    Exact,
    /// Simulated annealing (the paper's method).
    Anneal,
}

/// `retarget` flags.
#[derive(Debug, clap::Args)]
pub struct RetargetArgs {
    /// Mask `.r16`.
    #[arg(long)]
    pub mask: PathBuf,
    /// Per-frame shift `SX,SY`; default `(round(N/g), round(N/g^2))`, g the plastic number.
    #[arg(long)]
    pub shift: Option<String>,
    /// Maximum Euclidean displacement.
    #[arg(long, default_value_t = 6)]
    pub radius: u32,
    /// Solver.
    #[arg(long, value_enum, default_value_t = Solver::Exact)]
    pub solver: Solver,
    /// PRNG seed (annealing).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Annealing proposals (default 15000 N^2).
    #[arg(long)]
    pub proposals: Option<u64>,
    /// Output `.bin`.
    #[arg(long)]
    pub out: PathBuf,
    /// Optional PNG view: R = dx, G = dy, mapped from `[-R, R]` to `[0, 255]`.
    #[arg(long)]
    pub png: Option<PathBuf>,
}

/// `keys` flags.
#[derive(Debug, clap::Args)]
pub struct KeysArgs {
    /// Tile edge (power of two, 16..=256).
    #[arg(long, default_value_t = 128)]
    pub tile: u32,
    /// Comma-separated sample counts (powers of two); one table each.
    #[arg(long, default_value = "1")]
    pub spp: String,
    /// Optimised sample dimensions (even: pairs); later ones fall back to Owen-Sobol.
    #[arg(long, default_value_t = 8)]
    pub dims: u32,
    /// Test integrands per dimension pair (half Heaviside steps, half Gaussians).
    #[arg(long, default_value_t = 16)]
    pub integrands: u32,
    /// Annealing proposals per pixel.
    #[arg(long, default_value_t = 128)]
    pub iterations: u32,
    /// Temperature steps.
    #[arg(long, default_value_t = 64)]
    pub rounds: u32,
    /// Error-distance scale of the energy (smaller: only near-equal errors repel).
    #[arg(long, default_value_t = 1.0)]
    pub sigma_s: f32,
    /// PRNG seed (integrands, initial keys, proposals).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output directory: writes `hbo19_t<tile>_spp<n>.bin` per spp.
    #[arg(long)]
    pub out: PathBuf,
}

/// `figures` flags.
#[derive(Debug, clap::Args)]
pub struct FiguresArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "out/figures")]
    pub out: PathBuf,
    /// Mask side.
    #[arg(long, default_value_t = 64)]
    pub size: usize,
    /// Seed of the blue and white masks.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `assets` flags.
#[derive(Debug, clap::Args)]
pub struct AssetsArgs {
    /// Asset root (run from the repository root so MANIFEST commands read `assets/...`).
    #[arg(long, default_value = "assets")]
    pub root: PathBuf,
}

/// `manifest` flags.
#[derive(Debug, clap::Args)]
pub struct ManifestArgs {
    /// Verify every listed hash (the only action so far).
    #[arg(long)]
    pub check: bool,
    /// The MANIFEST file; paths in it are relative to its directory.
    #[arg(long, default_value = "assets/MANIFEST")]
    pub manifest: PathBuf,
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
        Command::Assets(a) => commands::assets::assets(&a),
        Command::Manifest(a) => commands::assets::manifest(&a),
        Command::Scene(a) => scene(&a),
        Command::Sky(a) => commands::sky::sky(&a),
    }
}

/// Writes the bundled scene presets.
fn scene(a: &SceneArgs) -> anyhow::Result<()> {
    let names: Vec<&str> = if a.name == "all" {
        blueshift_scene::presets::PRESETS.to_vec()
    } else {
        vec![a.name.as_str()]
    };
    std::fs::create_dir_all(&a.out)?;
    for n in names {
        let p = blueshift_scene::presets::write_preset(n, &a.out)?;
        println!("wrote {}", p.display());
    }
    Ok(())
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
