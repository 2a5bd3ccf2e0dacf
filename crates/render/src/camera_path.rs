//! Camera paths: built-in presets and a small keyframe file format.
//!
//! File format (JSON): `{"keyframes": [{"frame": 0, "position": [x,y,z], "target": [x,y,z],
//! "yfov_degrees": 39.3}, ...]}`. Frames between keyframes interpolate linearly; before the
//! first and after the last keyframe the camera holds still. Frames must increase.
use blueshift_scene::Camera;
use glam::Vec3;
use serde::Deserialize;
use std::path::Path;

/// Where the camera is at each frame.
#[derive(Debug, Clone, PartialEq)]
pub enum CameraPath {
    Static,
    /// Image-space pan: the view window slides this many pixels per frame to the right, and
    /// back after [`PAN_SPAN`] px (a sensor shift: every point moves exactly the same amount,
    /// no parallax), so integer pans have exact motion vectors and one wide reference image
    /// covers all frames.
    Pan {
        px_per_frame: f32,
    },
    /// Orbit around the target by this many degrees per frame.
    Orbit {
        degrees_per_frame: f32,
    },
    /// An orbit that turns back after [`SWING_SPAN`] degrees, like a pan: the camera keeps
    /// circling its subject at full speed without turning it out of view.
    Swing {
        degrees_per_frame: f32,
    },
    Keyframes(Vec<Keyframe>),
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Keyframe {
    pub frame: u32,
    pub position: [f32; 3],
    pub target: [f32; 3],
    pub yfov_degrees: f32,
}

#[derive(Deserialize)]
struct PathFile {
    keyframes: Vec<Keyframe>,
}

/// How far (pixels) a pan travels before it turns back: far enough to show the effect of
/// motion, short enough that the view stays on the scene (the sensor is the frame plus this).
pub const PAN_SPAN: f32 = 64.0;

/// How far (degrees) a swing turns before it turns back. An orbit of 1 degree/frame shows the
/// Cornell box's open front at 24-47 degrees in frames 24-47, mostly its dark outside.
pub const SWING_SPAN: f32 = 12.0;

/// A triangle wave of slope `speed` per frame between 0 and `span` (sign of `speed`).
fn back_and_forth(speed: f32, frame: u32, span: f32) -> f32 {
    let d = (speed * frame as f32).abs() % (2.0 * span);
    let x = if d <= span { d } else { 2.0 * span - d };
    x.copysign(speed)
}

impl CameraPath {
    /// Parses `static`, `pan[:PX]`, `orbit[:DEG]`, `swing[:DEG]` or a path to a keyframe file.
    pub fn parse(spec: &str) -> Result<CameraPath, String> {
        let (name, arg) = spec
            .split_once(':')
            .map_or((spec, None), |(a, b)| (a, Some(b)));
        let number = |default: f32| -> Result<f32, String> {
            arg.map_or(Ok(default), |a| {
                a.parse::<f32>()
                    .ok()
                    .filter(|v| v.is_finite() && v.abs() <= 1000.0)
                    .ok_or_else(|| {
                        format!("camera path '{spec}': '{a}' is not a number in -1000..=1000")
                    })
            })
        };
        match name {
            "static" => Ok(CameraPath::Static),
            "pan" => Ok(CameraPath::Pan {
                px_per_frame: number(1.0)?,
            }),
            "orbit" => Ok(CameraPath::Orbit {
                degrees_per_frame: number(0.5)?,
            }),
            "swing" => Ok(CameraPath::Swing {
                degrees_per_frame: number(1.0)?,
            }),
            _ => Self::load(Path::new(spec)),
        }
    }

