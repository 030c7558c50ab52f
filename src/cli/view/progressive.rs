//! The viewer's renders, on a thread of their own: the model read (again
//! on each save), and for each view asked for a picture in passes — at a
//! reduced resolution that keeps up with a moving view, then at full
//! resolution, then anti-aliased — each abandoned the moment another view
//! is asked for. The window never waits for them: it asks ([`Renders`])
//! and is reported ([`Report`]).

use super::orbit::Orbit;
use super::Cli;
use crate::cli::jobs::{watched_scene, Job};
use crate::cli::output::{render_files, settings};
use crate::cli::watch::Follow;
use csgrt::geometry::Aabb;
use csgrt::render::{self, Hooks, Settings};
use csgrt::scene::openscad_view::Viewpoint;
use csgrt::Scene;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Instant;

/// What a reduced-resolution picture may take, seconds: a moving view
/// then shows 30 or more pictures a second (with the time to show them).
pub const MOVING_BUDGET: f64 = 0.022;
/// The fewest and the most pixels a side of a reduced picture's pixel
/// stands for.
pub const MIN_REDUCTION: u32 = 2;
pub const MAX_REDUCTION: u32 = 16;

/// A pass of a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// Each pixel of the picture stands for `n`×`n` of the window's.
    Reduced(u32),
    /// Full resolution, a sample at each pixel's centre (anti-aliasing's
    /// first pass).
    Full,
    /// The picture `csgrt` writes.
    Final,
}

/// A picture for the window.
pub struct Picture {
    /// The view it shows ([`Renders::ask`]'s count).
    pub view: u64,
    pub pass: Pass,
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
    /// The render's time.
    pub seconds: f64,
}

/// What the render thread tells the window.
pub enum Report {
    Picture(Picture),
    /// The model was read: the box View All frames, and the view the
    /// program sets (`$vp*`).
    Read(Aabb, Option<Viewpoint>),
    /// Reading the model failed: the message (file, line, column, what
    /// was expected).
    Failed(String),
    /// The picture was written: the equivalent command line.
    Saved(String),
}

/// What the window wants.
#[derive(Clone, Debug)]
struct Wanted {
    view: Orbit,
    width: u32,
    height: u32,
    /// Counts the views asked for.
    count: u64,
    read: bool,
    save: bool,
    quit: bool,
}

