//! The generated GLSL headers under shaders/include/generated/ equal what the Rust structs
//! produce now. Run with BLUESHIFT_BLESS=1 to rewrite them after changing a struct.
use std::path::PathBuf;

/// (file stem, header text) for every generated header.
fn headers() -> Vec<(&'static str, String)> {
    vec![]
}

#[test]
fn generated_headers_are_up_to_date() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shaders/include/generated");
    let bless = std::env::var("BLUESHIFT_BLESS").is_ok_and(|v| v == "1");
    let mut stale = Vec::new();
    for (stem, text) in headers() {
        let path = dir.join(format!("{stem}.glsl"));
        let current = std::fs::read_to_string(&path).unwrap_or_default();
        if current != text {
            if bless {
                std::fs::write(&path, &text).unwrap();
            } else {
                stale.push(path.display().to_string());
            }
        }
    }
    assert!(
        stale.is_empty(),
        "stale generated headers (rerun with BLUESHIFT_BLESS=1): {stale:?}"
    );
}
