//! `csgrt view MODEL`: a window showing the model as `csgrt` renders it,
//! moved with the mouse and keys as in OpenSCAD, following every save of
//! the model and what it reads (docs/CLI.md, "csgrt view").
//!
//! Three threads: the window's (events, showing pictures: `window.rs`),
//! the renders' (`progressive.rs`, with the render pool under it) and the
//! file watch's, which only waits for saves. The view is OpenSCAD's
//! `--camera` numbers (`orbit.rs`), so a picture found by hand is
//! written again, bit for bit, by the command line the viewer prints.

mod orbit;
mod overlay;
mod progressive;
mod window;

use super::jobs::Job;
use super::Cli;
use csgrt::error::{Error, Result};
use orbit::Orbit;

/// Whether the environment names a display a window can open on.
fn has_display() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

/// The message for a viewer that cannot open its window.
fn no_display(job: &Job, why: &str) -> Error {
    Error::Usage(format!(
        "csgrt view opens a window, and there is no display: {why} (over SSH, connect with \
         `ssh -X`; without a display, write the picture instead: `csgrt {}`)",
        quote(&job.model.to_string_lossy())
    ))
}

/// Runs the viewer on `job` until its window is closed.
pub(super) fn view(cli: &Cli, jobs: &[Job], pool: rayon::ThreadPool) -> Result<()> {
    let mut refused = std::iter::once(("--animate", cli.animate.is_some()))
        .chain(cli.one_file_outputs())
        .chain([
            ("--watch", cli.watch),
            ("--viewall", cli.viewall),
            ("--autocenter", cli.autocenter),
            ("-O", cli.output_dir.is_some()),
        ]);
    if let Some((opt, _)) = refused.find(|(_, on)| *on) {
        return Err(Error::Usage(format!(
            "{opt} is not for csgrt view (a window that follows the model; it starts from the \
             program's view or views all, and its `s` key writes the picture)"
        )));
    }
    let [job] = jobs else {
        return Err(Error::Usage("csgrt view shows one model".into()));
    };
    if job.output == std::path::Path::new("-") {
        return Err(Error::Usage(
            "-o - writes to standard output; csgrt view writes its pictures to files".into(),
        ));
    }
    // A model that is not there (or is a folder) is a mistake in the
    // command, not a file being saved.
    csgrt::source::model_file(&job.model)?;
    if !has_display() {
        return Err(no_display(
            job,
            "neither DISPLAY nor WAYLAND_DISPLAY is set",
        ));
    }
    window::run(cli, job, pool)
}

/// An argument as a POSIX shell reads it back.
fn quote(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-+=.,/:@%".contains(c));
    if plain {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

/// The command line that writes the picture of `view` in a
/// `width`×`height` window: the model, its options, `--camera`, `--size`
/// and `--projection`.
fn command_line(cli: &Cli, job: &Job, view: &Orbit, width: u32, height: u32) -> String {
    let mut args = vec!["csgrt".to_string(), quote(&job.model.to_string_lossy())];
    let mut add = |a: &str, v: String| {
        args.push(a.to_string());
        args.push(v);
    };
    for d in &cli.define {
        add("-D", quote(d));
    }
    add("--camera", view.camera_arg());
    add("--size", format!("{width}x{height}"));
    if view.projection == csgrt::scene::Projection::Orthographic {
        add("--projection", "ortho".into());
    }
    if cli.facets != csgrt::scene::Facets::default() {
        add("--facets", super::facets_name(cli.facets).into());
    }
    if let Some(c) = &cli.colorscheme {
        add("--colorscheme", quote(c.name));
    }
    if cli.max_depth != super::DEFAULT_MAX_DEPTH {
        add("--max-depth", cli.max_depth.to_string());
    }
    if let Some(n) = cli.spp {
        add("--spp", n.to_string());
    }
    if let Some(o) = &cli.output {
        add("-o", quote(&o.to_string_lossy()));
    }
    if cli.strict {
        args.push("--strict".into());
    }
    args.join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quoted argument is one word to the shell, the same text.
    #[test]
    fn quoted_arguments_read_back() {
        for s in [
            "part.scad",
            "my part.scad",
            "it's",
            "a\"b",
            "$HOME",
            "",
            "x;rm",
            "ü.csg",
        ] {
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg(format!("printf %s {}", quote(s)))
                .output()
                .expect("sh");
            assert_eq!(String::from_utf8_lossy(&out.stdout), s);
        }
    }
}