/// The window's side: asks for views, reads, saves.
pub struct Renders {
    wanted: Arc<(Mutex<Wanted>, Condvar)>,
    /// The latest view's count, read by a render before each row.
    latest: Arc<AtomicU64>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Renders {
    /// Starts the render thread; it reads the model first and tells
    /// `tell` each thing it has.
    pub fn start(
        cli: &Cli,
        job: &Job,
        pool: rayon::ThreadPool,
        follow: Follow,
        tell: impl Fn(Report) + Send + Sync + 'static,
    ) -> csgrt::Result<Renders> {
        let wanted = Arc::new((
            Mutex::new(Wanted {
                view: Orbit::start(None, &Aabb::EMPTY, Default::default()),
                width: 0,
                height: 0,
                count: 0,
                read: true,
                save: false,
                quit: false,
            }),
            Condvar::new(),
        ));
        let latest = Arc::new(AtomicU64::new(0));
        let mut worker = Worker {
            cli: cli.clone(),
            job: job.clone(),
            wanted: wanted.clone(),
            latest: latest.clone(),
            follow,
            kept: None,
            scene: None,
            shown: None,
            per_pixel: None,
            broken: false,
        };
        let thread = std::thread::Builder::new()
            .name("csgrt view renders".into())
            .stack_size(csgrt::syntax::MAIN_STACK)
            .spawn(move || pool.install(|| worker.run(&tell)))
            .map_err(|e| csgrt::Error::Usage(format!("cannot start the render thread: {e}")))?;
        Ok(Renders {
            wanted,
            latest,
            thread: Some(thread),
        })
    }

    fn change(&self, f: impl FnOnce(&mut Wanted)) {
        let (lock, wake) = &*self.wanted;
        let mut w = lock.lock().unwrap_or_else(|p| p.into_inner());
        f(&mut w);
        wake.notify_one();
    }

    /// Counts one more thing asked that the render under way must stop
    /// for (at its next row); the new count.
    fn supersede(&self, w: &mut Wanted) -> u64 {
        w.count += 1;
        self.latest.store(w.count, Ordering::SeqCst);
        w.count
    }

    /// Asks for `view` in a `width`×`height` window; returns its count.
    /// The render under way stops at its next row.
    pub fn ask(&self, view: Orbit, width: u32, height: u32) -> u64 {
        let mut count = 0;
        self.change(|w| {
            (w.view, w.width, w.height) = (view, width, height);
            count = self.supersede(w);
        });
        count
    }

    /// Asks for the model to be read again (it was saved), then the
    /// current view.
    pub fn read(&self) {
        self.change(|w| {
            w.read = true;
            self.supersede(w);
        });
    }

    /// Asks for the current view written as `csgrt` would write it.
    pub fn save(&self) {
        self.change(|w| w.save = true);
    }
}

impl Drop for Renders {
    fn drop(&mut self) {
        self.change(|w| {
            w.quit = true;
            self.supersede(w);
        });
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

struct Worker {
    cli: Cli,
    job: Job,
    wanted: Arc<(Mutex<Wanted>, Condvar)>,
    latest: Arc<AtomicU64>,
    follow: Follow,
    /// A `.scad` model's export kept for a message.
    kept: Option<PathBuf>,
    scene: Option<Scene>,
    /// The count of the view whose final picture was last made.
    shown: Option<u64>,
    /// Seconds a pixel of a one-sample pass took last.
    per_pixel: Option<f64>,
    /// Whether the model's last read failed (the scene is the one before).
    broken: bool,
}

impl Worker {
    fn run(&mut self, tell: &(dyn Fn(Report) + Sync)) {
        loop {
            let w = {
                let (lock, wake) = &*self.wanted;
                let mut w = lock.lock().unwrap_or_else(|p| p.into_inner());
                while !(w.quit
                    || w.read
                    || (w.save && self.shown == Some(w.count))
                    || (w.width > 0 && self.scene.is_some() && self.shown != Some(w.count)))
                {
                    w = wake.wait(w).unwrap_or_else(|p| p.into_inner());
                }
                let now = w.clone();
                w.read = false;
                if self.shown == Some(w.count) {
                    w.save = false;
                }
                now
            };
            if w.quit {
                return;
            }
            if w.read {
                if !self.read(tell) {
                    // The last good model's picture of this view is the
                    // one shown: not rendered again.
                    self.shown = Some(w.count);
                }
                continue;
            }
            if w.save && self.shown == Some(w.count) {
                self.save(&w, tell);
                continue;
            }
            self.picture(&w, tell);
        }
    }

    /// Reads the model; on success follows the files it was read from.
    /// Whether it was read.
    fn read(&mut self, tell: &(dyn Fn(Report) + Sync)) -> bool {
        match watched_scene(&self.cli, &self.job, &mut self.kept) {
            Ok((scene, deps)) => {
                if let Err(e) = self.follow.set(&deps, &self.job.model) {
                    eprintln!("{e}");
                }
                tell(Report::Read(scene.result_bounds(), scene.scad_view));
                self.scene = Some(scene);
                self.shown = None;
                self.broken = false;
                true
            }
            Err(e) => {
                eprintln!("{e}");
                tell(Report::Failed(e.to_string()));
                self.broken = true;
                if self.follow.count() == 0 {
                    if let Err(e) = self.follow.set(&[], &self.job.model) {
                        eprintln!("{e}");
                    }
                }
                false
            }
        }
    }

    /// The passes of view `w.count`, each reported as it is done; stops where
    /// another view is asked for.
    fn picture(&mut self, w: &Wanted, tell: &(dyn Fn(Report) + Sync)) {
        let Some(scene) = self.scene.as_mut() else {
            return;
        };
        let stop = || self.latest.load(Ordering::SeqCst) != w.count;
        let full = settings(&self.cli, w.width, w.height, false);
        // Reduced so that a pass takes about MOVING_BUDGET at the last
        // pass's speed, and by 2 at least: the full pass is abandoned at
        // the next view, so a view that moves is only ever seen reduced.
        let pixels = w.width as f64 * w.height as f64;
        let n = self.per_pixel.map_or(4, |s| {
            ((pixels * s / MOVING_BUDGET).sqrt().ceil() as u32).clamp(MIN_REDUCTION, MAX_REDUCTION)
        });
        let (rw, rh) = ((w.width / n).max(1), (w.height / n).max(1));
        scene.camera = Some(w.view.camera(rw, rh));
        let reduced = Settings {
            width: rw,
            height: rh,
            spp: 1,
            adaptive: None,
            ..full
        };
        // Not stopped by the next view: views come faster than such
        // pictures while the mouse moves, and each is shown, the
        // latest view taken after it.
        let start = Instant::now();
        let img = render::render(scene, &reduced, &|_| {});
        let seconds = start.elapsed().as_secs_f64();
        self.per_pixel = Some(seconds / (rw as f64 * rh as f64));
        tell(Report::Picture(Picture {
            view: w.count,
            pass: Pass::Reduced(n),
            width: rw,
            height: rh,
            rgb: img.rgb,
            seconds,
        }));
        scene.camera = Some(w.view.camera(w.width, w.height));
        let start = Instant::now();
        let first = Mutex::new(None);
        let first_pass = |rgb: &[u8]| {
            let seconds = start.elapsed().as_secs_f64();
            *first.lock().unwrap_or_else(|p| p.into_inner()) = Some(seconds);
            tell(Report::Picture(Picture {
                view: w.count,
                pass: Pass::Full,
                width: w.width,
                height: w.height,
                rgb: rgb.to_vec(),
                seconds,
            }));
        };
        let hooks = Hooks {
            progress: &|_| {},
            stop: &stop,
            first_pass: &first_pass,
        };
        let done = render::render_with(scene, &full, &hooks);
        let seconds = start.elapsed().as_secs_f64();
        let one_pass = first.into_inner().unwrap_or_else(|p| p.into_inner());
        if let Some(s) = one_pass.or(done.is_some().then_some(seconds)) {
            self.per_pixel = Some(s / pixels);
        }
        let Some(img) = done else { return };
        self.shown = Some(w.count);
        tell(Report::Picture(Picture {
            view: w.count,
            pass: Pass::Final,
            width: w.width,
            height: w.height,
            rgb: img.rgb,
            seconds,
        }));
    }

    /// Writes the view as the command line would, through its own code,
    /// and tells the command line.
    fn save(&mut self, w: &Wanted, tell: &(dyn Fn(Report) + Sync)) {
        let Some(scene) = self.scene.as_mut() else {
            return;
        };
        if self.broken {
            // The command line would read the broken file.
            eprintln!(
                "csgrt view: not written: the model's last save has an error (above); \
                 the window shows the last good picture"
            );
            return;
        }
        let cli = Cli {
            size: (w.width, w.height),
            imgsize: None,
            camera: Some(w.view.viewpoint()),
            projection: Some(w.view.projection),
            ..self.cli.clone()
        };
        scene.camera = Some(w.view.camera(w.width, w.height));
        match render_files(&cli, &self.job, scene, false) {
            Ok(()) => tell(Report::Saved(super::command_line(
                &self.cli, &self.job, &w.view, w.width, w.height,
            ))),
            Err(e) => eprintln!("{e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use std::sync::mpsc;
    use std::time::Duration;

    /// The render thread without a window: a view's passes come reduced,
    /// full, then final, and the final picture is `render`'s with the
    /// command line's settings and `--camera`, bit for bit; views asked
    /// one after another end in the last one's final picture, none
    /// after it.
    #[test]
    fn a_views_passes_end_in_the_command_lines_picture() {
        let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/csg_ops.csg");
        let cli = Cli::try_parse_from(["csgrt", model, "--size", "160x120", "-q"]).unwrap();
        let job = crate::cli::jobs::jobs(&cli).unwrap().remove(0);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let (follow, _changes) = Follow::new().unwrap();
        let (tx, rx) = mpsc::channel();
        let tx = Mutex::new(tx);
        let renders = Renders::start(&cli, &job, pool, follow, move |r| {
            let _ = tx.lock().unwrap().send(r);
        })
        .unwrap();
        let next = || rx.recv_timeout(Duration::from_secs(60)).expect("a report");
        let Report::Read(bounds, view) = next() else {
            panic!("the model read first")
        };
        let orbit = Orbit::start(view, &bounds, Default::default());
        let final_of = |count: u64| loop {
            match next() {
                Report::Picture(p) if p.view == count && p.pass == Pass::Final => return p,
                Report::Picture(p) => assert!(p.view <= count),
                _ => panic!("only pictures"),
            }
        };
        let first = renders.ask(orbit, 160, 120);
        let mut passes = Vec::new();
        let got = loop {
            match next() {
                Report::Picture(p) if p.pass == Pass::Final => break p,
                Report::Picture(p) => passes.push(p.pass),
                _ => panic!("only pictures"),
            }
        };
        assert_eq!(got.view, first);
        assert!(
            matches!(passes[..], [Pass::Reduced(4), Pass::Full]),
            "{passes:?}"
        );
        let mut scene = csgrt::load(std::path::Path::new(model)).unwrap();
        scene.camera = Some(orbit.camera(160, 120));
        let want = render::render(&scene, &settings(&cli, 160, 120, false), &|_| {});
        assert!(got.rgb == want.rgb, "the final picture is not render's");
        let mut moved = orbit;
        let mut last = 0;
        for i in 0..8 {
            moved.rotate_by(7.0 * i as f64, 3.0, false);
            last = renders.ask(moved, 160, 120);
        }
        let p = final_of(last);
        scene.camera = Some(moved.camera(160, 120));
        let want = render::render(&scene, &settings(&cli, 160, 120, false), &|_| {});
        assert!(p.rgb == want.rgb);
        assert!(
            rx.recv_timeout(Duration::from_millis(300)).is_err(),
            "nothing after the last final"
        );
    }
}
