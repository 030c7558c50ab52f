//! The command line (CLI.md): options → render settings → files. No geometry
//! here. Every output is computed before any is written, and each file is
//! written to a temporary file beside its target and renamed into place, so
//! a failed run leaves nothing half-written and never touches the model.

use csgrt::error::{Error, Result};

mod animate;
mod jobs;
mod output;
mod view;
mod watch;

use clap::Parser;
use jobs::{jobs, scene_of, Job};
use output::{render_files, trace_rays};
use std::path::PathBuf;

/// The largest image side, in pixels.
pub const MAX_SIDE: u32 = 32_768;
/// The most pixels in one image (checked before anything is allocated).
pub const MAX_PIXELS: u64 = 100_000_000;
pub const MAX_SPP: u32 = 65_536;
pub const MAX_DEPTH: u32 = 64;
/// `--max-depth` when not given.
pub const DEFAULT_MAX_DEPTH: u32 = 5;
pub const MAX_THREADS: usize = 1024;
/// The most frames `--animate` renders.
pub const MAX_FRAMES: u32 = 100_000;

/// What `--help` ends with.
const EXAMPLES: &str = "\
Examples:
  csgrt part.scad                         part.png: OpenSCAD's view and colours, 800x600
  csgrt part.scad --size 1920x1080 -o big.png
  csgrt part.scad --camera 0,0,0,55,0,25,140 --projection ortho
                                          OpenSCAD's --camera (translate, rotate, distance)
  csgrt part.scad -D width=40 -D 'label=\"A\"'
                                          set the program's variables, as OpenSCAD's -D
  csgrt part.scad --animate 24            part00000.png ... part00023.png, $t = i/24
  csgrt part.scad --watch                 render again each time the file is saved
  csgrt view part.scad                    a window: orbit, pan and zoom as in OpenSCAD; it follows
                                          each save, and `s` writes the picture and prints its
                                          command line (docs/CLI.md)
  csgrt *.csg -O thumbnails/              one image per model";

/// csgrt renders CSG scenes exactly: OpenSCAD's `.csg` export plus camera,
/// lights and materials.
#[derive(Parser, Debug, Clone)]
#[command(name = "csgrt", version, about, long_about = None, after_help = EXAMPLES)]
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
    /// each pixel centre, then 16 where an edge crosses the pixel: a
    /// neighbour's centre and a corner differ by more than 0.3 (POV-Ray's
    /// default threshold, summed over red, green and blue).
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=MAX_SPP as i64))]
    pub spp: Option<u32>,
    /// Depth of the ray tree (reflection + refraction).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_DEPTH,
          value_parser = clap::value_parser!(u32).range(0..=MAX_DEPTH as i64))]
    pub max_depth: u32,
    /// Worker threads (default, or 0: all cores); the image is the same
    /// for any N.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u16).range(0..=MAX_THREADS as i64))]
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
    pub facets: csgrt::scene::Facets,

    /// OpenSCAD's camera, overriding the file's: `tx,ty,tz,rx,ry,rz,dist`
    /// (OpenSCAD's `$vpt`, `$vpr` in degrees and `$vpd`) or
    /// `ex,ey,ez,cx,cy,cz` (eye and centre); OpenSCAD's 22.5° vertical
    /// field of view.
    #[arg(long, value_name = "NUMBERS", allow_hyphen_values = true,
          value_parser = csgrt::scene::openscad_view::Viewpoint::parse)]
    pub camera: Option<csgrt::scene::openscad_view::Viewpoint>,
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
    pub projection: Option<csgrt::scene::Projection>,

    /// OpenSCAD's colour scheme for what the file leaves uncoloured: the
    /// background and the colour of solids without `color` (Cornfield,
    /// Metallic, Sunset, Starnight, BeforeDawn, Nature, DeepOcean,
    /// Solarized, Tomorrow, "Tomorrow Night", Monotone); default Cornfield.
    #[arg(long, value_name = "NAME", value_parser = parse_color_scheme)]
    pub colorscheme: Option<csgrt::scene::defaults::ColorScheme>,

    /// Render, then render again whenever the model changes (a `.scad`
    /// model: also what it includes, uses or imports, as OpenSCAD lists
    /// them); an error is reported and the watch goes on. Ctrl-C stops.
    #[arg(long)]
    pub watch: bool,

    /// Every warning an error: where OpenSCAD warns and renders the rest
    /// (a missing import, a non-finite size, …) csgrt does the same unless
    /// this is given; then the first warning stops the render, exit 2.
    #[arg(long)]
    pub strict: bool,

    /// No progress bar, no summary.
    #[arg(short, long)]
    pub quiet: bool,

    /// With `csgrt view`: a line on standard error for each picture the
    /// window shows (its pass, size and render time), for measuring the
    /// viewer.
    #[arg(long)]
    pub log_frames: bool,
}

