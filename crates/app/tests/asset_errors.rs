//! Asset errors: presets found through `--assets`, optional masks a method needs, and asset
//! files that do not fit together.
mod common;

use common::{Case, TINY, assets};

/// A preset is looked up in `--assets` first: with the default assets directory (here
/// `BLUESHIFT_ASSETS`) empty, `--assets` alone must find it; without it the preset is missing.
#[test]
fn scene_presets_come_from_the_assets_flag() {
    let c = Case::new();
    let empty = c.path("empty-assets");
    std::fs::create_dir(&empty).expect("mkdir");
    let env = [("BLUESHIFT_ASSETS", empty.to_str().expect("utf-8"))];
    let o = c.render(&["--scene", "edges"], &env);
    c.expect_error(&o, &["'edges' is neither a file nor a preset"]);
    let a = assets();
    let a = a.to_str().expect("utf-8");
    let o = c.render(&["--scene", "edges", "--assets", a], &env);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "stderr:\n{stderr}");
}

/// A directory of its own holding only the assets every method needs (no FAST mask, no
/// motion volume, no key tables).
fn required_assets(c: &Case, name: &str) -> std::path::PathBuf {
    let src = assets();
    let dir = c.path(name);
    for f in [
        "masks/bn64.r16",
        "masks/stbn64x32.r16",
        "retarget/bn64_s48_36_r6.bin",
    ] {
        let to = dir.join(f);
        std::fs::create_dir_all(to.parent().expect("parent")).expect("mkdir");
        std::fs::copy(src.join(f), &to).expect("copy asset");
    }
    dir
}

#[test]
fn fast_without_its_mask_names_the_tool() {
    let c = Case::new();
    let dir = required_assets(&c, "assets-without-fast");
    let a = dir.to_str().expect("utf-8");
    // `fast` is a comparison baseline: bench takes it, render does not.
    let mut args = vec!["bench", "--assets", a, "--method", "fast"];
    args.extend(TINY);
    let o = c.run(&args, &[]);
    c.expect_error(&o, &["no FAST mask", "blueshift-tools fast"]);
    let o = c.render(&["--assets", a, "--method", "fast"], &[]);
    c.expect_error(&o, &["unknown method 'fast'", "presets: white"]);
}

#[test]
fn the_default_without_its_motion_volume_names_the_asset() {
    let c = Case::new();
    let dir = required_assets(&c, "assets-without-motion");
    let a = dir.to_str().expect("utf-8");
    // Refused when the renderer is made, though a still view never reads it (the default
    // reads it in direct light).
    let out = c.out();
    let out = out.to_str().expect("utf-8");
    let direct = |method: &str| {
        let args = ["render", "--out", out, "--width", "8", "--height", "8"];
        let more = [
            "--frames",
            "1",
            "--bounces",
            "1",
            "--assets",
            a,
            "--method",
            method,
        ];
        c.run(&[&args[..], &more[..]].concat(), &[])
    };
    c.expect_error(
        &direct("sort-cycle"),
        &["no motion volume", "masks/stbn64x32_t0.5.r16"],
    );
    // The form that does not read it renders.
    let o = direct("sort-cycle:without=motion-volume");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "stderr:\n{stderr}");
}

#[test]
fn mask_size_does_not_match_retarget_table() {
    let c = Case::new();
    let dir = c.path("assets");
    for sub in ["masks", "retarget"] {
        std::fs::create_dir_all(dir.join(sub)).expect("mkdir");
    }
    let a = assets();
    let copy = |from: &str, to: &str| {
        std::fs::copy(a.join(from), dir.join(to)).expect("copy asset");
    };
    copy("masks/bn32.r16", "masks/bn64.r16"); // a 32x32 mask under the 64x64 name
    copy("retarget/bn64_s48_36_r6.bin", "retarget/bn64_s48_36_r6.bin");
    copy("masks/stbn64x32.r16", "masks/stbn64x32.r16");
    let o = c.render(&["--assets", dir.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["is for a 64x64 mask", "is 32x32"]);
}
