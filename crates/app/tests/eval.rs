//! A tiny `blueshift eval` on lavapipe (validation on): the report's JSON parses, every
//! configured run is present, and its numbers match a recomputation from the saved frames.
use blueshift_analysis::{Boundary, Gray, blurred_rmse, rmse};
use std::path::Path;
mod common;
use std::process::Command;

fn lum(path: &Path) -> Gray {
    Gray::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `blueshift GLOBAL eval` of `methods` on a static camera at 1 spp and 1 bounce, `frames`
/// frames of `size` x `size`, against 64-spp references cached in `dir/cache`, reporting to
/// `dir/report`.
fn tiny_eval(dir: &Path, global: &[&str], methods: &str, frames: &str, size: &str) -> Command {
    let mut cmd = common::clean(Command::new(common::BIN));
    cmd.args(global)
        .args([
            "eval",
            "--methods",
            methods,
            "--spp",
            "1",
            "--camera",
            "static",
        ])
        .args(["--bounces", "1", "--frames", frames, "--width", size])
        .args(["--height", size, "--reference-spp", "64"])
        .arg("--cache")
        .arg(dir.join("cache"))
        .arg("--out")
        .arg(dir.join("report"))
        .env("XDG_RUNTIME_DIR", dir);
    cmd
}

#[test]
fn tiny_eval_report_matches_recomputation_from_saved_frames() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let status = tiny_eval(
        dir.path(),
        &["--validation"],
        "white,sort-retarget",
        "8",
        "64",
    )
    .arg("--save-frames")
    .status()
    .unwrap();
    assert!(status.success(), "eval failed: {status}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert!(out.join("report.md").exists());
    let runs = report["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for run in runs {
        let method = run["method"].as_str().unwrap();
        let frames = out.join("frames").join(format!("static_b1_spp1_{method}"));
        // Metrics cover the second half of the frames (4..=7).
        let (mut se, mut sp1) = (0.0, 0.0);
        for t in 4..8 {
            let est = lum(&frames.join(format!("frame_{t:05}.exr")));
            let reference = lum(&frames.join(format!("reference_{t:05}.exr")));
            let e = est.sub(&reference).unwrap();
            se += rmse(&e).powi(2);
            sp1 += blurred_rmse(&e, 1.0, Boundary::Clamp).unwrap().powi(2);
        }
        let (want_rmse, want_p1) = ((se / 4.0).sqrt(), (sp1 / 4.0).sqrt());
        let got_rmse = run["raw"]["rmse"]["all"].as_f64().unwrap();
        let got_p1 = run["raw"]["p1"]["all"].as_f64().unwrap();
        // The report uses the shader's luminance, the recomputation Rec.709 luminance of the
        // saved RGB: equal up to float rounding.
        assert!(
            (got_rmse - want_rmse).abs() <= 1e-4 * want_rmse,
            "{method} RMSE {got_rmse} vs {want_rmse}"
        );
        assert!(
            (got_p1 - want_p1).abs() <= 1e-4 * want_p1,
            "{method} P1 {got_p1} vs {want_p1}"
        );
        assert!(want_rmse > 0.0);
    }
    // Equal time: each run's frame is the sum of its pass medians, and its equal-time P1
    // ratio is its P1 ratio times the square root of its frame time over white's.
    let frame = |run: &serde_json::Value| -> f64 {
        let passes = run["pass_ms_median"].as_object().unwrap();
        assert!(passes.contains_key("trace"), "{passes:?}");
        passes.values().map(|v| v.as_f64().unwrap()).sum()
    };
    let white_ms = frame(&runs[0]);
    assert!(white_ms > 0.0);
    for run in runs {
        let t = frame(run) / white_ms;
        let got = run["frame_time_ratio_vs_white"].as_f64().unwrap();
        assert!((got - t).abs() <= 1e-9 * t, "time ratio {got} vs {t}");
        let p1 = run["ratios_vs_white"]["p1_clean"].as_f64().unwrap();
        let eq = run["equal_time_p1_clean_ratio"].as_f64().unwrap();
        assert!(
            (eq - p1 * t.sqrt()).abs() <= 1e-9,
            "equal time {eq} vs {p1} x sqrt({t})"
        );
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("## Per frame / accumulated at equal frame time"),
        "{md}"
    );
    let white_ratio = runs[0]["ratios_vs_white"]["p1"].as_f64().unwrap();
    assert!(
        (white_ratio - 1.0).abs() < 1e-12,
        "white against itself: {white_ratio}"
    );
}

/// A cache file of the right name that is not the job's reference (another size, the same
/// texel count in another shape, truncated, another key, ...) is a cache miss with a warning:
/// the reference is rendered again and the file replaced, never a panic or a wrong image.
#[test]
fn unusable_reference_cache_files_are_rendered_again() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let eval = || {
        let o = tiny_eval(dir.path(), &[], "white", "2", "8")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "eval failed:\n{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        stderr
    };
    let stderr = eval();
    assert!(!stderr.contains("reference cache"), "{stderr}");
    let files = common::files_under(&cache);
    assert_eq!(files.len(), 1, "one static reference: {files:?}");
    let file = &files[0];
    let good = std::fs::read(file).unwrap();
    // Magic, width, height, the 24-digit key, 8 x 8 texels of 4 f32.
    assert_eq!(good.len(), 8 + 4 + 4 + 24 + 8 * 8 * 16);
    let with_size = |w: u32, h: u32| {
        let mut b = good.clone();
        b[8..12].copy_from_slice(&w.to_le_bytes());
        b[12..16].copy_from_slice(&h.to_le_bytes());
        b
    };
    let mut other_key = good.clone();
    other_key[16] ^= 1;
    let mut longer = good.clone();
    longer.extend([0; 16]);
    for (bytes, why) in [
        (with_size(65536, 65536), "declares a 65536x65536 image"),
        (with_size(4, 16), "declares a 4x16 image"),
        (good[..good.len() - 16].to_vec(), "(truncated?)"),
        (good[..8].to_vec(), "fewer than the 40-byte header"),
        (Vec::new(), "fewer than the 40-byte header"),
        (other_key, "another cache key"),
        (longer, "over the limit"),
    ] {
        std::fs::write(file, &bytes).unwrap();
        let stderr = eval();
        let warning = stderr
            .lines()
            .find(|l| l.starts_with("warning: reference cache"))
            .unwrap_or_else(|| panic!("{why}: no warning in:\n{stderr}"));
        assert!(warning.contains(why), "{why}: {warning}");
        assert!(
            warning.ends_with("rendering the reference again"),
            "{warning}"
        );
        assert_eq!(std::fs::read(file).unwrap(), good, "{why}: not rewritten");
        assert_eq!(
            common::files_under(&cache).len(),
            1,
            "{why}: a temporary file left"
        );
    }
}
