//! The command line (CLI.md): options → render settings → files. No geometry
//! here. Every output is computed before any is written, and each file is
//! written to a temporary file beside its target and renamed into place, so
//! a failed run leaves nothing half-written and never touches the model.

use crate::error::{Error, Result, Source};
use crate::render::{self, probe, Settings};
use crate::stats::Stats;
use crate::{dump, Scene};
use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The largest image side, in pixels.
pub const MAX_SIDE: u32 = 32_768;
/// The most pixels in one image (checked before anything is allocated).
pub const MAX_PIXELS: u64 = 100_000_000;
pub const MAX_SPP: u32 = 65_536;
pub const MAX_DEPTH: u32 = 64;
pub const MAX_THREADS: usize = 1024;
/// The most frames `--animate` renders.
pub const MAX_FRAMES: u32 = 100_000;

/// csgrt renders CSG scenes exactly: OpenSCAD's `.csg` export plus camera,
/// lights and materials.
#[derive(Parser, Debug)]
#[command(name = "csgrt", version, about, long_about = None)]
pub struct Cli {
    /// The scenes to render: `.csg`, the seed's `.ray` display list, or
    /// `.scad` (exported to `.csg` by `openscad` on PATH first). Several
    /// models give one image each (beside each model, or in `-O DIR`).
    #[arg(required = true, num_args = 1..)]
    pub model: Vec<PathBuf>,
    /// With several models: write each one's image into DIR (created if
    /// missing), named after the model (`part.csg` → `DIR/part.png`).
    #[arg(
        short = 'O',
        long = "output-dir",
        value_name = "DIR",
        conflicts_with = "output"
    )]
    pub output_dir: Option<PathBuf>,
    /// For a `.scad` model: render N frames, frame i with OpenSCAD's `$t` =
    /// i/N, named as OpenSCAD names them (`part.png` → `part00000.png`, …).
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub animate: Option<u32>,
    /// Passed to OpenSCAD for a `.scad` model: `-D name=value` sets a
    /// variable, as on OpenSCAD's own command line (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// The image to write, its format from its extension (`-`: PNG on
    /// standard output); default: MODEL with the extension `.png`.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", default_value = "800x600", value_parser = parse_size)]
    pub size: (u32, u32),
    /// OpenSCAD's spelling of `--size`: `--imgsize W,H`.
    #[arg(long, value_name = "W,H", value_parser = parse_imgsize, conflicts_with = "size")]
    pub imgsize: Option<(u32, u32)>,
    /// Samples per pixel, stratified and jittered inside the pixel (1: the
    /// pixel centre). Without it, adaptive anti-aliasing: one sample at
    /// each pixel centre, then 16 where a neighbour differs by more than
    /// 0.3 (POV-Ray's default threshold, summed over red, green and blue).
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=MAX_SPP as i64))]
    pub spp: Option<u32>,
    /// Depth of the ray tree (reflection + refraction).
    #[arg(long, value_name = "N", default_value_t = 5,
          value_parser = clap::value_parser!(u32).range(0..=MAX_DEPTH as i64))]
    pub max_depth: u32,
    /// Worker threads (default: all cores); the image is the same for any N.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u16).range(1..=MAX_THREADS as i64))]
    pub threads: Option<u16>,
    /// Also write an 8-bit grey PNG: 255 where the pixel-centre ray hits.
    #[arg(long, value_name = "FILE")]
    pub mask: Option<PathBuf>,
    /// Instead of an image: read rays `ox oy oz dx dy dz` from FILE (`-` =
    /// stdin) and print `t nx ny nz` or `miss` for each.
    #[arg(long, value_name = "FILE")]
    pub trace_rays: Option<PathBuf>,
    /// Write counters of the work done as one JSON object.
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<PathBuf>,
    /// Write the resolved scene as JSON (camera, lights, materials, tree).
    #[arg(long, value_name = "FILE")]
    pub dump_scene: Option<PathBuf>,
    /// Write the resolved scene as POV-Ray 3.7 SDL, keeping the CSG tree.
    #[arg(long, value_name = "FILE")]
    pub export_pov: Option<PathBuf>,
    /// How `$fn`, `$fa`, `$fs` are read: `shapes` (an explicit `$fn` of 3 to
    /// 8 makes circles, cylinders and spheres OpenSCAD's polygons and
    /// polyhedra; otherwise exact), `exact` (every curved solid exact),
    /// `openscad` (OpenSCAD's fragment rule on every circle, cylinder and
    /// sphere: the mesh OpenSCAD would export)
    #[arg(long, value_name = "MODE", default_value = "shapes", value_parser = parse_facets)]
    pub facets: crate::scene::Facets,

    /// OpenSCAD's camera, overriding the file's: `tx,ty,tz,rx,ry,rz,dist`
    /// (OpenSCAD's `$vpt`, `$vpr` in degrees and `$vpd`) or
    /// `ex,ey,ez,cx,cy,cz` (eye and centre); OpenSCAD's 22.5° vertical
    /// field of view.
    #[arg(long, value_name = "NUMBERS", allow_hyphen_values = true,
          value_parser = crate::scene::openscad_view::Viewpoint::parse)]
    pub camera: Option<crate::scene::openscad_view::Viewpoint>,
    /// As OpenSCAD: move the camera back until the whole scene is in view
    /// (without `--camera`, OpenSCAD's default view is used).
    #[arg(long)]
    pub viewall: bool,
    /// As OpenSCAD: with `--viewall`, look at the centre of the scene's box
    /// (without `--camera`, OpenSCAD's default view is used).
    #[arg(long)]
    pub autocenter: bool,
    /// `ortho` (or `o`, `orthogonal`) for parallel rays, `perspective` (or
    /// `p`), as OpenSCAD's `--projection`.
    #[arg(long, value_name = "ortho|perspective", value_parser = parse_projection)]
    pub projection: Option<crate::scene::Projection>,

    /// OpenSCAD's colour scheme for what the file leaves uncoloured: the
    /// background and the colour of solids without `color` (Cornfield,
    /// Metallic, Sunset, Starnight, BeforeDawn, Nature, DeepOcean,
    /// Solarized, Tomorrow, "Tomorrow Night", Monotone); default Cornfield.
    #[arg(long, value_name = "NAME", value_parser = parse_color_scheme)]
    pub colorscheme: Option<crate::scene::defaults::ColorScheme>,

    /// Render, then render again whenever the model changes (a `.scad`
    /// model: also what it includes, uses or imports, as OpenSCAD lists
    /// them); an error is reported and the watch goes on. Ctrl-C stops.
    #[arg(long)]
    pub watch: bool,

    /// No progress bar, no summary.
    #[arg(short, long)]
    pub quiet: bool,
}

