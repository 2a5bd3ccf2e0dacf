//! How the binary fails: every error is one `error: ...` line and exit code 1; a panic (a bug,
//! never a reaction to bad input) is one `internal error: ...` line and exit code 2.
use std::process::ExitCode;

/// Exit code of a panic.
pub const INTERNAL_ERROR: u8 = 2;

/// The error and its causes on one line, skipping a cause whose text the message before it
/// already contains (thiserror messages often embed their source).
pub fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if s.is_empty() || out.contains(&s) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&s);
    }
    out
}

/// Prints a panic as an internal error (with a backtrace when `RUST_BACKTRACE` asks for one).
pub fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        eprintln!(
            "internal error: Blueshift crashed; this is a bug, not a problem with your input. \
             Please report it with the command line. Details: {info}"
        );
        let bt = std::backtrace::Backtrace::capture();
        if bt.status() == std::backtrace::BacktraceStatus::Captured {
            eprintln!("{bt}");
        }
    }));
}

/// Runs `f`, mapping `Err` to `error: ...` + exit 1 and a panic to exit 2.
pub fn run(f: impl FnOnce() -> anyhow::Result<()>) -> ExitCode {
    let f = || {
        // Fault hook: proves a panic becomes an internal error (crates/app/tests/errors.rs).
        use blueshift_device::faults;
        if faults::var(faults::PANIC).is_some() {
            panic!("{} is set", faults::PANIC);
        }
        f()
    };
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("error: {}", message(&e));
            ExitCode::FAILURE
        }
        Err(_) => ExitCode::from(INTERNAL_ERROR),
    }
}

/// Parses the command line; a usage error exits 1 (like every other error), `--help` and
/// `--version` exit 0.
pub fn parse<T: clap::Parser>() -> Result<T, ExitCode> {
    T::try_parse().map_err(|e| {
        let _ = e.print();
        if e.use_stderr() {
            ExitCode::FAILURE
        } else {
            ExitCode::SUCCESS
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug)]
    struct Outer(std::io::Error);
    impl std::fmt::Display for Outer {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "outer: {}", self.0)
        }
    }
    impl std::error::Error for Outer {
        fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
            Some(&self.0)
        }
    }

    #[test]
    fn causes_already_in_the_message_are_not_repeated() {
        let e =
            anyhow::Error::new(Outer(std::io::Error::other("disk on fire"))).context("loading x");
        assert_eq!(message(&e), "loading x: outer: disk on fire");
    }
}
