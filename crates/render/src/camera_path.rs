//! Camera paths: built-in presets and a small keyframe file format.
//!
//! File format (JSON): `{"keyframes": [{"frame": 0, "position": [x,y,z], "target": [x,y,z],
//! "yfov_degrees": 39.3}, ...]}`. Frames between keyframes interpolate linearly; before the
//! first and after the last keyframe the camera holds still. Frames must increase.
use blueshift_scene::{Aabb, Camera};
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
    /// The camera translates sideways, looking straight ahead (parallax, disocclusion at
    /// depth edges), about this many pixels per frame at the scene's centre, and turns back
    /// after [`fit::STRAFE_SPAN`] of the view height. Holds still until [`CameraPath::fit`].
    Strafe {
        px_per_frame: f32,
        fit: Option<fit::StrafeFit>,
    },
    /// An orbit about the scene's centre at a distance where the whole scene stays in view,
    /// turning back after [`fit::ORBIT_VIEW_SPAN`] degrees. Holds still until
    /// [`CameraPath::fit`].
    OrbitView {
        degrees_per_frame: f32,
        fit: Option<fit::OrbitFit>,
    },
    Keyframes(Vec<Keyframe>),
}

#[path = "camera_fit.rs"]
pub mod fit;

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

/// The largest keyframe file read (a few keyframes take a few hundred bytes).
const MAX_PATH_FILE_BYTES: u64 = 16 << 20;

/// A triangle wave of slope `speed` per frame between 0 and `span` (sign of `speed`).
fn back_and_forth(speed: f32, frame: u32, span: f32) -> f32 {
    let d = (speed * frame as f32).abs() % (2.0 * span);
    let x = if d <= span { d } else { 2.0 * span - d };
    x.copysign(speed)
}

impl CameraPath {
    /// Parses `static`, `pan[:PX]`, `orbit[:DEG]`, `swing[:DEG]`, `strafe[:PX]`,
    /// `orbit-view[:DEG]` or a path to a keyframe file.
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
            "static" => match arg {
                None => Ok(CameraPath::Static),
                Some(a) => Err(format!(
                    "camera path '{spec}': static takes no argument (got '{a}'): a static \
                     camera does not move"
                )),
            },
            "pan" => Ok(CameraPath::Pan {
                px_per_frame: number(1.0)?,
            }),
            "orbit" => Ok(CameraPath::Orbit {
                degrees_per_frame: number(0.5)?,
            }),
            "swing" => Ok(CameraPath::Swing {
                degrees_per_frame: number(1.0)?,
            }),
            "strafe" => Ok(CameraPath::Strafe {
                px_per_frame: number(2.5)?,
                fit: None,
            }),
            "orbit-view" => Ok(CameraPath::OrbitView {
                degrees_per_frame: number(1.0)?,
                fit: None,
            }),
            _ => Self::load(Path::new(spec)),
        }
    }

    /// Loads a keyframe file.
    pub fn load(path: &Path) -> Result<CameraPath, String> {
        let unreadable = |e: &dyn std::fmt::Display| {
            format!(
                "camera path '{}': {e} (presets: static, pan:PX, orbit:DEG, swing:DEG, strafe:PX, orbit-view:DEG)",
                path.display()
            )
        };
        // A regular file of at most MAX_PATH_FILE_BYTES: a FIFO or device is refused unread.
        let bytes =
            blueshift_scene::read_regular(path, MAX_PATH_FILE_BYTES).map_err(|e| unreadable(&e))?;
        let text = String::from_utf8(bytes).map_err(|e| unreadable(&e))?;
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
            CameraPath::Strafe { px_per_frame, .. } => format!("strafe:{px_per_frame}"),
            CameraPath::OrbitView {
                degrees_per_frame, ..
            } => format!("orbit-view:{degrees_per_frame}"),
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

    /// The path fitted to a scene with `bounds`, seen from `base` in a `view` (w, h) frame:
    /// strafes and in-view orbits derive their motion from these (the other paths need
    /// nothing and come back unchanged).
    pub fn fit(self, bounds: &Aabb, base: &Camera, view: (u32, u32)) -> CameraPath {
        match self {
            CameraPath::Strafe { px_per_frame, .. } => CameraPath::Strafe {
                px_per_frame,
                fit: Some(fit::strafe(px_per_frame, bounds, base, view.1)),
            },
            CameraPath::OrbitView {
                degrees_per_frame, ..
            } => CameraPath::OrbitView {
                degrees_per_frame,
                fit: Some(fit::orbit(bounds, base, view)),
            },
            other => other,
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
            CameraPath::Strafe { fit: None, .. } | CameraPath::OrbitView { fit: None, .. } => *base,
            CameraPath::Strafe { fit: Some(f), .. } => {
                fit::strafed(base, f, back_and_forth(f.step, frame, f.span))
            }
            CameraPath::OrbitView {
                degrees_per_frame,
                fit: Some(f),
            } => fit::orbited(
                base,
                f,
                back_and_forth(*degrees_per_frame, frame, fit::ORBIT_VIEW_SPAN),
            ),
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
#[path = "camera_path_tests.rs"]
mod tests;
