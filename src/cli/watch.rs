//! `--watch`: render, then render again each time the model, or a file a
//! `.scad` model reads (OpenSCAD's own dependency list), changes.
//!
//! The folders holding those files are watched (not the files: editors
//! save by writing a new file and renaming it over the old one), and an
//! event counts when it names one of the files. Events that come within
//! [`SETTLE`] of each other are one change. A render that fails is
//! reported like any other and leaves the last good image in place; the
//! watch goes on until the process is stopped.

use super::jobs::{watched_scene, Job};
use super::output::render_files;
use super::Cli;
use csgrt::error::{Error, Result};
use notify::{RecursiveMode, Watcher};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long the files must be quiet before a change is rendered.
pub const SETTLE: Duration = Duration::from_millis(100);

/// `path` made absolute through its folder, which must exist (the file
/// itself may be mid-save).
fn absolute(path: &Path) -> Option<PathBuf> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    Some(dir.canonicalize().ok()?.join(path.file_name()?))
}

/// The watcher's failure at `what`, as the system's (exit status 1).
fn failed(
    what: impl Into<PathBuf>,
    e: impl Into<Box<dyn std::error::Error + Send + Sync>>,
) -> Error {
    Error::io(what, std::io::Error::other(e))
}

/// Renders `job` until the process is stopped; returns only if watching
/// cannot start or stops working.
pub(crate) fn watch(cli: &Cli, job: &Job) -> Result<()> {
    // A model that is not there (or is a folder) at the start is a
    // mistake in the command, not a file being saved: said, exit 2.
    csgrt::source::model_file(&job.model)?;
    let (tx, rx) = mpsc::channel();
    let mut watcher = notify::recommended_watcher(tx).map_err(|e| failed("<file watcher>", e))?;
    let mut folders = HashSet::new();
    let mut files: HashSet<PathBuf> = HashSet::new();
    // The last export kept for a message (one at a time).
    let mut kept = None;
    loop {
        let read = match watched_scene(cli, job, &mut kept) {
            Ok((scene, deps)) => render_files(cli, job, &scene, true).map(|()| deps),
            Err(e) => Err(e),
        };
        let before = files.clone();
        match read {
            Ok(deps) => files = deps.iter().filter_map(|p| absolute(p)).collect(),
            Err(e) => eprintln!("{e}"),
        }
        if files.is_empty() {
            files.extend(absolute(&job.model));
        }
        for f in &files {
            let dir = f.parent().unwrap_or(Path::new("/")).to_path_buf();
            if folders.insert(dir.clone()) {
                watcher
                    .watch(&dir, RecursiveMode::NonRecursive)
                    .map_err(|e| failed(&dir, e))?;
            }
        }
        if !cli.quiet && files != before {
            eprintln!(
                "csgrt: watching {} file{} for changes (Ctrl-C stops)",
                files.len(),
                if files.len() == 1 { "" } else { "s" }
            );
        }
        // Wait for a change to one of the files, then for them to be quiet
        // for SETTLE (reads, and changes to other files in the folders,
        // do not count).
        let changed = |e: &notify::Result<notify::Event>| {
            e.as_ref().is_ok_and(|e| {
                !matches!(e.kind, notify::EventKind::Access(_))
                    && e.paths.iter().any(|p| files.contains(p))
            })
        };
        let lost = |_: mpsc::RecvError| failed("<file watcher>", "the watch stopped");
        while !changed(&rx.recv().map_err(lost)?) {}
        let mut last = Instant::now();
        loop {
            match rx.recv_timeout(SETTLE.saturating_sub(last.elapsed())) {
                Ok(e) if changed(&e) => last = Instant::now(),
                Ok(_) => {}
                Err(mpsc::RecvTimeoutError::Timeout) => break,
                Err(mpsc::RecvTimeoutError::Disconnected) => return Err(lost(mpsc::RecvError)),
            }
        }
    }
}
