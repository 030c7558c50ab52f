//! The images a command line asks for ([`Job`]s), and each job's model
//! loaded and viewed as the options say.

use super::Cli;
use csgrt::error::{Error, Result};
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
        let single = [
            ("--mask", cli.mask.is_some()),
            ("--stats-json", cli.stats_json.is_some()),
            ("--dump-scene", cli.dump_scene.is_some()),
            ("--export-pov", cli.export_pov.is_some()),
            ("--trace-rays", cli.trace_rays.is_some()),
        ];
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
                    let mut defines = cli.define.clone();
                    // OpenSCAD's own frame time, `frame * (1.0 / frames)`.
                    defines.push(format!("$t={:?}", i as f64 * (1.0 / n as f64)));
                    out.push(Job {
                        model: model.clone(),
                        defines,
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
    finish_scene(cli, &mut scene)?;
    Ok(scene)
}

/// [`scene_of`], and the files it was read from: the model, and for a
/// `.scad` model what OpenSCAD says it read.
pub(super) fn watched_scene(cli: &Cli, job: &Job) -> Result<(Scene, Vec<PathBuf>)> {
    if !is_scad(&job.model) {
        return Ok((scene_of(cli, job)?, vec![job.model.clone()]));
    }
    let (src, deps) = csgrt::import::scad::export_with(&job.model, &job.defines, true)?;
    let mut scene = csgrt::load_csg_with(&src, cli.facets)?;
    finish_scene(cli, &mut scene)?;
    Ok((scene, deps))
}

/// The command line's view and colours applied to a loaded scene; its
/// warnings printed, or under `--strict` the first of them the error.
fn finish_scene(cli: &Cli, scene: &mut Scene) -> Result<()> {
    if cli.strict {
        if let Some(w) = scene.warnings.first() {
            let mut d = w.clone();
            d.severity = csgrt::error::Severity::Error;
            d.label = format!("{} (an error under --strict)", d.label);
            return Err(csgrt::Error::Scene(Box::new(d)));
        }
    }
    set_view(cli, scene);
    if let Some(c) = &cli.colorscheme {
        scene.apply_color_scheme(c);
    }
    for w in &scene.warnings {
        eprintln!("{w}");
    }
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
        eprintln!("{d}");
    }
    Ok(())
}

/// The command line's camera options put into the scene: OpenSCAD's camera
/// for any of `--camera`, `--viewall` or `--autocenter`; `--projection`
/// alone keeps the file's camera (or csgrt's framing) and sets how it
/// projects.
fn set_view(cli: &Cli, scene: &mut Scene) {
    use csgrt::scene::openscad_view::{self, ViewOptions};
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let opts = ViewOptions {
        camera: cli.camera,
        viewall: cli.viewall,
        autocenter: cli.autocenter,
        projection: cli.projection,
    };
    if opts.is_openscad() {
        let bounds = scene.result_bounds();
        scene.camera = Some(openscad_view::camera(&opts, &bounds, width, height));
        return;
    }
    // Found once: the render, the mask and the dumps each take the view.
    scene.fix_framing();
    if let Some(projection) = cli.projection {
        scene.camera = Some(csgrt::scene::CameraSpec {
            projection,
            ..scene.view(width, height)
        });
    }
}
