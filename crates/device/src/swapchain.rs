//! A swapchain for presenting to a [`Surface`]: format and present-mode choice as
//! docs/build.md advises, recreation on resize / out-of-date / suboptimal, and a paused
//! state for a zero-sized (minimised) window.
//!
//! Images are filled by copies (`TRANSFER_DST`), so any 8-bit RGBA/BGRA UNORM format works;
//! sRGB is already encoded by the renderer's tonemap, so `*_SRGB` formats are never chosen.
//! "Image acquired" semaphores take turns, one per frame in flight ([`ACQUIRE_SEMAPHORES`]):
//! the caller waits for the submission that waited on a semaphore before acquiring with it
//! again; "render finished" semaphores are per swapchain image.
use crate::device::Device;
use crate::error::{DeviceError, Result, VkContext};
use crate::surface::Surface;
use ash::{khr, vk};

/// Frames a caller may have in flight: the "image acquired" semaphores that take turns.
pub const ACQUIRE_SEMAPHORES: usize = 2;

/// Formats the presenter can fill with packed 8-bit colour, best first.
pub const PRESENTABLE_FORMATS: [vk::Format; 3] = [
    vk::Format::B8G8R8A8_UNORM,
    vk::Format::R8G8B8A8_UNORM,
    vk::Format::A8B8G8R8_UNORM_PACK32,
];

/// Whether the bytes of `format` are B, G, R, A in memory (else R, G, B, A).
pub fn is_bgra(format: vk::Format) -> bool {
    format == vk::Format::B8G8R8A8_UNORM
}

/// The first of [`PRESENTABLE_FORMATS`] the surface offers (in sRGB-nonlinear colour space)
/// and `usable` accepts.
pub fn choose_format(
    offered: &[vk::SurfaceFormatKHR],
    usable: impl Fn(vk::Format) -> bool,
) -> Option<vk::SurfaceFormatKHR> {
    PRESENTABLE_FORMATS.iter().find_map(|&want| {
        offered
            .iter()
            .find(|f| {
                f.format == want
                    && f.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR
                    && usable(f.format)
            })
            .copied()
    })
}

/// MAILBOX (no tearing, lowest latency) unless `vsync`, else FIFO (always supported).
/// FIFO is not throttled on Xvfb, so both run as fast as the renderer there.
pub fn choose_present_mode(offered: &[vk::PresentModeKHR], vsync: bool) -> vk::PresentModeKHR {
    if !vsync && offered.contains(&vk::PresentModeKHR::MAILBOX) {
        vk::PresentModeKHR::MAILBOX
    } else {
        vk::PresentModeKHR::FIFO
    }
}

/// The surface's current extent, or the window size clamped to the limits when the surface
/// leaves it to the swapchain (`0xFFFFFFFF`). Zero area means "minimised: pause".
pub fn choose_extent(caps: &vk::SurfaceCapabilitiesKHR, window: (u32, u32)) -> vk::Extent2D {
    if caps.current_extent.width != u32::MAX {
        return caps.current_extent;
    }
    let (lo, hi) = (caps.min_image_extent, caps.max_image_extent);
    vk::Extent2D {
        width: window.0.clamp(lo.width, hi.width.max(lo.width)),
        height: window.1.clamp(lo.height, hi.height.max(lo.height)),
    }
}

/// One more than the minimum (so acquire never waits on the presentation engine), capped.
pub fn choose_image_count(caps: &vk::SurfaceCapabilitiesKHR) -> u32 {
    let want = caps.min_image_count + 1;
    if caps.max_image_count == 0 {
        want
    } else {
        want.min(caps.max_image_count)
    }
}

/// An acquired swapchain image, valid until it is presented.
#[derive(Debug, Clone, Copy)]
pub struct SwapImage {
    pub index: u32,
    pub image: vk::Image,
    /// Signalled when the image may be written: wait for it (at TRANSFER) in the submission.
    pub acquired: vk::Semaphore,
    /// Signal this from the submission; presentation waits for it.
    pub rendered: vk::Semaphore,
}

