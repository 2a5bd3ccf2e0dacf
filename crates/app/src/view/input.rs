//! Input handling without a window: events in, commands and camera motion out. The window
//! glue (window.rs) only translates winit events into [`Event`]s, so everything here is
//! unit-tested with synthetic events.
//!
//! Flying: hold a mouse button and drag to look; while it is held, W/A/S/D/Q/E fly
//! (forward/left/back/right/down/up). The arrow keys and PageUp/PageDown fly at any time.
//! Without a mouse button held the letter keys are commands (A accumulation, S split, E error).
use blueshift_scene::Camera;
use glam::{Quat, Vec3};

/// A key, independent of the windowing library. Characters are as typed (Shift+B is 'B').
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Key {
    Char(char),
    Tab,
    Escape,
    Up,
    Down,
    Left,
    Right,
    PageUp,
    PageDown,
}

/// One input event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event {
    Key {
        key: Key,
        pressed: bool,
        repeat: bool,
    },
    /// Any mouse button.
    Button { pressed: bool },
    /// Cursor position in window pixels.
    Cursor { x: f64, y: f64 },
    /// Wheel movement in lines (positive = away from the user = faster).
    Scroll { lines: f32 },
    /// The window lost focus: release everything.
    FocusLost,
}

/// A command given by a key press.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Keys 1-6: index into `controls::VIEW_METHODS`.
    Method(usize),
    Block(i32),
    Spp(i32),
    Bounces(i32),
    ToggleAccumulation,
    Reset,
    ToggleSplit,
    ToggleError,
    SwitchSide,
    Quit,
}

/// The command of a key pressed while not looking around, if any.
pub fn action_of(key: Key) -> Option<Action> {
    Some(match key {
        Key::Char(c @ '1'..='6') => Action::Method(c as usize - '1' as usize),
        Key::Char('b') => Action::Block(1),
        Key::Char('B') => Action::Block(-1),
        Key::Char('+' | '=') => Action::Spp(1),
        Key::Char('-' | '_') => Action::Spp(-1),
        Key::Char(']') => Action::Bounces(1),
        Key::Char('[') => Action::Bounces(-1),
        Key::Char('a' | 'A') => Action::ToggleAccumulation,
        Key::Char('r' | 'R') => Action::Reset,
        Key::Char('s' | 'S') => Action::ToggleSplit,
        Key::Char('e' | 'E') => Action::ToggleError,
        Key::Tab => Action::SwitchSide,
        Key::Escape => Action::Quit,
        _ => return None,
    })
}

/// Longest time step applied at once: lavapipe frames take up to a second, so movement stays
/// time-based at that rate, but a stall (a renderer rebuild) does not fling the camera away.
const MAX_STEP_SECONDS: f32 = 1.0;

/// Flying letters, lowercase: forward, left, back, right, down, up.
const FLY_LETTERS: [char; 6] = ['w', 'a', 's', 'd', 'q', 'e'];

fn normalise(key: Key) -> Key {
    match key {
        Key::Char(c) if FLY_LETTERS.contains(&c.to_ascii_lowercase()) => {
            Key::Char(c.to_ascii_lowercase())
        }
        k => k,
    }
}

/// Held keys, mouse look and speed; turns time and events into camera motion.
#[derive(Debug, Clone)]
pub struct Input {
    held: Vec<Key>,
    looking: bool,
    cursor: Option<(f64, f64)>,
    look: (f64, f64),
    /// Flying speed in scene units per second.
    pub speed: f32,
    /// Radians per pixel of mouse movement.
    pub sensitivity: f32,
}

impl Input {
    /// Starts with a speed that crosses the camera-to-target distance in two seconds.
    pub fn new(camera: &Camera) -> Self {
        let d = (camera.target - camera.position).length();
        Self {
            held: Vec::new(),
            looking: false,
            cursor: None,
            look: (0.0, 0.0),
            speed: if d.is_finite() && d > 1e-4 {
                d * 0.5
            } else {
                1.0
            },
            sensitivity: 0.005,
        }
    }

