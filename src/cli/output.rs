//! What a render writes: images in their formats, `--trace-rays`,
//! `--stats-json`, `--dump-scene` and `--export-pov`, each computed before
//! any is written and written atomically beside its target.

use super::jobs::Job;
use super::Cli;
use csgrt::error::{Error, Result};
use csgrt::export::{dump, pov};
use csgrt::render::{self, probe, Settings};
use csgrt::source::{extension, read_source};
use csgrt::stats::Stats;
use csgrt::{Scene, Source};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::{IsTerminal, Read, Write};
use std::path::Path;
use std::time::Instant;

pub(super) fn trace_rays(cli: &Cli, job: &Job, scene: &Scene, input: &Path) -> Result<()> {
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
    if let Some(p) = &cli.stats_json {
        check_target(p, &job.model)?;
    }
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
        stage(p, stats_json(&stats, seconds).as_bytes())?.commit()?;
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

/// The render the command line asks for, of a `width`×`height` picture
/// (`radiance`: its linear radiance kept, for HDR and EXR files).
pub(super) fn settings(cli: &Cli, width: u32, height: u32, radiance: bool) -> Settings {
    Settings {
        width,
        height,
        spp: cli.spp.unwrap_or(render::ADAPTIVE_SPP),
        max_depth: cli.max_depth,
        adaptive: cli.spp.is_none().then_some(render::Adaptive {
            threshold: render::ADAPTIVE_THRESHOLD,
        }),
        radiance,
    }
}

pub(super) fn render_files(cli: &Cli, job: &Job, scene: &Scene, bar: bool) -> Result<()> {
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let output = &job.output;
    // An export alone (`--export-pov`, `--dump-scene`) writes no image
    // unless `-o` names one.
    let exports = cli.export_pov.is_some() || cli.dump_scene.is_some();
    let image_wanted = cli.output.is_some() || !exports;
    // Every target checked before anything is rendered: a missing folder
    // or a folder in a file's place is found now, not after the render.
    for p in [
        image_wanted.then_some(output),
        cli.mask.as_ref(),
        cli.stats_json.as_ref(),
        cli.dump_scene.as_ref(),
        cli.export_pov.as_ref(),
    ]
    .into_iter()
    .flatten()
    {
        if p != Path::new("-") {
            check_target(p, &job.model)?;
        }
    }
    // Formats before rendering: nothing is drawn for an output csgrt cannot
    // write.
    let format = ImageFormat::of(output)?;
    let mask_format = match cli.mask.as_deref() {
        None => None,
        Some(p) => match ImageFormat::of(p) {
            Ok(f) if !f.is_linear() => Some(f),
            _ => {
                return Err(Error::Usage(format!(
                    "{}: a mask is an 8-bit grey image; expected .png, .jpg, .jpeg, .bmp, \
                     .tif, .tiff or .webp (or `-` for PNG on standard output)",
                    p.display()
                )))
            }
        },
    };
    let to_terminal = |p: &Path| p == Path::new("-") && std::io::stdout().is_terminal();
    if (image_wanted && to_terminal(output)) || cli.mask.as_deref().is_some_and(to_terminal) {
        return Err(Error::Usage(
            "-: standard output is a terminal, which would show the image's bytes; \
             redirect it (`> part.png`) or pipe it to a program"
                .into(),
        ));
    }
    let settings = settings(cli, width, height, format.is_linear());

    if output == Path::new("-") && cli.mask.as_deref() == Some(Path::new("-")) {
        return Err(Error::Usage(
            "the image and the mask cannot both go to standard output".into(),
        ));
    }
    if !image_wanted && cli.mask.is_none() && cli.stats_json.is_none() {
        // Nothing that needs the render: the exports alone.
        return write_exports(cli, scene, Vec::new());
    }
    let bar = (bar && !cli.quiet && std::io::stderr().is_terminal()).then(|| {
        // In samples, not rows: a row of sky costs little, a row through
        // the part much more, and the second pass of adaptive
        // anti-aliasing is added when it is planned.
        let b = ProgressBar::new(0);
        b.set_style(
            ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent}%, {eta} left")
                .expect("a valid template")
                .progress_chars("=> "),
        );
        b
    });
    let start = Instant::now();
    let tick = |p: render::Progress| {
        if let Some(b) = &bar {
            match p {
                render::Progress::Planned(n) => b.inc_length(n),
                render::Progress::Done(n) => b.inc(n),
            }
        }
    };
    let image = render::render(scene, &settings, &tick);
    let seconds = start.elapsed().as_secs_f64();
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let mask = cli.mask.as_ref().map(|_| render::mask(scene, &settings));
    // Everything is computed; now each file is staged beside its target,
    // and only when all are staged are they renamed into place.
    let mut staged = Vec::new();
    let mut to_out = None;
    if image_wanted {
        let rgb = if format.is_linear() {
            format.encode_linear(&image.radiance, width, height)?
        } else {
            format.encode(&image.rgb, width, height, image::ExtendedColorType::Rgb8)?
        };
        if output == Path::new("-") {
            to_out = Some(rgb);
        } else {
            staged.push(stage(output, &rgb)?);
        }
    }
    if let (Some(p), Some(m), Some(f)) = (&cli.mask, &mask, mask_format) {
        let grey = f.encode(m, width, height, image::ExtendedColorType::L8)?;
        if p == Path::new("-") {
            to_out = Some(grey);
        } else {
            staged.push(stage(p, &grey)?);
        }
    }
    if let Some(p) = &cli.stats_json {
        staged.push(stage(p, stats_json(&image.stats, seconds).as_bytes())?);
    }
    write_exports(cli, scene, staged)?;
    if let Some(bytes) = to_out {
        to_stdout(&bytes)?;
    }
    if !image_wanted {
        return Ok(());
    }
    if !cli.quiet {
        let name = if output == Path::new("-") {
            "<stdout>".to_string()
        } else {
            csgrt::error::printable(&output.display().to_string()).into_owned()
        };
        let sampling = match settings.adaptive {
            None => format!("{} spp", settings.spp),
            Some(_) => format!(
                "adaptive: {} of {} pixels at {} spp",
                image.refined, image.stats.pixels, settings.spp
            ),
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

/// `--dump-scene` and `--export-pov` staged beside `staged` (the render's
/// files), then all of them renamed into place.
fn write_exports(cli: &Cli, scene: &Scene, mut staged: Vec<Staged>) -> Result<()> {
    let (width, height) = cli.imgsize.unwrap_or(cli.size);
    let cam = scene.view(width, height);
    if let Some(p) = &cli.dump_scene {
        let json = serde_json::to_string_pretty(&dump::scene_json(scene, &cam, width, height))
            .expect("JSON of plain values");
        staged.push(stage(p, json.as_bytes())?);
    }
    if let Some(p) = &cli.export_pov {
        let sdl = pov::scene_sdl(scene, &cam, width, height, cli.max_depth);
        staged.push(stage(p, sdl.as_bytes())?);
    }
    staged.into_iter().try_for_each(Staged::commit)
}

/// Refuses, before anything is computed, an output that could not be
/// written: one that names the model, one in a folder that does not exist
/// (or is a file), one in the place of a folder, a device or a pipe.
/// These are the user's to fix (exit 2); a write that fails later all the
/// same (a full disk, permissions) is the system's (exit 1).
fn check_target(path: &Path, model: &Path) -> Result<()> {
    let same = match (path.canonicalize(), model.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => path == model,
    };
    let refuse = |why: &str| Err(Error::Usage(format!("{}: {why}", path.display())));
    if same {
        return refuse("an output may not overwrite the model");
    }
    let dir = folder_of(path);
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => return refuse(&format!("{} is not a folder", dir.display())),
        Err(_) => return refuse(&format!("no such folder: {}", dir.display())),
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
            return refuse("it is a folder");
        }
        if !m.is_file() {
            return refuse(
                "it exists and is not a regular file; outputs replace regular files only",
            );
        }
    }
    Ok(())
}

/// The folder a file is written into (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A file written in full to a temporary file beside its target, not yet
/// in place.
struct Staged {
    tmp: tempfile::NamedTempFile,
    path: std::path::PathBuf,
}

impl Staged {
    /// Renames the file into place.
    fn commit(self) -> Result<()> {
        self.tmp
            .persist(&self.path)
            .map_err(|e| Error::io(&self.path, e.error))?;
        Ok(())
    }
}

/// `bytes` written to a temporary file beside `path` (checked already by
/// [`check_target`]); dropped uncommitted, it is removed.
fn stage(path: &Path, bytes: &[u8]) -> Result<Staged> {
    let dir = folder_of(path);
    let mut builder = tempfile::Builder::new();
    builder.prefix(".csgrt-");
    // An image is an ordinary file: readable by all, like one `create`d.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
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
    Ok(Staged {
        tmp,
        path: path.to_path_buf(),
    })
}

/// The counters as one JSON object.
pub fn stats_json(s: &Stats, seconds: f64) -> String {
    let v = serde_json::json!({
        "pixels": s.pixels,
        "primary_rays": s.primary_rays,
        "screen_culled": s.screen_culled,
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
        "approximated_nodes": s.approximated_nodes,
        "render_seconds": seconds,
    });
    serde_json::to_string_pretty(&v).expect("JSON of plain values") + "\n"
}
