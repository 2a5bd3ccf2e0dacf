//! A legal scene of 20,000 coincident primitives (crates/scene/tests/data/
//! coincident_primitives_20k.gltf) was refused by the trace pass's loop guard: its copies of
//! one triangle are dropped at load with one warning, and it renders the image of that one
//! triangle.
mod common;

use common::Case;

const SEED: &[u8] = include_bytes!("../../scene/tests/data/coincident_primitives_20k.gltf");

/// The seed with one primitive: the triangle it draws 20,000 times, drawn once.
fn one_primitive() -> Vec<u8> {
    let mut doc: serde_json::Value = serde_json::from_slice(SEED).expect("JSON");
    let prims = doc["meshes"][0]["primitives"]
        .as_array_mut()
        .expect("primitives");
    prims.truncate(1);
    serde_json::to_vec(&doc).expect("JSON")
}

/// The bytes of every file in `dir`, by name.
fn files(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| {
            let e = e.expect("entry");
            let name = e.file_name().into_string().expect("utf-8");
            (name, std::fs::read(e.path()).expect("read"))
        })
        .collect();
    out.sort();
    out
}

#[test]
fn coincident_primitives_render_the_one_triangle_with_a_warning() {
    let c = Case::new();
    let seed = c.write("seed.gltf", SEED);
    let one = c.write("one.gltf", one_primitive());
    let render = |scene: &std::path::Path, out: &str, extra: &[&str]| {
        let out = c.path(out);
        let mut args = vec![
            "--validation",
            "render",
            "--scene",
            scene.to_str().expect("utf-8"),
        ];
        args.extend([
            "--width",
            "32",
            "--height",
            "32",
            "--out",
            out.to_str().expect("utf-8"),
        ]);
        args.extend(extra);
        let o = c.run(&args, &[]);
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{stderr}");
        (files(&out), stderr)
    };
    let frames = ["--frames", "2"];
    let (seed_files, stderr) = render(&seed, "seed", &frames);
    let warnings: Vec<_> = stderr.lines().filter(|l| l.contains("duplicate")).collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].starts_with("warning: ")
            && warnings[0].contains("19,999 duplicate triangles dropped"),
        "{stderr}"
    );
    // The same image, byte for byte, as the triangle drawn once.
    let (one_files, stderr) = render(&one, "one", &frames);
    assert!(!stderr.contains("duplicate"), "{stderr}");
    assert_eq!(seed_files.len(), 2);
    assert!(seed_files == one_files, "the images differ");
    // And that image is the triangle over the environment (radiance 1): some pixels see the
    // environment, some the triangle.
    let y = blueshift_analysis::Gray::load(&c.path("seed/frame_00001.exr")).expect("EXR");
    let sky = y.data.iter().filter(|&&v| (v - 1.0).abs() < 1e-3).count();
    let share = sky as f64 / y.data.len() as f64;
    assert!((0.05..0.95).contains(&share), "{sky} environment pixels");

    // The camera path that turned onto the pile at frame 6 and was refused there.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/camera_turns_to_overlap.json"
    );
    let extra = ["--frames", "8", "--all-frames", "--camera-path", path];
    let (moving, _) = render(&seed, "moving", &extra);
    assert_eq!(moving.len(), 16, "8 frames, PNG and EXR");
}

#[test]
fn coincident_triangles_that_differ_are_still_refused_by_the_loop_guard() {
    // The same 20,000 copies, each of its own material: none is a duplicate (the tie-break
    // decides which shows), a ray tests all of them, and the frame is refused, not rendered
    // with paths cut short.
    let c = Case::new();
    let mut doc: serde_json::Value = serde_json::from_slice(SEED).expect("JSON");
    let n = 20_000;
    doc["meshes"][0]["primitives"] = (0..n)
        .map(|i| serde_json::json!({ "attributes": { "POSITION": 0 }, "material": i }))
        .collect();
    doc["materials"] = (0..n)
        .map(
            |i| serde_json::json!({ "pbrMetallicRoughness": { "roughness": i as f64 / n as f64 } }),
        )
        .collect();
    let p = c.write("materials.gltf", serde_json::to_vec(&doc).expect("JSON"));
    let o = c.render_sized(
        ("32", "32"),
        "1",
        &["--scene", p.to_str().expect("utf-8")],
        &[],
    );
    let line = c.expect_error(&o, &["lavapipe loop limit", "(guard 40000"]);
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("duplicate"),
        "{line}"
    );
}
