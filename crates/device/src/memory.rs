//! Named buffers and storage images allocated through gpu-allocator, each listed with its name
//! and memory location while it lives ([`Device::allocations`]). Device-local buffers are
//! written and read through host-visible staging copies.
use crate::device::Device;
use crate::error::{DeviceError, Result, VkContext};
use ash::vk;
use gpu_allocator::MemoryLocation;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};

fn alloc_error(name: &str, bytes: u64, e: gpu_allocator::AllocationError) -> DeviceError {
    match e {
        gpu_allocator::AllocationError::OutOfMemory => DeviceError::OutOfMemory {
            name: name.to_string(),
            bytes,
            detail: e.to_string(),
        },
        other => DeviceError::Allocation {
            name: name.to_string(),
            detail: other.to_string(),
        },
    }
}

/// One live allocation: what [`Device::allocations`] lists.
#[derive(Debug, Clone, PartialEq)]
pub struct LiveAllocation {
    pub name: String,
    pub bytes: u64,
    pub location: MemoryLocation,
    /// (memory handle, offset): unique among live allocations.
    key: (u64, u64),
}

fn key(a: &Allocation) -> (u64, u64) {
    // SAFETY: only the handle value is used, as a key.
    (vk::Handle::as_raw(unsafe { a.memory() }), a.offset())
}

impl Device {
    /// Every live buffer and image allocation, with its name and memory location, in the
    /// order they were made.
    pub fn allocations(&self) -> Vec<LiveAllocation> {
        self.shared
            .live
            .lock()
            .map(|l| l.clone())
            .unwrap_or_default()
    }
}

fn allocate(
    dev: &Device,
    name: &str,
    requirements: vk::MemoryRequirements,
    location: MemoryLocation,
    linear: bool,
) -> Result<Allocation> {
    let info = dev.info();
    let out_of_memory = |detail: String| DeviceError::OutOfMemory {
        name: name.to_string(),
        bytes: requirements.size,
        detail,
    };
    if requirements.size > info.max_memory_allocation_size {
        return Err(out_of_memory(format!(
            "over the device's maxMemoryAllocationSize of {} bytes",
            info.max_memory_allocation_size
        )));
    }
    let in_use = dev.allocated_bytes();
    if in_use.saturating_add(requirements.size) > info.memory_budget {
        return Err(out_of_memory(format!(
            "{in_use} bytes are in use and the device memory budget is {} bytes; use a smaller resolution or scene",
            info.memory_budget
        )));
    }
    let mut guard = dev.allocator()?;
    let alloc = guard
        .as_mut()
        .ok_or_else(|| DeviceError::Usage("allocator already destroyed".into()))?;
    let a = alloc
        .allocate(&AllocationCreateDesc {
            name,
            requirements,
            location,
            linear,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        })
        .map_err(|e| alloc_error(name, requirements.size, e))?;
    if let Ok(mut live) = dev.shared.live.lock() {
        live.push(LiveAllocation {
            name: name.to_string(),
            bytes: requirements.size,
            location,
            key: key(&a),
        });
    }
    Ok(a)
}

fn free(dev: &Device, allocation: Option<Allocation>) {
    if let Some(a) = &allocation
        && let Ok(mut live) = dev.shared.live.lock()
    {
        let k = key(a);
        live.retain(|l| l.key != k);
    }
    if let (Some(a), Ok(mut guard)) = (allocation, dev.allocator())
        && let Some(alloc) = guard.as_mut()
    {
        let _ = alloc.free(a);
    }
}

/// A named buffer. Host-visible locations (`CpuToGpu`, `GpuToCpu`) are persistently mapped;
/// `GpuOnly` ones are read and written through staging copies.
pub struct Buffer {
    dev: Device,
    pub raw: vk::Buffer,
    allocation: Option<Allocation>,
    location: MemoryLocation,
    pub size: u64,
    pub name: String,
}

