//! The loader's budget derived from a device's limits ([`LoadBudget::for_device`]) is exactly
//! what that device holds: a scene at the budget passes the device checks that come after
//! loading, one triangle more is refused by the loader from its counts (before the scene is
//! expanded), and the same file loaded without the device's budget is then refused by those
//! later checks, so the budget refuses nothing the device could hold.

mod common;

use blueshift_scene::presets::hostile;
use blueshift_scene::{DeviceLimits, EnvMap, LoadBudget, Scene, SceneError, SceneGpu};
use common::load_budgeted as load;
use glam::Vec3;
use std::sync::Arc;

/// Whether every scene image of `scene` fits `rows` rows (what `SceneImages` checks against
/// `maxImageDimension2D`).
fn images_fit(scene: &Scene, rows: u32) -> bool {
    let gpu = SceneGpu::build(scene);
    gpu.texel_sources().iter().all(|s| s.extent().1 <= rows)
}

/// `n` distinct triangles (one per node, each node moved along z: no duplicates).
fn triangles(n: u64) -> Vec<u8> {
    hostile::instanced(n as usize, 1)
}

#[test]
fn the_storage_range_budget_is_the_boundary_of_check_limits() {
    // (The node buffer, 36 bytes a node and 2n - 1 nodes, is the first to overflow.)
    for range in [4 << 10, 64 << 10, 1 << 20] {
        let device = DeviceLimits {
            max_storage_buffer_range: range,
            max_image_dimension_2d: 16384,
            memory_budget: u64::MAX,
        };
        let budget = LoadBudget::for_device(&device);
        let n = budget.triangles;
        assert!(n > 0 && n < LoadBudget::default().triangles, "{range}: {n}");
        let at = load(&triangles(n), budget).expect("a scene at the budget loads");
        assert_eq!(at.triangles.len() as u64, n, "{range}");
        at.check_limits(&device).expect("and fits the device");
        SceneGpu::build(&at)
            .check_limits(range)
            .expect("exactly, once built");

        let over = triangles(n + 1);
        match load(&over, budget) {
            Err(SceneError::OverBudget { count, limit, .. }) => {
                assert_eq!((count, limit), (n + 1, n), "{range}")
            }
            other => panic!("{range}: one triangle over the budget: {other:?}"),
        }
        let unbounded = load(&over, LoadBudget::default()).expect("the default budget loads it");
        assert!(
            matches!(
                unbounded.check_limits(&device),
                Err(SceneError::OverLimit { .. })
            ),
            "{range}: the device refuses what the budget refused"
        );
    }
}

#[test]
fn the_image_budget_is_the_boundary_of_the_scene_images() {
    for rows in [1, 3] {
        let device = DeviceLimits {
            max_storage_buffer_range: u64::MAX,
            max_image_dimension_2d: rows,
            memory_budget: u64::MAX,
        };
        let budget = LoadBudget::for_device(&device);
        let n = budget.triangles;
        let at = load(&triangles(n), budget).expect("a scene at the budget loads");
        assert!(images_fit(&at, rows), "{rows} rows: {n} triangles");
        at.check_limits(&device)
            .expect("and passes the device check");
        assert!(matches!(
            load(&triangles(n + 1), budget),
            Err(SceneError::OverBudget { .. })
        ));
        let over = load(&triangles(n + 1), LoadBudget::default()).expect("loads unbounded");
        assert!(!images_fit(&over, rows), "{rows} rows: {} triangles", n + 1);
        assert!(matches!(
            over.check_limits(&device),
            Err(SceneError::ImageOverLimit { .. })
        ));
    }
}

#[test]
fn the_memory_budget_bounds_the_scene_images() {
    // 16 bytes a texel: a triangle's record, its shading and two BVH nodes (4 + 4 + 2 x 2),
    // plus one row of 4096 texels of each of the seven images that may be left unused.
    let (per_triangle, rows) = (16 * 12, 7 * 4096 * 16);
    let device = DeviceLimits {
        max_storage_buffer_range: u64::MAX,
        max_image_dimension_2d: 16384,
        memory_budget: rows + 10_000 * per_triangle + per_triangle / 2,
    };
    let budget = LoadBudget::for_device(&device);
    assert_eq!(budget.triangles, 10_000);
    let at = load(&triangles(10_000), budget).expect("at the budget");
    at.check_limits(&device).expect("fits the memory budget");
    let e = load(&triangles(10_001), budget).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("10001 triangles") && msg.contains("limit of 10000"),
        "{msg}"
    );
    assert!(msg.contains("memory budget 2378848 bytes"), "{msg}");
    // Within those rows of the boundary: a budget a row smaller is refused.
    let smaller = DeviceLimits {
        memory_budget: 10_000 * per_triangle - rows,
        ..device
    };
    assert!(matches!(
        at.check_limits(&smaller),
        Err(SceneError::MemoryOverLimit { .. })
    ));
}

#[test]
fn the_default_budget_is_that_of_an_unbounded_device_with_16384_rows() {
    let unbounded = LoadBudget::for_device(&DeviceLimits {
        max_storage_buffer_range: u64::MAX,
        max_image_dimension_2d: 16384,
        memory_budget: u64::MAX,
    });
    assert_eq!(
        LoadBudget {
            device: None,
            ..unbounded
        },
        LoadBudget::default()
    );
    // Tighter devices never get more.
    let small = LoadBudget::for_device(&DeviceLimits {
        max_storage_buffer_range: 128 << 20,
        max_image_dimension_2d: 16384,
        memory_budget: 2 << 30,
    });
    assert!(small.triangles < unbounded.triangles && small.lights < unbounded.lights);
    assert!(small.texels < unbounded.texels && small.vertices == 3 * small.triangles);
}

#[test]
fn an_environment_map_is_held_to_the_light_image_rows_not_the_storage_range() {
    // The map is sampled from the light image: an 8192 x 4096 map (512 MiB) is an ordinary
    // one, and it was refused on lavapipe for its 128 MiB storage-buffer range. Here in small:
    // a 64 x 32 map (33 KiB of texels) on a device with a 4 KiB range and images of one row.
    let device = DeviceLimits {
        max_storage_buffer_range: 4096,
        max_image_dimension_2d: 1,
        memory_budget: u64::MAX,
    };
    let with_map = |w, h| {
        let mut scene = load(&triangles(1), LoadBudget::default()).expect("one triangle");
        scene.environment_map = Some(Arc::new(EnvMap::constant(w, h, Vec3::ONE)));
        scene
    };
    let fits = with_map(64, 32);
    fits.check_limits(&device)
        .expect("2048 + 32 texels fit one row");
    assert!(images_fit(&fits, 1));
    let over = with_map(128, 32);
    let e = over.check_limits(&device).unwrap_err();
    assert!(
        matches!(
            e,
            SceneError::ImageOverLimit {
                rows: 2,
                limit: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("environment map"), "{e}");
    assert!(
        !images_fit(&over, 1),
        "the built light image needs two rows too"
    );
}

#[test]
fn the_scene_images_are_held_to_the_memory_budget() {
    // Seven images of one row each (4096 texels of 16 bytes): 448 KiB in all.
    let scene = load(&triangles(1), LoadBudget::default()).expect("one triangle");
    let row = 4096 * 16;
    let device = |memory_budget| DeviceLimits {
        memory_budget,
        ..DeviceLimits::LAVAPIPE
    };
    scene.check_limits(&device(7 * row)).expect("fits");
    let e = scene.check_limits(&device(7 * row - 1)).unwrap_err();
    assert!(matches!(e, SceneError::MemoryOverLimit { .. }), "{e}");
}