/// The swapchain; it owns the surface, so the surface is destroyed after it.
pub struct Swapchain {
    dev: Device,
    loader: khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    images: Vec<vk::Image>,
    rendered: Vec<vk::Semaphore>,
    acquired: [vk::Semaphore; ACQUIRE_SEMAPHORES],
    /// The semaphore the next acquire signals.
    next_acquired: usize,
    format: vk::SurfaceFormatKHR,
    present_mode: vk::PresentModeKHR,
    extent: vk::Extent2D,
    vsync: bool,
    generation: u32,
    surface: Surface,
}

impl std::fmt::Debug for Swapchain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Swapchain")
            .field("format", &self.format.format)
            .field("present_mode", &self.present_mode)
            .field("extent", &(self.extent.width, self.extent.height))
            .field("images", &self.images.len())
            .finish()
    }
}

impl Swapchain {
    /// Creates a swapchain for `surface` (the device must have been created with it) sized
    /// for a window of `window` pixels; a zero-sized window gives a paused swapchain.
    pub fn new(dev: &Device, surface: Surface, window: (u32, u32), vsync: bool) -> Result<Self> {
        if !dev.swapchain_enabled() {
            return Err(DeviceError::Usage(
                "the device was created without a surface (DeviceDesc::surface)".into(),
            ));
        }
        let loader = khr::swapchain::Device::new(dev.instance().raw(), dev.raw());
        // SAFETY: valid create info; destroyed in Drop.
        let mut acquired = [vk::Semaphore::null(); ACQUIRE_SEMAPHORES];
        for (i, a) in acquired.iter_mut().enumerate() {
            // SAFETY: valid create info; destroyed in Drop (a failure leaks the earlier ones).
            *a = unsafe {
                dev.raw()
                    .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
            }
            .vk("vkCreateSemaphore")?;
            dev.set_name(*a, &format!("swapchain.image_acquired{i}"));
        }
        // The surface stays unnamed: naming an instance-level object through the device makes
        // the validation layer (1.3.239) crash.
        let mut s = Self {
            dev: dev.clone(),
            loader,
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            rendered: Vec::new(),
            acquired,
            next_acquired: 0,
            format: vk::SurfaceFormatKHR::default(),
            present_mode: vk::PresentModeKHR::FIFO,
            extent: vk::Extent2D::default(),
            vsync,
            generation: 0,
            surface,
        };
        s.recreate(window)?;
        Ok(s)
    }

    /// Paused: the surface has zero area (minimised). Call [`Self::recreate`] when it changes.
    pub fn is_paused(&self) -> bool {
        self.raw == vk::SwapchainKHR::null()
    }
    /// Image size in pixels ((0, 0) while paused).
    pub fn extent(&self) -> (u32, u32) {
        (self.extent.width, self.extent.height)
    }
    pub fn format(&self) -> vk::Format {
        self.format.format
    }
    pub fn present_mode(&self) -> vk::PresentModeKHR {
        self.present_mode
    }
    pub fn image_count(&self) -> usize {
        self.images.len()
    }

