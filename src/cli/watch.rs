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
use std::sync::{mpsc, Arc, Mutex};
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

/// The files a render was read from, their folders watched for changes;
/// [`Changes`] waits for the next one.
pub(super) struct Follow {
    watcher: notify::RecommendedWatcher,
    folders: HashSet<PathBuf>,
    files: Arc<Mutex<HashSet<PathBuf>>>,
}

/// The events of a [`Follow`]'s watcher, waited on (by another thread, if
/// need be, than the one that changes what is followed).
pub(super) struct Changes {
    rx: mpsc::Receiver<notify::Result<notify::Event>>,
    files: Arc<Mutex<HashSet<PathBuf>>>,
}

impl Follow {
    pub(super) fn new() -> Result<(Follow, Changes)> {
        let (tx, rx) = mpsc::channel();
        let watcher = notify::recommended_watcher(tx).map_err(|e| failed("<file watcher>", e))?;
        let files = Arc::new(Mutex::new(HashSet::new()));
        let changes = Changes {
            rx,
            files: files.clone(),
        };
        let follow = Follow {
            watcher,
            folders: HashSet::new(),
            files,
        };
        Ok((follow, changes))
    }

    /// Follows `deps` (a render's files; none: the model alone) from now
    /// on; whether they are other files than before.
    pub(super) fn set(&mut self, deps: &[PathBuf], model: &Path) -> Result<bool> {
        let mut files: HashSet<PathBuf> = deps.iter().filter_map(|p| absolute(p)).collect();
        if files.is_empty() {
            files.extend(absolute(model));
        }
        for f in &files {
            let dir = f.parent().unwrap_or(Path::new("/")).to_path_buf();
            if self.folders.insert(dir.clone()) {
                self.watcher
                    .watch(&dir, RecursiveMode::NonRecursive)
                    .map_err(|e| failed(&dir, e))?;
            }
        }
        let mut now = self.files.lock().unwrap_or_else(|p| p.into_inner());
        let other = *now != files;
        *now = files;
        Ok(other)
    }

    /// How many files are followed.
    pub(super) fn count(&self) -> usize {
        self.files.lock().unwrap_or_else(|p| p.into_inner()).len()
    }
}

impl Changes {
    /// Waits for a change to one of the files, then for them to be quiet
    /// for [`SETTLE`] (reads, and changes to other files in the folders,
    /// do not count).
    pub(super) fn next(&self) -> Result<()> {
        let changed = |e: &notify::Result<notify::Event>| {
            let files = self.files.lock().unwrap_or_else(|p| p.into_inner());
            e.as_ref().is_ok_and(|e| {
                !matches!(e.kind, notify::EventKind::Access(_))
                    && e.paths.iter().any(|p| files.contains(p))
            })
        };
        let lost = |_: mpsc::RecvError| failed("<file watcher>", "the watch stopped");
        while !changed(&self.rx.recv().map_err(lost)?) {}
        let mut last = Instant::now();
        loop {
            match self.rx.recv_timeout(SETTLE.saturating_sub(last.elapsed())) {
                Ok(e) if changed(&e) => last = Instant::now(),
                Ok(_) => {}
                Err(mpsc::RecvTimeoutError::Timeout) => return Ok(()),
                Err(mpsc::RecvTimeoutError::Disconnected) => return Err(lost(mpsc::RecvError)),
            }
        }
    }
}

/// Renders `job` until the process is stopped; returns only if watching
/// cannot start or stops working.
pub(crate) fn watch(cli: &Cli, job: &Job) -> Result<()> {
    // A model that is not there (or is a folder) at the start is a
    // mistake in the command, not a file being saved: said, exit 2.
    csgrt::source::model_file(&job.model)?;
    let (mut follow, changes) = Follow::new()?;
    // The last export kept for a message (one at a time).
    let mut kept = None;
    loop {
        let read = match watched_scene(cli, job, &mut kept) {
            Ok((scene, deps)) => render_files(cli, job, &scene, true).map(|()| deps),
            Err(e) => Err(e),
        };
        let deps = match read {
            Ok(deps) => Some(deps),
            Err(e) => {
                eprintln!("{e}");
                None
            }
        };
        // (A failed read keeps following the files it was last read from.)
        let other = match &deps {
            Some(d) => follow.set(d, &job.model)?,
            None if follow.count() == 0 => follow.set(&[], &job.model)?,
            None => false,
        };
        if !cli.quiet && other {
            let n = follow.count();
            eprintln!(
                "csgrt: watching {n} file{} for changes (Ctrl-C stops)",
                if n == 1 { "" } else { "s" }
            );
        }
        changes.next()?;
    }
}
