//! The harness of crates/app/tests/errors.rs and flags.rs: runs the binary in a temp dir
//! with a clean environment and checks an error run (exit code 1, one `error:` line, no
//! output file).
// Each test binary that includes it uses a part of it.
#![allow(dead_code)]
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub const BIN: &str = env!("CARGO_BIN_EXE_blueshift");
/// A tiny, fast render.
pub const TINY: [&str; 8] = [
    "--width",
    "8",
    "--height",
    "8",
    "--bounces",
    "1",
    "--frames",
    "1",
];

/// `cmd` without any inherited `BLUESHIFT_*` variable (settings and fault hooks alike), so a
/// test sees only what it sets.
pub fn clean(mut cmd: Command) -> Command {
    for (var, _) in std::env::vars_os() {
        if var.to_string_lossy().starts_with("BLUESHIFT_") {
            cmd.env_remove(var);
        }
    }
    cmd
}

pub fn assets() -> PathBuf {
    // Runtime variable (set by `cargo test`): right even if the binary came from another checkout.
    Path::new(&std::env::var_os("CARGO_MANIFEST_DIR").expect("run under cargo"))
        .join("../../assets")
}

pub struct Case {
    dir: tempfile::TempDir,
}

impl Case {
    pub fn new() -> Self {
        Self {
            dir: tempfile::tempdir().expect("tempdir"),
        }
    }
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
    pub fn out(&self) -> PathBuf {
        self.path("out")
    }
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let p = self.path(name);
        std::fs::write(&p, bytes).expect("write input");
        p
    }
    /// Runs `blueshift ARGS` with a clean environment (no inherited BLUESHIFT_* settings).
    pub fn run(&self, args: &[&str], env: &[(&str, &str)]) -> Output {
        let mut cmd = clean(Command::new(BIN));
        cmd.args(args).env("XDG_RUNTIME_DIR", self.dir.path());
        for (k, v) in env {
            cmd.env(k, v);
        }
        cmd.output().expect("run blueshift")
    }
    /// `blueshift render` of a tiny image into `out/` with extra arguments.
    pub fn render(&self, extra: &[&str], env: &[(&str, &str)]) -> Output {
        self.render_sized(("8", "8"), "1", extra, env)
    }
    /// `blueshift render` into `out/` at a size and frame count, at 2 bounces (where the
    /// default sorts: in direct light on the untextured box it reads no seed and skips it).
    pub fn render_sized(
        &self,
        (w, h): (&str, &str),
        frames: &str,
        extra: &[&str],
        env: &[(&str, &str)],
    ) -> Output {
        let out = self.out();
        let mut args = vec!["render", "--out", out.to_str().expect("utf-8 temp path")];
        args.extend([
            "--width",
            w,
            "--height",
            h,
            "--bounces",
            "2",
            "--frames",
            frames,
        ]);
        args.extend(extra);
        self.run(&args, env)
    }
    /// Exit code 1, one `error:` line containing every `needle`, no panic, no output file.
    pub fn expect_error(&self, o: &Output, needles: &[&str]) -> String {
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(1), "exit code; stderr:\n{stderr}");
        assert!(!stderr.contains("panicked"), "panic:\n{stderr}");
        let line = stderr
            .lines()
            .find(|l| l.starts_with("error: "))
            .unwrap_or_else(|| panic!("no 'error:' line in:\n{stderr}"));
        for n in needles {
            assert!(line.contains(n), "'{n}' missing from: {line}");
        }
        assert_eq!(files_under(&self.out()), Vec::<PathBuf>::new(), "{line}");
        line.to_string()
    }
}

/// Every file below `dir` (none when it does not exist).
pub fn files_under(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files = Vec::new();
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files.extend(files_under(&p));
        } else {
            files.push(p);
        }
    }
    files
}

/// A one-triangle glTF with an embedded buffer holding `positions`.
pub fn triangle_gltf(positions: [[f32; 3]; 3], extensions: &str) -> String {
    let bytes: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
          "min":[0,0,0],"max":[1,1,0]}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{}"}}]{extensions}}}"#,
        base64(&bytes)
    )
}

pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for i in 0..4 {
            if i <= c.len() {
                s.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}
