//! Every GLSL compute shader under the workspace's `shaders/`, compiled to SPIR-V at build time
//! (see build.rs) and looked up by its path without extension, e.g. `"test/rng"`.

include!(concat!(env!("OUT_DIR"), "/shaders.rs"));

mod canonical;
pub use canonical::canonical_words;

/// The SPIR-V words of shader `name`, or `None` if no such shader exists.
pub fn spirv(name: &str) -> Option<Vec<u32>> {
    SHADERS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, bytes)| bytemuck::pod_collect_to_vec(bytes))
}

/// Names of all compiled shaders.
pub fn names() -> impl Iterator<Item = &'static str> {
    SHADERS.iter().map(|(n, _)| *n)
}

/// Like [`spirv`], with an error message listing what exists.
pub fn require(name: &str) -> Result<Vec<u32>, String> {
    spirv(name).ok_or_else(|| {
        format!(
            "no shader named '{name}'; known: {}",
            names().collect::<Vec<_>>().join(", ")
        )
    })
}

/// The checked compute pipeline of shader `name` (bindings and push size are verified against
/// its SPIR-V by [`blueshift_device::ComputePipeline::new`]).
pub fn pipeline(
    dev: &blueshift_device::Device,
    name: &str,
    bindings: &[blueshift_device::Binding],
    push_size: usize,
) -> Result<blueshift_device::ComputePipeline, blueshift_device::DeviceError> {
    let spirv = require(name).map_err(|detail| blueshift_device::DeviceError::Shader {
        shader: name.to_string(),
        detail,
    })?;
    blueshift_device::ComputePipeline::new(dev, name, &spirv, bindings, push_size as u32)
}
