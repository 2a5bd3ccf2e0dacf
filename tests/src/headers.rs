//! The generated GLSL headers under shaders/include/generated/ equal what the Rust structs
//! produce now. After changing a struct: `cargo run -p blueshift-headers -- --write`.

#[test]
fn generated_headers_are_up_to_date() {
    let stale = blueshift_headers::stale();
    assert!(
        stale.is_empty(),
        "stale generated headers (run `cargo run -p blueshift-headers -- --write`): {stale:?}"
    );
}

/// The check can fail: fresh headers pass, a header with one changed byte is reported.
#[test]
fn a_modified_header_is_detected() {
    let dir = std::env::temp_dir().join(format!("blueshift-headers-{}", std::process::id()));
    blueshift_headers::write_all_in(&dir).unwrap();
    assert!(blueshift_headers::stale_in(&dir).is_empty());
    let (stem, text) = blueshift_headers::all().remove(0);
    let path = dir.join(format!("{stem}.glsl"));
    std::fs::write(&path, text.replacen("const", "const ", 1)).unwrap();
    assert_eq!(blueshift_headers::stale_in(&dir), vec![path]);
    std::fs::remove_dir_all(&dir).unwrap();
}