impl std::fmt::Debug for Buffer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Buffer")
            .field("name", &self.name)
            .field("size", &self.size)
            .finish()
    }
}

/// Usage every buffer gets: storage for passes, transfer for copies, fills and readback.
const BUFFER_USAGE: vk::BufferUsageFlags = vk::BufferUsageFlags::from_raw(
    vk::BufferUsageFlags::STORAGE_BUFFER.as_raw()
        | vk::BufferUsageFlags::TRANSFER_SRC.as_raw()
        | vk::BufferUsageFlags::TRANSFER_DST.as_raw(),
);

impl Buffer {
    /// Creates a storage buffer of `size` bytes (at least 4) named `name`.
    pub fn new(dev: &Device, name: &str, size: u64, location: MemoryLocation) -> Result<Self> {
        let size = size.max(4).next_multiple_of(4);
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(BUFFER_USAGE)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        let raw_dev = dev.raw();
        // SAFETY: valid create info.
        let raw = unsafe { raw_dev.create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        // SAFETY: `raw` was just created on this device.
        let req = unsafe { raw_dev.get_buffer_memory_requirements(raw) };
        let allocation = match allocate(dev, name, req, location, true) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: unused buffer.
                unsafe { raw_dev.destroy_buffer(raw, None) };
                return Err(e);
            }
        };
        // SAFETY: fresh allocation sized for this buffer.
        unsafe { raw_dev.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
            .vk("vkBindBufferMemory")?;
        dev.set_name(raw, name);
        Ok(Self {
            dev: dev.clone(),
            raw,
            allocation: Some(allocation),
            location,
            size,
            name: name.to_string(),
        })
    }

    /// A host-visible buffer filled with `data`.
    pub fn from_slice<T: bytemuck::Pod>(dev: &Device, name: &str, data: &[T]) -> Result<Self> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let mut b = Self::new(dev, name, bytes.len() as u64, MemoryLocation::CpuToGpu)?;
        b.write(0, data)?;
        Ok(b)
    }

    /// A device-local buffer filled with `data` through a staging copy.
    pub fn upload<T: bytemuck::Pod>(dev: &Device, name: &str, data: &[T]) -> Result<Self> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let mut b = Self::new(dev, name, bytes.len() as u64, MemoryLocation::GpuOnly)?;
        b.write(0, data)?;
        Ok(b)
    }

    /// The buffer's memory location.
    pub fn location(&self) -> MemoryLocation {
        self.location
    }

    /// Whether the host can read and write the buffer directly.
    pub fn is_mapped(&self) -> bool {
        self.allocation
            .as_ref()
            .is_some_and(|a| a.mapped_ptr().is_some())
    }

    /// Writes `data` at byte `offset`: directly when host-visible, else through a staging
    /// buffer and one submission of its own that waits (set-up and resets, not per frame).
    pub fn write<T: bytemuck::Pod>(&mut self, offset: u64, data: &[T]) -> Result<()> {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let name = self.name.clone();
        if !self.is_mapped() {
            if offset + bytes.len() as u64 > self.size {
                return Err(DeviceError::Usage(format!(
                    "write of {} bytes past the end of '{name}'",
                    bytes.len()
                )));
            }
            let staging = Self::from_slice(&self.dev, &format!("{name}.staging"), bytes)?;
            return crate::Recorder::one_shot(&self.dev, "upload", |rec| {
                rec.copy_region(&staging, self, offset, bytes.len() as u64)
            });
        }
        let slice = self
            .allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .ok_or_else(|| DeviceError::Usage(format!("buffer '{name}' is not mapped")))?;
        let end = offset as usize + bytes.len();
        let dst = slice.get_mut(offset as usize..end).ok_or_else(|| {
            DeviceError::Usage(format!(
                "write of {} bytes past the end of '{name}'",
                bytes.len()
            ))
        })?;
        dst.copy_from_slice(bytes);
        Ok(())
    }

    /// Reads the whole buffer as `T`s: directly when host-visible, else through a readback
    /// buffer and one submission of its own that waits (tests, reports, screenshots; per-frame
    /// readbacks record their copies into the frame instead).
    pub fn read<T: bytemuck::Pod>(&self) -> Result<Vec<T>> {
        if !self.is_mapped() {
            let name = format!("{}.readback", self.name);
            let readback = Self::new(&self.dev, &name, self.size, MemoryLocation::GpuToCpu)?;
            crate::Recorder::one_shot(&self.dev, "readback", |rec| {
                rec.copy_buffer(self, &readback, None)
            })?;
            return readback.read();
        }
        let slice = self
            .allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .ok_or_else(|| DeviceError::Usage(format!("buffer '{}' is not mapped", self.name)))?;
        let n = slice.len() / std::mem::size_of::<T>().max(1);
        let bytes = &slice[..n * std::mem::size_of::<T>()];
        Ok(bytemuck::pod_collect_to_vec(bytes))
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: callers wait for GPU work that uses the buffer before dropping it.
        unsafe { self.dev.raw().destroy_buffer(self.raw, None) };
        free(&self.dev, self.allocation.take());
    }
}

