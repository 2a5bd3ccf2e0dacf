//! `blueshift bench` of a method other than `white` also times `white` in the same run and
//! prints the frame-time ratio and its square root (what a P1 ratio is scaled by at equal
//! frame time).
mod common;
use std::process::Command;

#[test]
fn bench_times_white_in_the_same_run_for_the_frame_time_ratio() {
    let run = |method: &str| {
        let o = common::clean(Command::new(common::BIN))
            .args([
                "bench", "--method", method, "--width", "16", "--height", "16",
            ])
            .args(["--frames", "2", "--warmup", "1", "--bounces", "1"])
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        stdout
    };
    let out = run("sort-cycle");
    let line = out
        .lines()
        .find(|l| l.starts_with("frame median"))
        .unwrap_or_else(|| panic!("{out}"));
    // "frame median A ms (every pass); white's W ms in the same run: Rx (... q * S)"
    let num = |after: &str, upto: &str| -> f64 {
        let rest = &line[line.find(after).unwrap_or_else(|| panic!("{line}")) + after.len()..];
        rest[..rest.find(upto).unwrap()].trim().parse().unwrap()
    };
    let (a, w) = (num("frame median", "ms"), num("white's", "ms"));
    let (r, s) = (num("same run:", "x"), num("q *", ")"));
    assert!(a > 0.0 && w > 0.0, "{line}");
    // Each printed to three decimals: the ratio of the rounded times is off by their rounding.
    let slack = 0.0005 + r * (0.0005 / a + 0.0005 / w);
    assert!((r - a / w).abs() <= slack, "{line}");
    assert!((s - r.sqrt()).abs() <= 0.0005 + slack, "{line}");
    // White needs no second run.
    let white = run("white");
    assert!(!white.contains("white's"), "{white}");
    assert!(white.contains("frame median"), "{white}");
}
