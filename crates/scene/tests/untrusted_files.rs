//! Files from outside ("Untrusted files, second round"): reads outside the scene directory,
//! special files, buffers shorter or longer than declared, values that overflow f32, spec
//! violations. Each gets a clear error naming the file and the problem, or a warning and a
//! correct scene.

mod common;

use blueshift_scene::presets::GltfBuilder;
use blueshift_scene::{LoadOptions, Scene, SceneError};
use common::{assert_contains, load, one_quad, quad_doc, triangles, write, write_json};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

fn allowing_outside() -> LoadOptions {
    LoadOptions {
        quiet: true,
        allow_outside_paths: true,
        ..Default::default()
    }
}

/// A one-quad scene whose buffer is at `uri` (the bytes are the caller's to place).
fn quad_with_buffer_uri(uri: &str) -> (Value, Vec<u8>) {
    let b = one_quad();
    (b.json(Some(uri.to_string())), b.bin().to_vec())
}

/// `dir/scene`, created.
fn scene_dir(dir: &Path) -> PathBuf {
    let d = dir.join("scene");
    std::fs::create_dir_all(&d).expect("scene dir");
    d
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs")
        .success();
    assert!(ok, "mkfifo {}", path.display());
}

#[test]
fn the_outside_uri_seed_is_refused_naming_the_uri() {
    // tests/data/uri_outside_scene_dir.gltf: its buffer is `../../(...)/etc/passwd`, once
    // read and rendered as geometry.
    let dir = tmp();
    let deep = dir.path().join("a/b");
    std::fs::create_dir_all(&deep).expect("mkdir");
    let seed = include_bytes!("data/uri_outside_scene_dir.gltf");
    let p = write(&deep, "seed.gltf", seed);
    let e = load(&p).unwrap_err();
    match &e {
        SceneError::OutsidePath {
            what, uri, reason, ..
        } => {
            assert_eq!(what, "buffer 0");
            assert!(uri.ends_with("../etc/passwd"), "{uri}");
            assert_eq!(reason, "'..' climbs out of it");
        }
        _ => panic!("wrong error {e}"),
    }
    let start = format!("{}: buffer 0 URI '../", p.display());
    let end = "); reading it needs --allow-outside-paths";
    let msg = e.to_string();
    assert!(msg.starts_with(&start) && msg.ends_with(end), "{msg}");
    assert_contains(&msg, &["etc/passwd' points outside the scene directory"]);
}

#[test]
fn buffers_outside_the_scene_directory_load_only_when_allowed() {
    let dir = tmp();
    let scene = scene_dir(dir.path());
    let outside = dir.path().join("outside.bin");
    let (_, bin) = quad_with_buffer_uri("");
    std::fs::write(&outside, &bin).expect("write");
    let absolute = outside.to_str().expect("utf-8").to_string();
    for (uri, reason) in [
        ("../outside.bin".to_string(), "'..' climbs out of it"),
        (absolute.clone(), "it is an absolute path"),
        (format!("file://{absolute}"), "it is a file: URI"),
    ] {
        let (doc, _) = quad_with_buffer_uri(&uri);
        let p = write_json(&scene, "out.gltf", &doc);
        match load(&p).unwrap_err() {
            SceneError::OutsidePath {
                uri: named,
                reason: why,
                ..
            } => assert_eq!((named.as_str(), why.as_str()), (uri.as_str(), reason)),
            e => panic!("{uri}: wrong error {e}"),
        }
        assert_eq!(triangles(&p, Some(&allowing_outside())), 2, "{uri}");
    }
}

#[cfg(unix)]
#[test]
fn symlinks_leading_outside_count_as_outside() {
    let dir = tmp();
    let scene = scene_dir(dir.path());
    let (doc, bin) = quad_with_buffer_uri("link.bin");
    std::fs::write(dir.path().join("outside.bin"), &bin).expect("write");
    std::fs::write(scene.join("inside.bin"), &bin).expect("write");
    std::os::unix::fs::symlink(dir.path().join("outside.bin"), scene.join("link.bin"))
        .expect("symlink");
    let p = write_json(&scene, "link.gltf", &doc);
    let e = load(&p).unwrap_err();
    assert!(matches!(e, SceneError::OutsidePath { .. }), "{e}");
    assert!(e.to_string().contains("through a symlink it is "), "{e}");
    assert_eq!(triangles(&p, Some(&allowing_outside())), 2);
    // A symlink that stays inside is an ordinary file.
    std::fs::remove_file(scene.join("link.bin")).expect("rm");
    std::os::unix::fs::symlink(scene.join("inside.bin"), scene.join("link.bin")).expect("symlink");
    assert_eq!(triangles(&p, None), 2);
}