/// A named 2D image with a view, kept in `GENERAL` layout (storage + transfer).
pub struct Image {
    dev: Device,
    pub raw: vk::Image,
    pub view: vk::ImageView,
    allocation: Option<Allocation>,
    pub format: vk::Format,
    pub width: u32,
    pub height: u32,
    pub name: String,
}

impl std::fmt::Debug for Image {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Image")
            .field("name", &self.name)
            .field("extent", &(self.width, self.height))
            .finish()
    }
}

impl Image {
    /// Creates a storage image. It starts in `UNDEFINED`; record
    /// [`crate::Recorder::init_image`] before first use.
    pub fn new(
        dev: &Device,
        name: &str,
        width: u32,
        height: u32,
        format: vk::Format,
    ) -> Result<Self> {
        let max = dev.info().max_image_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(DeviceError::Usage(format!(
                "image '{name}' size {width}x{height} is outside 1..={max} (the device's maxImageDimension2D)"
            )));
        }
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D {
                width,
                height,
                depth: 1,
            })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(
                vk::ImageUsageFlags::STORAGE
                    | vk::ImageUsageFlags::TRANSFER_SRC
                    | vk::ImageUsageFlags::TRANSFER_DST,
            )
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let raw_dev = dev.raw();
        // SAFETY: valid create info.
        let raw = unsafe { raw_dev.create_image(&info, None) }.vk("vkCreateImage")?;
        // SAFETY: image from this device.
        let req = unsafe { raw_dev.get_image_memory_requirements(raw) };
        let allocation = match allocate(dev, name, req, MemoryLocation::GpuOnly, false) {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: unused image.
                unsafe { raw_dev.destroy_image(raw, None) };
                return Err(e);
            }
        };
        // SAFETY: fresh allocation for this image.
        unsafe { raw_dev.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
            .vk("vkBindImageMemory")?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(format)
            .subresource_range(color_range());
        // SAFETY: image is bound.
        let view =
            unsafe { raw_dev.create_image_view(&view_info, None) }.vk("vkCreateImageView")?;
        dev.set_name(raw, name);
        dev.set_name(view, &format!("{name}.view"));
        Ok(Self {
            dev: dev.clone(),
            raw,
            view,
            allocation: Some(allocation),
            format,
            width,
            height,
            name: name.to_string(),
        })
    }
}

/// The single-mip, single-layer colour subresource.
pub fn color_range() -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: 1,
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        // SAFETY: callers wait for GPU work that uses the image before dropping it.
        unsafe {
            self.dev.raw().destroy_image_view(self.view, None);
            self.dev.raw().destroy_image(self.raw, None);
        }
        free(&self.dev, self.allocation.take());
    }
}
