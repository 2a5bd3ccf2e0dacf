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

    /// A GLB header or chunk header that is inconsistent (a length below the header size or
    /// past the end, a wrong version or chunk type). Checked before the glTF reader, which
    /// panics on some of these.
    #[error("{}: not a valid glTF 2.0 file: {problem}", path.display())]
    Glb { path: PathBuf, problem: String },

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

    /// NaN or infinite vertex positions (in the file, or after the node transform) are an
    /// error, not a silent skip: they mean the file is corrupt.
    #[error(
        "{}: mesh {mesh} primitive {primitive}: vertex {vertex} has a non-finite position \
         {position:?}",
        path.display()
    )]
    NonFinitePosition {
        path: PathBuf,
        mesh: String,
        primitive: usize,
        vertex: usize,
        position: [f32; 3],
    },

    #[error("{}: node hierarchy is deeper than {max_depth} levels (cyclic?)", path.display())]
    NodeDepth { path: PathBuf, max_depth: usize },

    #[error("{}: the scene has no triangles to render ({reason})", path.display())]
    EmptyScene { path: PathBuf, reason: String },

    /// A GPU buffer would exceed the device's `maxStorageBufferRange`.
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
