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
//! span lists → shading → pixels). [`cli`] wires them to the command line.

pub mod cli;
pub mod csg;
pub mod drawing;
pub mod dump;
pub mod error;
pub mod geometry;
pub mod math;
#[doc(hidden)]
pub mod harness;
pub mod meshfile;
#[doc(hidden)]
pub mod mutant;
pub mod plane;
pub mod pov;
pub mod render;
pub mod scad;
pub mod scene;
pub mod stats;
pub mod svg;
pub mod syntax;
pub mod text;
mod watch;

pub use error::{Error, Result, Source};
pub use scene::Scene;

/// Parses and resolves `.csg` text into a scene.
pub fn load_csg(src: &Source) -> Result<Scene> {
    load_csg_with(src, scene::Facets::default())
}

/// [`load_csg`] with `$fn`, `$fa`, `$fs` read as `facets` says.
pub fn load_csg_with(src: &Source, facets: scene::Facets) -> Result<Scene> {
    let ast = syntax::parse_csg(src)?;
    scene::resolve_with(src, &ast, facets)
}
