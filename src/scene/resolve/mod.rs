//! Syntax tree → [`Scene`]: transforms composed, materials inherited,
//! defaults applied, every problem reported at its place in the file.
//!
//! The walk over the tree is here; each kind of statement is read in its
//! own file: `solids` (the table of solid statements and their binders),
//! `transforms`, `appearance` and `statements` (camera, lights).

mod appearance;
mod approximate;
mod extrude;
mod facet_mesh;
mod hull_minkowski;
mod planar;
mod projection;
mod resize;
mod solids;
mod statements;
mod transforms;

pub use solids::later_statements;

use super::args::{Args, SCENE};
use super::builder::SceneBuilder;
use super::{defaults, Material, Scene};
use crate::error::{Result, Severity, TextRange};
use crate::geometry::transform::{Degenerate, MAX_MAGNITUDE};
use crate::geometry::{Shape, Transform};
use crate::math::boolean::Op;
use crate::mutant;
use crate::source::Source;
use crate::syntax::ast::Statement;
use glam::DAffine3;

/// The most fragments `--facets openscad` builds for one circle.
pub const MAX_FRAGMENTS: usize = 100_000;

const TRANSFORMS: &[&str] = &["multmatrix", "translate", "rotate", "scale", "mirror"];
const OPERATIONS: &[&str] = &["union", "intersection", "difference", "group", "render"];
const APPEARANCE: &[&str] = &["color", "material"];

pub fn resolve(src: &Source, stmts: &[Statement]) -> Result<Scene> {
    resolve_with(src, stmts, super::Facets::default())
}

/// [`resolve`] with `$fn`, `$fa` and `$fs` read as `facets` says.
pub fn resolve_with(src: &Source, stmts: &[Statement], facets: super::Facets) -> Result<Scene> {
    let mut r = Resolver {
        src,
        b: SceneBuilder::new(),
        camera_at: None,
        subtracted: false,
        facets,
        projections: Vec::new(),
        plane_notes: Vec::new(),
    };
    // Scene statements are read first, wherever they stand at the top level.
    for s in stmts {
        if SCENE.contains(&s.name.as_str()) && !skipped(s) {
            r.scene_statement(s)?;
        }
    }
    // `!` makes the first subtree that carries it the whole design.
    let root = find_root(stmts);
    let solids: Vec<&Statement> = match root {
        Some(s) => vec![s],
        None => r
            .operands(stmts.iter().filter(|s| !SCENE.contains(&s.name.as_str())))
            .into_iter()
            .flatten()
            .collect(),
    };
    let mut ids = Vec::new();
    let mut planar = true;
    for s in solids {
        if let Some(id) = r.statement(s, DAffine3::IDENTITY, defaults::MATERIAL, 0)? {
            ids.push(id);
            planar &= resize::is_planar(s);
        }
    }
    let root = r.b.union(ids);
    let place = stmts.first().map_or(TextRange::default(), |s| s.span);
    let mut scene = r.b.finish(src, root, place, defaults::BACKGROUND);
    scene.planar = planar && root.is_some();
    Ok(scene)
}

fn skipped(s: &Statement) -> bool {
    s.modifiers.disable || s.modifiers.background
}

fn find_root(stmts: &[Statement]) -> Option<&Statement> {
    for s in stmts {
        if skipped(s) {
            continue;
        }
        if s.modifiers.root {
            return Some(s);
        }
        if let Some(r) = find_root(&s.children) {
            return Some(r);
        }
    }
    None
}

pub(crate) struct Resolver<'a> {
    src: &'a Source,
    b: SceneBuilder,
    /// Where the camera statement stands, once read.
    camera_at: Option<TextRange>,
    /// Whether the statement being read is subtracted by a difference (an
    /// odd number of times), for the preview slab of a 2-D shape.
    subtracted: bool,
    /// How `$fn`, `$fa`, `$fs` are read.
    facets: super::Facets,
    /// The `projection` statements read in 2-D trees, by the number their
    /// [`Figure::Section`](crate::plane::figure::Figure::Section) holds:
    /// their children are read only when the tree is extruded.
    projections: Vec<Statement>,
    /// The notes of 2-D shapes flattened by the certified approximation,
    /// with their error in the plane, until an extrusion places them
    /// ([`Resolver::placed_plane_notes`]).
    plane_notes: Vec<(crate::error::Diagnostic, f64)>,
}