impl Cli {
    /// The options that each write one file of their own (for one image),
    /// and whether each is given.
    pub(crate) fn one_file_outputs(&self) -> [(&'static str, bool); 5] {
        [
            ("--mask", self.mask.is_some()),
            ("--stats-json", self.stats_json.is_some()),
            ("--dump-scene", self.dump_scene.is_some()),
            ("--export-pov", self.export_pov.is_some()),
            ("--trace-rays", self.trace_rays.is_some()),
        ]
    }
}

/// `--facets`' name for a mode.
pub(crate) fn facets_name(f: csgrt::scene::Facets) -> &'static str {
    use csgrt::scene::Facets;
    match f {
        Facets::Shapes => "shapes",
        Facets::Exact => "exact",
        Facets::OpenScad => "openscad",
    }
}

fn parse_facets(s: &str) -> std::result::Result<csgrt::scene::Facets, String> {
    use csgrt::scene::Facets;
    match s {
        "shapes" => Ok(Facets::Shapes),
        "exact" => Ok(Facets::Exact),
        "openscad" => Ok(Facets::OpenScad),
        _ => Err(format!(
            "`{s}` is not a facets mode: expected shapes, exact or openscad"
        )),
    }
}

fn parse_projection(s: &str) -> std::result::Result<csgrt::scene::Projection, String> {
    use csgrt::scene::Projection;
    match s {
        "o" | "ortho" | "orthogonal" => Ok(Projection::Orthographic),
        "p" | "perspective" => Ok(Projection::Perspective),
        _ => Err(format!(
            "`{s}` is not a projection: expected ortho (o, orthogonal) or perspective (p)"
        )),
    }
}

fn parse_color_scheme(s: &str) -> std::result::Result<csgrt::scene::defaults::ColorScheme, String> {
    use csgrt::scene::defaults::COLOR_SCHEMES;
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
    // `csgrt view MODEL …`: the same options, a window instead of a file
    // (a model is a file with an extension, so `view` names none).
    let mut args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let view = args.get(1).is_some_and(|a| a == "view");
    if view {
        args.remove(1);
    }
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return e.exit_code();
        }
    };
    // The stages walk the model's tree recursively: nested
    // `MAX_NESTING` deep, they need more stack than a thread's default
    // (`syntax::MAIN_STACK`).
    let ran = std::thread::Builder::new()
        .stack_size(csgrt::syntax::MAIN_STACK)
        .spawn(move || run(&cli, view))
        .map_err(|e| Error::Usage(format!("cannot start the main thread: {e}")))
        .and_then(|t| t.join().unwrap_or_else(|p| std::panic::resume_unwind(p)));
    match ran {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("{e}");
            e.exit_code()
        }
    }
}

pub fn run(cli: &Cli, view: bool) -> Result<()> {
    let jobs = jobs(cli)?;
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(csgrt::syntax::WORKER_STACK);
    // (0: rayon's default, a thread a core.)
    if let Some(n) = cli.threads {
        pool = pool.num_threads(n as usize);
    }
    let pool = pool
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {:?} threads: {e}", cli.threads)))?;
    if let Some(dir) = &cli.output_dir {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    if view {
        return view::view(cli, &jobs, pool);
    }
    if let [job] = &jobs[..] {
        if cli.watch {
            return pool.install(|| watch::watch(cli, job));
        }
        // In the pool: what the scene's reading casts (its framing) runs
        // on its threads, with their stacks.
        return pool.install(|| {
            let scene = scene_of(cli, job)?;
            match &cli.trace_rays {
                Some(input) => trace_rays(cli, job, &scene, input),
                None => render_files(cli, job, &scene, true),
            }
        });
    }
    // Several images: each is rendered and written on its own; one that
    // fails is reported and the others still come out. The exit status is
    // the worst of theirs. Frames of an animation are exported together
    // and rendered side by side (each render uses the whole pool too).
    let one = |job: &Job| scene_of(cli, job).and_then(|s| render_files(cli, job, &s, false));
    let results: Vec<Result<()>> = pool.install(|| {
        if cli.animate.is_some() {
            animate::animate(cli, &jobs)
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
