//! `projection(cut = false)` extruded: the shadow of its children on the
//! plane z = 0, exactly, for the children it can be shown exact for.
//!
//! The shadow of a union is the union of the shadows. An upright prism's
//! (a straight `linear_extrude`, a cylinder, a box, standing along z, or a
//! combination of them all over one height) is its section, and the
//! shadow of an intersection one of whose operands is such a prism over
//! the whole height of the others is that section met with the others'
//! shadow: the prism is its section at every height the others reach.
//! Both are drawn exactly, by the prisms' own leaves swept over the
//! shadow's height. A mesh's (a
//! polyhedron, an imported file) is the union of its triangles' shadows,
//! and a cube's of its six faces' ([`crate::geometry::shadow`]); a sphere
//! under its transform is an ellipsoid, whose shadow is the ellipse
//! E·(unit disc) with E·Eᵀ = P·Pᵀ, P the transform's x and y rows. The
//! children are read once, in the projection's own frame, to be measured,
//! and dropped. Anything else (an intersection or a difference, whose
//! shadow is not its operands', or a cylinder's, a convex hull of two
//! ellipses) is cut into convex polytopes within a certified distance
//! (`resolve::approximate`), whose faces cast the shadow.

use super::Resolver;
use crate::csg::NodeKind;
use crate::error::Result;
use crate::geometry::shadow::Soup;
use crate::geometry::{Cone, Shadow, Shape};
use crate::math::boolean::Op;
use crate::scene::Material;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DMat2, DMat3, DVec2, DVec3};
use std::sync::Arc;

/// The corners of a box, and its twelve triangles (two a face).
const BOX_TRIS: [[u32; 3]; 12] = [
    [0, 1, 3],
    [0, 3, 2],
    [4, 5, 7],
    [4, 7, 6],
    [0, 1, 5],
    [0, 5, 4],
    [2, 3, 7],
    [2, 7, 6],
    [0, 2, 6],
    [0, 6, 4],
    [1, 3, 7],
    [1, 7, 5],
];

/// A shadow's parts, read from the projected tree before it is dropped.
enum Cast {
    /// The shadows of faces (triangles on the plane) and of ellipsoids
    /// (an ellipse's matrix and centre).
    Flat {
        pts: Vec<DVec2>,
        tris: Vec<[u32; 3]>,
        ellipses: Vec<(DMat2, DVec2)>,
    },
    /// An upright prism's leaf, placed so that its height is z = 0 to 1.
    Upright(Shape, DAffine3),
    Op(Op, Vec<Cast>),
}

