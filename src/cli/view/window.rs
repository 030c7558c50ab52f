//! The viewer's window: winit's events (mouse, keys, size) turned into
//! views asked of the renders, and the pictures they tell shown through
//! softbuffer — the reduced ones scaled up by whole pixels, a broken
//! save's message over the last picture.
//!
//! Mouse and keys as in OpenSCAD 2021.01: left drag orbits (shift: about
//! the view's own axis), right drag pans, middle drag moves along the line
//! of sight, shift with right or middle drag zooms, the wheel zooms about
//! the cursor (OpenSCAD's default mouse-centric zoom); Ctrl+4 to
//! Ctrl+9 top, bottom, left, right, front, back; Ctrl+0 diagonal;
//! Ctrl+Shift+0 centre; Ctrl+Shift+V view all; Ctrl+] and Ctrl+[ zoom.
//! csgrt's own: `r` reset view, `p` perspective, `o` orthogonal, `s`
//! write the picture and print its command line, F5 read the model
//! again, `q` or Escape close.

use super::orbit::{Orbit, ViewKey, NOTCH};
use super::progressive::{Pass, Picture, Renders, Report};
use super::{no_display, overlay, Cli};
use crate::cli::jobs::Job;
use crate::cli::watch::Follow;
use csgrt::error::{Error, Result};
use csgrt::geometry::Aabb;
use csgrt::scene::openscad_view::Viewpoint;
use std::num::NonZeroU32;
use std::rc::Rc;
use std::sync::Mutex;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, ModifiersState, PhysicalKey};
use winit::window::{Window, WindowId};

/// What reaches the window from the other threads.
enum Note {
    Report(Report),
    /// A file the model was read from was saved.
    Saved,
    /// The file watch stopped: its message.
    WatchFailed(String),
}

struct Shown {
    window: Rc<Window>,
    surface: softbuffer::Surface<Rc<Window>, Rc<Window>>,
}

struct App {
    job: Job,
    renders: Renders,
    shown: Option<Shown>,
    /// Why the window could not be made.
    failed: Option<Error>,
    view: Orbit,
    /// Whether the model has been read once (the view then starts).
    started: bool,
    bounds: Aabb,
    size: PhysicalSize<u32>,
    /// The last picture, and the count of the view it shows.
    frame: Option<Picture>,
    /// The view asked for last.
    asked: u64,
    error: Option<String>,
    cursor: Option<PhysicalPosition<f64>>,
    buttons: [bool; 3],
    mods: ModifiersState,
    log: bool,
    /// `--camera`: the first view, in place of the program's.
    camera: Option<Viewpoint>,
    began: Instant,
}

/// Opens the window and runs it until it is closed.
pub(super) fn run(cli: &Cli, job: &Job, pool: rayon::ThreadPool) -> Result<()> {
    let mut builder = EventLoop::<Note>::with_user_event();
    // The command line runs on a thread of its own (for its stack); X11
    // and Wayland allow the window there.
    winit::platform::x11::EventLoopBuilderExtX11::with_any_thread(&mut builder, true);
    let event_loop = builder
        .build()
        .map_err(|e| no_display(job, &format!("the window system says: {e}")))?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let proxy = Mutex::new(event_loop.create_proxy());
    let tell = move |t: Report| {
        let _ = proxy
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .send_event(Note::Report(t));
    };
    let (follow, changes) = Follow::new()?;
    let watch_proxy = event_loop.create_proxy();
    std::thread::Builder::new()
        .name("csgrt view watch".into())
        .spawn(move || loop {
            match changes.next() {
                Ok(()) => {
                    if watch_proxy.send_event(Note::Saved).is_err() {
                        return;
                    }
                }
                Err(e) => {
                    let _ = watch_proxy.send_event(Note::WatchFailed(e.to_string()));
                    return;
                }
            }
        })
        .map_err(|e| Error::Usage(format!("cannot start the file watch: {e}")))?;
    let (w, h) = cli.imgsize.unwrap_or(cli.size);
    let mut app = App {
        job: job.clone(),
        renders: Renders::start(cli, job, pool, follow, tell)?,
        shown: None,
        failed: None,
        view: Orbit::start(None, &Aabb::EMPTY, cli.projection.unwrap_or_default()),
        started: false,
        bounds: Aabb::EMPTY,
        size: PhysicalSize::new(w, h),
        frame: None,
        asked: 0,
        error: None,
        cursor: None,
        buttons: [false; 3],
        mods: ModifiersState::empty(),
        log: cli.log_frames,
        camera: cli.camera,
        began: Instant::now(),
    };
    if app.log {
        // The clock the lines' times count from, for a benchmark's own.
        let epoch = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0.0, |d| d.as_secs_f64());
        eprintln!("csgrt view: began at {epoch:.4} s after 1970");
    }
    let ran = event_loop.run_app(&mut app);
    // The window closes first; then the renders stop (a render at its
    // next row, a `.scad` export when OpenSCAD is done).
    drop(app.shown.take());
    ran.map_err(|e| no_display(job, &format!("the window system says: {e}")))?;
    match app.failed.take() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

