//! The images a command line asks for ([`Job`]s), and each job's model
//! loaded and viewed as the options say.

use super::Cli;
use csgrt::error::{Error, Result};
use csgrt::geometry::Aabb;
use csgrt::source::is_scad;
use csgrt::{load_model, Scene};
use std::path::{Path, PathBuf};

/// One image to render: a model (with OpenSCAD variables for a `.scad`
/// one) and where its image goes.
#[derive(Clone, Debug)]
pub(super) struct Job {
    pub model: PathBuf,
    pub defines: Vec<String>,
    pub output: PathBuf,
}

/// `path` with `suffix` added to its file stem (`a/b.png`, `00003` →
/// `a/b00003.png`), as OpenSCAD names animation frames.
fn with_stem_suffix(path: &Path, suffix: &str) -> PathBuf {
    let mut name = path.file_stem().unwrap_or_default().to_owned();
    name.push(suffix);
    if let Some(e) = path.extension() {
        name.push(".");
        name.push(e);
    }
    path.with_file_name(name)
}

/// The images the command line asks for, checked before anything is read
/// or created: options that name one file need one model, `-D` and
/// `--animate` a `.scad` one, `--watch` one image file, and no two images
/// may share a name.
pub(super) fn jobs(cli: &Cli) -> Result<Vec<Job>> {
    let several = cli.model.len() > 1;
    if several || cli.animate.is_some() {
        let single = cli.one_file_outputs();
        let what = if several {
            "several models"
        } else {
            "--animate"
        };
        if several && cli.output.is_some() {
            return Err(Error::Usage(
                "-o names one image; for several models use -O DIR (one image per model)".into(),
            ));
        }
        if let Some((opt, _)) = single.iter().find(|(_, on)| *on) {
            return Err(Error::Usage(format!(
                "{opt} writes one file, for one image; it cannot be used with {what}"
            )));
        }
        if cli.output.as_deref() == Some(Path::new("-")) {
            return Err(Error::Usage(
                "-o - writes one image to standard output; it cannot be used with --animate".into(),
            ));
        }
    }
    if let Some(dir) = &cli.output_dir {
        if dir.exists() && !dir.is_dir() {
            return Err(Error::Usage(format!(
                "-O {}: is a file, not a folder",
                dir.display()
            )));
        }
    }
    let mut out = Vec::new();
    for model in &cli.model {
        if !is_scad(model) {
            for (opt, on) in [
                ("-D", !cli.define.is_empty()),
                ("--animate", cli.animate.is_some()),
            ] {
                if on {
                    return Err(Error::Usage(format!(
                        "{}: {opt} sets OpenSCAD variables, for a `.scad` model only",
                        model.display()
                    )));
                }
            }
        }
        let image = model.with_extension("png");
        let output = match (&cli.output, &cli.output_dir) {
            (Some(o), _) => o.clone(),
            (None, Some(dir)) => dir.join(image.file_name().unwrap_or_default()),
            (None, None) => image,
        };
        match cli.animate {
            None => out.push(Job {
                model: model.clone(),
                defines: cli.define.clone(),
                output,
            }),
            Some(n) => {
                for i in 0..n {
                    out.push(Job {
                        model: model.clone(),
                        defines: cli.define.clone(),
                        output: with_stem_suffix(&output, &format!("{i:05}")),
                    });
                }
            }
        }
    }
    if cli.watch {
        if out.len() != 1 {
            return Err(Error::Usage(
                "--watch renders one image; give one model and no --animate".into(),
            ));
        }
        if cli.trace_rays.is_some() || out[0].output == Path::new("-") {
            return Err(Error::Usage(
                "--watch writes image files; it cannot be used with --trace-rays or -o -".into(),
            ));
        }
    }
    let mut seen = std::collections::HashMap::new();
    for j in &out {
        if let Some(first) = seen.insert(j.output.clone(), &j.model) {
            return Err(Error::Usage(format!(
                "{} and {} would both be written to {}; render them with separate -O folders",
                first.display(),
                j.model.display(),
                j.output.display()
            )));
        }
    }
    Ok(out)
}

/// A job's model read and viewed as the command line says, its warnings
/// printed.
pub(super) fn scene_of(cli: &Cli, job: &Job) -> Result<Scene> {
    let mut scene = load_model(&job.model, cli.facets, &job.defines)?;
    for said in finish_scene(cli, &mut scene, None)? {
        eprintln!("{said}");
    }
    Ok(scene)
}

