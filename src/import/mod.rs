//! Readers of the files a model names, each through a well-kept crate:
//! SVG drawings ([`svg`], roxmltree and svgtypes), DXF drawings ([`dxf`],
//! the dxf crate), meshes ([`meshfile`]: STL, OFF, OBJ, AMF, 3MF and
//! OpenSCAD's `surface` height maps; [`nef3`]: CGAL's Nef polyhedra, read
//! here, no crate reads them), fonts and shaped text ([`text`],
//! fontdb, ttf-parser and rustybuzz), and `.scad` programs through
//! OpenSCAD's own export ([`scad`]). Each gives plain data (outlines,
//! triangles, glyph curves, CSG text); the scene turns it into solids.

pub mod dxf;
pub mod dxf_figure;
pub mod meshfile;
pub mod nef3;
pub mod scad;
pub mod svg;
pub mod svg_figure;
pub mod text;
