//! `--watch`: the image follows the model, and for a `.scad` model the
//! files OpenSCAD says it read; a broken save is reported and leaves the
//! last image; the watch goes on.

use crate::common;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

struct Watching(Child);

impl Drop for Watching {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn spawn(dir: &Path, args: &[&str], path: Option<&Path>) -> Watching {
    let log = std::fs::File::create(dir.join("log.txt")).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_csgrt"));
    cmd.current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(log);
    if let Some(p) = path {
        cmd.env("PATH", p);
    }
    Watching(cmd.spawn().unwrap())
}

/// Waits (up to 30 s) until `ok` holds; `log` is shown if it does not.
fn until(log: &Path, what: &str, mut ok: impl FnMut() -> bool) {
    let start = Instant::now();
    while !ok() {
        if start.elapsed() > Duration::from_secs(30) {
            let said = std::fs::read_to_string(log).unwrap_or_default();
            panic!("gave up waiting for {what}; csgrt said:\n{said}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn bytes(p: &Path) -> Option<Vec<u8>> {
    std::fs::read(p).ok()
}

/// A save as editors make it: a new file renamed over the old one.
fn save(p: &Path, text: &str) {
    let tmp = p.with_extension("tmp~");
    std::fs::write(&tmp, text).unwrap();
    std::fs::rename(&tmp, p).unwrap();
}

/// Follows three saves of `changed` (good, broken, good) while `csgrt` runs
/// with `args` and PATH `path`, writing `w.png`.
fn follows(
    dir: &Path,
    args: &[&str],
    path: Option<&Path>,
    changed: &Path,
    good: [&str; 2],
    bad: &str,
) {
    let out = dir.join("w.png");
    let log = dir.join("log.txt");
    let _w = spawn(dir, args, path);
    until(&log, "the first image", || bytes(&out).is_some());
    until(&log, "the watch to start", || {
        std::fs::read_to_string(&log).unwrap().contains("watching")
    });
    let first = bytes(&out).unwrap();
    save(changed, good[0]);
    until(&log, "the image of the first change", || {
        bytes(&out).is_some_and(|b| b != first)
    });
    let second = bytes(&out).unwrap();
    // Not the first image again: a sphere now (checked against a render
    // of it alone below by the caller's choice of models).
    assert_ne!(second, first);
    std::fs::write(changed, bad).unwrap();
    until(&log, "the error of the broken save", || {
        std::fs::read_to_string(&log).unwrap().contains("error")
    });
    assert_eq!(
        bytes(&out).unwrap(),
        second,
        "a failed render leaves the last image"
    );
    save(changed, good[1]);
    until(&log, "the image after the fix", || {
        bytes(&out).is_some_and(|b| b != second)
    });
    assert_eq!(
        bytes(&out).unwrap(),
        first,
        "the first model again, the first image"
    );
}

#[test]
fn watch_follows_a_csg_model() {
    let cube = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\ncube(2, center = true);\n";
    let ball = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\nsphere(1.2);\n";
    let (dir, model) = common::scene("m.csg", cube);
    follows(
        dir.path(),
        &["m.csg", "--watch", "--size", "40x30", "-o", "w.png"],
        None,
        &model,
        [ball, cube],
        "cube(2;\n",
    );
}

/// The stand-in `openscad` exports the contents of `part.inc` and lists
/// it, as OpenSCAD's `-d` does, among the files the program read.
#[cfg(unix)]
#[test]
fn watch_follows_what_a_scad_model_includes() {
    let cube = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\ncube(2, center = true);\n";
    let ball = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\nsphere(1.2);\n";
    let (dir, _) = common::scene("part.scad", "include <part.inc>\n");
    std::fs::write(dir.path().join("part.inc"), cube).unwrap();
    let bin = common::fake_openscad(
        r#"[ "$3" = "-d" ] || exit 3
while IFS= read -r l; do printf '%s\n' "$l"; done < part.inc > "$2"
printf 'out.csg: \\\n\tpart.inc \\\n\tpart.scad\n' > "$4""#,
    );
    follows(
        dir.path(),
        &["part.scad", "--watch", "--size", "40x30", "-o", "w.png"],
        Some(bin.path()),
        &dir.path().join("part.inc"),
        [ball, cube],
        "cube(2;\n",
    );
}

#[test]
fn watch_takes_one_image() {
    let (dir, _) = common::scene("a.csg", "cube(1);\n");
    std::fs::write(dir.path().join("b.csg"), "cube(1);\n").unwrap();
    for args in [
        &["a.csg", "b.csg", "--watch"][..],
        &["a.csg", "--watch", "-o", "-"],
        &["a.csg", "--watch", "--trace-rays", "-"],
        // Refused before the folder is made.
        &["a.csg", "b.csg", "--watch", "-O", "out"],
    ] {
        common::refused(dir.path(), args, "--watch", &["a.csg", "b.csg"]);
    }
}

/// A model that is not there when the watch starts is a mistake in the
/// command, said at once (exit 2), not waited for.
#[test]
fn watch_of_a_missing_model_stops_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let mut w = spawn(dir.path(), &["missing.csg", "--watch", "-q"], None);
    let log = dir.path().join("log.txt");
    until(&log, "csgrt to stop", || {
        matches!(w.0.try_wait(), Ok(Some(_)))
    });
    let status = w.0.wait().unwrap();
    assert_eq!(status.code(), Some(2));
    let said = std::fs::read_to_string(&log).unwrap();
    assert_eq!(said, "error: missing.csg: no such file\n");
}
