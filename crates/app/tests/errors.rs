//! Every bad input of the table of docs/errors.md: the binary prints one
//! `error: ...` line naming the problem, exits with code 1 (never a panic), and leaves no
//! output file behind.
mod common;

use common::{Case, TINY, files_under, triangle_gltf};
use std::path::Path;

const GOOD: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

#[test]
fn missing_scene_file() {
    let c = Case::new();
    let o = c.render(&["--scene", "/nonexistent/scene.gltf"], &[]);
    c.expect_error(&o, &["/nonexistent/scene.gltf", "file not found"]);
    let o = c.render(&["--scene", "cornel-box"], &[]);
    c.expect_error(
        &o,
        &["'cornel-box' is neither a file nor a preset", "cornell-box"],
    );
}

#[test]
fn unreadable_scene_file() {
    let c = Case::new();
    let dir = c.path("a-directory.gltf");
    std::fs::create_dir(&dir).expect("mkdir");
    let o = c.render(&["--scene", dir.to_str().expect("utf-8")], &[]);
    c.expect_error(
        &o,
        &["a-directory.gltf", "cannot read", "not a regular file"],
    );
}

#[test]
fn missing_asset_and_camera_path_files() {
    let c = Case::new();
    let empty = c.path("no-assets");
    std::fs::create_dir(&empty).expect("mkdir");
    let o = c.render(&["--assets", empty.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["masks/bn64.r16", "No such file"]);
    let o = c.render(&["--camera-path", "/nonexistent/path.json"], &[]);
    c.expect_error(
        &o,
        &["camera path '/nonexistent/path.json'", "presets: static"],
    );
}

/// A FIFO where a file is expected (environment map, camera path, mask asset) is refused
/// before it is opened: opening it would block until a writer appears.
#[test]
fn special_files_are_refused_unopened() {
    let c = Case::new();
    let fifo = |name: &str| {
        let p = c.path(name);
        if let Some(dir) = p.parent() {
            std::fs::create_dir_all(dir).expect("mkdir");
        }
        let ok = std::process::Command::new("mkfifo")
            .arg(&p)
            .status()
            .expect("mkfifo runs")
            .success();
        assert!(ok, "mkfifo {}", p.display());
        p.to_str().expect("utf-8").to_string()
    };
    let env = fifo("sky.hdr");
    let o = c.render(&["--environment", &env], &[]);
    c.expect_error(&o, &["sky.hdr", "not a regular file (a FIFO)"]);
    let path = fifo("path.json");
    let o = c.render(&["--camera-path", &path], &[]);
    c.expect_error(
        &o,
        &["camera path", "path.json", "not a regular file (a FIFO)"],
    );
    let mask = fifo("assets/masks/bn64.r16");
    let dir = mask.trim_end_matches("/masks/bn64.r16");
    let o = c.render(&["--assets", dir], &[]);
    c.expect_error(&o, &["masks/bn64.r16", "not a regular file (a FIFO)"]);
}

#[test]
fn malformed_gltf_and_camera_path() {
    let c = Case::new();
    let p = c.write("broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, ");
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    let line = c.expect_error(&o, &["broken.gltf", "not a valid glTF 2.0 file"]);
    // The parser's message is printed once, not repeated by the error chain.
    assert_eq!(line.matches("EOF").count(), 1, "{line}");
    let p = c.write("glb.glb", b"glTF\x02\x00\x00\x00\xff\xff\xff\xff");
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["glb.glb", "not a valid glTF 2.0 file"]);
    let p = c.write("path.json", r#"{"keyframes": 3}"#);
    let o = c.render(&["--camera-path", p.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["path.json", "expected a sequence"]);
}

#[test]
fn bad_buffer_uris() {
    let c = Case::new();
    let good = triangle_gltf(GOOD, "");
    let start = good.find("data:").expect("data URI");
    let end = start + good[start..].find('"').expect("end of URI");
    for (name, uri, needle) in [
        ("gone.gltf", "gone.bin", "No such file"),
        (
            "percent.gltf",
            "%FF.bin",
            "percent-encoding does not decode to UTF-8",
        ),
    ] {
        let doc = format!("{}{uri}{}", &good[..start], &good[end..]);
        let p = c.write(name, doc);
        let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
        c.expect_error(
            &o,
            &[name, &format!("buffer 0 ({uri}): cannot load"), needle],
        );
    }
    // An absolute path leads outside the scene directory: refused before anything is opened.
    let p = c.write(
        "zero.gltf",
        format!("{}/dev/zero{}", &good[..start], &good[end..]),
    );
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    c.expect_error(
        &o,
        &[
            "zero.gltf: buffer 0 URI '/dev/zero' points outside the scene directory",
            "(it is an absolute path)",
        ],
    );
    // Allowed to lead outside, the URI still names no regular file: refused unread.
    let zero = p.to_str().expect("utf-8");
    let o = c.render(&["--scene", zero, "--allow-outside-paths"], &[]);
    c.expect_error(&o, &["zero.gltf: buffer 0", "not a regular file"]);
}

#[test]
fn unsupported_extension() {
    let c = Case::new();
    let required = r#","extensionsUsed":["EXT_unknown"],"extensionsRequired":["EXT_unknown"]"#;
    let p = c.write("required.gltf", triangle_gltf(GOOD, required));
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    c.expect_error(
        &o,
        &["required.gltf: requires unsupported extension EXT_unknown"],
    );
    // Used but not required: a warning, and the scene renders without it.
    let p = c.write(
        "used.gltf",
        triangle_gltf(GOOD, r#","extensionsUsed":["EXT_unknown"]"#),
    );
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: extension EXT_unknown not supported, ignored"),
        "{stderr}"
    );
    assert_eq!(files_under(&c.out()).len(), 2); // PNG + EXR
}

#[test]
fn non_finite_geometry() {
    let c = Case::new();
    for (name, bad) in [("nan.gltf", f32::NAN), ("inf.gltf", f32::INFINITY)] {
        let p = c.write(
            name,
            triangle_gltf([[0.0; 3], [bad, 0.0, 0.0], [0.0, 1.0, 0.0]], ""),
        );
        let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
        c.expect_error(&o, &[name, "vertex 1 has a non-finite position"]);
    }
}

#[test]
fn empty_scene() {
    let c = Case::new();
    let p = c.write(
        "empty.gltf",
        r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[]}]}"#,
    );
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["empty.gltf", "no triangles to render"]);
    let p = c.write("degenerate.gltf", triangle_gltf([[0.0; 3]; 3], ""));
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["degenerate.gltf", "non-zero area"]);
}

