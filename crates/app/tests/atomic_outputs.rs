//! `eval` and `bench` runs that fail halfway (the device lost after some frames were done)
//! leave nothing behind: no report, no saved frame, no temporary directory, no output
//! directory they created, no partial table on stdout; an existing output directory keeps its
//! files as they were. Successful runs still write everything.
mod common;

use common::{Case, files_under};
use std::path::Path;

/// The device is lost from the third trace submission on: after two frames of a method ran
/// (and, with `--save-frames`, were saved), when the references come from the cache.
const LOST: [(&str, &str); 1] = [("BLUESHIFT_TEST_DEVICE_LOST", "trace@2")];

/// `blueshift eval` of `white` alone, 4 frames of 16x16 at 1 spp and 1 bounce, 64-spp
/// references cached in `cache/`, with `--save-frames`, into `out`.
fn eval(c: &Case, out: &Path, env: &[(&str, &str)]) -> std::process::Output {
    let (cache, out) = (c.path("cache"), out.to_str().expect("utf-8"));
    let mut args = vec!["--validation", "eval", "--methods", "white", "--spp", "1"];
    args.extend(["--camera", "static", "--bounces", "1", "--frames", "4"]);
    args.extend(["--width", "16", "--height", "16", "--reference-spp", "64"]);
    args.extend(["--save-frames", "--out", out, "--cache"]);
    args.push(cache.to_str().expect("utf-8"));
    c.run(&args, env)
}

/// Every file below `dir`, relative to it, sorted.
fn relative_files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = files_under(dir)
        .iter()
        .map(|p| {
            let rel = p.strip_prefix(dir).expect("below dir");
            rel.to_string_lossy().into_owned()
        })
        .collect();
    names.sort();
    names
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_failed_eval_leaves_no_report_and_no_frames() {
    let c = Case::new();
    // A successful run (it also fills the reference cache, so the runs below trace only the
    // method's frames): the report, the figures and the saved frames.
    let ok = c.path("ok");
    let o = eval(&c, &ok, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = relative_files(&ok);
    for want in [
        "report.json",
        "report.md",
        "frames/static_b1_spp1_white/frame_00003.exr",
        "frames/static_b1_spp1_white/reference_00003.exr",
    ] {
        assert!(written.iter().any(|f| f == want), "{want} in {written:?}");
    }
    assert!(written.iter().all(|f| !f.contains(".blueshift-partial")));

    // Lost halfway into a new directory: nothing, not even the directory.
    let o = eval(&c, &c.out(), &LOST);
    c.expect_error(&o, &["device was lost while running pass 'trace'"]);
    assert!(!c.out().exists(), "the output directory it created is left");

    // Into an existing directory holding an older report, saved frames and a file of the
    // user's: all stay as they were, nothing is added.
    let old = [
        ("report.md", "an older report"),
        (
            "frames/static_b1_spp1_white/frame_00000.exr",
            "an older frame",
        ),
        ("notes.txt", "mine"),
    ];
    for (name, text) in old {
        let p = c.out().join(name);
        std::fs::create_dir_all(p.parent().expect("parent")).expect("mkdir");
        std::fs::write(p, text).expect("write");
    }
    let mut before: Vec<String> = old.iter().map(|(n, _)| n.to_string()).collect();
    before.sort();
    let o = eval(&c, &c.out(), &LOST);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(relative_files(&c.out()), before, "{}", stderr(&o));
    assert_eq!(
        std::fs::read_dir(c.out()).expect("read").count(),
        3,
        "no temporary directory is left"
    );
    for (name, text) in old {
        let got = std::fs::read_to_string(c.out().join(name)).expect("read");
        assert_eq!(got, text);
    }

    // A successful run into it: its files replace the older ones, the user's file stays.
    let o = eval(&c, &c.out(), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut want = written.clone();
    want.push("notes.txt".into());
    want.sort();
    assert_eq!(relative_files(&c.out()), want);
    let md = std::fs::read_to_string(c.out().join("report.md")).expect("read");
    assert!(md.starts_with("# Blueshift evaluation"), "{md}");
}

#[test]
fn a_file_where_eval_puts_its_frames_is_named_before_anything_moves() {
    let c = Case::new();
    std::fs::create_dir(c.out()).expect("mkdir");
    std::fs::write(c.out().join("frames"), "in the way").expect("write");
    let o = eval(&c, &c.out(), &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.lines().any(|l| l.starts_with("error: cannot write ")
            && l.contains("frames/: a file of that name is in the way")),
        "{err}"
    );
    // Nothing was moved in: not even report.json, whose name is free.
    assert_eq!(relative_files(&c.out()), ["frames"]);
    assert_eq!(std::fs::read_dir(c.out()).expect("read").count(), 1);
}

/// `blueshift bench` of 8x8 at 1 spp, one warm-up and one timed frame, with the loop table.
fn bench(c: &Case, env: &[(&str, &str)]) -> std::process::Output {
    let mut args = vec!["--validation", "bench", "--width", "8", "--height", "8"];
    args.extend(["--warmup", "1", "--frames", "1", "--loop-stats"]);
    c.run(&args, env)
}

#[test]
fn a_failed_bench_prints_no_results() {
    let c = Case::new();
    let o = bench(&c, &[]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    for want in ["trace median", "Msamples/s", "all loops"] {
        assert!(stdout.contains(want), "{want} missing from:\n{stdout}");
    }
    // Lost in the loop-counting frames, after the timed ones: no partial table.
    let o = bench(&c, &LOST);
    c.expect_error(&o, &["device was lost while running pass 'trace'"]);
    assert_eq!(String::from_utf8_lossy(&o.stdout), "");
}
