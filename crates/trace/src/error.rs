//! Errors of the path-tracing pass.

#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    #[error(transparent)]
    Device(#[from] blueshift_device::DeviceError),
    /// The scene does not fit the device (storage-buffer range, image size).
    #[error("scene: {0}")]
    Scene(String),
    #[error("{0}")]
    Invalid(String),
    /// A SIMD batch of the trace pass reached the loop guard ([`crate::TRACE_LOOP_GUARD`]).
    #[error(
        "lavapipe loop limit: a batch of the trace pass ran {iterations} loop iterations \
         (guard {guard}, llvmpipe silently ends loops at 65535), so some paths may be cut \
         short; lower --spp per frame or scene complexity"
    )]
    LoopLimit { iterations: u32, guard: u32 },
}

pub type Result<T, E = TraceError> = std::result::Result<T, E>;