#[test]
fn scene_over_device_limits() {
    let c = Case::new();
    // The test hook lowers the device's maxStorageBufferRange to 2 KiB, while the 8x8 image's
    // buffers (1 KiB) still fit: the BVH of n triangles has up to 2n - 1 nodes of 36 bytes,
    // so the loader takes at most (2048 / 36 + 1) / 2 = 28 triangles, fewer than the Cornell
    // box's, and refuses it from its counts.
    let o = c.render(&[], &[("BLUESHIFT_MAX_STORAGE_BUFFER_RANGE", "2048")]);
    c.expect_error(
        &o,
        &[
            "triangles after instancing, over the loader's limit of 28",
            "what this device holds: maxStorageBufferRange 2048 bytes",
        ],
    );
}

#[test]
fn node_graphs_that_are_not_trees_and_scenes_over_the_budget() {
    use blueshift_scene::presets::hostile;
    let c = Case::new();
    // Found at run time (see loader_limits.rs): the target directory may be shared.
    let seed = blueshift_assets::workspace_path(
        "fuzz/corpus/gltf/seed_regress_node_cycle.glb",
        Path::is_file,
    );
    let cases = [
        (
            "cycle.glb",
            std::fs::read(seed).expect("regression seed"),
            "node 0 is its own ancestor",
        ),
        (
            "parents.glb",
            hostile::two_parents(),
            "node 2 has two parents, nodes 0 and 1",
        ),
        (
            "chain.glb",
            hostile::shared_chain(40),
            "node 39 is listed more than once among the children of node 38",
        ),
        (
            "instanced.glb",
            hostile::instanced(1025, 16384),
            "16793600 triangles after instancing, over the loader's limit of",
        ),
        // Within the default budget (2^24) but not within lavapipe's 128 MiB storage-buffer
        // range (a BVH node buffer of 295 MB): refused from the counts, by the device's budget,
        // before seconds of loading and building.
        (
            "instanced_4m.glb",
            hostile::instanced(250, 16384),
            "4096000 triangles after instancing, over the loader's limit of",
        ),
    ];
    for (name, bytes, needle) in cases {
        let p = c.write(name, bytes);
        let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
        let basis = ["what this device holds"];
        let device = if name.starts_with("instanced") {
            &basis[..]
        } else {
            &[]
        };
        c.expect_error(&o, &[&[name, needle][..], device].concat());
    }
    // An image header declaring 60,000 x 60,000 texels: the texture is skipped, the scene renders.
    let p = c.write("huge.glb", hostile::huge_texture(60_000, 60_000));
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: image 0 cannot be used (its header declares 60000 x 60000"),
        "{stderr}"
    );
}