/// [`scene_of`], and the files it was read from: the model, and for a
/// `.scad` model what OpenSCAD says it read. A `.scad` model's export that
/// a message points into is kept, in place of the one `kept` names (the
/// last render's), which is removed.
pub(super) fn watched_scene(
    cli: &Cli,
    job: &Job,
    kept: &mut Option<PathBuf>,
) -> Result<(Scene, Vec<PathBuf>)> {
    if !is_scad(&job.model) {
        return Ok((scene_of(cli, job)?, vec![job.model.clone()]));
    }
    let export = csgrt::import::scad::export_frames(&job.model, &job.defines, None, true)?;
    let loaded = csgrt::load_scad_frame(&export.frames[0], cli.facets);
    let deps = export.deps.clone();
    if csgrt::keeps_export(loaded.as_ref().ok(), &export.frames[0]) {
        if let Some(old) = kept.replace(export.keep()) {
            let _ = std::fs::remove_dir_all(old);
        }
    }
    let mut scene = loaded?;
    for said in finish_scene(cli, &mut scene, None)? {
        eprintln!("{said}");
    }
    Ok((scene, deps))
}

/// The command line's view and colours applied to a loaded scene (with
/// `frames`, the box of all an animation's frames, framed by each); the
/// warnings and notes to print, or under `--strict` the first warning the
/// error.
pub(super) fn finish_scene(
    cli: &Cli,
    scene: &mut Scene,
    frames: Option<&Aabb>,
) -> Result<Vec<String>> {
    if cli.strict {
        if let Some(w) = scene.warnings.first() {
            let mut d = w.clone();
            d.severity = csgrt::error::Severity::Error;
            d.label = format!("{} (an error under --strict)", d.label);
            return Err(csgrt::Error::Scene(Box::new(d)));
        }
    }
    let mut told: Vec<String> = Vec::new();
    set_view(cli, scene, frames, &mut told);
    if let Some(c) = &cli.colorscheme {
        scene.apply_color_scheme(c);
    }
    told.extend(scene.warnings.iter().map(|w| w.to_string()));
    // Each approximated statement once, with its largest error at this
    // view (a statement may approximate several parts).
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let cam = scene.view(width, height);
    let mut said: Vec<(csgrt::error::Diagnostic, f64)> = Vec::new();
    for a in &scene.approximations {
        let px = a.pixels(&cam, width);
        let n = &a.note;
        let same = |d: &csgrt::error::Diagnostic| {
            (&d.file, d.line, d.col, &d.message) == (&n.file, n.line, n.col, &n.message)
        };
        match said.iter_mut().find(|(d, _)| same(d)) {
            Some(worst) if px > worst.1 => *worst = (n.clone(), px),
            Some(_) => {}
            None => said.push((n.clone(), px)),
        }
    }
    for (mut d, px) in said {
        d.label = format!(
            "{}; {px:.2} pixels at this view{}",
            d.label,
            if px < 0.5 {
                ""
            } else {
                " (over half a pixel: the bound is for views where this part spans fewer than 4096 pixels)"
            }
        );
        told.push(d.to_string());
    }
    Ok(told)
}

/// The command line's camera options put into the scene: OpenSCAD's camera
/// for any of `--camera`, `--viewall` or `--autocenter`, or for the view a
/// `.scad` program sets (`$vp*`, which `--camera` overrides and which
/// turn `--viewall` and `--autocenter` off, as in OpenSCAD); `--projection`
/// alone keeps the file's camera (or csgrt's framing) and sets how it
/// projects. `frames`: the box to frame instead of the scene's own (an
/// animation's, the same for every frame).
fn set_view(cli: &Cli, scene: &mut Scene, frames: Option<&Aabb>, told: &mut Vec<String>) {
    use csgrt::scene::openscad_view::{self, ViewOptions};
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let file_view = scene.scad_view.filter(|_| cli.camera.is_none());
    let mut opts = ViewOptions {
        camera: cli.camera.or(file_view),
        viewall: cli.viewall,
        autocenter: cli.autocenter,
        projection: cli.projection,
    };
    if file_view.is_some() && (opts.viewall || opts.autocenter) {
        told.push(
            "warning: --viewall and --autocenter give way to the view the program sets with $vp*, as in OpenSCAD"
                .to_string(),
        );
        (opts.viewall, opts.autocenter) = (false, false);
    }
    if opts.is_openscad() {
        let bounds = frames.copied().unwrap_or_else(|| scene.result_bounds());
        scene.camera = Some(openscad_view::camera(&opts, &bounds, width, height));
        return;
    }
    // Found once: the render, the mask and the dumps each take the view.
    match frames {
        Some(b) if scene.camera.is_none() => scene.framed = Some(*b),
        _ => scene.fix_framing(),
    }
    if let Some(projection) = cli.projection {
        scene.camera = Some(csgrt::scene::CameraSpec {
            projection,
            ..scene.view(width, height)
        });
    }
}
