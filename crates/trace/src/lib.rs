//! The path-tracing pass.
