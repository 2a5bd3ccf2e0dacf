//! `blueshift view` in a real window on lavapipe with validation on (any validation message
//! makes the binary fail). Without a DISPLAY each test starts its own Xvfb (on a free display
//! number, via `-displayfd`) and stops it at the end, even when the test fails.
use std::io::{BufRead, BufReader};
use std::path::Path;
mod common;
use std::process::{Child, Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// A running Xvfb, killed on drop.
struct Xvfb {
    child: Child,
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // SIGTERM lets Xvfb remove its socket and lock file; SIGKILL if it lingers.
        let pid = self.child.id().to_string();
        let _ = Command::new("kill").args(["-TERM", &pid]).status();
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The display to use: `$DISPLAY` when set, else a fresh Xvfb (kept alive by the guard).
fn display() -> (String, Option<Xvfb>) {
    if let Ok(d) = std::env::var("DISPLAY")
        && !d.is_empty()
    {
        return (d, None);
    }
    let child = Command::new("Xvfb")
        .args([
            "-displayfd",
            "1",
            "-screen",
            "0",
            "1024x768x24",
            "-nolisten",
            "tcp",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| {
            panic!(
                "DISPLAY is unset and Xvfb could not be started ({e}). Install it with \
                 `apt-get install xvfb` (scripts/setup.sh does), or set DISPLAY."
            )
        });
    let mut guard = Xvfb { child };
    // Xvfb prints its display number once it accepts connections.
    let stdout = guard.child.stdout.take().expect("piped stdout");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx
        .recv_timeout(Duration::from_secs(30))
        .expect("Xvfb did not report a display number within 30 s");
    let n: u32 = line
        .trim()
        .parse()
        .unwrap_or_else(|_| panic!("Xvfb printed '{line}' instead of a display number"));
    let socket = format!("/tmp/.X11-unix/X{n}");
    assert!(
        Path::new(&socket).exists(),
        "Xvfb is up but {socket} is missing"
    );
    (format!(":{n}"), Some(guard))
}

/// Runs the binary with `args`, killing it after `timeout`.
fn blueshift(args: &[&str], display: &str, dir: &Path, timeout: Duration) -> Output {
    let mut child = common::clean(Command::new(common::BIN))
        .args(args)
        .env("DISPLAY", display)
        .env("XDG_RUNTIME_DIR", dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start blueshift");
    let start = Instant::now();
    while child.try_wait().expect("poll blueshift").is_none() {
        if start.elapsed() > timeout {
            let _ = child.kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().expect("blueshift output");
    assert!(
        out.status.success(),
        "blueshift {args:?} failed ({}):\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

const TIMEOUT: Duration = Duration::from_secs(300);

#[test]
fn scripted_screenshot_equals_the_headless_render_of_the_same_frame() {
    let dir = tempfile::tempdir().unwrap();
    let (display, _xvfb) = display();
    let shot = dir.path().join("view.png");
    let common = ["--method", "white", "--bounces", "1", "--frames", "8"];
    let size = ["--width", "96", "--height", "64"];
    let mut args = vec!["--validation", "view", "--scale", "1", "--screenshot"];
    args.push(shot.to_str().unwrap());
    let out = blueshift(
        &[&args[..], &common, &size].concat(),
        &display,
        dir.path(),
        TIMEOUT,
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("8 frames presented"));
    let rendered = dir.path().join("render");
    let mut args = vec!["--validation", "render", "--out"];
    args.push(rendered.to_str().unwrap());
    blueshift(
        &[&args[..], &common, &size].concat(),
        &display,
        dir.path(),
        TIMEOUT,
    );
    // Same method, seeds, camera and frame index at scale 1: the presented image is the
    // renderer's tonemapped output, so the pixels are equal, not merely close.
    let (view, headless) = (png(&shot), png(&rendered.join("frame_00007.png")));
    assert_eq!(view.dimensions(), (96, 64));
    assert_eq!(view.dimensions(), headless.dimensions());
    let differing = view
        .pixels()
        .zip(headless.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differing, 0, "pixels differ between view and render");
}

#[test]
fn resize_mid_run_keeps_presenting_in_split_and_error_views() {
    let dir = tempfile::tempdir().unwrap();
    let (display, _xvfb) = display();
    let shot = dir.path().join("resized.png");
    let args = [
        "--validation",
        "view",
        "--split",
        "--error-view",
        "--bounces",
        "1",
        "--scale",
        "2",
        "--width",
        "96",
        "--height",
        "64",
        "--frames",
        "8",
        "--resize-at",
        "2",
        "128x96",
        "--screenshot",
        shot.to_str().unwrap(),
    ];
    blueshift(&args, &display, dir.path(), TIMEOUT);
    let img = png(&shot);
    assert_eq!(
        img.dimensions(),
        (128, 96),
        "the resize reached the swapchain"
    );
    // The split-screen divider sits at the middle column, full height.
    for y in [0, 47, 95] {
        assert_eq!(
            img.get_pixel(64, y).0,
            [0xff, 0xd0, 0x40, 0xff],
            "divider at y={y}"
        );
    }
}
