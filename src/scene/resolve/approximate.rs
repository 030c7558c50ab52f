//! The certified approximation: a node that has no exact hull, Minkowski
//! sum or shadow (an intersection, a difference, a cylinder's shadow) cut
//! into convex polytopes within [`APPROXIMATION`] of its size
//! ([`crate::csg::Csg::convex_pieces`]), recorded with its error so that
//! csgrt says it once, in pixels at the view (`Scene::approximations`).

use super::Resolver;
use crate::csg::NodeKind;
use crate::error::Severity;
use crate::geometry::polytope::Polytope;
use crate::syntax::ast::Statement;
use glam::DAffine3;

/// The certified approximation's error bound, relative to the longest side
/// of the box of the node approximated: each polytope stays within this of
/// the exact solid, so the hull or sum made of them does too — under half
/// a pixel at any view where that node spans fewer than 4096 pixels.
pub const APPROXIMATION: f64 = 1.0 / 8192.0;

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
            let size = (b.max - b.min).max_element();
            let eps = size * APPROXIMATION;
            let tol = crate::geometry::polytope::plane_tolerance(&b);
            let what = match &self.b.csg.nodes[node as usize].kind {
                NodeKind::Op(op, _) => format!("a 3-D {}", op.name()),
                NodeKind::Leaf(i) => format!("a `{}`", self.b.csg.prims[*i as usize].shape.name()),
                NodeKind::Section(..) => "a projection".to_string(),
            };
            let cut = self.b.csg.convex_pieces(node, eps, tol, columns);
            out.extend(cut.map_err(|e| match self.b.csg.nodes[node as usize].kind {
                NodeKind::Leaf(_) => e,
                _ => format!("{what} with {e} in it"),
            })?);
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
}
