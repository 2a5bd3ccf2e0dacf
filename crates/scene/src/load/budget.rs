//! Counting before allocating: what the scene will hold, from the JSON alone (accessor counts,
//! node references), compared with [`LoadBudget`] before any vertex is read.

use crate::{DeviceLimits, SceneError};
use gltf::mesh::Mode;
use std::path::Path;

/// Rows of `SCENE_TEXELS_WIDTH` texels that a scene image may have: `maxImageDimension2D` of
/// lavapipe and of most desktop GPUs. Each default below is what fits in such images.
const IMAGE_ROWS: u64 = 16384;

/// Device bytes of the scene images per triangle: its triangle and shading records and, at
/// worst, two BVH nodes (`crate::gpu::texels`).
const IMAGE_BYTES_PER_TRIANGLE: u64 = 16
    * (crate::gpu::TRIANGLE_TEXELS + crate::gpu::SHADING_TEXELS + 2 * crate::gpu::NODE_TEXELS)
        as u64;
/// Device bytes of the scene images that do not grow with the triangles: one row of each of
/// the seven images at least, the last rows of the three triangle arrays at most partly used.
const IMAGE_BYTES_FIXED: u64 = 7 * 16 * crate::gpu::SCENE_TEXELS_WIDTH as u64;

/// The most a scene may hold; larger scenes are refused while loading, before they are read
/// (the device's own limits are checked again, exactly, when the scene is uploaded).
///
/// The default is what a device with `maxImageDimension2D` 16384 and no other limit can hold
/// in the scene images (`crate::gpu::texels`): four texels per triangle and per BVH pair, at
/// most four per light, and four texture texels per atlas texel. The commands use
/// [`LoadBudget::for_device`]. The loaded scene holds about 100 bytes per triangle and 4 per
/// texture texel; loading, building its GPU form and writing its texels for the upload peak
/// at about 245 bytes per triangle, plus the file (docs/architecture.md).
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
    /// The device the budget was derived from, named in the refusal.
    pub device: Option<DeviceLimits>,
}

impl Default for LoadBudget {
    fn default() -> Self {
        let mut budget = LoadBudget::for_device(&DeviceLimits {
            max_storage_buffer_range: u64::MAX,
            max_image_dimension_2d: IMAGE_ROWS as u32,
            memory_budget: u64::MAX,
        });
        budget.device = None;
        budget
    }
}

impl LoadBudget {
    /// The most `device` can hold of each kind alone: a scene of this many triangles (and
    /// nothing else) passes [`crate::Scene::check_limits`]; where the storage-buffer range or
    /// the image rows bound it, one more triangle does not (the memory budget is met within
    /// the rows a scene image may leave unused). A scene near several limits at once can
    /// still be refused by `check_limits`, which is cheap (before the BVH is built).
    pub fn for_device(device: &DeviceLimits) -> Self {
        use crate::gpu::{BvhNode, GpuLight, GpuTriangle, SCENE_TEXELS_WIDTH, TriangleShading};
        let range = device.max_storage_buffer_range;
        let image = SCENE_TEXELS_WIDTH as u64 * device.max_image_dimension_2d as u64;
        let size = |bytes: usize| bytes as u64;
        // `Scene::check_limits`: (2n - 1) BVH nodes, n triangle and shading records.
        let triangles = [
            (range / size(size_of::<BvhNode>())).saturating_add(1) / 2,
            range / size(size_of::<GpuTriangle>()),
            range / size(size_of::<TriangleShading>()),
            image / 4,
            device.memory_budget.saturating_sub(IMAGE_BYTES_FIXED) / IMAGE_BYTES_PER_TRIANGLE,
        ];
        // One record per light plus one (the table is never empty), 16 bytes each.
        let lights = [
            (range / size(size_of::<GpuLight>())).saturating_sub(1),
            image / 4,
            device.memory_budget / 16,
        ];
        // Four bytes per texture texel, four texels per image texel.
        let texels = [
            range / 4,
            image.saturating_mul(crate::gpu::ATLAS_WORDS_PER_TEXEL as u64),
            device.memory_budget / 4,
        ];
        let min = |v: &[u64]| v.iter().copied().min().unwrap_or(0);
        let triangles = min(&triangles);
        LoadBudget {
            triangles,
            vertices: triangles.saturating_mul(3),
            lights: min(&lights),
            texels: min(&texels),
            device: Some(*device),
        }
    }

    /// Where the limits come from, for a refusal.
    fn basis(&self) -> String {
        let bytes = |b: u64| match b {
            b if b % (1 << 20) == 0 => format!("{} MiB", b >> 20),
            b => format!("{b} bytes"),
        };
        match &self.device {
            Some(d) => format!(
                "what this device holds: maxStorageBufferRange {}, maxImageDimension2D {}, \
                 memory budget {}",
                bytes(d.max_storage_buffer_range),
                d.max_image_dimension_2d,
                bytes(d.memory_budget)
            ),
            None => format!("what scene images of {IMAGE_ROWS} rows hold"),
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
            basis: budget.basis(),
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
