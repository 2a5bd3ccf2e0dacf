//! `cargo run -p blueshift-headers -- [--write]`: check (default) or rewrite the generated headers.
fn main() -> std::process::ExitCode {
    if std::env::args().any(|a| a == "--write") {
        if let Err(e) = blueshift_headers::write_all() {
            eprintln!("error: writing {}: {e}", blueshift_headers::dir().display());
            return std::process::ExitCode::FAILURE;
        }
        println!(
            "wrote {} header(s) to {}",
            blueshift_headers::all().len(),
            blueshift_headers::dir().display()
        );
        return std::process::ExitCode::SUCCESS;
    }
    let stale = blueshift_headers::stale();
    for p in &stale {
        eprintln!("stale: {}", p.display());
    }
    if stale.is_empty() {
        std::process::ExitCode::SUCCESS
    } else {
        std::process::ExitCode::FAILURE
    }
}
