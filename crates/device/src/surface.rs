//! An optional presentation surface; the device works with or without one.
use crate::error::{Result, VkContext};
use crate::instance::Instance;
use ash::{khr, vk};
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};

/// A `VkSurfaceKHR` with its loader. Create the instance with
/// [`Surface::required_extensions`] in `InstanceDesc::extensions`.
pub struct Surface {
    pub(crate) instance: Instance,
    pub loader: khr::surface::Instance,
    pub raw: vk::SurfaceKHR,
}

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Surface").field("raw", &self.raw).finish()
    }
}

impl Surface {
    /// Instance extensions needed to create a surface for this display.
    pub fn required_extensions(display: RawDisplayHandle) -> Result<Vec<&'static std::ffi::CStr>> {
        let exts = ash_window::enumerate_required_extensions(display)
            .vk("enumerate surface extensions")?;
        // SAFETY: ash-window returns pointers to static extension-name constants.
        Ok(exts
            .iter()
            .map(|&p| unsafe { std::ffi::CStr::from_ptr(p) })
            .collect())
    }

    /// Creates a surface for a window.
    ///
    /// # Safety
    /// The window and display must outlive the surface.
    pub unsafe fn new(
        instance: &Instance,
        display: RawDisplayHandle,
        window: RawWindowHandle,
    ) -> Result<Self> {
        // SAFETY: forwarded to the caller's contract.
        let raw = unsafe {
            ash_window::create_surface(instance.entry(), instance.raw(), display, window, None)
        }
        .vk("vkCreate*SurfaceKHR")?;
        Ok(Self {
            instance: instance.clone(),
            loader: khr::surface::Instance::new(instance.entry(), instance.raw()),
            raw,
        })
    }

    /// Whether queue family `qf` of `pd` can present to this surface.
    pub fn supports(&self, pd: vk::PhysicalDevice, qf: u32) -> Result<bool> {
        // SAFETY: valid handles.
        unsafe {
            self.loader
                .get_physical_device_surface_support(pd, qf, self.raw)
        }
        .vk("vkGetPhysicalDeviceSurfaceSupportKHR")
    }
}

impl Drop for Surface {
    fn drop(&mut self) {
        let _keep_instance_alive = &self.instance;
        // SAFETY: the swapchain using this surface must be gone (it borrows the surface).
        unsafe { self.loader.destroy_surface(self.raw, None) };
    }
}