    /// Loads a keyframe file.
    pub fn load(path: &Path) -> Result<CameraPath, String> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            format!(
                "camera path '{}': {e} (presets: static, pan:PX, orbit:DEG, swing:DEG)",
                path.display()
            )
        })?;
        Self::from_json(&text, &path.display().to_string())
    }

    /// Parses and validates keyframe JSON (module docs); `name` only labels errors.
    pub fn from_json(text: &str, name: &str) -> Result<CameraPath, String> {
        let file: PathFile =
            serde_json::from_str(text).map_err(|e| format!("camera path '{name}': {e}"))?;
        let k = &file.keyframes;
        if k.is_empty() {
            return Err(format!("camera path '{name}': no keyframes"));
        }
        for w in k.windows(2) {
            if w[1].frame <= w[0].frame {
                return Err(format!(
                    "camera path '{name}': keyframe frames must increase"
                ));
            }
        }
        for kf in k {
            let p = Vec3::from(kf.position);
            let t = Vec3::from(kf.target);
            if !p.is_finite() || !t.is_finite() || !(0.1..179.0).contains(&kf.yfov_degrees) {
                return Err(format!(
                    "camera path '{name}': keyframe at frame {} has a non-finite position/target or a fov outside 0.1..179 degrees",
                    kf.frame
                ));
            }
        }
        Ok(CameraPath::Keyframes(file.keyframes))
    }

    /// A short name for reports (`static`, `pan:1`, `orbit:0.5`, `file`).
    pub fn label(&self) -> String {
        match self {
            CameraPath::Static => "static".into(),
            CameraPath::Pan { px_per_frame } => format!("pan:{px_per_frame}"),
            CameraPath::Orbit { degrees_per_frame } => format!("orbit:{degrees_per_frame}"),
            CameraPath::Swing { degrees_per_frame } => format!("swing:{degrees_per_frame}"),
            CameraPath::Keyframes(_) => "keyframes".into(),
        }
    }

    /// The nominal view (sensor) size for a `frames`-frame sequence of `width x height`
    /// frames, and where frame 0's window sits on it. A pan sweeps the middle band of a square
    /// sensor just wide enough for the whole sweep (at most [`PAN_SPAN`] px), so every frame
    /// sees the scene; other paths use the frame as the sensor. Offsets are whole pixels for
    /// whole-pixel pans, so a wide reference crops exactly.
    pub fn view_window(&self, frames: u32, width: u32, height: u32) -> ((u32, u32), (f32, f32)) {
        match self {
            CameraPath::Pan { px_per_frame } => {
                let sweep = (px_per_frame.abs() * frames.saturating_sub(1) as f32)
                    .min(PAN_SPAN)
                    .ceil() as u32;
                let side = width.saturating_add(sweep).max(height);
                let x0 = if *px_per_frame < 0.0 {
                    sweep as f32
                } else {
                    0.0
                };
                ((side, side), (x0, ((side - height) / 2) as f32))
            }
            _ => ((width, height), (0.0, 0.0)),
        }
    }

    /// Sensor shift (pixels) at `frame` relative to frame 0: non-zero only for pans.
    pub fn view_offset(&self, frame: u32) -> (f32, f32) {
        match self {
            CameraPath::Pan { px_per_frame } => {
                // Back and forth over PAN_SPAN px, at |px_per_frame| px/frame.
                (back_and_forth(*px_per_frame, frame, PAN_SPAN), 0.0)
            }
            _ => (0.0, 0.0),
        }
    }

    /// The camera at `frame` for a base camera.
    pub fn camera(&self, base: &Camera, frame: u32) -> Camera {
        match self {
            CameraPath::Static => *base,
            CameraPath::Pan { .. } => *base,
            CameraPath::Orbit { degrees_per_frame } => {
                orbit(base, degrees_per_frame * frame as f32)
            }
            CameraPath::Swing { degrees_per_frame } => {
                orbit(base, back_and_forth(*degrees_per_frame, frame, SWING_SPAN))
            }
            CameraPath::Keyframes(k) => interpolate(k, frame),
        }
    }
}

/// `base` turned by `degrees` around its target (about its up axis).
fn orbit(base: &Camera, degrees: f32) -> Camera {
    let offset = base.position - base.target;
    let axis = base.up.normalize_or_zero();
    let rotated = glam::Quat::from_axis_angle(axis, degrees.to_radians()) * offset;
    Camera {
        position: base.target + rotated,
        ..*base
    }
}