    /// (Re)creates the swapchain for the surface's current size; waits for the device first.
    pub fn recreate(&mut self, window: (u32, u32)) -> Result<()> {
        self.dev.wait_idle()?;
        let pd = self.dev.physical();
        let (sl, sr) = (&self.surface.loader, self.surface.raw);
        // SAFETY: plain queries on live handles.
        let (caps, formats, modes) = unsafe {
            (
                sl.get_physical_device_surface_capabilities(pd, sr)
                    .vk("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")?,
                sl.get_physical_device_surface_formats(pd, sr)
                    .vk("vkGetPhysicalDeviceSurfaceFormatsKHR")?,
                sl.get_physical_device_surface_present_modes(pd, sr)
                    .vk("vkGetPhysicalDeviceSurfacePresentModesKHR")?,
            )
        };
        let extent = choose_extent(&caps, window);
        if extent.width == 0 || extent.height == 0 || window.0 == 0 || window.1 == 0 {
            self.destroy_chain();
            self.extent = vk::Extent2D::default();
            return Ok(());
        }
        if !caps
            .supported_usage_flags
            .contains(vk::ImageUsageFlags::TRANSFER_DST)
        {
            return Err(DeviceError::Usage(
                "the surface does not support TRANSFER_DST swapchain images".into(),
            ));
        }
        let inst = self.dev.instance().raw();
        let format = choose_format(&formats, |f| {
            // SAFETY: plain query.
            let props = unsafe { inst.get_physical_device_format_properties(pd, f) };
            props
                .optimal_tiling_features
                .contains(vk::FormatFeatureFlags::TRANSFER_DST)
        })
        .ok_or_else(|| {
            DeviceError::Usage(format!(
                "the surface offers no 8-bit UNORM RGBA/BGRA format usable as a copy target: {:?}",
                formats.iter().map(|f| f.format).collect::<Vec<_>>()
            ))
        })?;
        let present_mode = choose_present_mode(&modes, self.vsync);
        let alpha = [
            vk::CompositeAlphaFlagsKHR::OPAQUE,
            vk::CompositeAlphaFlagsKHR::INHERIT,
            vk::CompositeAlphaFlagsKHR::PRE_MULTIPLIED,
            vk::CompositeAlphaFlagsKHR::POST_MULTIPLIED,
        ]
        .into_iter()
        .find(|&a| caps.supported_composite_alpha.contains(a))
        .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(sr)
            .min_image_count(choose_image_count(&caps))
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(vk::ImageUsageFlags::TRANSFER_DST)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(alpha)
            .present_mode(present_mode)
            .clipped(true)
            .old_swapchain(old);
        // SAFETY: valid create info; `old` is retired by this call and destroyed below.
        let raw = unsafe { self.loader.create_swapchain(&info, None) };
        self.destroy_chain();
        let raw = raw.vk("vkCreateSwapchainKHR")?;
        self.raw = raw;
        self.generation += 1;
        let g = self.generation;
        self.dev.set_name(raw, &format!("swapchain.{g}"));
        // SAFETY: the swapchain was just created.
        self.images =
            unsafe { self.loader.get_swapchain_images(raw) }.vk("vkGetSwapchainImagesKHR")?;
        for (i, &img) in self.images.iter().enumerate() {
            self.dev.set_name(img, &format!("swapchain.{g}.image{i}"));
            // SAFETY: valid create info; destroyed with the chain.
            let sem = unsafe {
                self.dev
                    .raw()
                    .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
            }
            .vk("vkCreateSemaphore")?;
            self.dev
                .set_name(sem, &format!("swapchain.{g}.render_finished{i}"));
            self.rendered.push(sem);
        }
        self.format = format;
        self.present_mode = present_mode;
        self.extent = extent;
        Ok(())
    }