impl App {
    /// Asks for the current view at the window's size.
    fn ask(&mut self) {
        if self.started && self.size.width > 0 && self.size.height > 0 {
            self.asked = self
                .renders
                .ask(self.view, self.size.width, self.size.height);
            self.note(&format!("asked view {}", self.asked));
        }
        self.title();
    }

    /// A line of `--log-frames`: seconds since the window began.
    fn note(&self, what: &str) {
        if self.log {
            let t = self.began.elapsed().as_secs_f64();
            eprintln!("csgrt view: {t:.4} s: {what}");
        }
    }

    fn title(&self) {
        let Some(s) = &self.shown else { return };
        let state = if self.error.is_some() {
            "error (the last good picture)"
        } else {
            match &self.frame {
                Some(f) if f.view == self.asked && f.pass == Pass::Final => "ready",
                _ => "rendering",
            }
        };
        s.window.set_title(&format!(
            "csgrt view — {} — {state}",
            csgrt::error::printable(&self.job.model.to_string_lossy())
        ));
    }

    /// The last picture (scaled to the window) and the error over it.
    fn draw(&mut self) {
        let Some(s) = &mut self.shown else { return };
        let PhysicalSize { width, height } = s.window.inner_size();
        let (Some(w), Some(h)) = (NonZeroU32::new(width), NonZeroU32::new(height)) else {
            return;
        };
        if s.surface.resize(w, h).is_err() {
            return;
        }
        let Ok(mut buf) = s.surface.buffer_mut() else {
            return;
        };
        match &self.frame {
            Some(f) => {
                // Each window pixel from the picture's pixel under it: the
                // same size, or a reduced picture's pixel n×n times.
                for y in 0..height {
                    let fy = ((y as u64 * f.height as u64) / height as u64) as usize;
                    let row = &mut buf[(y * width) as usize..((y + 1) * width) as usize];
                    for (x, p) in row.iter_mut().enumerate() {
                        let fx = ((x as u64 * f.width as u64) / width as u64) as usize;
                        let i = 3 * (fy * f.width as usize + fx);
                        let (r, g, b) = (f.rgb[i] as u32, f.rgb[i + 1] as u32, f.rgb[i + 2] as u32);
                        *p = r << 16 | g << 8 | b;
                    }
                }
            }
            None => buf.fill(0x00_30_30_30),
        }
        if let Some(e) = &self.error {
            overlay::draw(&mut buf, width, height, e);
        }
        let _ = buf.present();
    }

    fn key(&mut self, el: &ActiveEventLoop, code: KeyCode) {
        let ctrl = self.mods.control_key();
        let shift = self.mods.shift_key();
        let view = match (ctrl, shift, code) {
            (true, false, KeyCode::Digit4) => Some(ViewKey::Top),
            (true, false, KeyCode::Digit5) => Some(ViewKey::Bottom),
            (true, false, KeyCode::Digit6) => Some(ViewKey::Left),
            (true, false, KeyCode::Digit7) => Some(ViewKey::Right),
            (true, false, KeyCode::Digit8) => Some(ViewKey::Front),
            (true, false, KeyCode::Digit9) => Some(ViewKey::Back),
            (true, false, KeyCode::Digit0) => Some(ViewKey::Diagonal),
            (true, true, KeyCode::Digit0) => Some(ViewKey::Center),
            (true, true, KeyCode::KeyV) => Some(ViewKey::ViewAll),
            (true, _, KeyCode::BracketRight) => Some(ViewKey::ZoomIn),
            (true, _, KeyCode::BracketLeft) => Some(ViewKey::ZoomOut),
            (false, false, KeyCode::KeyR) => Some(ViewKey::Reset),
            (false, false, KeyCode::KeyP) => Some(ViewKey::Perspective),
            (false, false, KeyCode::KeyO) => Some(ViewKey::Orthogonal),
            _ => None,
        };
        if let Some(k) = view {
            self.view.key(k, &self.bounds);
            self.ask();
            return;
        }
        match (ctrl, code) {
            (false, KeyCode::KeyS) => self.renders.save(),
            (_, KeyCode::F5) => self.renders.read(),
            (false, KeyCode::KeyQ) | (_, KeyCode::Escape) => el.exit(),
            _ => {}
        }
    }