fn interpolate(k: &[Keyframe], frame: u32) -> Camera {
    let at = |kf: &Keyframe| Camera {
        position: Vec3::from(kf.position),
        target: Vec3::from(kf.target),
        up: Vec3::Y,
        yfov: kf.yfov_degrees.to_radians(),
    };
    let Some(next) = k.iter().position(|kf| kf.frame > frame) else {
        return at(&k[k.len() - 1]);
    };
    if next == 0 {
        return at(&k[0]);
    }
    let (a, b) = (&k[next - 1], &k[next]);
    let t = (frame - a.frame) as f32 / (b.frame - a.frame) as f32;
    let (ca, cb) = (at(a), at(b));
    // a * (1 - t) + b * t, not glam's a + (b - a) * t: b - a overflows for large coordinates.
    let lerp = |a: Vec3, b: Vec3| a * (1.0 - t) + b * t;
    Camera {
        position: lerp(ca.position, cb.position),
        target: lerp(ca.target, cb.target),
        up: Vec3::Y,
        yfov: ca.yfov + (cb.yfov - ca.yfov) * t,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> Camera {
        Camera {
            position: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            yfov: 0.7,
        }
    }

    #[test]
    fn presets_parse() {
        assert_eq!(CameraPath::parse("static").unwrap(), CameraPath::Static);
        assert_eq!(
            CameraPath::parse("pan:8").unwrap(),
            CameraPath::Pan { px_per_frame: 8.0 }
        );
        assert!(CameraPath::parse("pan:abc").is_err());
        assert_eq!(
            CameraPath::parse("swing:2").unwrap(),
            CameraPath::Swing {
                degrees_per_frame: 2.0
            }
        );
        assert!(
            CameraPath::parse("/nonexistent/path.json")
                .unwrap_err()
                .contains("presets")
        );
    }

    #[test]
    fn keyframes_far_apart_interpolate_to_finite_cameras() {
        let text = r#"{"keyframes": [
            {"frame": 0, "position": [-3e38, 0, 0], "target": [0, 0, 0], "yfov_degrees": 40},
            {"frame": 9, "position": [3e38, 0, 0], "target": [0, 0, 1], "yfov_degrees": 40}]}"#;
        let path = CameraPath::from_json(text, "far").unwrap();
        for f in 0..10 {
            assert!(path.camera(&base(), f).position.is_finite(), "frame {f}");
        }
        assert!(CameraPath::from_json(r#"{"keyframes": []}"#, "x").is_err());
        assert!(CameraPath::from_json("{", "x").unwrap_err().contains("'x'"));
    }

    #[test]
    fn pan_shifts_the_view_not_the_camera() {
        let p = CameraPath::Pan { px_per_frame: 2.0 };
        assert_eq!(p.camera(&base(), 10), base());
        assert_eq!(p.view_offset(10), (20.0, 0.0));
        assert_eq!(CameraPath::Static.view_offset(10), (0.0, 0.0));
    }

    #[test]
    fn pans_turn_back_and_stay_inside_their_sensor() {
        let p = CameraPath::Pan { px_per_frame: 8.0 };
        let xs: Vec<f32> = (0..20).map(|t| p.view_offset(t).0).collect();
        assert_eq!(
            &xs[..10],
            &[0.0, 8.0, 16.0, 24.0, 32.0, 40.0, 48.0, 56.0, 64.0, 56.0]
        );
        assert_eq!(xs[16], 0.0);
        let (view, base) = p.view_window(48, 128, 100);
        assert_eq!(view, (128 + PAN_SPAN as u32, 128 + PAN_SPAN as u32));
        assert_eq!(base, (0.0, ((view.1 - 100) / 2) as f32));
        for t in 0..48 {
            let x = base.0 + p.view_offset(t).0;
            assert!(x >= 0.0 && x + 128.0 <= view.0 as f32, "frame {t}");
        }
        // A slow pan uses only the sensor it needs; leftward pans start at the right.
        let slow = CameraPath::Pan { px_per_frame: 1.0 };
        assert_eq!(slow.view_window(10, 32, 32), ((41, 41), (0.0, 4.0)));
        let left = CameraPath::Pan { px_per_frame: -1.0 };
        assert_eq!(
            left.view_window(10, 32, 32).1.0 + left.view_offset(9).0,
            0.0
        );
        assert_eq!(
            CameraPath::Static.view_window(5, 32, 16),
            ((32, 16), (0.0, 0.0))
        );
    }

    /// A swing follows the orbit up to SWING_SPAN degrees, then turns back to where it began.
    #[test]
    fn swings_turn_back_at_their_span() {
        let (swing, orbit) = (
            CameraPath::Swing {
                degrees_per_frame: 1.0,
            },
            CameraPath::Orbit {
                degrees_per_frame: 1.0,
            },
        );
        let b = base();
        let span = SWING_SPAN as u32;
        for f in 0..=span {
            assert_eq!(swing.camera(&b, f), orbit.camera(&b, f), "frame {f}");
        }
        for f in 0..=span {
            let (a, c) = (swing.camera(&b, span + f), orbit.camera(&b, span - f));
            assert!(
                (a.position - c.position).length() < 1e-5,
                "frame {}",
                span + f
            );
        }
        assert!((swing.camera(&b, 2 * span).position - b.position).length() < 1e-5);
    }

    #[test]
    fn keyframes_interpolate_linearly() {
        let k = vec![
            Keyframe {
                frame: 0,
                position: [0.0, 0.0, 4.0],
                target: [0.0; 3],
                yfov_degrees: 40.0,
            },
            Keyframe {
                frame: 10,
                position: [2.0, 0.0, 4.0],
                target: [0.0; 3],
                yfov_degrees: 60.0,
            },
        ];
        let c = CameraPath::Keyframes(k).camera(&base(), 5);
        assert!((c.position.x - 1.0).abs() < 1e-6);
        assert!((c.yfov.to_degrees() - 50.0).abs() < 1e-4);
    }
}
