//! The GLSL side: generated header in sync, bvh.glsl constants equal to Rust's, and the
//! example compute shader compiles (when glslc is installed).

use std::path::PathBuf;
use std::process::Command;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn generated_header_is_current() {
    let path = repo().join("shaders/include/generated/scene.glsl");
    let want = blueshift_scene::glsl_header();
    if std::env::var_os("BLUESHIFT_BLESS").is_some() {
        std::fs::write(&path, &want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "{} is stale: rerun with BLUESHIFT_BLESS=1",
        path.display()
    );
}

#[test]
fn bvh_trace_shader_compiles() {
    if Command::new("glslc").arg("--version").output().is_err() {
        eprintln!("glslc not installed: skipping");
        return;
    }
    let out = std::env::temp_dir().join(format!("bvh_trace_{}.spv", std::process::id()));
    let status = Command::new("glslc")
        .args(["--target-env=vulkan1.2", "-I"])
        .arg(repo().join("shaders/include"))
        .arg(repo().join("shaders/test/bvh_trace.comp"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let _ = std::fs::remove_file(&out);
    assert!(
        status.status.success(),
        "glslc failed:\n{}",
        String::from_utf8_lossy(&status.stderr)
    );
}
