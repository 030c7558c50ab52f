//! The certified approximation: a node that has no exact hull, Minkowski
//! sum or shadow (an intersection, a difference, a cylinder's shadow) cut
//! into convex polytopes within [`APPROXIMATION`] of its size
//! ([`crate::csg::Csg::convex_pieces`]), recorded with its error so that
//! csgrt says it once, in pixels at the view (`Scene::approximations`).

use super::Resolver;
use crate::csg::NodeKind;
use crate::error::Severity;
use crate::geometry::convex::ConvexPart;
use crate::geometry::polytope::Polytope;
use crate::geometry::Aabb;
use crate::plane::figure::Figure;
use crate::scene::args::Args;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DVec2, DVec3};

/// The certified approximation's error bound, relative to the longest side
/// of the box of the node approximated: each polytope stays within this of
/// the exact solid, so the hull or sum made of them does too — under half
/// a pixel at any view where that node spans fewer than 4096 pixels.
pub const APPROXIMATION: f64 = 1.0 / 8192.0;

/// The most corners a hull's exactly taken parts are cut into beside its
/// cut nodes ([`Resolver::part_polytopes`]); past it they stay exact.
pub const MAX_PART_CORNERS: usize = 200_000;

/// What the certified approximation takes, said where it cannot.
pub const LIMITS: &str = "csgrt cuts bounded solids into at most 250000 convex pieces within 1/8192 of their size (every limit is listed in docs/LANGUAGE.md)";

impl Resolver<'_> {
    /// Nodes `cut` as convex polytopes within [`APPROXIMATION`] of their
    /// size, each recorded as approximated at statement `s` placed by
    /// `frame` (cells cut in `columns` along z, for a shadow); or what
    /// stands in the way.
    pub(super) fn polytopes(
        &mut self,
        s: &Statement,
        cut: &[u32],
        frame: DAffine3,
        columns: bool,
    ) -> std::result::Result<Vec<Polytope>, String> {
        let mut out = Vec::new();
        for &node in cut {
            let b = self.b.csg.nodes[node as usize].bounds;
            if b.is_empty() {
                continue;
            }
            if !b.is_bounded() {
                return Err("an unbounded solid (a halfspace)".into());
            }
            let what = match &self.b.csg.nodes[node as usize].kind {
                NodeKind::Op(op, _) => format!("a 3-D {}", op.name()),
                NodeKind::Leaf(i) => format!("a `{}`", self.b.csg.prims[*i as usize].shape.name()),
                NodeKind::Section(..) => "a projection".to_string(),
            };
            let (pieces, eps) = self.pieces_within(node, columns).map_err(|e| {
                match self.b.csg.nodes[node as usize].kind {
                    NodeKind::Leaf(_) => e,
                    _ => format!("{what} (in it {e})"),
                }
            })?;
            out.extend(pieces);
            let world = crate::geometry::solid::corner_box(&b, &frame);
            let eps = eps * crate::geometry::polytope::stretch(&frame);
            let note = self.src.diagnostic(
                Severity::Note,
                s.name_span,
                format!("`{}` of {what} is approximated by convex polytopes", s.name),
                format!("within {eps:.3e} of the exact solid (1/8192 of its size)"),
            );
            self.b.approximations.push(crate::scene::Approximation {
                note,
                bounds: world,
                eps,
            });
        }
        Ok(out)
    }

    /// The parts a hull takes exactly (by their support points) when
    /// others of it are cut already: the hull is approximated anyway, so
    /// these are cut into convex polytopes too, within `eps` (the least
    /// distance any cut node is cut within: [`Resolver::cut_within`]), and
    /// the hull of them all is one polytope, met with no support-function
    /// steps, within what the cut nodes' notes (those from `noted` on)
    /// say; their boxes grow to take in the parts. The pieces' corners;
    /// `None` where a part cannot be cut or they would pass
    /// [`MAX_PART_CORNERS`] (the parts stay exact).
    pub(super) fn part_polytopes(
        &mut self,
        parts: &[ConvexPart],
        eps: f64,
        frame: DAffine3,
        noted: usize,
    ) -> Option<Vec<DVec3>> {
        let eps = if crate::mutant::active("hull_parts_coarse") {
            8.0 * eps
        } else {
            eps
        };
        let (mut corners, mut all) = (Vec::new(), Aabb::EMPTY);
        for p in parts {
            let b = p.shape.world_bounds(&p.to_world);
            // (A part far larger than the cut nodes: cut that finely, too
            // many corners; past eight times its own fineness, exact.)
            if b.is_empty() || !b.is_bounded() || cut_distance(&b) > 8.0 * eps {
                return None;
            }
            let tol = crate::geometry::polytope::plane_tolerance(&b);
            let pieces =
                crate::geometry::polytope::pieces_of(&p.shape, &p.to_world, eps, tol).ok()?;
            corners.extend(pieces.iter().flat_map(|q| q.vertices()));
            if corners.len() > MAX_PART_CORNERS {
                return None;
            }
            all = all.union(&b);
        }
        let world = crate::geometry::solid::corner_box(&all, &frame);
        for a in &mut self.b.approximations[noted..] {
            a.bounds = a.bounds.union(&world);
        }
        Some(corners)
    }

    /// The least distance nodes `cut` are cut within by
    /// [`Resolver::polytopes`].
    pub(super) fn cut_within(&self, cut: &[u32]) -> f64 {
        cut.iter()
            .map(|&c| cut_distance(&self.b.csg.nodes[c as usize].bounds))
            .fold(f64::INFINITY, f64::min)
    }

    /// Bounded node `node` cut into convex polytopes within
    /// [`APPROXIMATION`] of the longest side of its box (planes as thick
    /// as [`crate::geometry::polytope::plane_tolerance`] says), and that
    /// distance.
    fn pieces_within(
        &self,
        node: u32,
        columns: bool,
    ) -> std::result::Result<(Vec<Polytope>, f64), String> {
        let b = self.b.csg.nodes[node as usize].bounds;
        let eps = cut_distance(&b);
        let tol = crate::geometry::polytope::plane_tolerance(&b);
        Ok((self.b.csg.convex_pieces(node, eps, tol, columns)?, eps))
    }
}

