//! Errors of the device and of a run under way (no Vulkan device, no validation layers, a
//! lost device, running out of memory, a render that fails halfway): one `error:` line
//! naming the problem, exit code 1, and no output file left behind.
mod common;

use common::Case;
use std::path::Path;

#[test]
fn no_vulkan_device() {
    let c = Case::new();
    let env = [
        ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
        ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
    ];
    let o = c.render(&[], &env);
    c.expect_error(&o, &["no Vulkan device", "mesa-vulkan-drivers"]);
    let o = c.run(&["info"], &env);
    c.expect_error(&o, &["no Vulkan device"]);
}

#[test]
fn validation_layers_not_installed() {
    let c = Case::new();
    let env = [
        ("VK_LAYER_PATH", "/nonexistent"),
        ("VK_ADD_LAYER_PATH", "/nonexistent"),
        ("XDG_DATA_DIRS", "/nonexistent"),
        ("XDG_DATA_HOME", "/nonexistent"),
        ("VK_INSTANCE_LAYERS", ""),
    ];
    let o = c.render(&["--validation"], &env);
    c.expect_error(
        &o,
        &[
            "VK_LAYER_KHRONOS_validation is not installed",
            "vulkan-validationlayers",
        ],
    );
}

#[test]
fn device_lost_names_the_pass() {
    let c = Case::new();
    for pass in ["trace", "sort_seeds"] {
        let o = c.render(&[], &[("BLUESHIFT_TEST_DEVICE_LOST", pass)]);
        c.expect_error(
            &o,
            &[&format!("device was lost while running pass '{pass}'")],
        );
    }
}

/// A run that fails halfway (the device lost from the fourth frame's trace on, after earlier
/// frames were written) leaves nothing: not the frames before the failure, not the output
/// directory it created; a directory that was there keeps its files as they were.
#[test]
fn a_render_that_fails_halfway_leaves_no_frames() {
    let c = Case::new();
    let lost = [("BLUESHIFT_TEST_DEVICE_LOST", "trace@3")];
    let o = c.render_sized(("8", "8"), "8", &["--all-frames"], &lost);
    c.expect_error(&o, &["device was lost while running pass 'trace'"]);
    assert!(!c.out().exists(), "the output directory it created is left");
    // The same run writing only the last frame.
    let o = c.render_sized(("8", "8"), "8", &[], &lost);
    c.expect_error(&o, &["device was lost while running pass 'trace'"]);
    assert!(!c.out().exists(), "the output directory it created is left");

    // An existing directory: an older frame and another file stay as they were, nothing is
    // added (no frame, no temporary directory).
    std::fs::create_dir(c.out()).expect("mkdir");
    let old = [("frame_00000.png", "an older frame"), ("notes.txt", "mine")];
    for (name, text) in old {
        std::fs::write(c.out().join(name), text).expect("write");
    }
    let o = c.render_sized(("8", "8"), "8", &["--all-frames"], &lost);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert_eq!(
        names(&c.out()),
        ["frame_00000.png", "notes.txt"],
        "{stderr}"
    );
    for (name, text) in old {
        assert_eq!(
            std::fs::read_to_string(c.out().join(name)).expect("read"),
            text
        );
    }
    // A successful run replaces the frame, keeps the other file, and leaves no temporary
    // directory.
    let o = c.render_sized(("8", "8"), "2", &["--all-frames"], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let want = [
        "frame_00000.exr",
        "frame_00000.png",
        "frame_00001.exr",
        "frame_00001.png",
        "notes.txt",
    ];
    assert_eq!(names(&c.out()), want);
    let png = std::fs::read(c.out().join("frame_00000.png")).expect("read");
    assert!(
        png.starts_with(b"\x89PNG"),
        "the older frame is still there"
    );
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").file_name().into_string().expect("utf-8"))
        .collect();
    names.sort();
    names
}

/// A name the frames need that a directory already has is found before anything is moved
/// into the output directory.
#[test]
fn a_directory_in_the_way_of_a_frame_is_named() {
    let c = Case::new();
    std::fs::create_dir_all(c.out().join("frame_00001.exr")).expect("mkdir");
    let o = c.render_sized(("8", "8"), "3", &["--all-frames"], &[]);
    c.expect_error(&o, &["frame_00001.exr", "a directory"]);
    assert_eq!(names(&c.out()), ["frame_00001.exr"]);
}

#[test]
fn out_of_memory_names_the_resource_or_the_passes() {
    let c = Case::new();
    // A real budget check (the device's largest heap, lowered here): the first allocation
    // that does not fit is named, before any work is done. (The scene images, 7 rows of 64 KiB
    // and 192 bytes a triangle, fit 1 MB; the masks and frame buffers then do not.)
    let o = c.render(&[], &[("BLUESHIFT_MEMORY_BUDGET", "1000000")]);
    c.expect_error(
        &o,
        &[
            "out of memory allocating '",
            "the device memory budget is 1000000 bytes",
        ],
    );
    // Below what the scene images alone need: the loader refuses the scene from its counts.
    let o = c.render(&[], &[("BLUESHIFT_MEMORY_BUDGET", "300000")]);
    c.expect_error(
        &o,
        &[
            "36 triangles after instancing, over the loader's limit of 0",
            "memory budget 300000 bytes",
        ],
    );
    // A submission the driver could not run: the error lists the passes in it.
    let o = c.render(&[], &[("BLUESHIFT_TEST_SUBMIT_OOM", "sort_seeds")]);
    c.expect_error(
        &o,
        &[
            "out of memory while running pass(es)",
            "trace",
            "sort_seeds",
        ],
    );
}
