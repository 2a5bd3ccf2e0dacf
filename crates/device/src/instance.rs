//! Vulkan instance with optional validation whose messages are counted, not just printed.
use crate::error::{DeviceError, Result, VkContext};
use ash::{ext, vk};
use std::ffi::{CStr, CString, c_char, c_void};
use std::sync::{Arc, Mutex};

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Messages reported by the validation layer, kept so tests can assert there were none.
#[derive(Debug, Default)]
pub struct ValidationLog {
    messages: Mutex<Vec<String>>,
}

impl ValidationLog {
    /// Warnings and errors seen so far (info/verbose messages are not kept).
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().map(|m| m.clone()).unwrap_or_default()
    }
    /// Number of warnings and errors seen so far.
    pub fn count(&self) -> usize {
        self.messages.lock().map(|m| m.len()).unwrap_or(0)
    }
    fn push(&self, msg: String) {
        if let Ok(mut m) = self.messages.lock() {
            m.push(msg);
        }
    }
}

/// How to create the instance.
#[derive(Debug, Default, Clone)]
pub struct InstanceDesc {
    /// Enable `VK_LAYER_KHRONOS_validation` and count its messages.
    pub validation: bool,
    /// Extra instance extensions (e.g. from `ash_window::enumerate_required_extensions`).
    pub extensions: Vec<&'static CStr>,
}

impl InstanceDesc {
    /// Validation on when asked, or when `BLUESHIFT_VALIDATION=1` is set.
    pub fn from_env(validation_flag: bool) -> Self {
        let env = std::env::var("BLUESHIFT_VALIDATION").is_ok_and(|v| v == "1");
        Self {
            validation: validation_flag || env,
            extensions: Vec::new(),
        }
    }
}

pub(crate) struct InstanceShared {
    pub entry: ash::Entry,
    pub raw: ash::Instance,
    pub debug_utils: Option<(ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    /// Also the debug callback's user data: it outlives the messenger (destroyed in Drop).
    pub log: Arc<ValidationLog>,
}

impl Drop for InstanceShared {
    fn drop(&mut self) {
        // SAFETY: every child object holds an Arc to this and is gone by now.
        unsafe {
            if let Some((du, m)) = self.debug_utils.take() {
                du.destroy_debug_utils_messenger(m, None);
            }
            self.raw.destroy_instance(None);
        }
    }
}

/// A Vulkan instance. Cheap to clone.
#[derive(Clone)]
pub struct Instance {
    pub(crate) shared: Arc<InstanceShared>,
}

impl std::fmt::Debug for Instance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Instance").finish_non_exhaustive()
    }
}

unsafe extern "system" fn debug_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: the loader passes valid callback data; `user` points at the ValidationLog that
    // InstanceShared keeps alive until after the messenger is destroyed.
    unsafe {
        let msg = if data.is_null() || (*data).p_message.is_null() {
            "(no message)".to_string()
        } else {
            CStr::from_ptr((*data).p_message)
                .to_string_lossy()
                .into_owned()
        };
        let log = &*(user as *const ValidationLog);
        let level = if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
            "error"
        } else {
            "warning"
        };
        eprintln!("[vulkan validation {level}] {msg}");
        log.push(format!("{level}: {msg}"));
    }
    vk::FALSE
}

impl Instance {
    /// Loads Vulkan and creates an instance (API 1.2).
    pub fn new(desc: &InstanceDesc) -> Result<Self> {
        // SAFETY: loading the system loader; failure is reported, not assumed.
        let entry =
            unsafe { ash::Entry::load() }.map_err(|e| DeviceError::Loader(e.to_string()))?;
        let mut layers: Vec<*const c_char> = Vec::new();
        let mut exts: Vec<*const c_char> = desc.extensions.iter().map(|e| e.as_ptr()).collect();
        if desc.validation {
            // SAFETY: plain enumeration.
            let available = unsafe { entry.enumerate_instance_layer_properties() }
                .vk("vkEnumerateInstanceLayerProperties")?;
            let found = available
                .iter()
                .any(|l| l.layer_name_as_c_str().is_ok_and(|n| n == VALIDATION_LAYER));
            if !found {
                return Err(DeviceError::ValidationMissing);
            }
            layers.push(VALIDATION_LAYER.as_ptr());
            exts.push(ext::debug_utils::NAME.as_ptr());
        }
        let app_name = CString::from(c"blueshift");
        let app = vk::ApplicationInfo::default()
            .application_name(&app_name)
            .engine_name(&app_name)
            .api_version(vk::API_VERSION_1_2);
        let info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layers)
            .enabled_extension_names(&exts);
        // SAFETY: all pointers in `info` outlive the call.
        let raw = match unsafe { entry.create_instance(&info, None) } {
            // The loader found no driver (no ICD manifest, or none that loads).
            Err(vk::Result::ERROR_INCOMPATIBLE_DRIVER) => return Err(DeviceError::NoDevice),
            r => r.vk("vkCreateInstance")?,
        };
        let log = Arc::new(ValidationLog::default());
        let mut debug_utils = None;
        if desc.validation {
            let du = ext::debug_utils::Instance::new(&entry, &raw);
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(
                    vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                        | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
                )
                .message_type(
                    vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                        | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
                )
                .pfn_user_callback(Some(debug_callback))
                .user_data(Arc::as_ptr(&log) as *mut c_void);
            // SAFETY: the log lives as long as the messenger (both in InstanceShared).
            let messenger = unsafe { du.create_debug_utils_messenger(&info, None) }
                .vk("vkCreateDebugUtilsMessengerEXT")?;
            debug_utils = Some((du, messenger));
        }
        Ok(Self {
            shared: Arc::new(InstanceShared {
                entry,
                raw,
                debug_utils,
                log,
            }),
        })
    }

    /// The validation messages counted so far (empty without validation).
    pub fn validation_log(&self) -> &Arc<ValidationLog> {
        &self.shared.log
    }
    /// Whether validation is on.
    pub fn validation_enabled(&self) -> bool {
        self.shared.debug_utils.is_some()
    }
    pub fn entry(&self) -> &ash::Entry {
        &self.shared.entry
    }
    pub fn raw(&self) -> &ash::Instance {
        &self.shared.raw
    }
}
