//! One error type for the device layer.
use ash::vk;

/// Everything that can go wrong below the passes.
#[derive(Debug, thiserror::Error)]
pub enum DeviceError {
    #[error(
        "could not load the Vulkan loader (libvulkan.so.1): {0}. Install it with `apt-get install libvulkan1 mesa-vulkan-drivers`"
    )]
    Loader(String),
    #[error(
        "no Vulkan device with a compute queue was found (if VK_DRIVER_FILES or VK_ICD_FILENAMES is set, check it names an installed driver). For a CPU device install Mesa lavapipe: `apt-get install mesa-vulkan-drivers`"
    )]
    NoDevice,
    #[error("device index {index} is out of range: {count} Vulkan device(s) found ({names})")]
    DeviceIndex {
        index: usize,
        count: usize,
        names: String,
    },
    #[error(
        "validation was requested but VK_LAYER_KHRONOS_validation is not installed: `apt-get install vulkan-validationlayers`"
    )]
    ValidationMissing,
    #[error("device '{device}' lacks a required feature: {feature}")]
    MissingFeature { device: String, feature: String },
    #[error("{what} failed: {result}")]
    Vulkan { what: String, result: vk::Result },
    #[error("the device was lost while running pass '{pass}' ({what})")]
    DeviceLost { pass: String, what: String },
    #[error("out of memory allocating '{name}' ({bytes} bytes): {detail}")]
    OutOfMemory {
        name: String,
        bytes: u64,
        detail: String,
    },
    /// Out of memory while submitting or running a submission; names its passes.
    #[error("out of memory while running pass(es) {passes} ({what}: {result})")]
    SubmitOutOfMemory {
        passes: String,
        what: String,
        result: vk::Result,
    },
    #[error("allocation '{name}' failed: {detail}")]
    Allocation { name: String, detail: String },
    #[error("shader '{shader}': {detail}")]
    Shader { shader: String, detail: String },
    #[error("shader '{shader}', set {set}, binding {binding}: {detail}")]
    BindingMismatch {
        shader: String,
        set: u32,
        binding: u32,
        detail: String,
    },
    #[error("{0}")]
    Usage(String),
}

/// Result alias for the device layer.
pub type Result<T, E = DeviceError> = std::result::Result<T, E>;

/// Attaches a description to a raw `vk::Result`.
pub(crate) trait VkContext<T> {
    fn vk(self, what: &str) -> Result<T>;
}

impl<T> VkContext<T> for std::result::Result<T, vk::Result> {
    fn vk(self, what: &str) -> Result<T> {
        self.map_err(|result| DeviceError::Vulkan {
            what: what.to_string(),
            result,
        })
    }
}
