//! Files far cheaper to write than to expand: node graphs that are not trees, instancing over
//! the budget, an image header declaring billions of texels. Each is refused (or the image
//! skipped) from the counts, before the loader spends memory on it.

mod common;

use common::load_budgeted as load;

use blueshift_scene::presets::{self, GltfBuilder, hostile};
use blueshift_scene::{LoadBudget, SceneError};
use serde_json::json;
use std::path::Path;

#[test]
fn a_node_that_lists_itself_is_a_cycle() {
    // Found by the `gltf` fuzz target: node 0 lists itself three times among its children.
    // Its path is resolved at run time: a test binary built in another checkout sharing the target
    // directory would otherwise read that checkout's files (or none).
    let path = blueshift_assets::workspace_path(
        "fuzz/corpus/gltf/seed_regress_node_cycle.glb",
        Path::is_file,
    );
    let bytes = std::fs::read(&path).expect("regression seed");
    let e = load(&bytes, LoadBudget::default()).unwrap_err();
    assert!(matches!(e, SceneError::NodeCycle { node: 0, .. }), "{e}");
    assert!(e.to_string().ends_with("node 0 is its own ancestor"), "{e}");
}

#[test]
fn a_node_with_two_parents_is_refused() {
    let e = load(&hostile::two_parents(), LoadBudget::default()).unwrap_err();
    assert!(
        matches!(
            e,
            SceneError::NodeParents {
                node: 2,
                parents: [0, 1],
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn a_chain_of_shared_children_is_refused_before_expansion() {
    // 2^39 paths to the last node: expanded, this would never finish.
    let e = load(&hostile::shared_chain(40), LoadBudget::default()).unwrap_err();
    assert!(
        matches!(
            e,
            SceneError::NodeRepeated {
                node: 39,
                parent: 38,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn instancing_over_the_budget_names_the_count_and_the_limit() {
    let limit = LoadBudget::default().triangles;
    // One mesh of 16384 triangles drawn by 1025 nodes: one instance over 2^24 triangles.
    let glb = hostile::instanced(1025, 16384);
    assert!(glb.len() < 300_000, "{} bytes", glb.len());
    let e = load(&glb, LoadBudget::default()).unwrap_err();
    match &e {
        SceneError::OverBudget {
            what,
            count,
            limit: l,
            ..
        } => {
            assert!(what.starts_with("triangles"), "{e}");
            assert_eq!((*count, *l), (1025 * 16384, limit));
        }
        _ => panic!("wrong error {e}"),
    }
    assert!(e.to_string().contains(&format!("{}", 1025 * 16384)), "{e}");
    assert!(e.to_string().contains(&limit.to_string()), "{e}");
}

#[test]
fn the_triangle_count_is_exact_at_the_limit() {
    // The counted triangles are the file's: a budget of exactly that many loads, one fewer
    // refuses. (Each node's mesh repeats its one triangle 5 times: the copies are counted,
    // then dropped as duplicates, leaving one per node.)
    let glb = hostile::instanced(7, 5);
    let exact = LoadBudget {
        triangles: 35,
        ..LoadBudget::default()
    };
    assert_eq!(load(&glb, exact).expect("at the limit").triangles.len(), 7);
    let fewer = LoadBudget {
        triangles: 34,
        ..exact
    };
    let e = load(&glb, fewer).unwrap_err();
    assert!(matches!(e, SceneError::OverBudget { count: 35, .. }), "{e}");
}

#[test]
fn bundled_scenes_fit_a_budget_of_exactly_their_size() {
    for name in presets::PRESETS {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = presets::write_preset(name, dir.path()).expect("preset");
        let bytes = std::fs::read(&path).expect("read preset");
        let scene = load(&bytes, LoadBudget::default()).expect("preset loads");
        let emissive = scene
            .triangles
            .iter()
            .filter(|t| scene.materials[t.material as usize].emissive.max_element() > 0.0)
            .count() as u64;
        let texels: u64 = scene
            .images
            .iter()
            .map(|i| u64::from(i.width) * u64::from(i.height))
            .sum();
        let exact = LoadBudget {
            triangles: scene.triangles.len() as u64,
            lights: emissive + scene.lights.len() as u64,
            texels,
            ..LoadBudget::default()
        };
        let again = load(&bytes, exact).expect("exact budget");
        assert_eq!(again.triangles, scene.triangles, "{name}");
        assert_eq!(again.images, scene.images, "{name}");
        for smaller in [
            LoadBudget {
                triangles: exact.triangles - 1,
                ..exact
            },
            LoadBudget {
                lights: exact.lights - 1,
                ..exact
            },
        ] {
            let e = load(&bytes, smaller).unwrap_err();
            assert!(matches!(e, SceneError::OverBudget { .. }), "{name}: {e}");
        }
    }
}

#[test]
fn a_huge_image_header_is_skipped_with_a_warning_without_decoding() {
    let scene = load(
        &hostile::huge_texture(60_000, 60_000),
        LoadBudget::default(),
    )
    .expect("the scene loads without the texture");
    assert!(scene.images.is_empty() && scene.textures.is_empty());
    assert_eq!(scene.materials[0].base_color_texture, None);
    let warning = scene
        .warnings
        .iter()
        .find(|w| w.starts_with("image 0 cannot be used"))
        .expect("image warning");
    assert!(
        warning.contains("60000 x 60000 = 3600000000 texels"),
        "{warning}"
    );
}

#[test]
fn images_beyond_the_texel_budget_are_skipped_in_order() {
    // Three decodable 4x4 textures; a budget of 40 texels holds two of them.
    let png = common::solid_png(4, [200, 100, 50, 255]);
    let mut b = GltfBuilder::new();
    for k in 0..3 {
        let tex = b.add_png_texture(&format!("t{k}"), &png, json!({}));
        let m = b.add_material(json!({
            "pbrMetallicRoughness": { "baseColorTexture": { "index": tex } }
        }));
        let mesh = b.add_mesh("quad", &common::quad(true), Some(m));
        let n = b.add_node(json!({ "mesh": mesh }));
        b.add_root(n);
    }
    let budget = |texels| LoadBudget {
        texels,
        ..LoadBudget::default()
    };
    let all = load(&b.to_glb(), budget(48)).expect("loads");
    assert_eq!(all.images.len(), 3);
    let two = load(&b.to_glb(), budget(40)).expect("loads");
    assert_eq!(two.images.len(), 2);
    assert_eq!(two.materials[2].base_color_texture, None);
    assert!(
        two.warnings
            .iter()
            .any(|w| w.contains("image 2 cannot be used") && w.contains("over the 8 texels left")),
        "{:?}",
        two.warnings
    );
}
