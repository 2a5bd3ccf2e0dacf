//! Physical-device choice and the logical device with one compute queue.
use crate::error::{DeviceError, Result, VkContext};
use crate::instance::Instance;
use crate::surface::Surface;
use ash::{ext, khr, vk};
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use std::ffi::{CString, c_char};
use std::sync::{Arc, Mutex, MutexGuard};

/// How to pick and create the device.
#[derive(Debug, Default, Clone, Copy)]
pub struct DeviceDesc<'a> {
    /// Use this physical device (index into the enumeration `blueshift info` prints).
    /// `None` reads `BLUESHIFT_DEVICE_INDEX`, else prefers discrete > integrated > virtual > CPU.
    pub device_index: Option<usize>,
    /// When given, the queue must be able to present to it and the swapchain extension is enabled.
    pub surface: Option<&'a Surface>,
}

/// What the path tracer needs to know about the device, as `blueshift info` prints it.
#[derive(Debug, Clone)]
pub struct DeviceInfo {
    pub name: String,
    pub device_type: String,
    pub api_version: String,
    pub driver_name: String,
    pub driver_info: String,
    pub max_storage_buffer_range: u64,
    pub max_memory_allocation_size: u64,
    /// Bytes Blueshift may allocate in all: the largest memory heap (lavapipe: system RAM), or
    /// less with the fault hook [`crate::faults::MEMORY_BUDGET`]. Checked before every allocation so running out is
    /// an error naming the resource rather than a driver abort or the OOM killer.
    pub memory_budget: u64,
    pub max_compute_work_group_invocations: u32,
    pub max_compute_work_group_count: [u32; 3],
    pub max_compute_shared_memory_size: u32,
    pub max_image_dimension_2d: u32,
    pub max_push_constants_size: u32,
    pub subgroup_size: u32,
    pub timestamp_period_ns: f32,
    pub timestamp_valid_bits: u32,
    pub shader_int64: bool,
    pub shader_float64: bool,
    pub scalar_block_layout: bool,
    pub push_descriptor: bool,
}

pub(crate) struct DeviceShared {
    pub instance: Instance,
    pub physical: vk::PhysicalDevice,
    pub raw: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    pub allocator: Mutex<Option<Allocator>>,
    /// Every live allocation, for [`Device::allocations`].
    pub live: Mutex<Vec<crate::memory::LiveAllocation>>,
    pub push_descriptor: khr::push_descriptor::Device,
    pub debug_utils: Option<ext::debug_utils::Device>,
    pub info: DeviceInfo,
    pub swapchain_enabled: bool,
}

impl Drop for DeviceShared {
    fn drop(&mut self) {
        // SAFETY: all resources hold an Arc to this; they are gone. Free the allocator first.
        unsafe {
            let _ = self.raw.device_wait_idle();
            if let Ok(mut a) = self.allocator.lock() {
                a.take();
            }
            self.raw.destroy_device(None);
        }
    }
}

/// The logical device. Cheap to clone; resources keep it alive.
#[derive(Clone)]
pub struct Device {
    pub(crate) shared: Arc<DeviceShared>,
}

impl std::fmt::Debug for Device {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Device")
            .field("name", &self.shared.info.name)
            .finish()
    }
}

fn type_rank(t: vk::PhysicalDeviceType) -> u32 {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 3,
        _ => 4,
    }
}