fn parse_facets(s: &str) -> std::result::Result<crate::scene::Facets, String> {
    use crate::scene::Facets;
    match s {
        "shapes" => Ok(Facets::Shapes),
        "exact" => Ok(Facets::Exact),
        "openscad" => Ok(Facets::OpenScad),
        _ => Err(format!(
            "`{s}` is not a facets mode: expected shapes, exact or openscad"
        )),
    }
}

fn parse_projection(s: &str) -> std::result::Result<crate::scene::Projection, String> {
    use crate::scene::Projection;
    match s {
        "o" | "ortho" | "orthogonal" => Ok(Projection::Orthographic),
        "p" | "perspective" => Ok(Projection::Perspective),
        _ => Err(format!(
            "`{s}` is not a projection: expected ortho (o, orthogonal) or perspective (p)"
        )),
    }
}

fn parse_color_scheme(s: &str) -> std::result::Result<crate::scene::defaults::ColorScheme, String> {
    use crate::scene::defaults::COLOR_SCHEMES;
    let squash = |n: &str| n.replace([' ', '-', '_'], "").to_ascii_lowercase();
    COLOR_SCHEMES
        .iter()
        .find(|c| squash(c.name) == squash(s))
        .copied()
        .ok_or_else(|| {
            let names: Vec<&str> = COLOR_SCHEMES.iter().map(|c| c.name).collect();
            format!(
                "`{s}` is not one of OpenSCAD's colour schemes: expected {}",
                names.join(", ")
            )
        })
}

fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let bad = || format!("`{s}` is not a size: expected WxH, as in 800x600");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    within_limits(s, w, h)
}