impl Resolver<'_> {
    /// The shadow of projection `p`'s children (placed by `frame`, as
    /// [`Resolver::section`] places a slice) swept from z = 0 to 1.
    pub(super) fn shadow(
        &mut self,
        p: &Statement,
        frame: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let mark = self.b.csg.mark();
        let ids = self.projected(p, DAffine3::IDENTITY, mat)?;
        let Some(child) = self.union(ids) else {
            return Ok(None);
        };
        let cast = self.cast(p, child, frame);
        self.b.csg.rewind(mark);
        let cast = cast.map_err(|what| {
            self.src.error(
                p.name_span,
                format!("csgrt cannot cast the shadow (projection(cut = false)) of {what}"),
                super::approximate::LIMITS,
            )
        })?;
        self.placed_cast(p, cast, frame, mat)
    }

    /// The shadow of `node` (in the projection's frame), read off the tree.
    fn cast(
        &mut self,
        p: &Statement,
        node: u32,
        frame: DAffine3,
    ) -> std::result::Result<Cast, String> {
        let (mut pts, mut tris, mut ellipses) = (Vec::new(), Vec::new(), Vec::new());
        let mut parts = Vec::new();
        let mut stack = vec![node];
        // What has no exact shadow here: cut into polytopes.
        let mut cut = Vec::new();
        while let Some(n) = stack.pop() {
            if self.whole_prism(n) && self.upright_range(n).is_some() {
                parts.push(self.upright_cast(n));
                continue;
            }
            let csg = &self.b.csg;
            match &csg.nodes[n as usize].kind {
                NodeKind::Op(Op::Union, ch) => stack.extend(ch.iter().copied()),
                NodeKind::Op(Op::Intersection, ch) => {
                    let ch = ch.clone();
                    match self.met_upright(p, &ch, frame)? {
                        Some(c) => parts.push(c),
                        None => cut.push(n),
                    }
                }
                NodeKind::Leaf(i) => {
                    let prim = &csg.prims[*i as usize];
                    let m = prim.xf.to_world;
                    let flat = |v: DVec3| m.transform_point3(v).truncate();
                    match &prim.shape {
                        Shape::Mesh(mesh) => {
                            let base = pts.len() as u32;
                            pts.extend(mesh.data.verts.iter().map(|&v| flat(v)));
                            tris.extend(mesh.data.tris.iter().map(|t| t.map(|k| k + base)));
                        }
                        Shape::Cuboid(_) => {
                            let b = prim.shape.object_bounds();
                            let base = pts.len() as u32;
                            pts.extend((0..8).map(|i| {
                                flat(DVec3::new(
                                    if i & 1 == 0 { b.min.x } else { b.max.x },
                                    if i & 2 == 0 { b.min.y } else { b.max.y },
                                    if i & 4 == 0 { b.min.z } else { b.max.z },
                                ))
                            }));
                            tris.extend(BOX_TRIS.iter().map(|t| t.map(|k| k + base)));
                        }
                        Shape::Sphere(_) => {
                            // E·Eᵀ = P·Pᵀ: E the lower-triangular factor.
                            let (r0, r1) = (m.matrix3.row(0), m.matrix3.row(1));
                            let (a, b, c) = (r0.dot(r0), r0.dot(r1), r1.dot(r1));
                            let l00 = a.sqrt();
                            let l10 = if l00 > 0.0 { b / l00 } else { 0.0 };
                            let l11 = (c - l10 * l10).max(0.0).sqrt();
                            let e = DMat2::from_cols(DVec2::new(l00, l10), DVec2::new(0.0, l11));
                            if e.determinant() != 0.0 {
                                ellipses.push((e, m.translation.truncate()));
                            }
                        }
                        _ => cut.push(n),
                    }
                }
                NodeKind::Op(..) | NodeKind::Section(..) => cut.push(n),
            }
        }
        // In the projection's own frame: the note's box is placed by frame.
        let polytopes = self.polytopes(p, &cut, frame, true)?;
        // A convex polytope's shadow is that of its faces turned up: a
        // vertical line through it enters it through one of them.
        for face in polytopes.iter().flat_map(|p| &p.faces) {
            if face.n.z <= 0.0 {
                continue;
            }
            let base = pts.len() as u32;
            pts.extend(face.pts.iter().map(|v| v.truncate()));
            for i in 1..face.pts.len() as u32 - 1 {
                tris.push([base, base + i, base + i + 1]);
            }
        }
        parts.push(Cast::Flat {
            pts,
            tris,
            ellipses,
        });
        Ok(Cast::Op(Op::Union, parts))
    }

    /// The shadow of the intersection of `ch` where some of them are
    /// upright prisms over the whole height of the rest: their sections
    /// met with the rest's shadow. `None`: none is.
    fn met_upright(
        &mut self,
        p: &Statement,
        ch: &[u32],
        frame: DAffine3,
    ) -> std::result::Result<Option<Cast>, String> {
        let (upright, mut rest): (Vec<u32>, Vec<u32>) =
            ch.iter().partition(|&&c| self.upright_range(c).is_some());

        if upright.is_empty() || rest.is_empty() {
            return Ok(None);
        }
        // The height the rest reaches (their boxes', met).
        let nodes = &self.b.csg.nodes;
        let lo = rest
            .iter()
            .map(|&c| nodes[c as usize].bounds.min.z)
            .fold(f64::MIN, f64::max);
        let hi = rest
            .iter()
            .map(|&c| nodes[c as usize].bounds.max.z)
            .fold(f64::MAX, f64::min);
        let mut covering = Vec::new();
        for c in upright {
            match self.upright_range(c) {
                Some((a, b)) if a <= lo && hi <= b => covering.push(c),
                _ => rest.push(c),
            }
        }
        if covering.is_empty() {
            return Ok(None);
        }
        let mut parts: Vec<Cast> = covering.iter().map(|&c| self.upright_cast(c)).collect();
        if lo > hi {
            // The rest meet nowhere.
            return Ok(Some(Cast::Op(Op::Union, Vec::new())));
        }
        let others = if rest.len() == 1 {
            rest[0]
        } else {
            match self.op(Op::Intersection, rest.into_iter().map(Some).collect()) {
                Some(n) => n,
                None => return Ok(Some(Cast::Op(Op::Union, Vec::new()))),
            }
        };
        // The fault: the upright prisms' sections alone, the rest's shadow
        // not met.
        if !crate::mutant::active("shadow_upright_alone") {
            parts.push(self.cast(p, others, frame)?);
        }
        Ok(Some(Cast::Op(Op::Intersection, parts)))
    }

    /// The heights over which node `n` is an upright prism — each of its
    /// leaves a straight prism, a cylinder or a box standing along z over
    /// them all — or `None`.
    fn upright_range(&self, n: u32) -> Option<(f64, f64)> {
        let csg = &self.b.csg;
        match &csg.nodes[n as usize].kind {
            NodeKind::Leaf(i) => {
                let prim = &csg.prims[*i as usize];
                upright_leaf(&prim.shape, &prim.xf.to_world)
            }
            NodeKind::Op(_, ch) => {
                let mut range = (f64::MIN, f64::MAX);
                for &c in ch {
                    let (a, b) = self.upright_range(c)?;
                    range = (range.0.max(a), range.1.min(b));
                }
                (range.0 < range.1).then_some(range)
            }
            NodeKind::Section(..) => None,
        }
    }

    /// Whether upright node `n` is nothing but its section over its
    /// heights: every leaf over the same heights, or met with the others.
    fn whole_prism(&self, n: u32) -> bool {
        let csg = &self.b.csg;
        match &csg.nodes[n as usize].kind {
            NodeKind::Leaf(_) => true,
            NodeKind::Op(op, ch) => {
                ch.iter().all(|&c| self.whole_prism(c))
                    && (*op == Op::Intersection || {
                        let first = self.upright_range(ch[0]);
                        ch.iter().all(|&c| self.upright_range(c) == first)
                    })
            }
            NodeKind::Section(..) => false,
        }
    }

    /// Upright node `n`'s leaves, each swept over z = 0 to 1, combined as
    /// it combines them.
    fn upright_cast(&self, n: u32) -> Cast {
        let csg = &self.b.csg;
        match &csg.nodes[n as usize].kind {
            NodeKind::Leaf(i) => {
                let prim = &csg.prims[*i as usize];
                let m = prim.xf.to_world;
                let b = prim.shape.object_bounds();
                let k = 1.0 / (b.max.z - b.min.z);
                let placed = DAffine3::from_cols(
                    m.matrix3.x_axis,
                    m.matrix3.y_axis,
                    DVec3::new(0.0, 0.0, k),
                    DVec3::new(m.translation.x, m.translation.y, -k * b.min.z),
                );
                Cast::Upright(prim.shape.clone(), placed)
            }
            NodeKind::Op(op, ch) => {
                Cast::Op(*op, ch.iter().map(|&c| self.upright_cast(c)).collect())
            }
            NodeKind::Section(..) => unreachable!("a section is not upright"),
        }
    }

    /// Cast `cast` as leaves placed by `frame`.
    fn placed_cast(
        &mut self,
        p: &Statement,
        cast: Cast,
        frame: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        match cast {
            Cast::Flat {
                pts,
                tris,
                ellipses,
            } => {
                let mut parts = Vec::new();
                if let Some(soup) = Soup::new(pts, tris) {
                    let shape = Shape::Shadow(Shadow {
                        soup: Arc::new(soup),
                    });
                    parts.push(self.leaf(p, shape, frame, mat)?);
                }
                for (e, c) in ellipses {
                    let local = DAffine3::from_mat3_translation(
                        DMat3::from_cols(e.x_axis.extend(0.0), e.y_axis.extend(0.0), DVec3::Z),
                        c.extend(0.0),
                    );
                    let shape = Shape::Cone(Cone {
                        r0: 1.0,
                        r1: 1.0,
                        centered: false,
                    });
                    parts.push(self.leaf(p, shape, frame * local, mat)?);
                }
                Ok(self.op(Op::Union, parts))
            }
            Cast::Upright(shape, placed) => self.leaf(p, shape, frame * placed, mat),
            Cast::Op(op, ch) => {
                let mut parts = Vec::new();
                for c in ch {
                    parts.push(self.placed_cast(p, c, frame, mat)?);
                }
                Ok(self.op(op, parts))
            }
        }
    }
}

/// The heights a leaf stands over if it is an upright prism: a straight
/// prism (of a region or of an offset region), a cylinder or a box whose
/// transform keeps z apart from x and y (its section's plane level, its
/// axis along z, exactly: as a rotation about z or a multiple of 90° is).
fn upright_leaf(shape: &Shape, m: &DAffine3) -> Option<(f64, f64)> {
    let straight = match shape {
        Shape::Prism(pr) => pr.top == 1.0,
        Shape::OffsetPrism(_) | Shape::Cuboid(_) => true,
        Shape::Cone(c) => c.r0 == c.r1,
        _ => false,
    };
    let a = m.matrix3;
    let level = a.x_axis.z == 0.0 && a.y_axis.z == 0.0 && a.z_axis.x == 0.0 && a.z_axis.y == 0.0;
    if !straight || !level || a.z_axis.z == 0.0 {
        return None;
    }
    let b = shape.object_bounds();
    let (z0, z1) = (
        a.z_axis.z * b.min.z + m.translation.z,
        a.z_axis.z * b.max.z + m.translation.z,
    );
    Some((z0.min(z1), z0.max(z1)))
}
