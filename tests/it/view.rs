//! `csgrt view` on a virtual X display (Debian's `xvfb`, driven by
//! `xdotool`, its window read back by ImageMagick's `import`; `.ci/run`
//! installs them): the window's pixels, once refined, are the picture
//! `csgrt` writes with the command line the viewer printed — after
//! drags, the wheel and OpenSCAD's view keys — and the drags move the
//! camera by OpenSCAD's amounts; a save is followed, a broken save shows
//! its message over the last picture and the next good one clears it.
//! Without a display the viewer says so and stops (exit 2).

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_csgrt");
/// How long any one wait may take.
const PATIENCE: Duration = Duration::from_secs(40);

/// A process killed when dropped.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn needs(tool: &str) {
    let found = Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {tool}"))
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        found,
        "`{tool}` is not installed: the viewer's test needs Debian's xvfb, xdotool and \
         imagemagick (`apt-get install -y xvfb xdotool imagemagick`, as .ci/run does)"
    );
}

/// An X server of its own on a free display number (from `base` up: each
/// test its own range).
fn xvfb(base: u32) -> (Running, String) {
    for tool in ["Xvfb", "xdotool", "import"] {
        needs(tool);
    }
    for n in (base + std::process::id() % 200)..(base + 400) {
        if Path::new(&format!("/tmp/.X{n}-lock")).exists()
            || Path::new(&format!("/tmp/.X11-unix/X{n}")).exists()
        {
            continue;
        }
        let display = format!(":{n}");
        let x = Running(
            Command::new("Xvfb")
                .args([&display, "-screen", "0", "1024x768x24", "-nolisten", "tcp"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .expect("Xvfb starts"),
        );
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(10) {
            if Path::new(&format!("/tmp/.X11-unix/X{n}")).exists() {
                return (x, display);
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
    panic!("no X display could be started");
}

struct Viewer {
    display: String,
    window: String,
    out: PathBuf,
    log: PathBuf,
    dir: PathBuf,
    _child: Running,
}

impl Viewer {
    fn xdo(&self, args: &[&str]) -> String {
        let out = Command::new("xdotool")
            .args(args)
            .env("DISPLAY", &self.display)
            .output()
            .expect("xdotool runs");
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    }

    fn said(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }

    fn until(&self, what: &str, mut ok: impl FnMut() -> bool) {
        let start = Instant::now();
        while !ok() {
            if start.elapsed() > PATIENCE {
                panic!(
                    "gave up waiting for {what}; csgrt view said:\n{}",
                    self.said()
                );
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn title(&self) -> String {
        self.xdo(&["getwindowname", &self.window])
    }

    /// The window's pixels, read back from the X server.
    fn screenshot(&self) -> image::RgbImage {
        let path = self.dir.join("shot.png");
        let ok = Command::new("import")
            .args(["-window", &self.window, &format!("png:{}", path.display())])
            .env("DISPLAY", &self.display)
            .status()
            .is_ok_and(|s| s.success());
        assert!(ok, "import could not read the window");
        image::open(&path).expect("a screenshot").to_rgb8()
    }

    /// Presses `s` and returns the command line it prints.
    fn save(&self) -> String {
        let before = self.lines().len();
        self.xdo(&["key", "s"]);
        self.until("the command line", || self.lines().len() > before);
        self.lines()[before].clone()
    }

    fn lines(&self) -> Vec<String> {
        std::fs::read_to_string(&self.out)
            .unwrap_or_default()
            .lines()
            .map(String::from)
            .collect()
    }

    /// Waits until the window shows `want` exactly.
    fn shows(&self, want: &image::RgbImage, what: &str) {
        let start = Instant::now();
        loop {
            let got = self.screenshot();
            if got == *want {
                return;
            }
            if start.elapsed() > PATIENCE {
                let differ = if got.dimensions() == want.dimensions() {
                    got.pixels()
                        .zip(want.pixels())
                        .filter(|(a, b)| a != b)
                        .count()
                } else {
                    usize::MAX
                };
                panic!(
                    "the window never showed {what}: {differ} pixels differ (window {:?}, \
                     picture {:?}); csgrt view said:\n{}",
                    got.dimensions(),
                    want.dimensions(),
                    self.said()
                );
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// Drags with `button` from (x, y) by (dx, dy) in steps.
    fn drag(&self, button: &str, x: i32, y: i32, dx: i32, dy: i32, mods: Option<&str>) {
        let w = self.window.clone();
        self.xdo(&["mousemove", "--window", &w, &x.to_string(), &y.to_string()]);
        if let Some(m) = mods {
            self.xdo(&["keydown", m]);
        }
        self.xdo(&["mousedown", button]);
        for i in 1..=10 {
            let (px, py) = (x + dx * i / 10, y + dy * i / 10);
            self.xdo(&[
                "mousemove",
                "--window",
                &w,
                &px.to_string(),
                &py.to_string(),
            ]);
        }
        self.xdo(&["mouseup", button]);
        if let Some(m) = mods {
            self.xdo(&["keyup", m]);
        }
    }
}

/// `csgrt` run with a printed command line (its `csgrt` this build).
fn render(line: &str, dir: &Path) -> image::RgbImage {
    let rest = line.strip_prefix("csgrt ").expect("a csgrt command line");
    let path = dir.join("cli.png");
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("'{BIN}' {rest} -q -o '{}'", path.display()))
        .current_dir(dir)
        .output()
        .expect("csgrt runs");
    assert!(
        out.status.success(),
        "{line}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    image::open(&path).expect("the picture").to_rgb8()
}

/// The seven numbers of a printed `--camera`.
fn camera(line: &str) -> Vec<f64> {
    let words: Vec<&str> = line.split(' ').collect();
    let i = words
        .iter()
        .position(|w| *w == "--camera")
        .expect("--camera");
    words[i + 1]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect()
}

fn write(p: &Path, text: &str) {
    let tmp = p.with_extension("tmp~");
    std::fs::write(&tmp, text).unwrap();
    std::fs::rename(&tmp, p).unwrap();
}

const FIRST: &str = "color([0.9, 0.5, 0.2]) difference() {\n  cube(size = [20, 14, 10], center = true);\n  sphere(r = 8);\n}\ntranslate([16, 0, 0]) cylinder(h = 12, r1 = 4, r2 = 1, center = true);\n";
const SECOND: &str =
    "sphere(r = 9);\ntranslate([0, 0, 9]) cube(size = [4, 4, 8], center = true);\n";
const BROKEN: &str = "sphere(r = ;\n";

/// `csgrt view MODEL --size 320x240` in `dir` on its own display, once its
/// window is up and its first view refined.
fn open(dir: &Path, model: &str, base: u32) -> (Running, Viewer) {
    let (x, display) = xvfb(base);
    let (out, log) = (dir.join("out.txt"), dir.join("log.txt"));
    let child = Command::new(BIN)
        .args(["view", model, "--size", "320x240"])
        .current_dir(dir)
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out).unwrap())
        .stderr(std::fs::File::create(&log).unwrap())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    let mut v = Viewer {
        display,
        window: String::new(),
        out,
        log,
        dir: dir.to_path_buf(),
        _child: Running(child),
    };
    let found = v.xdo(&["search", "--sync", "--pid", &pid]);
    v.window = found.lines().next().expect("the window").to_string();
    v.xdo(&["windowfocus", "--sync", &v.window]);
    v.until("the first picture", || v.title().ends_with("ready"));
    (x, v)
}

#[test]
fn the_window_shows_what_the_printed_command_line_writes() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().to_path_buf();
    let model = dir.join("part.csg");
    write(&model, FIRST);
    let (_x, v) = open(&dir, "part.csg", 100);

    // The first view: OpenSCAD's reset view moved to see all.
    let line = v.save();
    let first = camera(&line);
    assert_eq!(&first[3..6], &[55.0, 0.0, 25.0], "{line}");
    let want = render(&line, &dir);
    assert_eq!(want.dimensions(), (320, 240));
    v.shows(&want, "the first view");
    // The picture `s` wrote is the command line's, to the byte.
    let written = image::open(dir.join("part.png")).unwrap().to_rgb8();
    assert!(
        written == want,
        "the written picture is not the command line's"
    );

    // A left drag: 0.7° a pixel, down tilts ($vpr.x falls), across turns
    // about z ($vpr.z falls), as in OpenSCAD.
    v.drag("1", 100, 100, 60, 20, None);
    let line = v.save();
    let moved = camera(&line);
    let near = |a: f64, b: f64| ((a - b + 540.0).rem_euclid(360.0) - 180.0).abs() < 1e-6;
    assert!(near(moved[3], first[3] - 0.7 * 20.0), "{line}");
    assert!(near(moved[5], first[5] - 0.7 * 60.0), "{line}");
    assert_eq!(moved[6], first[6]);
    v.shows(&render(&line, &dir), "the orbited view");

    // Right drag (pan), middle drag, shift+left, two notches of the wheel.
    v.drag("3", 150, 120, -40, 30, None);
    v.drag("2", 150, 120, 0, -25, None);
    v.drag("1", 120, 150, 30, 0, Some("shift"));
    v.xdo(&["click", "4", "click", "4"]);
    let line = v.save();
    let c = camera(&line);
    assert!(near(c[4], -0.7 * 30.0), "{line}");
    // The middle drag moved the centre along the line of sight, not the
    // distance; each notch in takes 0.9 of it. (Xvfb's XTest pointer
    // sends a notch twice, as a button and as a scroll valuator, and
    // winit reads both: two clicks are 2 or 4 notches.)
    let notches = (c[6] / moved[6]).ln() / 0.9f64.ln();
    assert!(
        [2.0, 4.0].iter().any(|n| (notches - n).abs() < 1e-9),
        "{notches} notches: {line} after {moved:?}"
    );
    v.shows(&render(&line, &dir), "the panned and zoomed view");

    // OpenSCAD's view keys: Ctrl+4 the top, then View All, orthogonal.
    v.xdo(&["key", "ctrl+4"]);
    let line = v.save();
    assert_eq!(&camera(&line)[3..6], &[0.0, 0.0, 0.0], "{line}");
    v.shows(&render(&line, &dir), "the top view");
    v.xdo(&["key", "ctrl+8", "ctrl+shift+v", "o"]);
    let line = v.save();
    assert!(line.contains("--projection ortho"), "{line}");
    assert_eq!(&camera(&line)[3..6], &[90.0, 0.0, 0.0], "{line}");
    let orthographic = render(&line, &dir);
    v.shows(&orthographic, "the front view, all of it, orthogonal");

    // A save of the model: the same view of the new model.
    write(&model, SECOND);
    let second = render(&line, &dir);
    assert!(second != orthographic);
    v.shows(&second, "the saved model");

    // A broken save: its message (file, line, column) over the last
    // picture, dimmed; the window title says so.
    write(&model, BROKEN);
    v.until("the broken save's message", || v.title().contains("error"));
    assert!(v.said().contains("part.csg:1:12"), "{}", v.said());
    let shot = v.screenshot();
    let white = shot.pixels().filter(|p| p.0 == [255, 255, 255]).count();
    assert!(white > 100, "{white} white pixels of text");
    let dimmed = shot
        .pixels()
        .zip(second.pixels())
        .filter(|(a, b)| {
            a.0.iter()
                .zip(b.0)
                .all(|(x, y)| *x as u32 <= (y as u32 * 3).div_ceil(10))
        })
        .count();
    assert!(dimmed > 320 * 240 * 8 / 10, "{dimmed} pixels dimmed");
    // `s` writes nothing while the model is broken (its command line
    // would read the broken file).
    let lines = v.lines().len();
    v.xdo(&["key", "s"]);
    v.until("the refusal to write", || v.said().contains("not written"));
    assert_eq!(v.lines().len(), lines);
    // Fixed again: the picture, the message gone.
    write(&model, SECOND.replace("r = 9", "r = 8").as_str());
    v.shows(&render(&line, &dir), "the model fixed again");
    assert!(v.title().ends_with("ready"));
    // One command line for each of the five `s` that wrote a picture.
    assert_eq!(v.lines().len(), 5, "{:?}", v.lines());
    v.xdo(&["key", "q"]);
}

/// Over SSH or headless: the viewer says there is no display, exit 2,
/// and writes nothing.
#[test]
fn without_a_display_the_viewer_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let model = tmp.path().join("part.csg");
    std::fs::write(&model, FIRST).unwrap();
    let out = Command::new(BIN)
        .args(["view", "part.csg"])
        .current_dir(tmp.path())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no display") && err.contains("DISPLAY"),
        "{err}"
    );
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 1);
    // A second model, or an option for files, is said as such.
    let out = Command::new(BIN)
        .args(["view", "part.csg", "--animate", "3"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// A `.scad` model: a save of a file it includes is followed too (the
/// files OpenSCAD says it read), the view kept.
#[test]
fn a_save_of_an_included_file_is_followed() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().to_path_buf();
    write(&dir.join("sizes.scad"), "w = 12;\n");
    write(
        &dir.join("part.scad"),
        "include <sizes.scad>\ndifference() { cube([w, 10, 8], center = true); cylinder(h = 20, r = 3, center = true); }\n",
    );
    let (_x, v) = open(&dir, "part.scad", 600);
    v.drag("1", 100, 100, -40, 10, None);
    let line = v.save();
    let before = render(&line, &dir);
    v.shows(&before, "the dragged view");
    write(&dir.join("sizes.scad"), "w = 24;\n");
    let after = render(&line, &dir);
    assert!(after != before);
    v.shows(&after, "the included file's change");
    v.xdo(&["key", "q"]);
}