/// OpenSCAD's smallest radius that is still a circle (`grid.h`).
pub(super) const GRID_FINE: f64 = 0.000_000_953_674_316_406_25;

impl Resolver<'_> {
    /// The regular polygon a circle, cylinder or sphere of radius `r` is
    /// made of, if any, by the `--facets` mode: OpenSCAD's
    /// `Calc::get_fragments_from_r` under `openscad` (3 below GRID_FINE;
    /// max($fn, 3) for a positive $fn; else ⌈max(min(360/$fa, 2πr/$fs), 5)⌉).
    fn fragments(&self, a: &Args, r: f64) -> Option<usize> {
        match self.facets {
            super::Facets::Exact => None,
            super::Facets::Shapes => a.few_facets(),
            super::Facets::OpenScad => {
                let fnv = a.special("$fn").unwrap_or(0.0);
                let fa = a.special("$fa").filter(|v| v.is_finite()).unwrap_or(12.0);
                let fs = a.special("$fs").filter(|v| v.is_finite()).unwrap_or(2.0);
                let n = if r < GRID_FINE || !fnv.is_finite() {
                    3.0
                } else if fnv > 0.0 {
                    fnv.max(3.0).floor()
                } else {
                    (360.0 / fa)
                        .min(r * 2.0 * std::f64::consts::PI / fs)
                        .max(5.0)
                        .ceil()
                };
                Some(n.min(MAX_FRAGMENTS as f64) as usize)
            }
        }
    }

    /// Under `--facets openscad`, a warning for a statement whose facets
    /// csgrt does not build: it is drawn exact (an error under --strict).
    fn facets_drawn_exact(&mut self, s: &Statement, what: &str) {
        if self.facets != super::Facets::OpenScad {
            return;
        }
        self.warn(
            s.name_span,
            &format!("{what} is drawn exact under `--facets openscad`"),
            "csgrt builds OpenSCAD's facets of circles, cylinders, spheres and of straight polygons turned or twisted, not of this",
        );
    }

    /// The bytes of a file the model names, or an error at `place` with
    /// the system's reason: "cannot read `what` `path`: …".
    fn read_named(
        &self,
        place: TextRange,
        path: &std::path::Path,
        what: &str,
        label: &str,
    ) -> Result<Vec<u8>> {
        // OpenSCAD: "Can't open import file", and the statement is empty.
        std::fs::read(path).map_err(|e| {
            self.src.lenient(
                place,
                format!("cannot read {what} `{}`: {e}", path.display()),
                label,
            )
        })
    }

    fn warn(&mut self, place: TextRange, message: &str, label: &str) {
        self.b.warn(self.src, place, message, label);
    }

    fn union(&mut self, ids: Vec<u32>) -> Option<u32> {
        self.b.union(ids)
    }

    fn children(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Vec<u32>> {
        let mut ids = Vec::new();
        for c in self.operands(&s.children).into_iter().flatten() {
            if let Some(id) = self.statement(c, xf, mat, depth + 1)? {
                ids.push(id);
            }
        }
        Ok(ids)
    }

    /// The children of a `projection`, which takes 3-D children only: a
    /// 2-D one is left out with OpenSCAD's warning (`applyToChildren3D`).
    fn projected(&mut self, p: &Statement, xf: DAffine3, mat: Material) -> Result<Vec<u32>> {
        let mut ids = Vec::new();
        for c in p.children.iter().filter(|c| !skipped(c)) {
            if resize::dimension(c) == Some(true) {
                self.left_out(c, true);
                continue;
            }
            ids.extend(self.statement(c, xf, mat, 1)?);
        }
        Ok(ids)
    }

    /// The live children of an operation (or a transform, or the top
    /// level) as OpenSCAD's render takes them: the operation has the
    /// dimension of its first child that has one, and a child of the other
    /// dimension stands as an empty operand (`None`), with OpenSCAD's
    /// warning (`GeometryEvaluator::collectChildren3D`/`2D`).
    fn operands<'s>(
        &mut self,
        children: impl IntoIterator<Item = &'s Statement>,
    ) -> Vec<Option<&'s Statement>> {
        let live: Vec<&Statement> = children.into_iter().filter(|c| !skipped(c)).collect();
        let dims: Vec<Option<bool>> = live.iter().map(|c| resize::dimension(c)).collect();
        let Some(&planar) = dims.iter().flatten().next() else {
            return live.into_iter().map(Some).collect();
        };
        live.into_iter()
            .zip(dims)
            .map(|(c, d)| match d {
                Some(d) if d != planar && !mutant::active("dimensions_mixed") => {
                    self.left_out(c, d);
                    None
                }
                _ => Some(c),
            })
            .collect()
    }

    /// OpenSCAD's warning for a child of the other dimension than its
    /// operation's (`planar`: the child's), which is left out.
    fn left_out(&mut self, c: &Statement, planar: bool) {
        let (other, this) = if planar { ("2D", "3D") } else { ("3D", "2D") };
        self.warn(
            c.name_span,
            &format!("Ignoring {other} child object for {this} operation"),
            "it is left out, as OpenSCAD's render leaves it out",
        );
    }

    /// One statement under the world transform `xf` and material `mat`;
    /// `None` when it adds no solid.
    fn statement(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        let r = self.solid_of(s, xf, mat, depth);
        self.rendered_past(s, r)
    }

    /// A statement's result as OpenSCAD renders past it: a problem it only
    /// warns about ([`Severity::Lenient`]) becomes that warning, and the
    /// statement is empty.
    pub(super) fn rendered_past<T>(
        &mut self,
        s: &Statement,
        r: Result<Option<T>>,
    ) -> Result<Option<T>> {
        match r {
            Err(crate::Error::Scene(mut d))
                if d.severity == Severity::Lenient && !mutant::active("lenient_refused") =>
            {
                d.severity = Severity::Warning;
                d.label = format!(
                    "{}; this `{}` is left out, as OpenSCAD leaves it out",
                    d.label, s.name
                );
                self.b.warnings.push(*d);
                Ok(None)
            }
            r => r,
        }
    }

    /// [`Resolver::statement`] before OpenSCAD's leniency.
    fn solid_of(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        if skipped(s) {
            return Ok(None);
        }
        let name = s.name.as_str();
        match solids::binder(name) {
            Some(Some(bind)) => {
                if !solids::WITH_CHILDREN.contains(&name) {
                    self.no_children(s)?;
                }
                return bind(self, s, xf, mat, depth);
            }
            Some(None) => return Err(self.unknown_to_openscad(s)),
            None => {}
        }
        if TRANSFORMS.contains(&name) {
            let local = self.transform(s)?;
            let world = if mutant::active("compose_reversed") {
                local * xf
            } else {
                xf * local
            };
            let ids = self.children(s, world, mat, depth)?;
            return Ok(self.union(ids));
        }
        if APPEARANCE.contains(&name) {
            let m = self.appearance(s, mat)?;
            let ids = self.children(s, xf, m, depth)?;
            return Ok(self.union(ids));
        }
        if OPERATIONS.contains(&name) {
            let params: &'static [&'static str] = if name == "render" {
                &["convexity"]
            } else {
                &[]
            };
            Args::bind(self.src, s, params)?;
            return match name {
                "difference" => self.difference(s, xf, mat, depth),
                "intersection" => {
                    // Every operand is built (so errors in any are reported);
                    // an empty operand makes the intersection empty.
                    let mut parts = Vec::new();
                    for c in self.operands(&s.children) {
                        parts.push(match c {
                            Some(c) => self.statement(c, xf, mat, depth + 1)?,
                            None => None,
                        });
                    }
                    Ok(self.op(Op::Intersection, parts))
                }
                _ => {
                    let ids = self.children(s, xf, mat, depth)?;
                    Ok(self.union(ids))
                }
            };
        }
        if SCENE.contains(&name) {
            let label = if depth == 0 {
                "a scene statement takes no modifiers here"
            } else {
                "move it to the top level of the file"
            };
            return Err(self.src.error(
                s.name_span,
                format!("`{name}` must stand at the top level"),
                label,
            ));
        }
        Err(self.src.error(
            s.name_span,
            format!("unknown statement `{name}`"),
            "expected a solid, a transform, a CSG operation, color, material or a scene statement",
        ))
    }

    /// `op` over `parts` (see [`combine`]), a new node when two or more
    /// are solids.
    fn op(&mut self, op: Op, parts: Vec<Option<u32>>) -> Option<u32> {
        let csg = &mut self.b.csg;
        crate::math::boolean::combine_parts(op, parts, |op, ids| csg.add_op(op, ids))
    }

    /// OpenSCAD 2021.01's warning for a statement of [`solids::SOLIDS`]
    /// without a binder (newer than that release, unknown to it): left
    /// out, as it leaves it out.
    fn unknown_to_openscad(&self, s: &Statement) -> crate::error::Error {
        self.src.lenient(
            s.name_span,
            format!("Ignoring unknown module '{}'", s.name),
            format!(
                "`{}` is newer than OpenSCAD 2021.01, which csgrt renders as",
                s.name
            ),
        )
    }

    /// An error if the solid `s` has children.
    fn no_children(&self, s: &Statement) -> Result<()> {
        match s.children.first() {
            Some(c) => Err(self.src.error(
                c.span,
                format!("`{}` takes no children", s.name),
                "a solid stands alone; end it with `;`",
            )),
            None => Ok(()),
        }
    }

    /// The first child minus the union of the others; empty if the first
    /// child is.
    fn difference(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        let operands = self.operands(&s.children);
        let mut kids = operands.into_iter();
        let Some(Some(first)) = kids.next() else {
            return Ok(None);
        };
        let Some(a) = self.statement(first, xf, mat, depth + 1)? else {
            return Ok(None);
        };
        let mut ids = vec![a];
        self.subtracted = !self.subtracted;
        for c in kids.flatten() {
            if let Some(id) = self.statement(c, xf, mat, depth + 1)? {
                ids.push(id);
            }
        }
        self.subtracted = !self.subtracted;
        Ok(Some(if ids.len() == 1 {
            a
        } else {
            self.b.csg.add_op(Op::Difference, ids)
        }))
    }

    pub(super) fn leaf(
        &mut self,
        s: &Statement,
        shape: Shape,
        world: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let xf = match Transform::new(world) {
            Ok(xf) => xf,
            Err(Degenerate::Flat) => return Ok(self.flattened(s)),
            Err(Degenerate::OutOfRange) => {
                return Err(self.src.error(
                    s.name_span,
                    format!("this `{}` is out of range", s.name),
                    format!("expected sizes and positions within ±{MAX_MAGNITUDE:e}"),
                ));
            }
        };
        let material = self.b.material_id(mat);
        Ok(Some(self.b.leaf(shape, xf, material)))
    }

    /// A statement flattened by a singular transform: warned, left out.
    pub(super) fn flattened(&mut self, s: &Statement) -> Option<u32> {
        self.warn(
            s.name_span,
            &format!("this `{}` is flattened by a singular transform", s.name),
            "it has no volume and is left out, as in OpenSCAD",
        );
        None
    }

    /// A problem OpenSCAD reports and goes on past: the same message as a
    /// warning, with what is done instead. Anything but a problem in the
    /// file stays an error.
    pub(super) fn go_on(&mut self, e: crate::Error, instead: &str) -> Result<()> {
        match e {
            crate::Error::Scene(mut d) => {
                d.severity = crate::error::Severity::Warning;
                d.message = format!("{}; {instead}", d.message);
                self.b.warnings.push(*d);
                Ok(())
            }
            e => Err(e),
        }
    }

    pub(super) fn empty(&mut self, s: &Statement, why: &str) -> Result<Option<u32>> {
        self.warn(s.args_span, &format!("this `{}` is empty", s.name), why);
        Ok(None)
    }
}
