//! # csgrt — an exact constructive-solid-geometry ray tracer
//!
//! csgrt reads OpenSCAD's CSG text (plus camera, light and material
//! statements of its own) and renders it exactly, with no meshing: every
//! primitive returns the spans of a ray inside it, CSG nodes combine those
//! lists from the leaves to the root, and the Whitted model of the seed
//! lecture shades the first surface.
//!
//! Data flows one way:
//! [`syntax`] (pest grammar → AST with spans) → [`scene`] (AST → [`Scene`]:
//! transforms, materials, defaults) → [`render`] (camera rays → [`csg`]
//! span lists → shading → pixels). The command line (`src/main.rs` and
//! `src/cli/`) is the binary's, outside the library.

pub mod csg;
pub mod error;
pub mod export;
pub mod geometry;
#[doc(hidden)]
pub mod harness;
pub mod import;
pub mod math;
#[doc(hidden)]
pub mod mutant;
pub mod plane;
pub mod render;
pub mod scene;
pub mod source;
pub mod stats;
pub mod syntax;

pub use error::{Error, Result};
pub use source::Source;

pub use scene::Scene;
use std::path::Path;

/// Parses and resolves `.csg` text into a scene.
pub fn load_csg(src: &Source) -> Result<Scene> {
    load_csg_with(src, scene::Facets::default())
}

/// [`load_csg`] with `$fn`, `$fa`, `$fs` read as `facets` says.
pub fn load_csg_with(src: &Source, facets: scene::Facets) -> Result<Scene> {
    let ast = syntax::parse_csg(src)?;
    scene::resolve_with(src, &ast, facets)
}

/// Parses and resolves a `.ray` display list into a scene.
pub fn load_ray(src: &Source) -> Result<Scene> {
    scene::resolve_ray(src, &syntax::ray::parse_ray(src)?)
}

/// A frame of OpenSCAD's export of a `.scad` program resolved into a
/// scene, with the view the program sets (`$vpt`, `$vpr`, `$vpd`).
pub fn load_scad_frame(frame: &import::scad::Frame, facets: scene::Facets) -> Result<Scene> {
    let mut scene = load_csg_with(&frame.source, facets)?;
    scene.scad_view = frame.view.map(scene::openscad_view::Viewpoint::of_scad);
    Ok(scene)
}

/// Whether a frame's export must be kept: a message of its scene points
/// into it, or loading it failed (`None`: its error may).
pub fn keeps_export(loaded: Option<&Scene>, frame: &import::scad::Frame) -> bool {
    loaded.map_or(true, |s| s.mentions(&frame.source.name))
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
    match source::extension(path).as_deref() {
        Some("csg") => crate::load_csg_with(&source::read_source(path)?, facets),
        Some("ray") => load_ray(&source::read_source(path)?),
        Some("scad") => {
            let export = crate::import::scad::export(path, defines)?;
            let loaded = load_scad_frame(&export.frames[0], facets);
            if keeps_export(loaded.as_ref().ok(), &export.frames[0]) {
                export.keep();
            }
            loaded
        }
        // A missing file or a folder said as such before its extension.
        _ => source::model_file(path).and(Err(Error::Usage(format!(
            "{}: unknown model format; expected a `.csg` scene, a `.ray` display list or a `.scad` program",
            path.display()
        )))),
    }
}