    fn reported(&mut self, t: Report) {
        match t {
            Report::Picture(f) => {
                // The newest picture is shown, of the view asked or of
                // one before it: while the mouse moves, each picture
                // comes after the next view has been asked for.
                if self.frame.as_ref().is_some_and(|old| old.view > f.view) {
                    return;
                }
                let pass = match f.pass {
                    Pass::Reduced(n) => format!("reduced 1/{n}"),
                    Pass::Full => "full".to_string(),
                    Pass::Final => "final".to_string(),
                };
                self.note(&format!(
                    "view {} {pass} {}x{} in {:.4} s",
                    f.view, f.width, f.height, f.seconds
                ));
                self.frame = Some(f);
                self.title();
                if let Some(s) = &self.shown {
                    s.window.request_redraw();
                }
            }
            Report::Read(bounds, file_view) => {
                self.bounds = bounds;
                self.error = None;
                if !self.started {
                    self.started = true;
                    let given = self.camera.or(file_view);
                    self.view = Orbit::start(given, &bounds, self.view.projection);
                }
                self.note("read");
                self.ask();
            }
            Report::Failed(message) => {
                self.error = Some(message);
                self.title();
                if let Some(s) = &self.shown {
                    s.window.request_redraw();
                }
            }
            Report::Saved(line) => println!("{line}"),
        }
    }
}

impl ApplicationHandler<Note> for App {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        if self.shown.is_some() {
            return;
        }
        let shown = el
            .create_window(
                Window::default_attributes()
                    .with_title("csgrt view")
                    .with_inner_size(self.size),
            )
            .map_err(|e| e.to_string())
            .and_then(|w| {
                let window = Rc::new(w);
                let context =
                    softbuffer::Context::new(window.clone()).map_err(|e| e.to_string())?;
                let surface = softbuffer::Surface::new(&context, window.clone())
                    .map_err(|e| e.to_string())?;
                Ok(Shown { window, surface })
            });
        match shown {
            Ok(s) => {
                self.shown = Some(s);
                self.title();
            }
            Err(e) => {
                self.failed = Some(no_display(&self.job, &format!("no window: {e}")));
                el.exit();
            }
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, note: Note) {
        match note {
            Note::Report(t) => self.reported(t),
            Note::Saved => {
                self.note("a file was saved");
                self.renders.read();
            }
            Note::WatchFailed(e) => eprintln!("{e}"),
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::RedrawRequested => self.draw(),
            WindowEvent::Resized(size) => {
                if size != self.size {
                    self.size = size;
                    self.ask();
                }
                if let Some(s) = &self.shown {
                    s.window.request_redraw();
                }
            }
            WindowEvent::ModifiersChanged(m) => self.mods = m.state(),
            // (winit makes up presses of the keys held when the window
            // gains focus: not the user's commands.)
            WindowEvent::KeyboardInput {
                event,
                is_synthetic: false,
                ..
            } => {
                if event.state == ElementState::Pressed && !event.repeat {
                    if let PhysicalKey::Code(code) = event.physical_key {
                        self.key(el, code);
                    }
                } else if event.state == ElementState::Pressed {
                    // Held zoom keys repeat.
                    if let PhysicalKey::Code(c @ (KeyCode::BracketLeft | KeyCode::BracketRight)) =
                        event.physical_key
                    {
                        self.key(el, c);
                    }
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let i = match button {
                    MouseButton::Left => 0,
                    MouseButton::Right => 1,
                    MouseButton::Middle => 2,
                    _ => return,
                };
                self.buttons[i] = state == ElementState::Pressed;
            }
            WindowEvent::CursorMoved { position, .. } => {
                let last = self.cursor.replace(position);
                let Some(last) = last else { return };
                let (dx, dy) = (position.x - last.x, position.y - last.y);
                if dx == 0.0 && dy == 0.0 {
                    return;
                }
                let shift = self.mods.shift_key();
                if self.buttons[0] {
                    self.view.rotate_by(dx, dy, shift);
                } else if self.buttons[1] || self.buttons[2] {
                    let (w, h) = (self.size.width, self.size.height);
                    self.view.pan_by(dx, dy, self.buttons[2], shift, w, h);
                } else {
                    return;
                }
                self.ask();
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::MouseWheel { delta, .. } => {
                let v = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y as f64 * NOTCH,
                    MouseScrollDelta::PixelDelta(p) => p.y,
                };
                if v != 0.0 {
                    let (w, h) = (self.size.width, self.size.height);
                    match self.cursor {
                        Some(c) => self.view.zoom_at(v, c.x, c.y, w, h),
                        None => self.view.zoom_by(v),
                    }
                    self.ask();
                }
            }
            _ => {}
        }
    }
}
