//! Raw Vulkan over ash for Blueshift: instance (validation on request, messages counted), device
//! choice that works headless and with a surface, named gpu-allocator buffers and images,
//! compute pipelines whose bindings are checked against the SPIR-V, command recording with
//! per-pass timestamps and crash markers, and a swapchain for windowed presentation. It knows
//! nothing of scenes or passes.
//!
//! ```no_run
//! use blueshift_device::{Device, DeviceDesc, Instance, InstanceDesc};
//! let instance = Instance::new(&InstanceDesc::from_env(true))?;
//! let device = Device::new(&instance, &DeviceDesc::default())?;
//! println!("{}", device.info().name);
//! # Ok::<(), blueshift_device::DeviceError>(())
//! ```
mod commands;
mod device;
mod error;
pub mod faults;
mod instance;
mod memory;
mod pipeline;
mod present;
mod submit;
mod surface;
mod swapchain;
mod transfer;

pub use ash::{self, vk};
pub use commands::{PassTime, Recorder, Res};
pub use device::{Device, DeviceDesc, DeviceInfo, list_physical_devices};
pub use error::{DeviceError, Result};
pub use gpu_allocator::MemoryLocation;
pub use instance::{Instance, InstanceDesc, ValidationLog};
pub use memory::{Buffer, Image, LiveAllocation};
pub use pipeline::{
    Binding, BindingKind, ComputePipeline, PipelineCache, ShaderInterface, check_bindings, reflect,
};
pub use surface::Surface;
pub use swapchain::{
    ACQUIRE_SEMAPHORES, PRESENTABLE_FORMATS, SwapImage, Swapchain, choose_extent, choose_format,
    choose_image_count, choose_present_mode, is_bgra,
};

/// Creates an instance and device in one call (the common headless case).
pub fn headless(validation: bool, device_index: Option<usize>) -> Result<Device> {
    let instance = Instance::new(&InstanceDesc::from_env(validation))?;
    Device::new(
        &instance,
        &DeviceDesc {
            device_index,
            surface: None,
        },
    )
}
