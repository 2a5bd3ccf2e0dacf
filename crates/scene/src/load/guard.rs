//! The last line of defence: a panic while reading a file (the glTF reader still has some our
//! pre-checks may miss) becomes [`SceneError::Internal`], never a crash, and is not printed.

use crate::{Result, Scene, SceneError};
use std::path::Path;

thread_local! {
    static QUIET_PANICS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// `file:line` of the last quiet panic (named in the error).
    static PANIC_LOCATION: std::cell::RefCell<Option<String>> =
        const { std::cell::RefCell::new(None) };
}

/// Runs `f`, turning a panic into [`SceneError::Internal`] naming `path` and where it happened.
pub(crate) fn catch_panics(path: &Path, f: impl FnOnce() -> Result<Scene>) -> Result<Scene> {
    install_quiet_panic_hook();
    QUIET_PANICS.with(|q| q.set(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    QUIET_PANICS.with(|q| q.set(false));
    result.unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "panic".into());
        let location = PANIC_LOCATION.with(|l| l.take()).unwrap_or_default();
        Err(SceneError::Internal {
            path: path.to_path_buf(),
            message: format!("{message} (at {location})"),
        })
    })
}

/// Wraps the process panic hook once so that a panic caught by [`catch_panics`] on this thread
/// is not printed; every other panic goes to the previous hook unchanged.
fn install_quiet_panic_hook() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if QUIET_PANICS.with(|q| q.get()) {
                let at = info
                    .location()
                    .map(|l| format!("{}:{}", l.file(), l.line()));
                PANIC_LOCATION.with(|l| *l.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
}