fn cstr_field(bytes: &[c_char]) -> String {
    let bytes: Vec<u8> = bytes
        .iter()
        .take_while(|&&c| c != 0)
        .map(|&c| c as u8)
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Names of all physical devices, in enumeration order.
pub fn list_physical_devices(instance: &Instance) -> Result<Vec<String>> {
    let raw = instance.raw();
    // SAFETY: plain enumeration on a live instance.
    let devices = unsafe { raw.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
    Ok(devices
        .iter()
        // SAFETY: handles come from the enumeration above.
        .map(|&d| cstr_field(&unsafe { raw.get_physical_device_properties(d) }.device_name))
        .collect())
}

impl Device {
    /// Picks a physical device and creates the logical device, queue and allocator.
    pub fn new(instance: &Instance, desc: &DeviceDesc) -> Result<Self> {
        let raw_inst = instance.raw();
        // SAFETY: plain enumeration on a live instance.
        let devices =
            unsafe { raw_inst.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
        if devices.is_empty() {
            return Err(DeviceError::NoDevice);
        }
        let env_index = std::env::var("BLUESHIFT_DEVICE_INDEX")
            .ok()
            .map(|v| {
                v.parse::<usize>().map_err(|_| {
                    DeviceError::Usage(format!("BLUESHIFT_DEVICE_INDEX='{v}' is not a number"))
                })
            })
            .transpose()?;
        let mut candidates = Vec::new();
        for (i, &pd) in devices.iter().enumerate() {
            if let Some(qf) = compute_queue_family(instance, pd, desc.surface)? {
                candidates.push((i, pd, qf));
            }
        }
        let chosen = match desc.device_index.or(env_index) {
            Some(index) => {
                let names = list_physical_devices(instance)?.join(", ");
                let (_, pd, qf) = candidates.iter().find(|c| c.0 == index).copied().ok_or(
                    DeviceError::DeviceIndex {
                        index,
                        count: devices.len(),
                        names,
                    },
                )?;
                (pd, qf)
            }
            None => {
                candidates.sort_by_key(|&(i, pd, _)| {
                    // SAFETY: handle from the enumeration.
                    let p = unsafe { raw_inst.get_physical_device_properties(pd) };
                    (type_rank(p.device_type), i)
                });
                let &(_, pd, qf) = candidates.first().ok_or(DeviceError::NoDevice)?;
                (pd, qf)
            }
        };
        Self::create(instance, chosen.0, chosen.1, desc.surface.is_some())
    }

    fn create(
        instance: &Instance,
        pd: vk::PhysicalDevice,
        qf: u32,
        swapchain: bool,
    ) -> Result<Self> {
        let raw_inst = instance.raw();
        let mut info = query_info(instance, pd);
        if let Some(limit) = env_limit(crate::faults::MAX_STORAGE_BUFFER_RANGE)? {
            info.max_storage_buffer_range = info.max_storage_buffer_range.min(limit);
        }
        if let Some(limit) = env_limit(crate::faults::MEMORY_BUDGET)? {
            info.memory_budget = info.memory_budget.min(limit);
        }
        // SAFETY: plain query on a handle from the enumeration.
        let families = unsafe { raw_inst.get_physical_device_queue_family_properties(pd) };
        info.timestamp_valid_bits = families
            .get(qf as usize)
            .map_or(0, |f| f.timestamp_valid_bits);
        for (ok, feature) in [
            (info.scalar_block_layout, "scalarBlockLayout (Vulkan 1.2)"),
            (info.push_descriptor, "VK_KHR_push_descriptor"),
        ] {
            if !ok {
                return Err(DeviceError::MissingFeature {
                    device: info.name.clone(),
                    feature: feature.to_string(),
                });
            }
        }
        let prio = [1.0f32];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(qf)
            .queue_priorities(&prio)];
        let mut exts: Vec<*const c_char> = vec![khr::push_descriptor::NAME.as_ptr()];
        if swapchain {
            exts.push(khr::swapchain::NAME.as_ptr());
        }
        let features = vk::PhysicalDeviceFeatures::default()
            .shader_int64(info.shader_int64)
            .shader_float64(info.shader_float64);
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default()
            .scalar_block_layout(true)
            .host_query_reset(true);
        let create = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_extension_names(&exts)
            .enabled_features(&features)
            .push_next(&mut f12);
        // SAFETY: `create` and everything it points to outlive the call.
        let raw = unsafe { raw_inst.create_device(pd, &create, None) }.vk("vkCreateDevice")?;
        // SAFETY: the family/index were requested above.
        let queue = unsafe { raw.get_device_queue(qf, 0) };
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: raw_inst.clone(),
            device: raw.clone(),
            physical_device: pd,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        })
        .map_err(|e| DeviceError::Allocation {
            name: "allocator".into(),
            detail: e.to_string(),
        })?;
        let push_descriptor = khr::push_descriptor::Device::new(raw_inst, &raw);
        let debug_utils = instance
            .validation_enabled()
            .then(|| ext::debug_utils::Device::new(raw_inst, &raw));
        let dev = Self {
            shared: Arc::new(DeviceShared {
                instance: instance.clone(),
                physical: pd,
                raw,
                queue,
                queue_family: qf,
                allocator: Mutex::new(Some(allocator)),
                live: Mutex::new(Vec::new()),
                push_descriptor,
                debug_utils,
                info,
                swapchain_enabled: swapchain,
            }),
        };
        dev.set_name(dev.shared.queue, "queue.compute");
        Ok(dev)
    }

    /// Names a Vulkan object for validation messages and debuggers (no-op without validation).
    pub fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(du) = &self.shared.debug_utils {
            let Ok(cname) = CString::new(name) else {
                return;
            };
            let info = vk::DebugUtilsObjectNameInfoEXT::default()
                .object_handle(handle)
                .object_name(&cname);
            // SAFETY: handle belongs to this device; naming cannot affect correctness.
            let _ = unsafe { du.set_debug_utils_object_name(&info) };
        }
    }

    pub fn info(&self) -> &DeviceInfo {
        &self.shared.info
    }
    pub fn raw(&self) -> &ash::Device {
        &self.shared.raw
    }
    pub fn instance(&self) -> &Instance {
        &self.shared.instance
    }
    pub fn physical(&self) -> vk::PhysicalDevice {
        self.shared.physical
    }
    pub fn queue(&self) -> vk::Queue {
        self.shared.queue
    }
    pub fn queue_family(&self) -> u32 {
        self.shared.queue_family
    }
    pub fn swapchain_enabled(&self) -> bool {
        self.shared.swapchain_enabled
    }
    /// Validation messages seen so far on this device's instance.
    pub fn validation_messages(&self) -> Vec<String> {
        self.shared.instance.validation_log().messages()
    }
    pub(crate) fn allocator(&self) -> Result<MutexGuard<'_, Option<Allocator>>> {
        self.shared
            .allocator
            .lock()
            .map_err(|_| DeviceError::Usage("allocator mutex poisoned".into()))
    }
    /// Bytes currently allocated through gpu-allocator (for leak/soak checks).
    pub fn allocated_bytes(&self) -> u64 {
        self.allocator()
            .ok()
            .and_then(|a| {
                a.as_ref()
                    .map(|a| a.generate_report().total_allocated_bytes)
            })
            .unwrap_or(0)
    }
    /// Waits until the queue is idle.
    pub fn wait_idle(&self) -> Result<()> {
        // SAFETY: the device is alive.
        unsafe { self.shared.raw.device_wait_idle() }.vk("vkDeviceWaitIdle")
    }
}

