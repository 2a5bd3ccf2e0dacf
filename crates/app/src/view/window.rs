//! winit glue: the window, translating its events for `input`, and the frame loop (including
//! the scripted `--frames N --screenshot FILE` run).
use super::controls::{Change, Settings, title};
use super::gpu::{Frame, Options, ViewGpu};
use super::input::{Event, Input, Key};
use crate::output::{png_rgba8, write_atomic};
use anyhow::{Context, Result};
use blueshift_device::{Device, Instance, InstanceDesc, Surface};
use blueshift_scene::Camera;
use std::path::PathBuf;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::{Key as WinitKey, NamedKey};
use winit::raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use winit::window::{Window, WindowId};

/// A scripted run: stop after `frames` presented frames, optionally saving the last one, and
/// optionally request a new window size after some frame.
#[derive(Debug, Clone, Default)]
pub struct Script {
    pub frames: Option<u32>,
    pub screenshot: Option<PathBuf>,
    pub resize_at: Option<(u32, (u32, u32))>,
}

/// `gpu` is declared before `window`, so the surface (owned by the swapchain inside `gpu`) is
/// destroyed before the window it was created for.
struct Running {
    gpu: ViewGpu,
    window: Window,
}

/// Frame counts and times of the run, for the closing summary.
#[derive(Debug, Default)]
struct Timing {
    presented: u32,
    first: Option<Instant>,
    last: Option<Instant>,
}

/// The application state winit drives.
pub struct App {
    pending: Option<Options>,
    validation: bool,
    size: (u32, u32),
    settings: Settings,
    script: Script,
    camera: Camera,
    input: Input,
    running: Option<Running>,
    device: Option<Device>,
    timing: Timing,
    last_update: Instant,
    paused: bool,
    /// The readout of the last presented frame (printed at the end of a scripted run).
    readout: String,
    error: Option<anyhow::Error>,
}

impl App {
    pub fn new(
        opts: Options,
        validation: bool,
        size: (u32, u32),
        settings: Settings,
        script: Script,
    ) -> Self {
        let camera = opts.scene.camera_or_default();
        Self {
            pending: Some(opts),
            validation,
            size,
            settings,
            script,
            input: Input::new(&camera),
            camera,
            running: None,
            device: None,
            timing: Timing::default(),
            last_update: Instant::now(),
            paused: false,
            readout: String::new(),
            error: None,
        }
    }

    /// After the event loop returned: releases the window and GPU objects, then fails on an
    /// error of the run or on any validation message (teardown included).
    pub fn finish(mut self) -> Result<()> {
        self.running = None;
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(dev) = &self.device {
            crate::check_validation(dev)?;
        }
        let t = &self.timing;
        if let (Some(a), Some(b)) = (t.first, t.last)
            && t.presented > 1
        {
            let s = (b - a).as_secs_f64();
            let n = t.presented - 1;
            println!(
                "view: {} frames presented; after the first: {n} in {s:.2} s = {:.2} fps ({:.1} ms per frame)",
                t.presented,
                n as f64 / s,
                s * 1000.0 / n as f64
            );
            println!("view: last frame: {}", self.readout);
        }
        Ok(())
    }

    fn fail(&mut self, el: &ActiveEventLoop, e: anyhow::Error) {
        if self.error.is_none() {
            self.error = Some(e);
        }
        el.exit();
    }

    fn start(&mut self, el: &ActiveEventLoop) -> Result<Running> {
        let opts = self
            .pending
            .take()
            .context("the window was already created")?;
        let attrs = Window::default_attributes()
            .with_title("blueshift")
            .with_inner_size(PhysicalSize::new(self.size.0, self.size.1));
        let window = el.create_window(attrs).context("creating the window")?;
        let display = window.display_handle()?.as_raw();
        let handle = window.window_handle()?.as_raw();
        let mut desc = InstanceDesc::from_env(self.validation);
        desc.extensions = Surface::required_extensions(display)?;
        let instance = Instance::new(&desc)?;
        // SAFETY: `Running` drops the swapchain (which owns the surface) before the window.
        let surface = unsafe { Surface::new(&instance, display, handle) }?;
        let size = window.inner_size();
        let gpu = ViewGpu::new(
            &instance,
            surface,
            (size.width, size.height),
            opts,
            &self.settings,
        )?;
        let sc = gpu.swapchain();
        let (rw, rh) = gpu.render_size();
        eprintln!(
            "view: {} | swapchain {:?} {:?}, {} images, {}x{} | render {rw}x{rh}",
            gpu.device().info().name,
            sc.format(),
            sc.present_mode(),
            sc.image_count(),
            sc.extent().0,
            sc.extent().1,
        );
        self.device = Some(gpu.device().clone());
        window.request_redraw();
        Ok(Running { gpu, window })
    }

