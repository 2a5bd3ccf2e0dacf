//! End-to-end runs of the `blueshift-tools` binary on small inputs.

mod common;

use common::{fails, ok, s};

#[test]
fn masks_spectrum_dither_retarget_figures() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bn = d.join("bn16.r16");
    ok(&["mask", "--size", "16", "--seed", "3", "--out", s(&bn)]);
    assert_eq!(std::fs::metadata(&bn).unwrap().len(), 2 * 256);
    let png = image::open(d.join("bn16.png")).unwrap();
    assert_eq!(png.color(), image::ColorType::L16);
    ok(&[
        "mask",
        "--size",
        "16",
        "--frames",
        "4",
        "--out",
        s(&d.join("st.r16")),
    ]);
    ok(&["bayer", "--size", "8", "--out", s(&d.join("bayer8.r16"))]);
    ok(&[
        "white",
        "--size",
        "16",
        "--seed",
        "2",
        "--out",
        s(&d.join("w16.r16")),
    ]);
    let out = ok(&[
        "spectrum",
        s(&bn),
        s(&d.join("w16.r16")),
        s(&d.join("bn16.png")),
        "--out",
        s(&d.join("spec")),
    ]);
    assert!(out.contains("bn16") && out.contains("periodogram"), "{out}");
    assert!(d.join("spec/radial.png").exists() && d.join("spec/bn16_spectrum.png").exists());
    ok(&[
        "spectrum",
        s(&d.join("st.r16")),
        "--stbn-size",
        "16",
        "--out",
        s(&d.join("spec2")),
    ]);
    ok(&[
        "dither",
        s(&d.join("bn16.png")),
        "--mask",
        s(&bn),
        "--compare",
        "--out",
        s(&d.join("dither.png")),
    ]);
    assert_eq!(
        image::open(d.join("dither.png")).unwrap().width(),
        3 * 16 + 2 * 8
    );
    let out = ok(&[
        "retarget",
        "--mask",
        s(&bn),
        "--radius",
        "3",
        "--solver",
        "anneal",
        "--proposals",
        "200000",
        "--out",
        s(&d.join("t.bin")),
        "--png",
        s(&d.join("t.png")),
    ]);
    assert!(out.contains("shift (12, 9)"), "{out}");
    let t = blueshift_assets::load_retarget(&d.join("t.bin")).unwrap();
    assert_eq!((t.n, t.radius), (16, 3));
    ok(&["figures", "--size", "16", "--out", s(&d.join("fig"))]);
    for f in [
        "blue_spectrum.png",
        "radial_profiles.png",
        "dither_gradient.png",
        "bayer_texture.png",
    ] {
        assert!(d.join("fig").join(f).exists(), "{f}");
    }
}

#[test]
fn same_seed_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.r16"), dir.path().join("b.r16"));
    ok(&["white", "--size", "32", "--seed", "9", "--out", s(&a)]);
    ok(&["white", "--size", "32", "--seed", "9", "--out", s(&b)]);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

#[test]
fn bad_input_gives_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.r16");
    fails(&["mask", "--size", "48", "--out", s(&out)], "power of two");
    fails(
        &["bayer", "--size", "512", "--out", s(&out)],
        "power of two",
    );
    fails(
        &["retarget", "--mask", "/nonexistent/m.r16", "--out", s(&out)],
        "/nonexistent/m.r16",
    );
    std::fs::write(&out, [1u8, 0, 1, 0, 2, 0, 3, 0]).unwrap();
    fails(
        &[
            "retarget",
            "--mask",
            s(&out),
            "--out",
            s(&dir.path().join("t.bin")),
        ],
        "twice",
    );
    let m = dir.path().join("m.r16");
    ok(&["bayer", "--size", "16", "--out", s(&m)]);
    fails(
        &[
            "retarget",
            "--mask",
            s(&m),
            "--shift",
            "3;4",
            "--out",
            s(&out),
        ],
        "SX,SY",
    );
    fails(
        &[
            "retarget",
            "--mask",
            s(&m),
            "--radius",
            "8",
            "--out",
            s(&out),
        ],
        "radius",
    );
    fails(
        &["spectrum", "/nonexistent/i.png", "--out", s(dir.path())],
        "/nonexistent/i.png",
    );
    assert!(!dir.path().join("t.bin").exists(), "no half-written output");
}

#[test]
fn manifest_check_command_passes_on_committed_assets() {
    let m = blueshift_assets::default_assets_dir().join("MANIFEST");
    let out = ok(&["manifest", "--check", "--manifest", s(&m)]);
    assert!(out.contains("all"), "{out}");
}