/// A size's sides and pixels within csgrt's limits.
fn within_limits(s: &str, w: u32, h: u32) -> std::result::Result<(u32, u32), String> {
    if w == 0 || h == 0 {
        return Err(format!("`{s}`: width and height must be at least 1"));
    }
    if w > MAX_SIDE || h > MAX_SIDE {
        return Err(format!("`{s}`: each side may be at most {MAX_SIDE} pixels"));
    }
    if w as u64 * h as u64 > MAX_PIXELS {
        return Err(format!("`{s}`: at most {MAX_PIXELS} pixels in all"));
    }
    Ok((w, h))
}

/// `W,H`, as OpenSCAD's `--imgsize` takes it, within `--size`'s limits.
fn parse_imgsize(s: &str) -> std::result::Result<(u32, u32), String> {
    let bad = || format!("`{s}` is not a size: expected W,H, as in 800,600");
    let (w, h) = s.split_once(',').ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    within_limits(s, w, h)
}

/// Runs csgrt with the process's arguments; returns the exit status.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return e.exit_code();
        }
    };
    match run(&cli) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
    }
}

/// The largest scene or ray file read, checked before reading it.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Reads a model file into a named source.
pub fn read_source(path: &Path) -> Result<Source> {
    let meta = model_file(path)?;
    if meta.len() > MAX_FILE_BYTES {
        return Err(Error::Usage(format!(
            "{}: the file has {} bytes; the limit is {} MiB",
            path.display(),
            meta.len(),
            MAX_FILE_BYTES >> 20
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| unreadable(path, e))?;
    let name = path.display().to_string();
    match String::from_utf8(bytes) {
        Ok(text) => Ok(Source::new(name, text)),
        Err(e) => {
            // The place of the first byte that is not UTF-8, in the text
            // as far as it is (the same bytes in its lossy reading).
            let at = e.utf8_error().valid_up_to();
            let byte = e.as_bytes()[at];
            let src = Source::new(name, String::from_utf8_lossy(e.as_bytes()).into_owned());
            Err(src.error(
                crate::error::TextRange::new(at, at + 1),
                format!("byte 0x{byte:02X} is not UTF-8 text"),
                "expected a file saved as UTF-8 (as OpenSCAD writes it)",
            ))
        }
    }
}

/// The metadata of a model or ray file, or why it is none: missing, not
/// readable or a folder, in plain words (see [`unreadable`]).
pub(crate) fn model_file(path: &Path) -> Result<std::fs::Metadata> {
    let meta = std::fs::metadata(path).map_err(|e| unreadable(path, e))?;
    if meta.is_dir() {
        return Err(Error::Usage(format!(
            "{}: is a folder, not a file",
            path.display()
        )));
    }
    Ok(meta)
}

/// A model or ray file that cannot be read, in plain words: missing, a
/// folder, or not readable are the user's to fix (exit 2); anything else
/// is the system's (exit 1).
fn unreadable(path: &Path, e: std::io::Error) -> Error {
    use std::io::ErrorKind;
    let why = match e.kind() {
        ErrorKind::NotFound => "no such file",
        ErrorKind::PermissionDenied => "permission denied: this user may not read it",
        _ => return Error::io(path, e),
    };
    Error::Usage(format!("{}: {why}", path.display()))
}

/// `path`'s extension in lower case, if it has one.
fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// Whether `path` names an OpenSCAD program (`.scad`).
fn is_scad(path: &Path) -> bool {
    extension(path).as_deref() == Some("scad")
}

/// Loads a model by its extension.
pub fn load(path: &Path) -> Result<Scene> {
    load_with(path, crate::scene::Facets::default())
}

/// [`load`] with `$fn`, `$fa`, `$fs` read as `facets` says (`.csg` only).
pub fn load_with(path: &Path, facets: crate::scene::Facets) -> Result<Scene> {
    load_model(path, facets, &[])
}

/// [`load_with`], a `.scad` model exported with OpenSCAD's `-D` `defines`.
pub fn load_model(path: &Path, facets: crate::scene::Facets, defines: &[String]) -> Result<Scene> {
    match extension(path).as_deref() {
        Some("csg") => crate::load_csg_with(&read_source(path)?, facets),
        Some("ray") => crate::syntax::ray::load_ray(&read_source(path)?),
        Some("scad") => crate::load_csg_with(&crate::scad::export(path, defines)?, facets),
        _ => Err(Error::Usage(format!(
            "{}: unknown model format; expected a `.csg` scene, a `.ray` display list or a `.scad` program",
            path.display()
        ))),
    }
}

/// One image to render: a model (with OpenSCAD variables for a `.scad`
/// one) and where its image goes.
#[derive(Clone, Debug)]
pub(crate) struct Job {
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
fn jobs(cli: &Cli) -> Result<Vec<Job>> {
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

pub fn run(cli: &Cli) -> Result<()> {
    let jobs = jobs(cli)?;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = cli.threads {
        pool = pool.num_threads(n as usize);
    }
    let pool = pool
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {:?} threads: {e}", cli.threads)))?;
    if let Some(dir) = &cli.output_dir {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    if let [job] = &jobs[..] {
        if cli.watch {
            return pool.install(|| crate::watch::watch(cli, job));
        }
        let scene = scene_of(cli, job)?;
        return pool.install(|| match &cli.trace_rays {
            Some(input) => trace_rays(cli, job, &scene, input),
            None => render_files(cli, job, &scene, true),
        });
    }
    // Several images: each is rendered and written on its own; one that
    // fails is reported and the others still come out. The exit status is
    // the worst of theirs. Frames of an animation are exported and
    // rendered side by side (each render uses the whole pool too).
    let one = |job: &Job| scene_of(cli, job).and_then(|s| render_files(cli, job, &s, false));
    let results: Vec<Result<()>> = pool.install(|| {
        if cli.animate.is_some() {
            use rayon::prelude::*;
            jobs.par_iter().map(one).collect()
        } else {
            jobs.iter().map(one).collect()
        }
    });
    let failed: Vec<Error> = results.into_iter().filter_map(|r| r.err()).collect();
    for e in &failed {
        eprintln!("{e}");
    }
    match failed.iter().map(Error::exit_code).max() {
        None => Ok(()),
        Some(code) => Err(Error::Several {
            failed: failed.len(),
            of: jobs.len(),
            code,
        }),
    }
}

/// A job's model read and viewed as the command line says, its warnings
/// printed.
fn scene_of(cli: &Cli, job: &Job) -> Result<Scene> {
    let mut scene = load_model(&job.model, cli.facets, &job.defines)?;
    finish_scene(cli, &mut scene);
    Ok(scene)
}

/// [`scene_of`], and the files it was read from: the model, and for a
/// `.scad` model what OpenSCAD says it read.
pub(crate) fn watched_scene(cli: &Cli, job: &Job) -> Result<(Scene, Vec<PathBuf>)> {
    if !is_scad(&job.model) {
        return Ok((scene_of(cli, job)?, vec![job.model.clone()]));
    }
    let (src, deps) = crate::scad::export_with(&job.model, &job.defines, true)?;
    let mut scene = crate::load_csg_with(&src, cli.facets)?;
    finish_scene(cli, &mut scene);
    Ok((scene, deps))
}

/// The command line's view and colours applied to a loaded scene; its
/// warnings printed.
fn finish_scene(cli: &Cli, scene: &mut Scene) {
    set_view(cli, scene);
    if let Some(c) = &cli.colorscheme {
        scene.apply_color_scheme(c);
    }
    for w in &scene.warnings {
        eprintln!("{w}");
    }
}

/// The command line's camera options put into the scene: OpenSCAD's camera
/// for any of `--camera`, `--viewall` or `--autocenter`; `--projection`
/// alone keeps the file's camera (or csgrt's framing) and sets how it
/// projects.
fn set_view(cli: &Cli, scene: &mut Scene) {
    use crate::scene::openscad_view::{self, ViewOptions};
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let opts = ViewOptions {
        camera: cli.camera,
        viewall: cli.viewall,
        autocenter: cli.autocenter,
        projection: cli.projection,
    };
    if opts.is_openscad() {
        let bounds = scene.framing_bounds();
        scene.camera = Some(openscad_view::camera(&opts, &bounds, width, height));
    } else if let Some(projection) = cli.projection {
        scene.camera = Some(crate::scene::CameraSpec {
            projection,
            ..scene.view(width, height)
        });
    }
}

fn trace_rays(cli: &Cli, job: &Job, scene: &Scene, input: &Path) -> Result<()> {
    let src = if input == Path::new("-") {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| Error::io("<stdin>", e))?;
        Source::new("<stdin>", text)
    } else {
        read_source(input)?
    };
    let rays = probe::parse_rays(&src)?;
    let start = Instant::now();
    let mut stats = Stats::default();
    // Timed: the hits and their normals; their printing is not.
    let hits: Vec<_> = rays
        .iter()
        .map(|ray| probe::trace(scene, ray, &mut stats))
        .collect();
    let seconds = start.elapsed().as_secs_f64();
    let mut out = String::with_capacity(rays.len() * 64);
    for h in &hits {
        out.push_str(&probe::line(h.as_ref()));
        out.push('\n');
    }
    if let Some(p) = &cli.stats_json {
        write_atomic(p, &job.model, stats_json(&stats, seconds).as_bytes())?;
    }
    to_stdout(out.as_bytes())
}

/// Bytes to standard output; a closed pipe (`| head`) is the reader's
/// choice, not an error.
fn to_stdout(bytes: &[u8]) -> Result<()> {
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(bytes).and_then(|_| stdout.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::io("<stdout>", e)),
        _ => Ok(()),
    }
}

pub(crate) fn render_files(cli: &Cli, job: &Job, scene: &Scene, bar: bool) -> Result<()> {
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let output = &job.output;
    for p in [
        Some(output),
        cli.mask.as_ref(),
        cli.stats_json.as_ref(),
        cli.dump_scene.as_ref(),
        cli.export_pov.as_ref(),
    ]
    .into_iter()
    .flatten()
    {
        refuse_model(p, &job.model)?;
    }
    // Formats before rendering: nothing is drawn for an output csgrt cannot
    // write.
    let format = ImageFormat::of(output)?;
    let mask_format = cli.mask.as_deref().map(ImageFormat::of).transpose()?;
    if let (Some(p), Some(f)) = (&cli.mask, mask_format) {
        if f.is_linear() {
            return Err(Error::Usage(format!(
                "{}: a mask is an 8-bit grey image; expected .png, .jpg, .bmp, .tif or .webp",
                p.display()
            )));
        }
    }
    let settings = Settings {
        width,
        height,
        spp: cli.spp.unwrap_or(render::ADAPTIVE_SPP),
        max_depth: cli.max_depth,
        adaptive: cli.spp.is_none().then_some(render::Adaptive {
            threshold: render::ADAPTIVE_THRESHOLD,
        }),
        radiance: format.is_linear(),
    };

    if output == Path::new("-") && cli.mask.as_deref() == Some(Path::new("-")) {
        return Err(Error::Usage(
            "the image and the mask cannot both go to standard output".into(),
        ));
    }
    let bar = (bar && !cli.quiet && std::io::stderr().is_terminal()).then(|| {
        let b = ProgressBar::new(height as u64);
        b.set_style(
            ProgressStyle::with_template(
                "{spinner} rendering [{bar:40}] {pos}/{len} rows, {eta} left",
            )
            .expect("a valid template")
            .progress_chars("=> "),
        );
        b
    });
    let start = Instant::now();
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let image = render::render(scene, &settings, &tick);
    let seconds = start.elapsed().as_secs_f64();
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let mask = cli.mask.as_ref().map(|_| render::mask(scene, &settings));
    // Everything is computed; now write.
    let rgb = if format.is_linear() {
        format.encode_linear(&image.radiance, width, height)?
    } else {
        format.encode(&image.rgb, width, height, image::ExtendedColorType::Rgb8)?
    };
    write_image(output, &job.model, &rgb)?;
    if let (Some(p), Some(m), Some(f)) = (&cli.mask, &mask, mask_format) {
        let grey = f.encode(m, width, height, image::ExtendedColorType::L8)?;
        write_image(p, &job.model, &grey)?;
    }
    if let Some(p) = &cli.dump_scene {
        let cam = scene.view(width, height);
        let json = serde_json::to_string_pretty(&dump::scene_json(scene, &cam, width, height))
            .expect("JSON of plain values");
        write_atomic(p, &job.model, json.as_bytes())?;
    }
    if let Some(p) = &cli.export_pov {
        let cam = scene.view(width, height);
        let sdl = crate::pov::scene_sdl(scene, &cam, width, height, cli.max_depth);
        write_atomic(p, &job.model, sdl.as_bytes())?;
    }
    if let Some(p) = &cli.stats_json {
        write_atomic(p, &job.model, stats_json(&image.stats, seconds).as_bytes())?;
    }
    if !cli.quiet {
        let name = if output == Path::new("-") {
            "<stdout>".to_string()
        } else {
            output.display().to_string()
        };
        let sampling = match settings.adaptive {
            None => format!("{} spp", settings.spp),
            Some(_) => {
                let again = (image.stats.primary_rays - image.stats.pixels) / settings.spp as u64;
                format!(
                    "adaptive: {again} of {} pixels at {} spp",
                    image.stats.pixels, settings.spp
                )
            }
        };
        eprintln!("csgrt: wrote {name} ({width}x{height}, {sampling}) in {seconds:.3} s");
    }
    Ok(())
}

/// The image formats csgrt writes, chosen by the output's extension
/// (`-`: PNG on standard output).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    Png,
    Jpeg,
    Bmp,
    Tiff,
    WebP,
    /// Radiance RGBE, linear.
    Hdr,
    /// OpenEXR, linear 32-bit float.
    Exr,
}

impl ImageFormat {
    fn of(path: &Path) -> Result<ImageFormat> {
        // (A folder is refused when written, as any output is.)
        if path == Path::new("-") || path.is_dir() {
            return Ok(ImageFormat::Png);
        }
        Ok(match extension(path).as_deref() {
            Some("png") => ImageFormat::Png,
            Some("jpg" | "jpeg") => ImageFormat::Jpeg,
            Some("bmp") => ImageFormat::Bmp,
            Some("tif" | "tiff") => ImageFormat::Tiff,
            Some("webp") => ImageFormat::WebP,
            Some("hdr") => ImageFormat::Hdr,
            Some("exr") => ImageFormat::Exr,
            other => {
                let what = other.map_or("no extension".to_string(), |e| format!("`.{e}`"));
                return Err(Error::Usage(format!(
                    "{}: {what} names no image format csgrt writes; expected .png, .jpg, \
                     .jpeg, .bmp, .tif, .tiff, .webp, .hdr or .exr (or `-` for PNG on \
                     standard output)",
                    path.display()
                )));
            }
        })
    }

    /// Whether the format holds linear radiance (HDR, EXR) rather than
    /// 8-bit colour.
    fn is_linear(self) -> bool {
        matches!(self, ImageFormat::Hdr | ImageFormat::Exr)
    }

    /// Linear RGB radiance (three `f32` a pixel) as an HDR or EXR file.
    fn encode_linear(self, rgb: &[f32], w: u32, h: u32) -> Result<Vec<u8>> {
        use image::ImageEncoder;
        let mut out = std::io::Cursor::new(Vec::new());
        let done = match self {
            ImageFormat::Hdr => {
                let px: Vec<image::Rgb<f32>> = rgb
                    .chunks_exact(3)
                    .map(|c| image::Rgb([c[0], c[1], c[2]]))
                    .collect();
                image::codecs::hdr::HdrEncoder::new(&mut out).encode(&px, w as usize, h as usize)
            }
            _ => image::codecs::openexr::OpenExrEncoder::new(&mut out).write_image(
                &rgb.iter()
                    .flat_map(|v| v.to_ne_bytes())
                    .collect::<Vec<u8>>(),
                w,
                h,
                image::ExtendedColorType::Rgb32F,
            ),
        };
        done.map_err(|e| Error::io(format!("<{self:?}>"), std::io::Error::other(e)))?;
        Ok(out.into_inner())
    }

    /// The encoded file (JPEG at quality 90; WebP lossless).
    fn encode(
        self,
        data: &[u8],
        w: u32,
        h: u32,
        color: image::ExtendedColorType,
    ) -> Result<Vec<u8>> {
        use image::ImageEncoder;
        let mut out = std::io::Cursor::new(Vec::new());
        let done = match self {
            ImageFormat::Png => {
                image::codecs::png::PngEncoder::new(&mut out).write_image(data, w, h, color)
            }
            ImageFormat::Jpeg => image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90)
                .write_image(data, w, h, color),
            ImageFormat::Bmp => {
                image::codecs::bmp::BmpEncoder::new(&mut out).write_image(data, w, h, color)
            }
            ImageFormat::Tiff => {
                image::codecs::tiff::TiffEncoder::new(&mut out).write_image(data, w, h, color)
            }
            ImageFormat::WebP => image::codecs::webp::WebPEncoder::new_lossless(&mut out)
                .write_image(data, w, h, color),
            ImageFormat::Hdr | ImageFormat::Exr => {
                unreachable!("linear formats are written from radiance, by encode_linear")
            }
        };
        done.map_err(|e| Error::io(format!("<{self:?}>"), std::io::Error::other(e)))?;
        Ok(out.into_inner())
    }
}

/// An image to its file, or to standard output for `-`.
fn write_image(path: &Path, model: &Path, bytes: &[u8]) -> Result<()> {
    if path == Path::new("-") {
        to_stdout(bytes)
    } else {
        write_atomic(path, model, bytes)
    }
}

/// Refuses an output path that names the model itself.
fn refuse_model(out: &Path, model: &Path) -> Result<()> {
    let same = match (out.canonicalize(), model.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => out == model,
    };
    if same {
        return Err(Error::Usage(format!(
            "{}: an output may not overwrite the model",
            out.display()
        )));
    }
    Ok(())
}

/// Writes `bytes` to a temporary file beside `path`, then renames it.
fn write_atomic(path: &Path, model: &Path, bytes: &[u8]) -> Result<()> {
    refuse_model(path, model)?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".csgrt-");
    // An image is an ordinary file: readable by all, like one `create`d.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
    let refuse = |why: String| {
        Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, why),
        ))
    };
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => return refuse(format!("{} is not a folder", dir.display())),
        Err(_) => return refuse(format!("no such folder: {}", dir.display())),
    }
    // The rename would replace a device or a pipe (say `/dev/null`) with a
    // file, and a folder cannot be replaced at all: only regular files.
    if let Ok(m) = std::fs::symlink_metadata(path) {
        let m = if m.file_type().is_symlink() {
            std::fs::metadata(path).unwrap_or(m)
        } else {
            m
        };
        if m.is_dir() {
            return refuse("it is a folder".to_string());
        }
        if !m.is_file() {
            return refuse(
                "it exists and is not a regular file; outputs replace regular files only"
                    .to_string(),
            );
        }
    }
    // tempfile's errors name its random file; say only what went wrong.
    let mut tmp = builder.tempfile_in(dir).map_err(|e| {
        let why = match e.kind() {
            std::io::ErrorKind::PermissionDenied => "permission denied".to_string(),
            std::io::ErrorKind::NotFound => "it takes no new files".to_string(),
            k => k.to_string(),
        };
        Error::io(
            path,
            std::io::Error::new(
                e.kind(),
                format!("cannot create a file in {}: {why}", dir.display()),
            ),
        )
    })?;
    tmp.write_all(bytes).map_err(|e| Error::io(path, e))?;
    tmp.persist(path).map_err(|e| Error::io(path, e.error))?;
    Ok(())
}

/// The counters as one JSON object.
pub fn stats_json(s: &Stats, seconds: f64) -> String {
    let v = serde_json::json!({
        "pixels": s.pixels,
        "primary_rays": s.primary_rays,
        "shadow_rays": s.shadow_rays,
        "reflected_rays": s.reflected_rays,
        "refracted_rays": s.refracted_rays,
        "primitive_tests": s.primitive_tests,
        "bound_tests": s.bound_tests,
        "triangle_tests": s.triangle_tests,
        "convex_steps": s.convex_steps,
        "bound_culled": s.bound_culled,
        "normals_computed": s.normals_computed,
        "span_allocations": s.span_allocations,
        "max_spans": s.max_spans,
        "nonfinite_samples": s.nonfinite_samples,
        "render_seconds": seconds,
    });
    serde_json::to_string_pretty(&v).expect("JSON of plain values") + "\n"
}