/// A quad whose base colour texture is the image at `uri`.
fn textured_quad(uri: &str) -> Value {
    let mut doc = quad_doc();
    doc["images"] = json!([{ "uri": uri }]);
    doc["textures"] = json!([{ "source": 0 }]);
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    doc
}

#[test]
fn images_outside_the_scene_directory_load_only_when_allowed() {
    let dir = tmp();
    let scene = scene_dir(dir.path());
    std::fs::write(
        dir.path().join("tex.png"),
        common::solid_png(4, [200, 100, 50, 255]),
    )
    .expect("write");
    let p = write_json(&scene, "tex.gltf", &textured_quad("../tex.png"));
    let e = load(&p).unwrap_err();
    match &e {
        SceneError::OutsidePath { what, uri, .. } => {
            assert_eq!((what.as_str(), uri.as_str()), ("image 0", "../tex.png"));
        }
        _ => panic!("wrong error {e}"),
    }
    let s = Scene::load_with(&p, &allowing_outside()).expect("allowed");
    assert_eq!(s.images.len(), 1);
    assert_eq!(s.images[0].rgba8[..4], [200, 100, 50, 255]);
}

#[cfg(unix)]
#[test]
fn fifos_are_refused_without_blocking() {
    // Opening a FIFO blocks until a writer comes: each of these would hang if it were opened.
    let dir = tmp();
    let fifo = dir.path().join("pipe");
    mkfifo(&fifo);
    let e = load(&fifo).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }), "{e}");
    assert!(
        e.to_string()
            .ends_with("pipe: cannot read: not a regular file (a FIFO)"),
        "{e}"
    );

    let (doc, _) = quad_with_buffer_uri("pipe");
    let e = load(&write_json(dir.path(), "buffer.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::Buffer { .. }), "{e}");
    assert!(e.to_string().contains("not a regular file (a FIFO)"), "{e}");

    let s = load(&write_json(
        dir.path(),
        "image.gltf",
        &textured_quad("pipe"),
    ))
    .unwrap();
    assert!(s.images.is_empty());
    assert_eq!(s.materials[0].base_color_texture, None);
    assert!(
        s.warnings
            .iter()
            .any(|w| w.starts_with("image 0 cannot be used")
                && w.contains("not a regular file (a FIFO)")),
        "{:?}",
        s.warnings
    );

    let e = blueshift_scene::open_regular(&fifo).unwrap_err();
    assert_eq!(e.to_string(), "not a regular file (a FIFO)");
    let e = blueshift_scene::read_regular(&fifo, 1 << 20).unwrap_err();
    assert_eq!(e.to_string(), "not a regular file (a FIFO)");
}

#[test]
fn a_buffer_reads_its_byte_length_and_no_more() {
    // An 8 GiB file (sparse on disk) behind a 200-byte buffer: only the 200 bytes are read.
    let dir = tmp();
    let (doc, bin) = quad_with_buffer_uri("huge.bin");
    let huge = std::fs::File::create(dir.path().join("huge.bin")).expect("create");
    std::io::Write::write_all(&mut &huge, &bin).expect("write");
    huge.set_len(8 << 30).expect("set_len");
    assert_eq!(
        triangles(&write_json(dir.path(), "huge.gltf", &doc), None),
        2
    );
}

#[test]
fn empty_and_truncated_buffers_say_so() {
    let dir = tmp();
    let (doc, bin) = quad_with_buffer_uri("quad.bin");
    let n = bin.len();
    let p = write_json(dir.path(), "quad.gltf", &doc);
    for (bytes, want) in [
        (
            &bin[..0],
            format!("the file is empty, but byteLength declares {n} bytes"),
        ),
        (
            &bin[..10],
            format!("the file has only 10 bytes, but byteLength declares {n} bytes"),
        ),
    ] {
        std::fs::write(dir.path().join("quad.bin"), bytes).expect("write");
        let e = load(&p).unwrap_err();
        assert!(matches!(e, SceneError::Buffer { index: 0, .. }), "{e}");
        assert!(e.to_string().contains(&want), "{e}");
        assert!(!e.to_string().contains("fill whole buffer"), "{e}");
    }

    let (mut doc, _) = quad_with_buffer_uri("data:application/octet-stream;base64,");
    let e = load(&write_json(dir.path(), "data.gltf", &doc)).unwrap_err();
    let want = format!("the data URI is empty, but byteLength declares {n} bytes");
    assert!(e.to_string().contains(&want), "{e}");

    // A GLB whose BIN chunk is shorter than the buffer declares, or missing.
    let b = one_quad();
    let mut json = b.json(None);
    json["buffers"][0]["byteLength"] = json!(n + 400);
    let glb = blueshift_scene::presets::glb(&json, b.bin());
    let e = load(&write(dir.path(), "short.glb", &glb)).unwrap_err();
    let want = format!(
        "the GLB BIN chunk has only {n} bytes, but byteLength declares {} bytes",
        n + 400
    );
    assert!(e.to_string().contains(&want), "{e}");
    doc["buffers"][0].as_object_mut().map(|b| b.remove("uri"));
    let e = load(&write_json(dir.path(), "nouri.gltf", &doc)).unwrap_err();
    assert!(
        e.to_string()
            .contains("it has no uri, and no GLB BIN chunk holds it"),
        "{e}"
    );
}

#[test]
fn a_light_whose_radiance_overflows_is_an_error() {
    // tests/data/light_overflow_black.gltf: colour 1e38 x intensity 1e38 rendered black.
    let dir = tmp();
    let seed = include_bytes!("data/light_overflow_black.gltf");
    let p = write(dir.path(), "light.gltf", seed);
    let e = load(&p).unwrap_err();
    assert!(matches!(e, SceneError::Light { .. }), "{e}");
    let parts = [
        "light.gltf: KHR_lights_punctual light 0 has color",
        "[1e38, 1e38, 1e38] times intensity 1e38, which overflows f32",
    ];
    assert_contains(&e.to_string(), &parts);

    // The same for an emissive material: factor x strength.
    let mut doc = quad_doc();
    doc["materials"][0]["name"] = json!("lamp");
    doc["materials"][0]["emissiveFactor"] = json!([4.0, 1.0, 1.0]);
    doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
        json!(1.0e38);
    let e = load(&write_json(dir.path(), "lamp.gltf", &doc)).unwrap_err();
    assert!(matches!(e, SceneError::Light { .. }), "{e}");
    assert!(
        e.to_string()
            .contains("lamp.gltf: material 0 ('lamp') has emissiveFactor [4.0, 1.0, 1.0]"),
        "{e}"
    );
    // A strength beyond f32 (read as infinity) once made the emission silently zero.
    doc["materials"][0]["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
        json!(1.0e39);
    let e = load(&write_json(dir.path(), "inf.gltf", &doc)).unwrap_err();
    assert!(
        e.to_string()
            .contains("times emissiveStrength inf, which is not finite"),
        "{e}"
    );
}

/// A quad mesh named "big" whose vertex 2 is at `corner`, under a node with `node`'s fields.
fn quad_at(corner: [f32; 3], node: Value) -> Vec<u8> {
    let mut b = GltfBuilder::new();
    let mut mesh = common::quad(true);
    mesh.positions[2] = corner;
    let m = b.add_mesh("big", &mesh, None);
    let mut node = node;
    node["mesh"] = json!(m);
    let n = b.add_node(node);
    b.add_root(n);
    b.to_gltf_embedded()
}

#[test]
fn coordinates_of_1e13_or_more_are_refused_naming_mesh_and_accessor() {
    let dir = tmp();
    let far = quad_at([1e13, 1.0, 0.0], json!({}));
    let p = write(dir.path(), "far.gltf", &far);
    let e = load(&p).unwrap_err();
    let place = match &e {
        SceneError::PositionOutOfRange {
            accessor,
            vertex,
            world,
            ..
        } => (*accessor, *vertex, *world),
        _ => panic!("wrong error {e}"),
    };
    assert_eq!(place, (0, 2, false));
    let parts = [
        "far.gltf: mesh 0 ('big') primitive 0: POSITION accessor 0: vertex 2 is at \
         [10000000000000.0, 1.0, 0.0], beyond the limit of 1e13 on any coordinate",
    ];
    assert_contains(&e.to_string(), &parts);
    // Just below the limit loads.
    let p = write(
        dir.path(),
        "near.gltf",
        &quad_at([9.9e12, 1.0, 0.0], json!({})),
    );
    assert_eq!(triangles(&p, None), 2);
}

#[test]
fn an_extent_that_overflows_f32_is_named_not_called_zero_area() {
    // Finite world positions of +-2e38 once had edges of 4e38 (inf in f32): every triangle
    // was "zero-area" and the scene "had no non-zero-area triangles". Such positions are now
    // refused first, as beyond the coordinate limit after the node transform.
    let dir = tmp();
    let node = json!({ "scale": [2.0e38, 2.0e38, 1.0] });
    let p = write(dir.path(), "wide.gltf", &quad_at([1.0, 1.0, 0.0], node));
    let e = load(&p).unwrap_err();
    let world = matches!(e, SceneError::PositionOutOfRange { world: true, .. });
    assert!(world, "{e}");
    let parts = [
        "vertex 0 is at [-2e38, -2e38, 0.0] after the node transform, beyond the limit of 1e13",
        "overflows the tracer's f32 arithmetic",
    ];
    assert_contains(&e.to_string(), &parts);
}

#[test]
fn many_missing_images_are_one_warning_line_with_a_count() {
    // 100,000 images, each used by a material, none of them on disk: one line. (Warnings are
    // kept in a hash map by kind; a line per image, or a scan of the lines per image, is what
    // this guards against. The count of lines is asserted, not the time.)
    let dir = tmp();
    let n = 100_000;
    let mut doc = quad_doc();
    doc["images"] = (0..n)
        .map(|i| json!({ "uri": format!("missing-{i}.png") }))
        .collect();
    doc["textures"] = (0..n).map(|i| json!({ "source": i })).collect();
    doc["materials"] = (0..n)
        .map(|i| json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": i } } }))
        .collect();
    let s = load(&write_json(dir.path(), "many.gltf", &doc)).expect("loads");
    assert_eq!(
        s.warnings.len(),
        1,
        "{:?}",
        &s.warnings[..s.warnings.len().min(3)]
    );
    let w = &s.warnings[0];
    assert!(
        w.starts_with("100,000 images missing; textures using them are ignored (first: image 0: "),
        "{w}"
    );
    assert!(w.ends_with("missing-0.png: file not found)"), "{w}");
}

#[test]
fn many_unsupported_extensions_are_one_warning_line() {
    let dir = tmp();
    let mut doc = quad_doc();
    let mut used: Vec<String> = (0..1000).map(|i| format!("EXT_thing_{i}")).collect();
    used.push("KHR_texture_transform".into());
    doc["extensionsUsed"] = json!(used);
    let s = load(&write_json(dir.path(), "ext.gltf", &doc)).expect("loads");
    assert_eq!(
        s.warnings,
        [
            "1,000 extensions not supported, ignored (first: EXT_thing_0)",
            "extension KHR_texture_transform ignored: textures are sampled without the transform",
        ]
    );
}

#[test]
fn truncated_and_oversized_image_files_are_named() {
    let dir = tmp();
    let png = common::solid_png(64, [1, 2, 3, 255]);
    // Cut after the header: the size reads, the texels do not.
    std::fs::write(dir.path().join("cut.png"), &png[..60]).expect("write");
    // A 1 x 1 image followed by 2 MiB: more than any 1 x 1 image needs, refused unread.
    let mut big = common::solid_png(1, [1, 2, 3, 255]);
    big.resize(2 << 20, 0);
    std::fs::write(dir.path().join("big.png"), &big).expect("write");
    for (name, want) in [
        (
            "cut.png",
            "the image data is truncated (unexpected end of file)",
        ),
        (
            "big.png",
            "the file has 2097152 bytes, more than an image of its declared size needs",
        ),
    ] {
        let p = write_json(dir.path(), "img.gltf", &textured_quad(name));
        let s = load(&p).expect("loads without the image");
        assert!(s.images.is_empty(), "{name}");
        assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
        assert_contains(&s.warnings[0], &["image 0 cannot be used (", want]);
    }
}
