//! Errors of the renderer.

/// What can go wrong creating or running a [`crate::Renderer`].
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Device(#[from] blueshift_device::DeviceError),
    #[error(transparent)]
    Permute(#[from] blueshift_permute::PermuteError),
    #[error("scene: {0}")]
    Scene(String),
    #[error("asset: {0}")]
    Asset(String),
    #[error("{0}")]
    Invalid(String),
    /// A SIMD batch of the trace pass ran `iterations` loop iterations, at or over the guard
    /// below llvmpipe's silent limit: some paths may have been cut short.
    #[error(
        "lavapipe loop limit: a batch of the trace pass ran {iterations} loop iterations \
         (guard {guard}, llvmpipe silently ends loops at 65535), so some paths may be cut \
         short; lower --spp per frame or scene complexity"
    )]
    LoopLimit { iterations: u32, guard: u32 },
}

pub type Result<T, E = RenderError> = std::result::Result<T, E>;