    fn command(&mut self, el: &ActiveEventLoop, event: Event) {
        let Some(action) = self.input.handle(event) else {
            return;
        };
        let change = self.settings.apply(action);
        if change == Change::Quit {
            el.exit();
            return;
        }
        if let Some(r) = &mut self.running
            && let Err(e) = r.gpu.apply(change, &self.settings)
        {
            self.fail(el, e);
        }
    }

    fn redraw(&mut self, el: &ActiveEventLoop) {
        let now = Instant::now();
        let dt = (now - self.last_update).as_secs_f32();
        self.last_update = now;
        if let Some(c) = self.input.update(&self.camera, dt) {
            self.camera = c;
        }
        let Some(r) = &mut self.running else {
            return;
        };
        let size = r.window.inner_size();
        let frame = r
            .gpu
            .frame(&self.settings, self.camera, (size.width, size.height));
        let frame_ms = now.elapsed().as_secs_f64() * 1000.0;
        match frame {
            Err(e) => self.fail(el, e),
            Ok(Frame::Paused) => self.paused = true,
            Ok(Frame::Skipped) => self.paused = false,
            Ok(Frame::Presented {
                stats,
                present_ms,
                reference_ms,
            }) => {
                self.paused = false;
                self.readout = title(&self.settings, frame_ms, &stats, present_ms);
                if let Some(ms) = reference_ms {
                    self.readout += &format!(" (reference {ms:.1} ms)");
                }
                r.window.set_title(&self.readout);
                let t = &mut self.timing;
                t.presented += 1;
                t.first.get_or_insert(Instant::now());
                t.last = Some(Instant::now());
                if let Err(e) = self.scripted(el) {
                    self.fail(el, e);
                }
            }
        }
    }

    /// The scripted run's steps after a presented frame.
    fn scripted(&mut self, el: &ActiveEventLoop) -> Result<()> {
        let (Some(r), n) = (&self.running, self.timing.presented) else {
            return Ok(());
        };
        if let Some((at, (w, h))) = self.script.resize_at
            && at == n
        {
            // The new size arrives as a Resized event; the next frames recreate the swapchain.
            let _ = r.window.request_inner_size(PhysicalSize::new(w, h));
        }
        if self.script.frames.is_some_and(|f| n >= f) {
            if let Some(path) = &self.script.screenshot {
                let (w, h, rgba) = r.gpu.read_presented()?;
                write_atomic(path, &png_rgba8(w, h, &rgba)?)?;
                eprintln!("view: wrote {} ({w}x{h})", path.display());
            }
            el.exit();
        }
        Ok(())
    }
}

/// winit's logical key as ours (characters as typed, so Shift+B is 'B').
fn key_of(key: &WinitKey) -> Option<Key> {
    Some(match key {
        WinitKey::Character(s) => Key::Char(s.chars().next()?),
        WinitKey::Named(NamedKey::Tab) => Key::Tab,
        WinitKey::Named(NamedKey::Escape) => Key::Escape,
        WinitKey::Named(NamedKey::ArrowUp) => Key::Up,
        WinitKey::Named(NamedKey::ArrowDown) => Key::Down,
        WinitKey::Named(NamedKey::ArrowLeft) => Key::Left,
        WinitKey::Named(NamedKey::ArrowRight) => Key::Right,
        WinitKey::Named(NamedKey::PageUp) => Key::PageUp,
        WinitKey::Named(NamedKey::PageDown) => Key::PageDown,
        _ => return None,
    })
}

impl ApplicationHandler for App {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        if self.running.is_some() || self.error.is_some() {
            return;
        }
        match self.start(el) {
            Ok(r) => self.running = Some(r),
            Err(e) => self.fail(el, e),
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::RedrawRequested => self.redraw(el),
            WindowEvent::Resized(_) => {
                if let Some(r) = &self.running {
                    r.window.request_redraw();
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                if let Some(key) = key_of(&event.logical_key) {
                    let pressed = event.state == ElementState::Pressed;
                    let repeat = event.repeat;
                    self.command(
                        el,
                        Event::Key {
                            key,
                            pressed,
                            repeat,
                        },
                    );
                }
            }
            WindowEvent::MouseInput { state, .. } => {
                let pressed = state == ElementState::Pressed;
                self.command(el, Event::Button { pressed });
            }
            WindowEvent::CursorMoved { position, .. } => {
                let (x, y) = (position.x, position.y);
                self.command(el, Event::Cursor { x, y });
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.command(el, Event::Scroll { lines });
            }
            WindowEvent::Focused(false) => self.command(el, Event::FocusLost),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, el: &ActiveEventLoop) {
        // Render continuously, except while minimised: then sleep until the next event
        // (a Resized event restores the window).
        if self.paused {
            el.set_control_flow(ControlFlow::Wait);
        } else {
            el.set_control_flow(ControlFlow::Poll);
            if let Some(r) = &self.running {
                r.window.request_redraw();
            }
        }
    }
}
