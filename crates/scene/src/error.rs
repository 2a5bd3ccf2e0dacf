//! The one error type of this crate. Every variant names the file (or buffer) and the problem.

use std::path::PathBuf;

/// Everything that can go wrong while loading, checking or writing a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{}: file not found", path.display())]
    NotFound { path: PathBuf },

    #[error("{}: cannot read: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// Malformed JSON, a broken GLB container, or a document that fails glTF validation.
    #[error("{}: not a valid glTF 2.0 file: {source}", path.display())]
    Parse {
        path: PathBuf,
        #[source]
        source: gltf::Error,
    },

    /// `asset.version` (or `asset.minVersion`) other than 2.x.
    #[error("{}: asset.{field} {version}: only glTF 2.0 is supported", path.display())]
    Version {
        path: PathBuf,
        field: &'static str,
        version: String,
    },

    /// An extension in `extensionsRequired` that the loader does not implement.
    #[error("{}: requires unsupported extension {extension}", path.display())]
    UnsupportedExtension { path: PathBuf, extension: String },

    /// A rule of the glTF 2.0 specification that the reader does not check itself (e.g.
    /// `byteStride` a multiple of 4).
    #[error("{}: not a valid glTF 2.0 file: {problem}", path.display())]
    Spec { path: PathBuf, problem: String },

    /// A light (punctual, or an emissive material) whose radiance overflows f32.
    #[error("{}: {what} {problem}", path.display())]
    Light {
        path: PathBuf,
        /// `KHR_lights_punctual light 0`, `material 2 ('lamp')`.
        what: String,
        problem: String,
    },

    /// A GLB header or chunk header that is inconsistent (a length below the header size or
    /// past the end, a wrong version or chunk type). Checked before the glTF reader, which
    /// panics on some of these.
    #[error("{}: not a valid glTF 2.0 file: {problem}", path.display())]
    Glb { path: PathBuf, problem: String },

    /// A buffer or image URI that leads outside the directory of the scene file (an absolute
    /// path, a `file:` URI, `..` climbing out, or a symlink whose target lies outside); refused
    /// unless [`crate::LoadOptions::allow_outside_paths`] is set.
    #[error(
        "{}: {what} URI '{uri}' points outside the scene directory {} ({reason}); reading it \
         needs --allow-outside-paths",
        path.display(),
        dir.display()
    )]
    OutsidePath {
        path: PathBuf,
        /// `buffer 0`, `image 3`.
        what: String,
        uri: String,
        dir: PathBuf,
        reason: String,
    },

    #[error("{}: buffer {index} ({uri}): {problem}", path.display())]
    Buffer {
        path: PathBuf,
        index: usize,
        uri: String,
        problem: String,
    },

    /// A primitive whose accessors cannot be read (wrong type, out of bounds, missing data).
    #[error("{}: mesh {mesh} primitive {primitive}: {problem}", path.display())]
    Primitive {
        path: PathBuf,
        mesh: String,
        primitive: usize,
        problem: String,
    },

    #[error(
        "{}: mesh {mesh} primitive {primitive}: vertex index {index} is out of range \
         (the primitive has {vertex_count} vertices)",
        path.display()
    )]
    IndexOutOfRange {
        path: PathBuf,
        mesh: String,
        primitive: usize,
        index: u32,
        vertex_count: usize,
    },

    /// A vertex position that is NaN, infinite, or has a coordinate of magnitude
    /// [`crate::MAX_COORDINATE`] or more, in the file or after the node transform (`world`).
    /// An error, not a silent skip: non-finite positions mean a corrupt file, and huge ones
    /// overflow the tracer's f32 arithmetic (extents, edges, ray offsets) or lose the scene to
    /// rounding, rendering a wrong image.
    #[error(
        "{}: mesh {mesh} primitive {primitive}: POSITION accessor {accessor}: vertex {vertex} {}",
        path.display(),
        position_problem(position, *world)
    )]
    PositionOutOfRange {
        path: PathBuf,
        mesh: String,
        primitive: usize,
        accessor: usize,
        vertex: usize,
        position: [f32; 3],
        /// Whether the position is the world-space one (after the node transforms).
        world: bool,
    },

    #[error("{}: node hierarchy is deeper than {max_depth} levels", path.display())]
    NodeDepth { path: PathBuf, max_depth: usize },

    /// glTF nodes form disjoint trees; the node graph of the scene is checked before it is
    /// expanded, since a cycle or a shared child repeats its subtree without bound.
    #[error("{}: node {node} is its own ancestor", path.display())]
    NodeCycle { path: PathBuf, node: usize },

    #[error("{}: node {node} has two parents, nodes {} and {}", path.display(), parents[0], parents[1])]
    NodeParents {
        path: PathBuf,
        node: usize,
        parents: [usize; 2],
    },

    #[error(
        "{}: node {node} is listed more than once among the children of node {parent}",
        path.display()
    )]
    NodeRepeated {
        path: PathBuf,
        node: usize,
        parent: usize,
    },

    #[error(
        "{}: node {node} is a root of scene {scene} and also a child of node {parent}",
        path.display()
    )]
    RootWithParent {
        path: PathBuf,
        scene: usize,
        node: usize,
        parent: usize,
    },

    #[error(
        "{}: node {node} is listed more than once among the roots of scene {scene}",
        path.display()
    )]
    RootRepeated {
        path: PathBuf,
        scene: usize,
        node: usize,
    },

    /// A count taken from the file before anything is allocated for it, over the loader's
    /// budget ([`crate::LoadBudget`]).
    #[error(
        "{}: the scene has {count} {what}, over the loader's limit of {limit} ({basis})",
        path.display()
    )]
    OverBudget {
        path: PathBuf,
        what: &'static str,
        count: u64,
        limit: u64,
        /// Where the limit comes from (the device's limits, or the default).
        basis: String,
    },

    #[error("{}: the scene has no triangles to render ({reason})", path.display())]
    EmptyScene { path: PathBuf, reason: String },

    /// A scene array would exceed the device's `maxStorageBufferRange`.
    #[error(
        "the {buffer} buffer needs {size} bytes ({size_mib:.1} MiB), over the device limit \
         maxStorageBufferRange = {limit} bytes ({limit_mib:.1} MiB)"
    )]
    OverLimit {
        buffer: &'static str,
        size: u64,
        size_mib: f64,
        limit: u64,
        limit_mib: f64,
    },

    /// A scene image would need more rows than the device's `maxImageDimension2D`.
    #[error(
        "the {image} image needs {rows} rows of 4096 texels, over the device limit \
         maxImageDimension2D = {limit}"
    )]
    ImageOverLimit {
        image: &'static str,
        rows: u64,
        limit: u32,
    },

    /// The scene images together would need more than the device's memory budget.
    #[error("the scene images need {mib} MiB, over the device's memory budget of {budget_mib} MiB")]
    MemoryOverLimit { mib: u64, budget_mib: u64 },

    #[error("unknown preset '{name}'; available presets: {available}")]
    UnknownPreset { name: String, available: String },

    #[error("cannot write {}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// Catch-all for a panic inside the glTF reader on malformed data.
    #[error("{}: malformed data made the glTF reader fail: {message}", path.display())]
    Internal { path: PathBuf, message: String },
}

impl SceneError {
    pub(crate) fn over_limit(buffer: &'static str, size: u64, limit: u64) -> Self {
        const MIB: f64 = 1024.0 * 1024.0;
        SceneError::OverLimit {
            buffer,
            size,
            size_mib: size as f64 / MIB,
            limit,
            limit_mib: limit as f64 / MIB,
        }
    }
}

/// What is wrong with a position: non-finite, or too large.
fn position_problem(position: &[f32; 3], world: bool) -> String {
    let after = if world {
        " after the node transform"
    } else {
        ""
    };
    if position.iter().all(|c| c.is_finite()) {
        format!(
            "is at {position:?}{after}, beyond the limit of {:e} on any coordinate (a scene \
             this large overflows the tracer's f32 arithmetic)",
            crate::MAX_COORDINATE
        )
    } else {
        format!("has a non-finite position {position:?}{after}")
    }
}