    /// Acquires the next image; `None` when paused or out of date (recreate, then retry).
    /// A suboptimal image is still returned: [`Self::present`] reports it.
    pub fn acquire(&mut self) -> Result<Option<SwapImage>> {
        if self.is_paused() {
            return Ok(None);
        }
        let acquired = self.acquired[self.next_acquired];
        // SAFETY: the semaphore is unsignalled: the submission that waited on it, at most
        // ACQUIRE_SEMAPHORES acquires ago, has completed (the caller waits for it first).
        let r = unsafe {
            self.loader
                .acquire_next_image(self.raw, u64::MAX, acquired, vk::Fence::null())
        };
        let index = match r {
            Ok((index, _suboptimal)) => {
                self.next_acquired = (self.next_acquired + 1) % ACQUIRE_SEMAPHORES;
                index
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => return Ok(None),
            Err(e) => return Err(e).vk("vkAcquireNextImageKHR"),
        };
        let i = index as usize;
        let (Some(&image), Some(&rendered)) = (self.images.get(i), self.rendered.get(i)) else {
            return Err(DeviceError::Usage(format!(
                "acquired image {index} of {}",
                self.images.len()
            )));
        };
        Ok(Some(SwapImage {
            index,
            image,
            acquired,
            rendered,
        }))
    }

    /// Presents `img` after its `rendered` semaphore. Returns `false` when the swapchain is
    /// out of date or suboptimal and should be recreated before the next frame.
    pub fn present(&mut self, img: &SwapImage) -> Result<bool> {
        let waits = [img.rendered];
        let chains = [self.raw];
        let indices = [img.index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&chains)
            .image_indices(&indices);
        // SAFETY: the image was acquired from this swapchain and its submission signals
        // `rendered`.
        match unsafe { self.loader.queue_present(self.dev.queue(), &info) } {
            Ok(suboptimal) => Ok(!suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(false),
            Err(e) => Err(e).vk("vkQueuePresentKHR"),
        }
    }

    fn destroy_chain(&mut self) {
        // SAFETY: the device is idle (recreate/drop wait first); nothing uses these any more.
        unsafe {
            for s in self.rendered.drain(..) {
                self.dev.raw().destroy_semaphore(s, None);
            }
            if self.raw != vk::SwapchainKHR::null() {
                self.loader.destroy_swapchain(self.raw, None);
            }
        }
        self.images.clear();
        self.raw = vk::SwapchainKHR::null();
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        let _ = self.dev.wait_idle();
        self.destroy_chain();
        // SAFETY: idle device; the semaphore is not in use.
        for s in self.acquired {
            // SAFETY: idle device; the semaphores are not in use.
            unsafe { self.dev.raw().destroy_semaphore(s, None) };
        }
        // `surface` is dropped after this, as a field.
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(format: vk::Format) -> vk::SurfaceFormatKHR {
        vk::SurfaceFormatKHR {
            format,
            color_space: vk::ColorSpaceKHR::SRGB_NONLINEAR,
        }
    }

    #[test]
    fn unorm_is_chosen_over_srgb_listed_first() {
        // Lavapipe's order (docs/build.md).
        let offered = [
            fmt(vk::Format::B8G8R8A8_SRGB),
            fmt(vk::Format::B8G8R8A8_UNORM),
        ];
        let f = choose_format(&offered, |_| true).map(|f| f.format);
        assert_eq!(f, Some(vk::Format::B8G8R8A8_UNORM));
        let rgba = [
            fmt(vk::Format::R8G8B8A8_SRGB),
            fmt(vk::Format::R8G8B8A8_UNORM),
        ];
        let f = choose_format(&rgba, |_| true).map(|f| f.format);
        assert_eq!(f, Some(vk::Format::R8G8B8A8_UNORM));
        assert!(choose_format(&offered[..1], |_| true).is_none());
        assert!(choose_format(&offered, |_| false).is_none());
    }

    #[test]
    fn mailbox_unless_vsync_else_fifo() {
        use vk::PresentModeKHR as P;
        let all = [P::IMMEDIATE, P::MAILBOX, P::FIFO, P::FIFO_RELAXED];
        assert_eq!(choose_present_mode(&all, false), P::MAILBOX);
        assert_eq!(choose_present_mode(&all, true), P::FIFO);
        assert_eq!(choose_present_mode(&[P::FIFO], false), P::FIFO);
    }

    #[test]
    fn extent_follows_surface_or_clamped_window() {
        let mut caps = vk::SurfaceCapabilitiesKHR {
            current_extent: vk::Extent2D {
                width: 0,
                height: 0,
            },
            min_image_extent: vk::Extent2D {
                width: 1,
                height: 1,
            },
            max_image_extent: vk::Extent2D {
                width: 1000,
                height: 1000,
            },
            min_image_count: 3,
            ..Default::default()
        };
        assert_eq!(choose_extent(&caps, (640, 480)).width, 0, "minimised");
        caps.current_extent = vk::Extent2D {
            width: u32::MAX,
            height: u32::MAX,
        };
        let e = choose_extent(&caps, (2000, 480));
        assert_eq!((e.width, e.height), (1000, 480));
        assert_eq!(choose_image_count(&caps), 4);
        caps.max_image_count = 3;
        assert_eq!(choose_image_count(&caps), 3);
    }
}
