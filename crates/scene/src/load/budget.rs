//! Counting before allocating: what the scene will hold, from the JSON alone (accessor counts,
//! node references), compared with [`LoadBudget`] before any vertex is read.

use crate::SceneError;
use gltf::mesh::Mode;
use std::path::Path;

/// Rows of `SCENE_TEXELS_WIDTH` texels that a scene image may have: `maxImageDimension2D` of
/// lavapipe and of most desktop GPUs. Each default below is what fits in such images.
const IMAGE_ROWS: u64 = 16384;
/// Texels of one scene image (`crate::gpu::texels`).
const IMAGE_TEXELS: u64 = crate::gpu::SCENE_TEXELS_WIDTH as u64 * IMAGE_ROWS;

/// The most a scene may hold; larger scenes are refused while loading, before they are read
/// (the device's own limits are checked again when the scene is uploaded).
///
/// The defaults are what one device with `maxImageDimension2D` 16384 can hold in the scene
/// images (`crate::gpu::texels`): four texels per triangle and per BVH pair, at most four per
/// light, and four texture texels per atlas texel. The loaded scene holds about 100 bytes per
/// triangle and 4 per texture texel; loading, building its GPU form and writing its texels
/// for the upload peak at about 245 bytes per triangle, plus the file (docs/architecture.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadBudget {
    /// Triangles after instancing: each mesh's triangles times the nodes that draw it.
    pub triangles: u64,
    /// Vertices read after instancing (three per triangle at most, for non-indexed meshes).
    pub vertices: u64,
    /// Emissive triangles (after instancing) plus punctual lights.
    pub lights: u64,
    /// Texels of all texture images together, read from each image's header. An image that
    /// would go over is skipped with a warning, as an undecodable one is.
    pub texels: u64,
}

impl Default for LoadBudget {
    fn default() -> Self {
        let triangles = IMAGE_TEXELS / 4;
        LoadBudget {
            triangles,
            vertices: 3 * triangles,
            lights: IMAGE_TEXELS / 4,
            texels: IMAGE_TEXELS * 4,
        }
    }
}

/// What the scene will hold (upper bounds: zero-area triangles are not yet known).
#[derive(Debug, Default, PartialEq)]
pub(super) struct Counts {
    pub triangles: u64,
    pub vertices: u64,
    pub lights: u64,
}

/// Counts the triangles, vertices and lights of `nodes` (each node of the scene once, as the
/// graph check returns them) and refuses a scene over `budget`.
pub(super) fn count(
    path: &Path,
    document: &gltf::Document,
    nodes: &[usize],
    budget: &LoadBudget,
) -> Result<Counts, SceneError> {
    let mut instances = vec![0u64; document.meshes().len()];
    let mut counts = Counts::default();
    let all: Vec<gltf::Node> = document.nodes().collect();
    for node in nodes.iter().filter_map(|&i| all.get(i)) {
        if let Some(mesh) = node.mesh() {
            instances[mesh.index()] += 1;
        }
        if node.light().is_some() {
            counts.lights += 1;
        }
    }
    for mesh in document.meshes() {
        let k = instances[mesh.index()];
        if k == 0 {
            continue;
        }
        for prim in mesh.primitives().filter(|p| p.mode() == Mode::Triangles) {
            let vertices = prim
                .get(&gltf::Semantic::Positions)
                .map_or(0, |a| a.count() as u64);
            let triangles = prim.indices().map_or(vertices, |a| a.count() as u64) / 3;
            let m = prim.material();
            let emission = m
                .emissive_factor()
                .map(|c| c * m.emissive_strength().unwrap_or(1.0));
            let emits = emission.iter().all(|c| c.is_finite()) && emission.iter().any(|&c| c > 0.0);
            counts.triangles = counts.triangles.saturating_add(k.saturating_mul(triangles));
            counts.vertices = counts.vertices.saturating_add(k.saturating_mul(vertices));
            if emits {
                counts.lights = counts.lights.saturating_add(k.saturating_mul(triangles));
            }
        }
    }
    let over = |what, count, limit| {
        (count > limit).then(|| SceneError::OverBudget {
            path: path.to_path_buf(),
            what,
            count,
            limit,
        })
    };
    let refusal = over(
        "triangles after instancing",
        counts.triangles,
        budget.triangles,
    )
    .or_else(|| {
        over(
            "vertices after instancing",
            counts.vertices,
            budget.vertices,
        )
    })
    .or_else(|| {
        over(
            "lights (emissive triangles and punctual lights)",
            counts.lights,
            budget.lights,
        )
    });
    match refusal {
        Some(e) => Err(e),
        None => Ok(counts),
    }
}
