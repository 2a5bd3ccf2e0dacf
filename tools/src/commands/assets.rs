//! `assets` (regenerate everything + MANIFEST) and `manifest --check`.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};

use crate::manifest::{self, Entry};

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

/// One generation step: the arguments, its seed, and the files it writes (relative to the
/// asset root).
pub struct Job {
    /// Arguments after `blueshift-tools`.
    pub args: Vec<String>,
    /// PRNG seed recorded in the MANIFEST.
    pub seed: u64,
    /// Outputs relative to the asset root.
    pub outputs: Vec<String>,
}

fn job(args: &str, seed: u64, outputs: &[&str], root: &str) -> Job {
    Job {
        args: args
            .replace("{root}", root)
            .split_whitespace()
            .map(str::to_string)
            .collect(),
        seed,
        outputs: outputs.iter().map(|s| s.to_string()).collect(),
    }
}

/// The committed assets, in generation order (masks before the tables that read them).
pub fn jobs(root: &str) -> Vec<Job> {
    let vc = "mask --sigma 1.9 --density 0.1";
    vec![
        job(
            &format!("{vc} --size 32 --seed 32 --out {{root}}/masks/bn32.r16"),
            32,
            &["masks/bn32.r16", "masks/bn32.png"],
            root,
        ),
        job(
            &format!("{vc} --size 64 --seed 64 --out {{root}}/masks/bn64.r16"),
            64,
            &["masks/bn64.r16", "masks/bn64.png"],
            root,
        ),
        job(
            &format!("{vc} --size 128 --seed 128 --out {{root}}/masks/bn128.r16"),
            128,
            &["masks/bn128.r16", "masks/bn128.png"],
            root,
        ),
        job(
            &format!(
                "{vc} --size 64 --frames 32 --sigma-t 1.9 --seed 6432 --out {{root}}/masks/stbn64x32.r16"
            ),
            6432,
            &["masks/stbn64x32.r16", "masks/stbn64x32.png"],
            root,
        ),
        job(
            &format!(
                "{vc} --size 64 --frames 32 --sigma-t 0.5 --seed 6433 --out {{root}}/masks/stbn64x32_t0.5.r16"
            ),
            6433,
            &["masks/stbn64x32_t0.5.r16", "masks/stbn64x32_t0.5.png"],
            root,
        ),
        job(
            "fast --size 64 --frames 32 --sigma 1 --temporal ema --alpha 0.1 --iterations 1024 \
             --rounds 64 --seed 2024 --out {root}/masks/fast64x32_s1_a0.1.r16",
            2024,
            &["masks/fast64x32_s1_a0.1.r16", "masks/fast64x32_s1_a0.1.png"],
            root,
        ),
        job(
            "retarget --mask {root}/masks/bn32.r16 --shift 24,18 --radius 6 --solver exact --seed 1 \
             --out {root}/retarget/bn32_s24_18_r6.bin",
            1,
            &["retarget/bn32_s24_18_r6.bin"],
            root,
        ),
        job(
            "retarget --mask {root}/masks/bn64.r16 --shift 48,36 --radius 6 --solver exact --seed 1 \
             --out {root}/retarget/bn64_s48_36_r6.bin",
            1,
            &["retarget/bn64_s48_36_r6.bin"],
            root,
        ),
        job(
            "retarget --mask {root}/masks/bn128.r16 --shift 97,73 --radius 6 --solver exact --seed 1 \
             --out {root}/retarget/bn128_s97_73_r6.bin",
            1,
            &["retarget/bn128_s97_73_r6.bin"],
            root,
        ),
        job(
            "keys --tile 128 --spp 1,2,4,8,16 --dims 8 --iterations 128 --rounds 64 --seed 19 \
             --out {root}/keys",
            19,
            &[
                "keys/hbo19_t128_spp1.bin",
                "keys/hbo19_t128_spp2.bin",
                "keys/hbo19_t128_spp4.bin",
                "keys/hbo19_t128_spp8.bin",
                "keys/hbo19_t128_spp16.bin",
            ],
            root,
        ),
        job(
            "scene --name all --out {root}/scenes",
            0,
            &[
                "scenes/cornell-box.gltf",
                "scenes/textured.gltf",
                "scenes/edges.gltf",
            ],
            root,
        ),
        job(
            "sky --width 256 --out {root}/environments/sky.hdr",
            0,
            &["environments/sky.hdr"],
            root,
        ),
    ]
}

/// Runs every job through `run` (which parses and runs one command line) and writes the
/// MANIFEST of their outputs.
pub(crate) fn assets(
    a: &AssetsArgs,
    run: impl Fn(Vec<String>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let root = a.root.to_str().context("--root must be valid UTF-8")?;
    if root.contains(char::is_whitespace) {
        bail!("--root {root:?}: no whitespace allowed (it goes into MANIFEST commands)");
    }
    let mut entries = Vec::new();
    for j in jobs(root) {
        let command = format!("blueshift-tools {}", j.args.join(" "));
        println!("$ {command}");
        let t = Instant::now();
        run(j.args.clone()).with_context(|| format!("running {command}"))?;
        println!("  ({:.2} s)", t.elapsed().as_secs_f64());
        for o in &j.outputs {
            entries.push(Entry {
                path: o.clone(),
                sha256: manifest::sha256_file(&a.root.join(o))?,
                seed: j.seed,
                command: command.clone(),
            });
        }
    }
    let path = a.root.join("MANIFEST");
    blueshift_assets::write_atomic(&path, manifest::format(&entries).as_bytes())?;
    println!("wrote {} ({} files)", path.display(), entries.len());
    Ok(())
}

pub(crate) fn manifest(a: &ManifestArgs) -> anyhow::Result<()> {
    if !a.check {
        bail!("nothing to do: pass --check");
    }
    let bad = manifest::check(&a.manifest)?;
    if !bad.is_empty() {
        for b in &bad {
            eprintln!("{b}");
        }
        bail!(
            "{} file(s) do not match {}",
            bad.len(),
            a.manifest.display()
        );
    }
    let n = manifest::parse(&std::fs::read_to_string(&a.manifest)?)?.len();
    println!("{}: all {n} hashes match", a.manifest.display());
    Ok(())
}
