//! `fast` (optimise a FAST texture) and `fast-bench` (FAST's unit benchmark).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use blueshift_assets::{StbnVolume, load_stbn, save_stbn};
use clap::ValueEnum;

use super::masks::{preview_path, save_preview};
use super::{bar, ensure_parent};
use crate::fast::bench::{Integrand, filtered_rmse, white_ranks};
use crate::fast::{
    Filter, Model, Params, Temporal, Volume, anneal, pair_loss, predicted_mse, stratified_init,
};

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

fn temporal(f: &FilterArgs) -> Temporal {
    match f.temporal {
        TemporalKind::Ema => Temporal::Ema { alpha: f.alpha },
        TemporalKind::Gauss => Temporal::Gauss { sigma: f.sigma_t },
    }
}

/// The loss, with the RMSE it predicts for scalar values.
fn describe(vol: &Volume, filter: &Filter, model: Model, loss: f64) -> String {
    if vol.dims == 1 {
        let rmse = predicted_mse(vol, filter, model, loss).sqrt();
        format!("{loss:.6} (RMSE {rmse:.5})")
    } else {
        format!("{loss:.6}")
    }
}

pub(crate) fn fast(a: &FastArgs) -> anyhow::Result<()> {
    let p = Params {
        n: a.size,
        frames: a.frames,
        dims: a.dims,
        sigma: a.filter.sigma,
        temporal: temporal(&a.filter),
        model: a.model,
        iterations: a.iterations,
        rounds: a.rounds,
        seed: a.seed,
    };
    p.validate()?;
    let start = Instant::now();
    let pb = bar(u64::from(a.rounds), "fast");
    let out = anneal::optimise(&p, &mut |r| pb.set_position(u64::from(r)))?;
    pb.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    let v = StbnVolume::new(a.size, a.frames, out.volume.ranks())
        .context("optimised texture is not a volume of permutations")?;
    anyhow::ensure!(
        out.volume.temporally_stratified(),
        "optimised texture lost its temporal strata"
    );
    ensure_parent(&a.out)?;
    save_stbn(&v, &a.out)?;
    save_preview(&v.ranks, v.n, &preview_path(&a.out))?;
    let init = stratified_init(p.n, p.frames, p.dims, p.seed);
    let init = Volume::from_ranks(p.n, p.frames, p.dims, &init);
    let filter = p.filter();
    println!(
        "{}: {t} slices of {n}x{n}, dims {}, model {:?}, loss L/N {} -> {}; {} proposals, {} \
         accepted ({} two-slice); {secs:.1} s",
        a.out.display(),
        p.dims,
        p.model,
        describe(&init, &filter, p.model, out.loss_initial),
        describe(&out.volume, &filter, p.model, out.loss_final),
        out.proposals,
        out.accepted,
        out.paired,
        n = p.n,
        t = p.frames,
    );
    Ok(())
}

fn load(path: &Path, n: usize, dims: usize) -> anyhow::Result<Volume> {
    let v = load_stbn(path, n).with_context(|| format!("loading {}", path.display()))?;
    Ok(Volume::from_ranks(v.n, v.t, dims, &v.ranks))
}

fn name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    )
}

pub(crate) fn fast_bench(a: &FastBenchArgs) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for f in &a.fast {
        rows.push((format!("FAST {}", name(f)), load(f, a.size, a.dims)?));
    }
    let frames = rows.first().map_or(32, |r| r.1.frames);
    let p = Params {
        n: a.size,
        frames,
        dims: a.dims,
        sigma: a.filter.sigma,
        temporal: temporal(&a.filter),
        model: Model::Shared,
        iterations: 1,
        rounds: 1,
        seed: a.seed,
    };
    p.validate()?;
    let (n, t, d) = (p.n, p.frames, p.dims);
    if d == 1 {
        rows.push((format!("STBN {}", name(&a.stbn)), load(&a.stbn, n, 1)?));
    }
    let white = white_ranks(n, t, a.seed);
    rows.push(("white noise".into(), Volume::from_ranks(n, t, d, &white)));
    let init = stratified_init(n, t, d, a.seed);
    rows.push((
        "stratified (FAST start)".into(),
        Volume::from_ranks(n, t, d, &init),
    ));
    let kinds = if a.integrand.is_empty() {
        Integrand::ALL.to_vec()
    } else {
        a.integrand.clone()
    };
    let start = Instant::now();
    let mut head: Vec<&str> = kinds.iter().map(|k| k.name()).collect();
    if d == 1 {
        head.extend(["predicted const", "predicted pixel"]);
    }
    println!(
        "Filtered RMSE, {n}x{n}, dims {d}, spatial Gaussian sigma {}, temporal {:?}, {} trials \
         per integrand kind\n",
        p.sigma, p.temporal, a.trials
    );
    println!("| texture | frames | {} |", head.join(" | "));
    println!("|---|---|{}", "---|".repeat(head.len()));
    for (label, vol) in &rows {
        let filter = Params {
            frames: vol.frames,
            ..p.clone()
        }
        .filter();
        let mut cols: Vec<String> = kinds
            .iter()
            .map(|&k| format!("{:.5}", filtered_rmse(vol, &filter, k, a.trials, a.seed)))
            .collect();
        if d == 1 {
            for model in [Model::Shared, Model::Pixel] {
                let loss = pair_loss(vol, &filter, &filter.support(0.0), model);
                cols.push(format!(
                    "{:.5}",
                    predicted_mse(vol, &filter, model, loss).sqrt()
                ));
            }
        }
        println!("| {label} | {} | {} |", vol.frames, cols.join(" | "));
    }
    println!("\n({:.1} s)", start.elapsed().as_secs_f64());
    Ok(())
}