    /// Records an event; returns the command it gives, if any.
    pub fn handle(&mut self, event: Event) -> Option<Action> {
        match event {
            Event::Key {
                key,
                pressed,
                repeat,
            } => {
                let k = normalise(key);
                if !pressed {
                    self.held.retain(|&h| h != k);
                    return None;
                }
                if !self.held.contains(&k) {
                    self.held.push(k);
                }
                let flies = matches!(k, Key::Char(c) if FLY_LETTERS.contains(&c));
                if repeat || (self.looking && flies) {
                    return None;
                }
                action_of(key)
            }
            Event::Button { pressed } => {
                self.looking = pressed;
                None
            }
            Event::Cursor { x, y } => {
                if let (true, Some((px, py))) = (self.looking, self.cursor) {
                    self.look.0 += x - px;
                    self.look.1 += y - py;
                }
                self.cursor = Some((x, y));
                None
            }
            Event::Scroll { lines } => {
                if lines.is_finite() {
                    self.speed =
                        (self.speed * 1.2f32.powf(lines.clamp(-10.0, 10.0))).clamp(1e-4, 1e6);
                }
                None
            }
            Event::FocusLost => {
                self.held.clear();
                self.looking = false;
                None
            }
        }
    }

    fn down(&self, key: Key) -> bool {
        self.held.contains(&key)
    }

    /// (forward, right, up) in -1..=1 from the held keys.
    pub fn direction(&self) -> (f32, f32, f32) {
        let fly = |c: char| self.looking && self.down(Key::Char(c));
        let axis = |pos: bool, neg: bool| pos as i32 as f32 - neg as i32 as f32;
        (
            axis(
                self.down(Key::Up) || fly('w'),
                self.down(Key::Down) || fly('s'),
            ),
            axis(
                self.down(Key::Right) || fly('d'),
                self.down(Key::Left) || fly('a'),
            ),
            axis(
                self.down(Key::PageUp) || fly('e'),
                self.down(Key::PageDown) || fly('q'),
            ),
        )
    }

