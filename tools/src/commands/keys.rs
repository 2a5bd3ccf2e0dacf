//! `keys`: optimise HBO+19 key tables (one file per spp).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};

use super::{bar, ensure_parent};
use crate::keys::{KeysParams, Problem, anneal};

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

/// Parses a comma-separated list of sample counts.
fn parse_spp(s: &str) -> anyhow::Result<Vec<u32>> {
    let v: Vec<u32> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<u32>()
                .with_context(|| format!("--spp {s:?}: {x:?} is not a number"))
        })
        .collect::<anyhow::Result<_>>()?;
    if v.is_empty() {
        bail!("--spp is empty");
    }
    Ok(v)
}

/// The file name of the table for `tile` and `spp`.
pub fn file_name(tile: u32, spp: u32) -> String {
    format!("hbo19_t{tile}_spp{spp}.bin")
}

pub(crate) fn keys(a: &KeysArgs) -> anyhow::Result<()> {
    if a.dims == 0 || a.dims % 2 != 0 {
        bail!(
            "--dims {} must be a positive even number (dimensions come in pairs)",
            a.dims
        );
    }
    for spp in parse_spp(&a.spp)? {
        let params = KeysParams {
            iterations: a.iterations,
            rounds: a.rounds,
            integrands: a.integrands,
            sigma_s: a.sigma_s,
            ..KeysParams::new(a.tile, spp, a.dims / 2, a.seed)
        };
        let p = Problem::new(params).map_err(|e| anyhow::anyhow!("--spp {spp}: {e}"))?;
        let start = Instant::now();
        let pb = bar(u64::from(a.rounds), &format!("keys spp {spp}"));
        let out = anneal::optimise(&p, &mut |r| pb.set_position(u64::from(r)));
        pb.finish_and_clear();
        let secs = start.elapsed().as_secs_f64();
        let table = p.table(out.keys).map_err(anyhow::Error::msg)?;
        let path = a.out.join(file_name(a.tile, spp));
        ensure_parent(&path)?;
        blueshift_assets::write_atomic(&path, &table.to_bytes())?;
        println!(
            "{}: {t}x{t} tile, spp {spp}, {} pairs, energy {:.1} -> {:.1} ({:.2}%), \
             error LF {:.4} -> {:.4} (white ~0.045), {} of {} proposals accepted, {secs:.1} s",
            path.display(),
            a.dims / 2,
            out.energy_initial,
            out.energy_final,
            100.0 * (out.energy_final / out.energy_initial - 1.0),
            out.lf_initial,
            out.lf_final,
            out.accepted,
            out.proposals,
            t = a.tile,
        );
    }
    Ok(())
}