/// The distance a solid boxed by `b` is cut within: [`APPROXIMATION`] of
/// the box's longest side.
fn cut_distance(b: &Aabb) -> f64 {
    (b.max - b.min).max_element() * APPROXIMATION
}

impl Resolver<'_> {
    /// Figure `f` of statement `s` flattened to straight polygons within
    /// [`APPROXIMATION`] of its size ([`crate::plane::flat`]; circles kept
    /// exact when `circles`), its note waiting for the extrusion that
    /// places it; `what` says what is approximated. `Ok(None)`: nothing
    /// with area is left.
    pub(super) fn flat_figure(
        &mut self,
        s: &Statement,
        f: &Figure,
        circles: bool,
        what: &str,
    ) -> std::result::Result<Option<Figure>, String> {
        if crate::plane::flat::straight(f, circles) {
            return Ok(Some(f.clone()));
        }
        // Projections first: their solids are read now, as polytopes.
        let mut sections = 0.0f64;
        let Some(f) = self.unsectioned(f, &mut sections)? else {
            return Ok(None);
        };
        let ((x0, x1), (y0, y1)) = (f.range(DVec2::X), f.range(DVec2::Y));
        let size = (x1 - x0).max(y1 - y0);
        if !size.is_finite() {
            return Err(format!("{what} of an unbounded shape"));
        }
        if size <= 0.0 {
            return Ok(None);
        }
        let eps = size * APPROXIMATION;
        let flat = crate::plane::flat::flattened(&f, eps, circles)
            .map_err(|e| format!("{what} of {e}"))?;
        let eps = eps.max(sections);
        let note = self.src.diagnostic(
            Severity::Note,
            s.name_span,
            format!("{what} is approximated by straight polygons"),
            format!("within {eps:.3e} of the exact shape (1/8192 of its size)"),
        );
        self.plane_notes.push((note, eps));
        Ok(flat)
    }

    /// `work`, whose notes of flattened shapes are taken back when it
    /// fails (nothing it flattened is then drawn).
    pub(super) fn noted_if_done<T>(
        &mut self,
        work: impl FnOnce(&mut Self) -> std::result::Result<T, String>,
    ) -> std::result::Result<T, String> {
        let mark = self.plane_notes.len();
        let done = work(self);
        if done.is_err() {
            self.plane_notes.truncate(mark);
        }
        done
    }

    /// `f` with each projection replaced by straight polygons: its solid
    /// (read now, in the projection's own frame) cut into convex
    /// polytopes within [`APPROXIMATION`] of its size, each projected onto
    /// z = 0 (the hull of its corners' shadows: a shadow moves no farther
    /// than the solid) or, for `cut = true`, met with it (the polygon of
    /// its edges' crossings: within the bound where the surface crosses
    /// the plane steeply, eps / sin θ at angle θ), their union placed in
    /// the plane. `worst` gets the largest error in the plane.
    fn unsectioned(
        &mut self,
        f: &Figure,
        worst: &mut f64,
    ) -> std::result::Result<Option<Figure>, String> {
        Ok(match f {
            Figure::Section(id, at) => {
                let p = self.projections[*id as usize].clone();
                let cut = Args::bind(self.src, &p, &["cut", "convexity"])
                    .and_then(|a| a.boolean("cut"))
                    .map_err(|_| "a projection whose `cut` is not a boolean".to_string())?
                    .unwrap_or(false);
                let mark = self.b.csg.mark();
                let noted = self.b.approximations.len();
                let found = self
                    .projected(&p, DAffine3::IDENTITY, crate::scene::defaults::MATERIAL)
                    .map_err(|e| e.to_string())
                    .and_then(|ids| match self.union(ids) {
                        None => Ok(None),
                        Some(node) => {
                            let b = self.b.csg.nodes[node as usize].bounds;
                            if !b.is_bounded() {
                                return Err(
                                    "a projection of an unbounded solid (a halfspace)".into()
                                );
                            }
                            self.pieces_within(node, false).map(Some)
                        }
                    });
                self.b.csg.rewind(mark);
                // What the solid's own statements approximated (a hull of
                // a difference in it) is in the shadow too: their notes
                // wait, in the plane, for the extrusion that places it.
                let inner: Vec<_> = self.b.approximations.drain(noted..).collect();
                let Some((pieces, eps)) = found? else {
                    return Ok(None);
                };
                let sigma = crate::plane::flat::largest_stretch(at.matrix2);
                for a in inner {
                    self.plane_notes.push((a.note, a.eps * sigma));
                }
                *worst = worst.max(eps * sigma);
                let polys: Vec<Option<Figure>> = pieces
                    .iter()
                    .map(|q| {
                        let pts = if cut { q.slice_z0() } else { q.shadow_z() };
                        let tol =
                            1e-12 * pts.iter().fold(1.0f64, |m, p| m.max(p.abs().max_element()));
                        let hull: Vec<DVec2> = crate::plane::hull::hull_indices_2d(&pts, tol)
                            .into_iter()
                            .map(|i| pts[i])
                            .collect();
                        (hull.len() >= 3)
                            .then(|| Figure::Polygon(crate::plane::Outlines::polygons(vec![hull])))
                    })
                    .collect();
                crate::math::boolean::combine_parts(
                    crate::math::boolean::Op::Union,
                    polys,
                    Figure::Op,
                )
                .map(|g| g.moved(*at))
            }
            Figure::Op(op, kids) => {
                let mut parts = Vec::new();
                for k in kids {
                    parts.push(self.unsectioned(k, worst)?);
                }
                crate::math::boolean::combine_parts(*op, parts, Figure::Op)
            }
            Figure::Hull(kids) => {
                let mut parts = Vec::new();
                for k in kids {
                    parts.extend(self.unsectioned(k, worst)?);
                }
                (!parts.is_empty()).then_some(Figure::Hull(parts))
            }
            _ => Some(f.clone()),
        })
    }

    /// The notes of 2-D approximations made since `mark`, placed with the
    /// extrusion `node` they became part of: its box, and the error
    /// stretched by at most `sigma` (none is left when it is empty).
    pub(super) fn placed_plane_notes(&mut self, mark: usize, node: Option<u32>, sigma: f64) {
        let notes: Vec<_> = self.plane_notes.drain(mark..).collect();
        let Some(node) = node else {
            return;
        };
        let bounds = self.b.csg.nodes[node as usize].bounds;
        for (note, eps) in notes {
            self.b.approximations.push(crate::scene::Approximation {
                note,
                bounds,
                eps: eps * sigma,
            });
        }
    }

    /// The approximations recorded since `mark` in a statement's own frame
    /// (the children of a hull or a sum), placed by `frame`.
    pub(super) fn placed_approximations(&mut self, mark: usize, frame: &DAffine3) {
        let sigma = crate::geometry::polytope::stretch(frame);
        for a in &mut self.b.approximations[mark..] {
            a.bounds = crate::geometry::solid::corner_box(&a.bounds, frame);
            a.eps *= sigma;
        }
    }
}
