//! Memory in proportion to the file: what the loader allocates, measured by a counting
//! allocator on the loading thread (no timings). Files that declare far more than they hold
//! (sparse accessors without a bufferView, a buffer file longer than its byteLength, images no
//! material uses) must cost what they hold.

mod common;

use blueshift_scene::{LoadOptions, Scene};
use common::{embedded_uri, one_quad, write_json};
use serde_json::json;
#[path = "common/counting.rs"]
mod counting;
use std::cell::Cell;

thread_local! {
    static NOW: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn add(bytes: isize) {
    // `try_with`: the counters may be gone while the thread exits.
    let _ = NOW.try_with(|now| {
        let n = now.get() + bytes;
        now.set(n);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(n)));
    });
}

/// Counts the bytes allocated: now, and the most at any time.
#[global_allocator]
static COUNTING: counting::Counting = counting::Counting(add);

/// `f()` and the most bytes this thread held at once while it ran, above what it held before.
fn peak_during<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = NOW.with(Cell::get);
    PEAK.with(|p| p.set(before));
    let r = f();
    (r, (PEAK.with(Cell::get) - before).max(0) as usize)
}

const MIB: usize = 1 << 20;

fn load(bytes: &[u8]) -> (Scene, usize) {
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let (scene, peak) = peak_during(|| Scene::from_slice(bytes, None, &options));
    (scene.expect("loads"), peak)
}

#[test]
fn the_sparse_positions_bomb_costs_what_the_file_holds() {
    // tests/data/sparse_positions_bomb.gltf: 605 bytes, a sparse-only POSITION accessor of
    // 50,331,648 vertices (the budget's limit) with 3 stored: it took 1.35 GB to load.
    let (scene, peak) = load(include_bytes!("data/sparse_positions_bomb.gltf"));
    assert!(peak < MIB, "{peak} bytes");
    // Its one real triangle is kept; the 16,777,215 others have two vertices at the origin.
    assert_eq!(scene.triangles.len(), 1);
    assert_eq!(
        scene.warnings,
        ["skipped 16,777,215 zero-area triangles"],
        "{:?}",
        scene.warnings
    );
}

/// Bytes of `values` as little-endian f32, then u32 `indices`.
fn bytes(values: &[f32], indices: &[u32]) -> Vec<u8> {
    let mut b: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    b.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    b
}

#[test]
fn sparse_only_attributes_and_indices_stay_sparse() {
    let n = 3 << 22; // 12,582,912 vertices (or indices), of which 3 (or 2) are stored
    let mut bin = bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], &[]); // view 0
    bin.extend(bytes(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &[])); // 1: normals
    bin.extend(bytes(&[0.25, 0.5, 0.75, 0.5, 0.25, 1.0], &[])); // 2: UVs
    bin.extend(bytes(&[], &[0, 1, 2])); // 3: where the vertices are stored
    bin.extend(bytes(&[], &[3, 5])); // 4: where the indices are stored
    bin.extend(bytes(&[], &[1, 2])); // 5: the stored indices
    let views: Vec<_> = [(0, 36), (36, 36), (72, 24), (96, 12), (108, 8), (116, 8)]
        .map(|(offset, length)| json!({ "buffer": 0, "byteOffset": offset, "byteLength": length }))
        .into();
    let sparse = |ty: &str, component: u32, stored: usize, at: usize, values: usize| {
        json!({ "componentType": component, "count": n, "type": ty, "sparse": { "count": stored,
            "indices": { "bufferView": at, "componentType": 5125 },
            "values": { "bufferView": values } } })
    };
    // The index stream is 0 but for 1 and 2 at 3 and 5: one triangle (1, 0, 2) has three
    // distinct vertices; every other one repeats vertex 0.
    let mut positions = sparse("VEC3", 5126, 3, 3, 0);
    positions["min"] = json!([0.0, 0.0, 0.0]);
    positions["max"] = json!([1.0, 1.0, 0.0]);
    let accessors = [
        positions,
        sparse("VEC3", 5126, 3, 3, 1),
        sparse("VEC2", 5126, 3, 3, 2),
        sparse("SCALAR", 5125, 2, 4, 5),
    ];
    for indexed in [false, true] {
        let mut prim = json!({ "attributes": { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 } });
        if indexed {
            prim["indices"] = json!(3);
        }
        let doc = json!({
            "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [0] }],
            "nodes": [{ "mesh": 0 }], "meshes": [{ "primitives": [prim] }],
            "accessors": accessors, "bufferViews": views,
            "buffers": [{ "byteLength": bin.len(), "uri": embedded_uri(&bin) }],
        });
        let (scene, peak) = load(&serde_json::to_vec(&doc).expect("json"));
        assert!(peak < MIB, "indexed {indexed}: {peak} bytes");
        assert_eq!(scene.triangles.len(), 1, "indexed {indexed}");
        let t = &scene.triangles[0];
        assert_eq!(t.normals, [glam::Vec3::Z; 3]);
        let mut uvs = t.uvs.map(|v| v.to_array());
        uvs.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
        assert_eq!(
            uvs,
            [[0.25, 0.5], [0.25, 1.0], [0.75, 0.5]],
            "indexed {indexed}"
        );
        assert_eq!(
            scene.warnings,
            ["skipped 4,194,303 zero-area triangles"],
            "indexed {indexed}"
        );
    }
}

#[test]
fn images_no_material_uses_are_not_read() {
    // A 4096 x 4096 PNG (64 MiB decoded) and a missing file, both unused: neither is decoded
    // nor opened, and neither gets a warning.
    let png = common::solid_png(4096, [9, 9, 9, 255]);
    let mut b = one_quad();
    b.add_png_texture("unused", &png, json!({}));
    let mut doc = b.json(Some(embedded_uri(b.bin())));
    doc["images"]
        .as_array_mut()
        .expect("images")
        .push(json!({ "uri": "missing.png" }));
    let dir = tempfile::tempdir().expect("tempdir");
    let p = write_json(dir.path(), "unused.gltf", &doc);
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let (scene, peak) = peak_during(|| Scene::load_with(&p, &options));
    let scene = scene.expect("loads");
    assert!(scene.images.is_empty());
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // The file and its decoded buffer are held; 64 MiB of texels are not.
    let file = std::fs::metadata(&p).expect("file").len() as usize;
    assert!(peak < 3 * file + MIB, "{peak} bytes for a {file}-byte file");
}

#[test]
fn a_buffer_file_longer_than_its_byte_length_is_not_read_whole() {
    // 64 MiB on disk behind a 200-byte buffer: 200 bytes are read.
    let dir = tempfile::tempdir().expect("tempdir");
    let b = one_quad();
    let doc = b.json(Some("long.bin".into()));
    let mut long = b.bin().to_vec();
    long.resize(64 * MIB, 7);
    std::fs::write(dir.path().join("long.bin"), &long).expect("write");
    drop(long);
    let p = write_json(dir.path(), "long.gltf", &doc);
    let options = LoadOptions {
        quiet: true,
        ..Default::default()
    };
    let (scene, peak) = peak_during(|| Scene::load_with(&p, &options));
    assert_eq!(scene.expect("loads").triangles.len(), 2);
    assert!(peak < MIB, "{peak} bytes");
}