#[test]
fn output_directory_not_writable() {
    let c = Case::new();
    let file = c.write("a-file", "not a directory");
    let out = file.join("out");
    let mut args = vec!["render", "--out", out.to_str().expect("utf-8")];
    args.extend(TINY);
    let o = c.run(&args, &[]);
    c.expect_error(&o, &["cannot create output directory", "a-file/out"]);
    // A read-only directory (root writes anyway: only checked as another user).
    let ro = c.path("read-only");
    std::fs::create_dir(&ro).expect("mkdir");
    set_mode(&ro, 0o555);
    if std::fs::write(ro.join("probe"), b"").is_err() {
        let mut args = vec!["render", "--out", ro.to_str().expect("utf-8")];
        args.extend(TINY);
        let o = c.run(&args, &[]);
        c.expect_error(&o, &["read-only", "is not writable"]);
    }
    set_mode(&ro, 0o755);
}

fn set_mode(p: &Path, mode: u32) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(p, std::fs::Permissions::from_mode(mode)).expect("chmod");
}

#[test]
fn bad_environments_and_lights() {
    let c = Case::new();
    let o = c.render(&["--environment", "/nonexistent/sky.hdr"], &[]);
    c.expect_error(&o, &["--environment", "/nonexistent/sky.hdr", "not found"]);
    let garbage = c.write("garbage.hdr", b"#?RADIANCE\nnot really\n");
    let o = c.render(&["--environment", garbage.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["garbage.hdr", "cannot decode the environment map"]);
    let empty = c.write("empty.hdr", b"");
    let o = c.render(&["--environment", empty.to_str().expect("utf-8")], &[]);
    c.expect_error(
        &o,
        &[
            "--environment",
            "empty.hdr: the environment map file is empty",
        ],
    );
    // Over the map limit by its header (16384 x 8193): refused before anything is decoded.
    let big = c.write(
        "big.hdr",
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8193 +X 16384\n",
    );
    let o = c.render(&["--environment", big.to_str().expect("utf-8")], &[]);
    c.expect_error(
        &o,
        &[
            "big.hdr: environment map is 16384x8193",
            "at most 16384x8192 = 134217728 texels in all",
        ],
    );
    let png = c.write("sky.png", b"\x89PNG");
    let o = c.render(&["--environment", png.to_str().expect("utf-8")], &[]);
    c.expect_error(&o, &["sky.png", ".hdr (Radiance) or .exr (OpenEXR)"]);
    let o = c.render(&["--environment", "1,-2,3"], &[]);
    c.expect_error(&o, &["--environment 1,-2,3", "R,G,B"]);
    let o = c.render(&["--environment-intensity", "-1"], &[]);
    c.expect_error(
        &o,
        &["--environment-intensity must be a finite number >= 0"],
    );
    // Finite numbers whose product is not: infinite radiance would render black.
    let big = [
        "--environment",
        "3e38,3e38,3e38",
        "--environment-intensity",
        "10",
    ];
    let o = c.render(&big, &[]);
    c.expect_error(
        &o,
        &[
            "--environment 3e38,3e38,3e38 times --environment-intensity 10 overflows f32",
            "scale the environment down",
        ],
    );

    // NaN and negative texels: a warning, and they count as black.
    let img =
        image::Rgb32FImage::from_raw(2, 1, vec![1.0, 1.0, 1.0, f32::NAN, -1.0, 0.0]).expect("2x1");
    let mut exr = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(img)
        .write_to(&mut exr, image::ImageFormat::OpenExr)
        .expect("exr");
    let map = c.write("nan.exr", exr.get_ref());
    let o = c.render(&["--environment", map.to_str().expect("utf-8")], &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("1 environment map texels are NaN"),
        "{stderr}"
    );

    // A light with a negative intensity: one warning, the light is skipped; with nothing
    // else emitting, the default environment and its warning.
    let mut doc: serde_json::Value = serde_json::from_str(&triangle_gltf(GOOD, "")).expect("json");
    doc["extensionsUsed"] = serde_json::json!(["KHR_lights_punctual"]);
    doc["extensions"] = serde_json::json!({ "KHR_lights_punctual": { "lights": [
        { "type": "point", "intensity": -5.0 } ] } });
    doc["nodes"][0]["extensions"] = serde_json::json!({ "KHR_lights_punctual": { "light": 0 } });
    let p = c.write("negative.gltf", doc.to_string());
    let o = c.render(&["--scene", p.to_str().expect("utf-8")], &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("light 0 has intensity -5"), "{stderr}");
    assert!(stderr.contains("nothing emits light"), "{stderr}");
    assert_eq!(stderr.matches("nothing emits light").count(), 1, "{stderr}");
    assert!(stderr.contains("uniform white environment"), "{stderr}");
    assert!(max_radiance(&c) > 0.0, "the default environment lights it");

    // Black asked for is black: no white substitute, and the warning says why nothing emits.
    let black = image::Rgb32FImage::from_raw(2, 1, vec![0.0; 6]).expect("2x1");
    let mut exr = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(black)
        .write_to(&mut exr, image::ImageFormat::OpenExr)
        .expect("exr");
    let black = c.write("black.exr", exr.get_ref());
    let black = black.to_str().expect("utf-8");
    let black_map = format!("--environment {black} is black");
    for (flags, why) in [
        (["--environment", "0,0,0"], "--environment 0,0,0 is black"),
        (["--environment", black], &black_map),
        (
            ["--environment-intensity", "0"],
            "--environment-intensity 0 turns the environment off",
        ),
    ] {
        let mut args = vec!["--scene", p.to_str().expect("utf-8")];
        args.extend(flags);
        let o = c.render(&args, &[]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{stderr}");
        let warning = stderr
            .lines()
            .find(|l| l.contains("nothing emits light"))
            .unwrap_or_else(|| panic!("{flags:?}: no warning in:\n{stderr}"));
        assert!(warning.contains(why), "{warning}");
        assert!(warning.ends_with("the frames will be black"), "{warning}");
        assert!(!stderr.contains("white"), "{stderr}");
        assert_eq!(max_radiance(&c), 0.0, "{flags:?}");
    }
}

/// The largest channel of the last render's linear output (`out/frame_00000.exr`).
fn max_radiance(c: &Case) -> f32 {
    let exr = image::open(c.out().join("frame_00000.exr")).expect("the render's EXR");
    exr.to_rgb32f()
        .pixels()
        .flat_map(|p| p.0)
        .fold(0.0, f32::max)
}
