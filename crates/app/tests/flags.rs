//! Bad flags of every command (the flag rows of docs/errors.md): one `error: ...` line that
//! names the flag and its range, exit code 1, never a panic; and the one exit code 2, an
//! internal error.
mod common;

use common::Case;

#[test]
fn resolution_out_of_range() {
    let c = Case::new();
    for (w, h) in [("0", "8"), ("8", "0"), ("20000", "8")] {
        let o = c.render_sized((w, h), "1", &[], &[]);
        c.expect_error(&o, &[&format!("resolution {w}x{h} is outside 1..=")]);
    }
    // Within the image limit but over the device's storage-buffer range.
    let o = c.render_sized(
        ("64", "64"),
        "1",
        &[],
        &[("BLUESHIFT_MAX_STORAGE_BUFFER_RANGE", "32768")],
    );
    c.expect_error(&o, &["resolution 64x64", "storage-buffer range"]);
}

#[test]
fn block_size_out_of_range() {
    let c = Case::new();
    for b in ["1", "9"] {
        let o = c.render(&["--block", b], &[]);
        c.expect_error(&o, &[&format!("block size {b} is outside 2..=8")]);
    }
    let o = c.run(
        &["bench", "--block", "0", "--width", "8", "--height", "8"],
        &[],
    );
    c.expect_error(&o, &["block size 0 is outside 2..=8"]);
}

#[test]
fn other_bad_arguments_are_errors_not_panics() {
    let c = Case::new();
    let o = c.render(&["--method", "nope"], &[]);
    c.expect_error(&o, &["unknown method 'nope'", "sort-retarget"]);
    let o = c.render(&["--method", "sort-retarget:key=history"], &[]);
    c.expect_error(&o, &["sort-retarget:key=history", "needs motion=reproject"]);
    let o = c.render(&["--sampler", "nope"], &[]);
    c.expect_error(&o, &["unknown sampler 'nope'"]);
    let o = c.render_sized(("8", "8"), "0", &[], &[]);
    c.expect_error(&o, &["--frames 0"]);
    let o = c.run(&["render", "--no-such-flag"], &[]);
    c.expect_error(&o, &["unexpected argument '--no-such-flag'"]);
    let out = c.out();
    let out = out.to_str().expect("utf-8");
    for (flag, value, want) in [
        (
            "--scene",
            "/nonexistent.glb",
            "/nonexistent.glb: file not found",
        ),
        (
            "--first-sequence",
            "4000000000",
            "--first-sequence 4000000000 is above",
        ),
    ] {
        let o = c.run(&["eval", flag, value, "--out", out], &[]);
        c.expect_error(&o, &[want]);
    }
    let o = c.run(
        &[
            "soak",
            "--method",
            "white",
            "--frames",
            "10",
            "--check-every",
            "5",
        ],
        &[],
    );
    c.expect_error(
        &o,
        &["--method must permute seeds", "sort-retarget", "not white"],
    );
    for (flag, value) in [("--frames", "0"), ("--warmup", "0"), ("--warmup", "5000")] {
        let o = c.run(
            &["bench", flag, value, "--width", "8", "--height", "8"],
            &[],
        );
        c.expect_error(&o, &[&format!("{flag} {value} is outside 1..=1000")]);
    }
    let o = c.run(&["soak", "--frames", "4", "--check-every", "5"], &[]);
    c.expect_error(&o, &["--check-every 5 is outside 1..=--frames (4)"]);
    let o = c.render(&["--camera-path", "static:5"], &[]);
    c.expect_error(
        &o,
        &["camera path 'static:5': static takes no argument (got '5')"],
    );
    let o = c.run(&["soak", "--camera-path", "/nonexistent/path.json"], &[]);
    c.expect_error(&o, &["/nonexistent/path.json", "orbit-view:DEG"]);
}

#[test]
fn a_panic_is_an_internal_error_with_exit_code_2() {
    let c = Case::new();
    let o = c.render(&[], &[("BLUESHIFT_TEST_PANIC", "1")]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.starts_with("internal error: "), "{stderr}");
    assert!(stderr.contains("this is a bug"), "{stderr}");
}
