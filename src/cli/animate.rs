//! `--animate N`: each `.scad` model exported once by `openscad --animate
//! N` (its frames with `$t` = i/N, set before the program's own
//! assignments, as OpenSCAD sets it), and its frames rendered with one
//! camera: the box of all the frames framed, so that what stands still in
//! the model stands still in the pictures. (OpenSCAD's own command line
//! frames each frame anew; its window keeps one view, as here.)

use super::jobs::{finish_scene, Job};
use super::output::render_files;
use super::Cli;
use csgrt::error::{Error, Result};
use csgrt::geometry::Aabb;
use rayon::prelude::*;

/// Renders the frames of every animated model; each frame that fails is
/// reported and the others still come out. Returns each frame's result, in
/// the order of `jobs`.
pub(super) fn animate(cli: &Cli, jobs: &[Job]) -> Vec<Result<()>> {
    let mut results = Vec::with_capacity(jobs.len());
    let mut rest = jobs;
    while let Some(first) = rest.first() {
        let n = rest.iter().take_while(|j| j.model == first.model).count();
        let (frames, after) = rest.split_at(n);
        match model_frames(cli, frames) {
            Ok(r) => results.extend(r),
            Err(e) => {
                // The export failed: said once, for all its frames.
                eprintln!("{e}");
                results.extend(frames.iter().map(|_| {
                    Err(Error::Usage(format!(
                        "{}: no frames (said above)",
                        first.model.display()
                    )))
                }));
            }
        }
        rest = after;
    }
    results
}

/// One model's frames: exported together, looked at once to find the box
/// they all frame, then each loaded again and rendered.
fn model_frames(cli: &Cli, frames: &[Job]) -> Result<Vec<Result<()>>> {
    let first = &frames[0];
    let export = csgrt::import::scad::export_frames(
        &first.model,
        &first.defines,
        Some(frames.len() as u32),
        false,
    )?;
    let load = |i: usize| csgrt::load_scad_frame(&export.frames[i], cli.facets);
    // The box every frame frames: OpenSCAD's box of the result under its
    // camera options, else csgrt's framing box (each found by casting rays:
    // only the one used).
    let openscad_view = cli.camera.is_some() || cli.viewall || cli.autocenter;
    let seen: Vec<Result<Aabb>> = (0..frames.len())
        .into_par_iter()
        .map(|i| {
            load(i).map(|s| {
                if openscad_view {
                    s.result_bounds()
                } else {
                    s.framing_bounds()
                }
            })
        })
        .collect();
    let whole = seen
        .iter()
        .flatten()
        .fold(Aabb::EMPTY, |all, b| all.union(b));
    // What the frames say is said once (each thing in the order first said).
    let told: Vec<Result<(csgrt::Scene, Vec<String>)>> = (0..frames.len())
        .into_par_iter()
        .map(|i| {
            let mut scene = load(i)?;
            let said = finish_scene(cli, &mut scene, Some(&whole))?;
            Ok((scene, said))
        })
        .collect();
    let mut said_once: Vec<&String> = Vec::new();
    for said in told.iter().flatten().flat_map(|(_, s)| s) {
        if !said_once.contains(&said) {
            said_once.push(said);
        }
    }
    for s in said_once {
        eprintln!("{s}");
    }
    let kept = told
        .iter()
        .zip(&export.frames)
        .any(|(t, frame)| csgrt::keeps_export(t.as_ref().ok().map(|(s, _)| s), frame));
    let results: Vec<Result<()>> = told
        .into_par_iter()
        .zip(frames.par_iter())
        .map(|(scene, job)| scene.and_then(|(scene, _)| render_files(cli, job, &scene, false)))
        .collect();
    if kept {
        // A message points into the export (or may): kept for it.
        export.keep();
    }
    Ok(results)
}
