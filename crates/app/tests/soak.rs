//! A 500-frame soak of the frame loop (the `blueshift soak` command at a tiny size): the seed
//! buffer stays a permutation and host/device memory stay flat; the figures are printed.
use std::process::Command;

#[test]
fn soak_500_frames_keeps_the_permutation_and_flat_memory() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = Command::new(env!("CARGO_BIN_EXE_blueshift"))
        .args([
            "soak",
            "--frames",
            "500",
            "--check-every",
            "100",
            "--warmup",
            "50",
        ])
        .args(["--width", "24", "--height", "20", "--bounces", "1"])
        .env("XDG_RUNTIME_DIR", dir.path())
        .env_remove("BLUESHIFT_TEST_DEVICE_LOST")
        .env_remove("BLUESHIFT_MAX_STORAGE_BUFFER_RANGE")
        .output()
        .expect("run blueshift soak");
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