/// A testing hook: an environment variable that lowers a device limit (so over-limit paths can
/// be tested without huge inputs). Unset = no change.
fn env_limit(var: &str) -> Result<Option<u64>> {
    match crate::faults::var(var) {
        None => Ok(None),
        Some(v) => v
            .trim()
            .parse::<u64>()
            .map(Some)
            .map_err(|_| DeviceError::Usage(format!("{var}='{v}' is not a number of bytes"))),
    }
}

fn compute_queue_family(
    instance: &Instance,
    pd: vk::PhysicalDevice,
    surface: Option<&Surface>,
) -> Result<Option<u32>> {
    // SAFETY: plain queries on a handle from the enumeration.
    let families = unsafe {
        instance
            .raw()
            .get_physical_device_queue_family_properties(pd)
    };
    for (i, f) in families.iter().enumerate() {
        if !f.queue_flags.contains(vk::QueueFlags::COMPUTE) {
            continue;
        }
        if let Some(s) = surface
            && !s.supports(pd, i as u32)?
        {
            continue;
        }
        return Ok(Some(i as u32));
    }
    Ok(None)
}

fn query_info(instance: &Instance, pd: vk::PhysicalDevice) -> DeviceInfo {
    let raw = instance.raw();
    let mut driver = vk::PhysicalDeviceDriverProperties::default();
    let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
    let mut m3 = vk::PhysicalDeviceMaintenance3Properties::default();
    let mut props2 = vk::PhysicalDeviceProperties2::default()
        .push_next(&mut driver)
        .push_next(&mut subgroup)
        .push_next(&mut m3);
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut features2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f12);
    // SAFETY: queries on a valid handle with correctly chained structs (Vulkan 1.2 instance).
    let exts = unsafe {
        raw.get_physical_device_properties2(pd, &mut props2);
        raw.get_physical_device_features2(pd, &mut features2);
        raw.enumerate_device_extension_properties(pd)
            .unwrap_or_default()
    };
    // SAFETY: plain query on a valid handle.
    let mem = unsafe { raw.get_physical_device_memory_properties(pd) };
    let memory_budget = mem
        .memory_heaps_as_slice()
        .iter()
        .map(|h| h.size)
        .max()
        .unwrap_or(0);
    let p = props2.properties;
    let f = features2.features;
    let l = p.limits;
    let push_descriptor = exts.iter().any(|e| {
        e.extension_name_as_c_str()
            .is_ok_and(|n| n == khr::push_descriptor::NAME)
    });
    let v = p.api_version;
    DeviceInfo {
        name: cstr_field(&p.device_name),
        device_type: format!("{:?}", p.device_type),
        api_version: format!(
            "{}.{}.{}",
            vk::api_version_major(v),
            vk::api_version_minor(v),
            vk::api_version_patch(v)
        ),
        driver_name: cstr_field(&driver.driver_name),
        driver_info: cstr_field(&driver.driver_info),
        max_storage_buffer_range: l.max_storage_buffer_range as u64,
        max_memory_allocation_size: m3.max_memory_allocation_size,
        memory_budget,
        max_compute_work_group_invocations: l.max_compute_work_group_invocations,
        max_compute_work_group_count: l.max_compute_work_group_count,
        max_compute_shared_memory_size: l.max_compute_shared_memory_size,
        max_image_dimension_2d: l.max_image_dimension2_d,
        max_push_constants_size: l.max_push_constants_size,
        subgroup_size: subgroup.subgroup_size,
        timestamp_period_ns: l.timestamp_period,
        timestamp_valid_bits: 0, // per queue family: filled in by Device::create
        shader_int64: f.shader_int64 == vk::TRUE,
        shader_float64: f.shader_float64 == vk::TRUE,
        scalar_block_layout: f12.scalar_block_layout == vk::TRUE,
        push_descriptor,
    }
}
