//! A 500-frame soak of the frame loop (the `blueshift soak` command at a tiny size): the seed
//! buffer stays a permutation and host/device memory stay flat; the figures are printed. And
//! short soaks with a moving camera, whose checks also read back the method's history.
mod common;
use std::process::{Command, Output};

fn soak(args: &[&str]) -> Output {
    let dir = tempfile::tempdir().expect("tempdir");
    common::clean(Command::new(common::BIN))
        .arg("soak")
        .args(args)
        // Two bounces: the default sorts there still and moving (in direct light on the
        // untextured box it reads no seed and skips the sort).
        .args(["--width", "24", "--height", "20", "--bounces", "2"])
        .env("XDG_RUNTIME_DIR", dir.path())
        .output()
        .expect("run blueshift soak")
}

/// The default method (a point-cycle history) on a strafe and a history-key method (history
/// means, reprojection) on an in-view orbit: every check reads finite history and no new
/// allocation.
#[test]
fn moving_soaks_keep_the_permutation_and_a_finite_history() {
    for (method, path) in [
        ("sort-cycle", "strafe:2.5"),
        ("sort-grid-adaptive", "orbit-view:3"),
    ] {
        let out = soak(&[
            "--method",
            method,
            "--camera-path",
            path,
            "--frames",
            "30",
            "--check-every",
            "10",
            "--warmup",
            "5",
        ]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "stdout:\n{stdout}\nstderr:\n{stderr}");
        assert!(stdout.contains(&format!("camera {path}")), "{stdout}");
        let checks: Vec<&str> = stdout.lines().filter(|l| l.starts_with("frame ")).collect();
        assert_eq!(checks.len(), 3, "{stdout}");
        for line in checks {
            assert!(line.contains("seeds a permutation"), "{line}");
            assert!(line.contains("history finite"), "{line}");
            assert!(line.contains("allocations (+0)"), "{line}");
        }
    }
}

#[test]
fn soak_500_frames_keeps_the_permutation_and_flat_memory() {
    let out = soak(&["--frames", "500", "--check-every", "100", "--warmup", "50"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "stdout:\n{stdout}\nstderr:\n{stderr}");
    assert!(
        stdout.contains("baseline after 50 frames: RSS "),
        "{stdout}"
    );
    let checks: Vec<&str> = stdout.lines().filter(|l| l.starts_with("frame ")).collect();
    assert_eq!(checks.len(), 5, "{stdout}");
    for (i, line) in checks.iter().enumerate() {
        assert!(
            line.contains(&format!("{}:", (i + 1) * 100)),
            "check {i}: {line}"
        );
        assert!(line.contains("seeds a permutation"), "{line}");
        assert!(
            line.contains("KiB") && line.contains("device memory"),
            "{line}"
        );
        assert!(line.contains("(+0 bytes)"), "device memory grew: {line}");
    }
    assert!(stdout.contains("soak passed: 500 frames"), "{stdout}");
}

/// A short soak without `--check-every` checks at its last frame (the default interval is
/// 1000 frames or `--frames`, if fewer), and the largest tolerances (once wrapped to -1 in
/// i64, failing every check) allow any growth.
#[test]
fn a_short_soak_needs_no_interval_and_any_tolerance_is_accepted() {
    let max = u64::MAX.to_string();
    let out = soak(&[
        "--frames",
        "4",
        "--rss-tolerance-kib",
        &max,
        "--device-tolerance",
        &max,
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "stdout:\n{stdout}\nstderr:\n{stderr}");
    assert!(stdout.contains("check every 4"), "{stdout}");
    let checks: Vec<&str> = stdout.lines().filter(|l| l.starts_with("frame ")).collect();
    assert_eq!(checks.len(), 1, "{stdout}");
    assert!(stdout.contains("soak passed: 4 frames"), "{stdout}");
}
