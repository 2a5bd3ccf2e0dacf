//! The asset MANIFEST: one line per file,
//! `path<TAB>sha256<TAB>seed<TAB>command`, where `path` is relative to the MANIFEST's
//! directory and `command` is the `blueshift-tools` command line, run from the repository
//! root, that wrote the file. Lines starting with `#` are comments.

use std::io::Read;
use std::path::Path;

use anyhow::{Context, bail};
use sha2::{Digest, Sha256};

/// One MANIFEST line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// Path relative to the MANIFEST's directory.
    pub path: String,
    /// Lower-case hex SHA-256.
    pub sha256: String,
    /// The PRNG seed of the command (0 if it uses none).
    pub seed: u64,
    /// The command line, starting with `blueshift-tools`.
    pub command: String,
}

impl Entry {
    /// The command's arguments after the program name (split on whitespace).
    pub fn args(&self) -> Vec<String> {
        self.command
            .split_whitespace()
            .skip(1)
            .map(str::to_string)
            .collect()
    }
}

/// Header written at the top of every MANIFEST.
pub const HEADER: &str = "# Blueshift assets. path (relative to this file)\tsha256\tseed\t\
command (run from the repository root). Regenerate all: blueshift-tools assets; verify: \
blueshift-tools manifest --check\n";

/// Parses MANIFEST text.
pub fn parse(text: &str) -> anyhow::Result<Vec<Entry>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = line.splitn(4, '\t').collect();
        if f.len() != 4 {
            bail!("MANIFEST line {}: expected 4 tab-separated fields", i + 1);
        }
        if f[1].len() != 64 || !f[1].bytes().all(|b| b.is_ascii_hexdigit()) {
            bail!("MANIFEST line {}: bad sha256 {:?}", i + 1, f[1]);
        }
        let seed = f[2]
            .parse()
            .with_context(|| format!("MANIFEST line {}: bad seed {:?}", i + 1, f[2]))?;
        out.push(Entry {
            path: f[0].to_string(),
            sha256: f[1].to_ascii_lowercase(),
            seed,
            command: f[3].to_string(),
        });
    }
    Ok(out)
}

/// Formats entries as MANIFEST text (with [`HEADER`]).
pub fn format(entries: &[Entry]) -> String {
    let mut s = String::from(HEADER);
    for e in entries {
        s.push_str(&format!(
            "{}\t{}\t{}\t{}\n",
            e.path, e.sha256, e.seed, e.command
        ));
    }
    s
}

/// Lower-case hex SHA-256 of a file.
pub fn sha256_file(path: &Path) -> anyhow::Result<String> {
    let mut f = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let mut h = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let k = f
            .read(&mut buf)
            .with_context(|| format!("reading {}", path.display()))?;
        if k == 0 {
            break;
        }
        h.update(&buf[..k]);
    }
    Ok(h.finalize().iter().map(|b| format!("{b:02x}")).collect())
}

/// Checks every entry of the MANIFEST at `manifest`; returns one message per mismatching or
/// missing file (empty when all match).
pub fn check(manifest: &Path) -> anyhow::Result<Vec<String>> {
    let text = std::fs::read_to_string(manifest)
        .with_context(|| format!("reading {}", manifest.display()))?;
    let dir = manifest.parent().unwrap_or(Path::new("."));
    let mut bad = Vec::new();
    for e in parse(&text)? {
        let p = dir.join(&e.path);
        match sha256_file(&p) {
            Ok(h) if h == e.sha256 => {}
            Ok(h) => bad.push(format!(
                "{}: sha256 {h}, MANIFEST says {}",
                e.path, e.sha256
            )),
            Err(err) => bad.push(format!("{}: {err:#}", e.path)),
        }
    }
    Ok(bad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_parse_round_trip() {
        let e = vec![Entry {
            path: "masks/a.r16".into(),
            sha256: "ab".repeat(32),
            seed: 7,
            command: "blueshift-tools mask --size 16 --out assets/masks/a.r16".into(),
        }];
        assert_eq!(parse(&format(&e)).unwrap(), e);
        assert_eq!(e[0].args()[0], "mask");
        assert!(parse("x\ty\n").is_err());
    }
}
