//! Fault injection for tests: environment variables that make the device layer (and the
//! binary) fail on purpose, so that error paths a real GPU rarely takes are tested. Compiled
//! in only with the `fault-injection` feature, which the workspace's tests turn on and a
//! release build of the binary leaves off: there these variables are ignored.

/// `=PASS`: a submission containing pass PASS reports a lost device. `=PASS@N`: only from the
/// N-th such submission of the process on (counted from 0), so a run fails halfway (a later
/// frame).
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

/// The pass and the first submission (counted from 0) that [`DEVICE_LOST`] loses the device
/// in: `PASS` or `PASS@N`.
pub(crate) fn device_lost() -> Option<(String, u32)> {
    let v = var(DEVICE_LOST)?;
    Some(match v.rsplit_once('@') {
        Some((pass, n)) => (pass.to_string(), n.parse().unwrap_or(0)),
        None => (v, 0),
    })
}

/// Counts the submissions (of every recorder) that contain the pass of [`DEVICE_LOST`]:
/// returns how many came before this one.
pub(crate) fn count_lost_pass_submission() -> u32 {
    use std::sync::atomic::{AtomicU32, Ordering};
    static SUBMISSIONS: AtomicU32 = AtomicU32::new(0);
    SUBMISSIONS.fetch_add(1, Ordering::Relaxed)
}
