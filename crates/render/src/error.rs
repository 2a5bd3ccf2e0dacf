//! Errors of the renderer.

/// What can go wrong creating or running a [`crate::Renderer`].
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Device(#[from] blueshift_device::DeviceError),
    #[error(transparent)]
    Permute(#[from] blueshift_permute::PermuteError),
    /// The trace pass: a scene over the device's limits, or the loop guard.
    #[error(transparent)]
    Trace(#[from] blueshift_trace::TraceError),
    /// A precomputed asset is missing, malformed, or does not fit the configuration.
    #[error("asset: {0}")]
    Asset(#[from] blueshift_assets::AssetError),
    #[error("{0}")]
    Invalid(String),
}

pub type Result<T, E = RenderError> = std::result::Result<T, E>;
