//! Fault injection for tests: environment variables that make the device layer (and the
//! binary) fail on purpose, so that error paths a real GPU rarely takes are tested. Compiled
//! in only with the `fault-injection` feature, which the workspace's tests turn on and a
//! release build of the binary leaves off: there these variables are ignored.

/// `=PASS`: a submission containing pass PASS reports a lost device.
pub const DEVICE_LOST: &str = "BLUESHIFT_TEST_DEVICE_LOST";
/// `=PASS`: a submission containing pass PASS reports running out of device memory.
pub const SUBMIT_OOM: &str = "BLUESHIFT_TEST_SUBMIT_OOM";
/// Set: the binary panics before it starts (the internal-error path).
pub const PANIC: &str = "BLUESHIFT_TEST_PANIC";
/// `=BYTES`: the device reports at most this `maxStorageBufferRange`.
pub const MAX_STORAGE_BUFFER_RANGE: &str = "BLUESHIFT_MAX_STORAGE_BUFFER_RANGE";
/// `=BYTES`: the device reports at most this memory budget.
pub const MEMORY_BUDGET: &str = "BLUESHIFT_MEMORY_BUDGET";

/// Whether this build reads the fault variables.
pub const ENABLED: bool = cfg!(feature = "fault-injection");

/// The value of fault variable `name` when this build reads them and it is set, non-empty.
pub fn var(name: &str) -> Option<String> {
    if !ENABLED {
        return None;
    }
    std::env::var(name).ok().filter(|v| !v.is_empty())
}
