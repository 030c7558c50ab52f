//! `projection(cut = false)` extruded: the shadow of its children on the
//! plane z = 0, exactly, for the children it can be shown exact for.
//!
//! The shadow of a union is the union of the shadows. A mesh's (a
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
        let (mut pts, mut tris, mut ellipses) = (Vec::new(), Vec::new(), Vec::new());
        let mut stack = vec![child];
        // What has no exact shadow here: cut into polytopes.
        let mut cut = Vec::new();
        while let Some(n) = stack.pop() {
            let csg = &self.b.csg;
            match &csg.nodes[n as usize].kind {
                NodeKind::Op(Op::Union, ch) => stack.extend(ch.iter().copied()),
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
        let polytopes = self.polytopes(p, &cut, frame, true);
        self.b.csg.rewind(mark);
        let polytopes = polytopes.map_err(|what| {
            self.src.error(
                p.name_span,
                format!("csgrt cannot cast the shadow (projection(cut = false)) of {what}"),
                super::approximate::LIMITS,
            )
        })?;
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
}
