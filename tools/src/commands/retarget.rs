//! `retarget`: compute and write a retargeting table.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};
use blueshift_analysis::assets::{RetargetTable, load_mask, save_retarget};
use clap::ValueEnum;

use super::{bar, ensure_parent, save_png};
use crate::retarget::{Problem, Summary, anneal, default_shift, exact};

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

/// Parses `SX,SY`.
pub(crate) fn parse_shift(s: &str) -> anyhow::Result<(u32, u32)> {
    let (x, y) = s
        .split_once(',')
        .with_context(|| format!("--shift {s:?}: expected SX,SY"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .with_context(|| format!("--shift {s:?}: {v:?} is not a non-negative integer"))
    };
    Ok((p(x)?, p(y)?))
}

pub(crate) fn retarget(a: &RetargetArgs) -> anyhow::Result<()> {
    let mask = load_mask(&a.mask)?;
    let n = mask.n;
    let shift = match &a.shift {
        Some(s) => parse_shift(s)?,
        None => default_shift(n),
    };
    if shift.0 as usize >= n || shift.1 as usize >= n {
        bail!("--shift {shift:?}: each component must be below the mask side {n}");
    }
    let p = Problem::new(&mask, shift, a.radius)?;
    let start = Instant::now();
    let target = match a.solver {
        Solver::Exact => {
            let pb = bar(p.len() as u64, "matching");
            let t = exact::solve(&p, &mut |k| pb.set_position(k));
            pb.finish_and_clear();
            t
        }
        Solver::Anneal => {
            let mut params = anneal::AnnealParams::defaults(n, a.seed);
            if let Some(k) = a.proposals {
                params.proposals = k;
            }
            let pb = bar(params.proposals, "annealing");
            let t = anneal::solve(&p, &params, &mut |k| pb.set_position(k));
            pb.finish_and_clear();
            t
        }
    };
    let secs = start.elapsed().as_secs_f64();
    let s = Summary::new(&p, &target);
    let table = RetargetTable::new(n, shift, a.radius, p.offsets(&target))?;
    ensure_parent(&a.out)?;
    save_retarget(&table, &a.out)?;
    if let Some(png) = &a.png {
        let r = a.radius as f64;
        let enc = |d: i8| ((f64::from(d) + r) * 255.0 / (2.0 * r)).round() as u8;
        let img = image::RgbImage::from_fn(n as u32, n as u32, |x, y| {
            let (dx, dy) = table.offsets[y as usize * n + x as usize];
            image::Rgb([enc(dx), enc(dy), 0])
        });
        ensure_parent(png)?;
        save_png(image::DynamicImage::ImageRgb8(img), png)?;
    }
    println!(
        "{}: {n}x{n} table, shift ({}, {}), radius {} (Euclidean disc), solver {:?}",
        a.out.display(),
        shift.0,
        shift.1,
        a.radius,
        a.solver
    );
    println!("  semantics: seed at mask coordinate u moves by offsets[u]; M(u + d(u) + s) ~= M(u)");
    println!(
        "  energy sum|M(u) - M(pi(u)+s)|: identity {} -> {} (mean {:.2} ranks of {}), \
         within 1% of range: {:.1}%, {secs:.3} s",
        s.energy_identity,
        s.energy,
        s.mean,
        n * n,
        100.0 * s.matched_share
    );
    Ok(())
}