    /// Applies `dt` seconds of flying and the mouse movement since the last call. Returns
    /// `None` when nothing moved, so a still camera stays bit-identical (and keeps
    /// accumulating).
    pub fn update(&mut self, camera: &Camera, dt: f32) -> Option<Camera> {
        let (look_x, look_y) = std::mem::take(&mut self.look);
        let (f, r, u) = self.direction();
        if (f, r, u) == (0.0, 0.0, 0.0) && look_x == 0.0 && look_y == 0.0 {
            return None;
        }
        let mut cam = *camera;
        let up = camera.up.try_normalize().unwrap_or(Vec3::Y);
        let offset = cam.target - cam.position;
        let dist = offset.length().max(1e-4);
        let mut fwd = offset.try_normalize().unwrap_or(Vec3::NEG_Z);
        if look_x != 0.0 || look_y != 0.0 {
            let pitch = fwd.dot(up).clamp(-1.0, 1.0).asin();
            let flat = (fwd - up * fwd.dot(up))
                .try_normalize()
                .unwrap_or_else(|| up.any_orthonormal_vector());
            let yaw = -(look_x as f32) * self.sensitivity;
            let limit = 89f32.to_radians();
            let pitch = (pitch - look_y as f32 * self.sensitivity).clamp(-limit, limit);
            let flat = Quat::from_axis_angle(up, yaw) * flat;
            fwd = flat * pitch.cos() + up * pitch.sin();
        }
        let right = fwd.cross(up).try_normalize().unwrap_or(Vec3::X);
        let dt = if dt.is_finite() {
            dt.clamp(0.0, MAX_STEP_SECONDS)
        } else {
            0.0
        };
        let step = (fwd * f + right * r + up * u) * self.speed * dt;
        cam.position += step;
        cam.target = cam.position + fwd * dist;
        Some(cam)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            position: Vec3::new(0.0, 1.0, 4.0),
            target: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            yfov: 0.7,
        }
    }
    fn press(key: Key) -> Event {
        Event::Key {
            key,
            pressed: true,
            repeat: false,
        }
    }
    fn release(key: Key) -> Event {
        Event::Key {
            key,
            pressed: false,
            repeat: false,
        }
    }

    #[test]
    fn keys_map_to_commands() {
        let mut i = Input::new(&camera());
        assert_eq!(i.handle(press(Key::Char('1'))), Some(Action::Method(0)));
        assert_eq!(i.handle(press(Key::Char('6'))), Some(Action::Method(5)));
        assert_eq!(i.handle(press(Key::Char('7'))), None);
        assert_eq!(i.handle(press(Key::Char('0'))), None);
        assert_eq!(i.handle(press(Key::Char('x'))), None);
        assert_eq!(i.handle(press(Key::Char('b'))), Some(Action::Block(1)));
        assert_eq!(i.handle(press(Key::Char('B'))), Some(Action::Block(-1)));
        assert_eq!(i.handle(press(Key::Char('+'))), Some(Action::Spp(1)));
        assert_eq!(i.handle(press(Key::Char('-'))), Some(Action::Spp(-1)));
        assert_eq!(i.handle(press(Key::Char(']'))), Some(Action::Bounces(1)));
        assert_eq!(i.handle(press(Key::Char('['))), Some(Action::Bounces(-1)));
        assert_eq!(i.handle(press(Key::Tab)), Some(Action::SwitchSide));
        assert_eq!(i.handle(press(Key::Escape)), Some(Action::Quit));
        let repeat = Event::Key {
            key: Key::Char('r'),
            pressed: true,
            repeat: true,
        };
        assert_eq!(i.handle(repeat), None, "auto-repeat gives no command");
    }

    #[test]
    fn letters_are_commands_unless_looking() {
        let mut i = Input::new(&camera());
        assert_eq!(i.handle(press(Key::Char('s'))), Some(Action::ToggleSplit));
        i.handle(release(Key::Char('s')));
        assert_eq!(i.direction(), (0.0, 0.0, 0.0), "S alone does not fly");
        i.handle(Event::Button { pressed: true });
        assert_eq!(i.handle(press(Key::Char('s'))), None);
        assert_eq!(i.handle(press(Key::Char('E'))), None);
        assert_eq!(i.direction(), (-1.0, 0.0, 1.0));
        i.handle(release(Key::Char('e')));
        i.handle(Event::Button { pressed: false });
        assert_eq!(
            i.direction(),
            (0.0, 0.0, 0.0),
            "letters stop with the button"
        );
        assert_eq!(
            i.handle(press(Key::Char('a'))),
            Some(Action::ToggleAccumulation)
        );
    }

    #[test]
    fn still_input_leaves_the_camera_untouched() {
        let mut i = Input::new(&camera());
        assert_eq!(i.update(&camera(), 0.016), None);
        i.handle(Event::Cursor { x: 10.0, y: 10.0 });
        i.handle(Event::Cursor { x: 50.0, y: 10.0 });
        assert_eq!(i.update(&camera(), 0.016), None, "moving without a button");
    }

    #[test]
    fn arrows_fly_along_the_view() {
        let mut i = Input::new(&camera());
        assert!((i.speed - 2.0).abs() < 1e-6);
        i.handle(press(Key::Up));
        let c = i.update(&camera(), 0.5).unwrap();
        assert!((c.position - Vec3::new(0.0, 1.0, 3.0)).length() < 1e-5);
        assert!((c.target - Vec3::new(0.0, 1.0, -1.0)).length() < 1e-5);
        i.handle(release(Key::Up));
        i.handle(press(Key::Right));
        i.handle(press(Key::PageUp));
        let c = i.update(&camera(), 0.5).unwrap();
        assert!((c.position - Vec3::new(1.0, 2.0, 4.0)).length() < 1e-5);
        let far = i.update(&camera(), 10.0).unwrap();
        let travelled = (far.position - camera().position).length();
        assert!(
            (travelled - 2.0 * 2f32.sqrt()).abs() < 1e-4,
            "dt clamped to 1 s"
        );
    }

    #[test]
    fn drag_turns_and_pitch_is_clamped() {
        let mut i = Input::new(&camera());
        i.handle(Event::Cursor { x: 100.0, y: 100.0 });
        i.handle(Event::Button { pressed: true });
        let quarter = std::f64::consts::FRAC_PI_2 / i.sensitivity as f64;
        i.handle(Event::Cursor {
            x: 100.0 + quarter,
            y: 100.0,
        });
        let c = i.update(&camera(), 0.016).unwrap();
        let fwd = (c.target - c.position).normalize();
        assert!(
            (fwd - Vec3::X).length() < 1e-4,
            "drag right looks right: {fwd}"
        );
        assert_eq!(c.position, camera().position);
        i.handle(Event::Cursor {
            x: 100.0 + quarter,
            y: -10_000.0,
        });
        let c = i.update(&c, 0.016).unwrap();
        let fwd = (c.target - c.position).normalize();
        assert!(
            fwd.y > 0.99 && fwd.y < 1.0,
            "pitch clamped below 90 deg: {fwd}"
        );
        assert!(((c.target - c.position).length() - 4.0).abs() < 1e-4);
    }

    #[test]
    fn scroll_changes_speed_and_focus_loss_releases() {
        let mut i = Input::new(&camera());
        let s = i.speed;
        i.handle(Event::Scroll { lines: 2.0 });
        assert!((i.speed - s * 1.44).abs() < 1e-5);
        i.handle(Event::Scroll { lines: f32::NAN });
        assert!(i.speed.is_finite());
        i.handle(press(Key::Down));
        i.handle(Event::Button { pressed: true });
        i.handle(Event::FocusLost);
        assert!(!i.looking);
        assert_eq!(i.direction(), (0.0, 0.0, 0.0));
    }
}
