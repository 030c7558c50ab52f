//! The extrusions that lift OpenSCAD's 2-D shapes into space.
//!
//! Below `linear_extrude` and `rotate_extrude` the statements live in the
//! plane, read into a [`Figure`] tree by [`super::planar`]. An extrusion maps every point of the plane one to one
//! (a straight or uniformly tapered prism at each height, a turn about z
//! for each angle), so the extrusion of a combination is the combination
//! of the extrusions: each 2-D leaf becomes one exact 3-D leaf — a prism
//! or a lathe over its polygon, a cylinder, cone, torus or ellipsoid for
//! its ellipse — under the same CSG.
//!
//! A 2-D shape where a solid is expected (at the top level, or mixed with
//! solids) is shown as OpenSCAD's preview shows it: a slab 1 thick centred
//! on its plane (1.1 when it is subtracted, so that a 2-D hole cuts
//! through), under its full 3-D transform.

use super::facet_mesh::Cut;
use super::planar::file_child;
use super::transforms::{basis_from_z, sin_cos_deg};
use super::Resolver;
use crate::error::Result;
use crate::geometry::polytope::stretch;
use crate::geometry::{
    Cone, Cuboid, Halfspace, Lathe, OffsetPrism, Prism, Ring, Shape, Sphere, Torus, TwistSection,
    Twisted,
};
use crate::math::boolean::Op;
use crate::plane::figure::{clip_right, is_circle, Figure};
use crate::plane::Region;
use crate::scene::args::Args;
use crate::scene::Material;
use crate::syntax::ast::Statement;
use glam::{DAffine2, DAffine3, DMat3, DVec2, DVec3};
use std::sync::Arc;
/// What the certified approximation in the plane flattens.
const FLATTENED: &str =
    "csgrt flattens curves, ellipses, hulls, offsets and projections of bounded solids";

/// How a linear extrusion sweeps its section: the top's scale in x and y,
/// and the twist (radians, OpenSCAD's clockwise).
#[derive(Clone, Copy, Debug)]
pub(super) struct Sweep {
    pub top: DVec2,
    pub twist: f64,
    /// From −h/2 to h/2 (OpenSCAD's `center`), kept in the leaf itself.
    pub centered: bool,
}

impl Resolver<'_> {
    /// A 2-D shape standing where a solid is expected: OpenSCAD's preview
    /// slab, 1 thick (1.1 when subtracted), centred on its plane.
    pub(super) fn slab(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let mark = self.plane_notes.len();
        let Some(f) = self.figure(s, DAffine2::IDENTITY, 0)? else {
            return Ok(None);
        };
        let h = if self.subtracted { 1.1 } else { 1.0 };
        let sweep = Sweep {
            top: DVec2::ONE,
            twist: 0.0,
            centered: true,
        };
        let node = self.linear(s, &f, xf, mat, h, sweep)?;
        self.placed_plane_notes(mark, node, stretch(&xf));
        Ok(node)
    }

    /// The straight, tapered or twisted prism of `f` from z = 0 to h under
    /// `xf`.
    fn linear(
        &mut self,
        s: &Statement,
        f: &Figure,
        xf: DAffine3,
        mat: Material,
        h: f64,
        sweep: Sweep,
    ) -> Result<Option<u32>> {
        let local = DAffine3::from_scale(DVec3::new(1.0, 1.0, h));
        let centered = sweep.centered;
        let top = sweep.top.x;
        let even = sweep.top.x == sweep.top.y;
        match f {
            Figure::Polygon(o) if even && sweep.twist == 0.0 => {
                // An upright box: a rectangle on the axes extruded straight.
                if let Some((lo, hi)) = o.axis_rectangle().filter(|_| top == 1.0) {
                    let z = crate::geometry::cone::bottom(centered);
                    let place = DAffine3::from_translation(lo.extend(z))
                        * DAffine3::from_scale((hi - lo).extend(1.0));
                    let shape = Shape::Cuboid(Cuboid { centered: false });
                    return self.leaf(s, shape, xf * local * place, mat);
                }
                let shape =
                    Shape::Prism(Prism::new(Arc::new(Region::new(o.clone())), top, centered));
                self.leaf(s, shape, xf * local, mat)
            }
            Figure::Polygon(o) => {
                if o.curved() {
                    return self.linear_flat(
                        s,
                        f,
                        xf,
                        mat,
                        h,
                        sweep,
                        "a twist or uneven scale of curved outlines",
                    );
                }
                let section = TwistSection::Region(Arc::new(Region::new(o.clone())));
                self.twisted(s, section, xf * local, mat, sweep)
            }
            // A circle about the axis is the same circle turned: only an
            // even taper changes it, and the cone below serves. Any other
            // ellipse is twisted as it is.
            Figure::Ellipse(e)
                if !even
                    || sweep.twist != 0.0
                        && !(e.translation == DVec2::ZERO && is_circle(e.matrix2)) =>
            {
                if e.matrix2.determinant().is_nan() || e.matrix2.determinant() == 0.0 {
                    return Ok(self.flattened(s));
                }
                self.twisted(s, TwistSection::Ellipse(*e), xf * local, mat, sweep)
            }
            Figure::Ellipse(e) => {
                // The cone over the ellipse with its apex where s(z) = 0:
                // (x, y, z) ↦ (E·(x, y) + s(z)·c, h·z) maps the upright
                // frustum of radii 1 and `top` onto it.
                let (r0, r1, k) = if top <= 1.0 {
                    (1.0, top, 1.0)
                } else {
                    (1.0 / top, 1.0, top)
                };
                // Centred, z runs from −1/2 and the shear's part of the
                // bottom moves to the translation.
                let c = e.translation;
                let m = DMat3::from_cols(
                    (e.matrix2.x_axis * k).extend(0.0),
                    (e.matrix2.y_axis * k).extend(0.0),
                    (c * (top - 1.0)).extend(h),
                );
                let base = if centered { c * (top + 1.0) * 0.5 } else { c };
                let local = DAffine3::from_mat3_translation(m, base.extend(0.0));
                let shape = Shape::Cone(Cone { r0, r1, centered });
                self.leaf(s, shape, xf * local, mat)
            }
            Figure::Section(p, at) => {
                let p = &self.projections[*p as usize].clone();
                if !even || top != 1.0 || sweep.twist != 0.0 {
                    return self.linear_flat(
                        s,
                        f,
                        xf,
                        mat,
                        h,
                        sweep,
                        "a twist or scale of a projection",
                    );
                }
                let z0 = if centered { -0.5 } else { 0.0 };
                let frame = xf
                    * local
                    * DAffine3::from_translation(DVec3::new(0.0, 0.0, z0))
                    * DAffine3::from_mat3_translation(
                        DMat3::from_mat2(at.matrix2),
                        at.translation.extend(0.0),
                    );
                let cut = Args::bind(self.src, p, &["cut", "convexity"])?.boolean("cut")?;
                if cut.unwrap_or(false) {
                    self.section(p, frame, mat)
                } else {
                    self.shadow(p, frame, mat)
                }
            }
            Figure::Op(op, kids) => {
                let mut parts = Vec::new();
                for k in kids {
                    parts.push(self.linear(s, k, xf, mat, h, sweep)?);
                }
                Ok(self.op(*op, parts))
            }
            Figure::Offset(o, at) => {
                if !even || top != 1.0 || sweep.twist != 0.0 {
                    return self.linear_flat(
                        s,
                        f,
                        xf,
                        mat,
                        h,
                        sweep,
                        "a twist or scale of an offset of curved outlines",
                    );
                }
                let det = at.matrix2.determinant();
                if det.is_nan() || det == 0.0 {
                    return Ok(self.flattened(s));
                }
                let place = DAffine3::from_mat3_translation(
                    DMat3::from_mat2(at.matrix2),
                    at.translation.extend(0.0),
                );
                let shape = Shape::OffsetPrism(OffsetPrism {
                    region: o.clone(),
                    centered,
                });
                self.leaf(s, shape, xf * local * place, mat)
            }
            // The hull of the shapes' extrusions: straight or tapered, a
            // section of the extrusion of a convex region is that region
            // scaled, so it is the extrusion of their hull.
            Figure::Hull(kids) => {
                if sweep.twist != 0.0 || !even {
                    return self.linear_flat(
                        s,
                        f,
                        xf,
                        mat,
                        h,
                        sweep,
                        "a twist or uneven scale of a 2-D hull",
                    );
                }
                let mark = self.b.csg.mark();
                // Extruded in the statement's own frame; the hull carries xf.
                let mut parts = Vec::new();
                for k in kids {
                    parts.push(self.linear(s, k, DAffine3::IDENTITY, mat, h, sweep)?);
                }
                let Some(node) = self.op(Op::Union, parts) else {
                    return Ok(None);
                };
                self.hull_of(s, node, mark, xf, mat)
            }
        }
    }

    /// `f` flattened to straight polygons (the certified approximation)
    /// for `what` it has no exact form of, or the error at `s` of what
    /// cannot be (`verb`: what the extrusion does).
    fn flat_for(
        &mut self,
        s: &Statement,
        f: &Figure,
        circles: bool,
        what: &str,
        verb: &str,
    ) -> Result<Option<Figure>> {
        self.flat_figure(s, f, circles, what).map_err(|why| {
            self.src
                .error(s.name_span, format!("{why} cannot be {verb}"), FLATTENED)
        })
    }

    /// [`Resolver::linear`] of `f` flattened to straight polygons.
    #[allow(clippy::too_many_arguments)]
    fn linear_flat(
        &mut self,
        s: &Statement,
        f: &Figure,
        xf: DAffine3,
        mat: Material,
        h: f64,
        sweep: Sweep,
        what: &str,
    ) -> Result<Option<u32>> {
        match self.flat_for(s, f, false, what, "extruded")? {
            Some(g) => self.linear(s, &g, xf, mat, h, sweep),
            None => Ok(None),
        }
    }

    /// [`Resolver::revolve`] of `f` flattened to straight polygons.
    fn revolve_flat(
        &mut self,
        s: &Statement,
        f: &Figure,
        xf: DAffine3,
        mat: Material,
        what: &str,
    ) -> Result<Option<u32>> {
        match self.flat_for(s, f, false, what, "turned")? {
            Some(g) => self.revolve(s, &g, xf, mat),
            None => Ok(None),
        }
    }

    /// The twisted or unevenly scaled prism of `section` under `world`.
    fn twisted(
        &mut self,
        s: &Statement,
        section: TwistSection,
        world: DAffine3,
        mat: Material,
        sweep: Sweep,
    ) -> Result<Option<u32>> {
        let twist = if crate::mutant::active("twist_reversed") {
            -sweep.twist
        } else {
            sweep.twist
        };
        let shape = Shape::Twisted(Twisted {
            section,
            twist,
            scale: sweep.top,
            centered: sweep.centered,
        });
        self.leaf(s, shape, world, mat)
    }

    /// The section z = 0 of projection `p`'s children (placed by `frame`)
    /// swept from z = 0 to 1 in `frame`: the section node met with the box
    /// of the children's slice (its caps; framing, as the oracle's).
    fn section(&mut self, p: &Statement, frame: DAffine3, mat: Material) -> Result<Option<u32>> {
        let xf = match crate::geometry::Transform::new(frame) {
            Ok(xf) => xf,
            Err(_) => {
                return Err(self.src.error(
                    p.name_span,
                    "this projection is flattened or out of range",
                    "expected an extrusion with a nonzero, finite size",
                ))
            }
        };
        let (prims, sections) = (self.b.csg.prims.len(), self.b.csg.sections.len());
        let ids = self.projected(p, frame, mat)?;
        let Some(child) = self.union(ids) else {
            return Ok(None);
        };
        // Colours below a projection are dropped, as in OpenSCAD.
        let material = self.b.material_id(mat);
        for q in &mut self.b.csg.prims[prims..] {
            q.material = material;
        }
        let b = self.b.csg.bounds_in(child, &xf.to_object);
        if !b.is_bounded() {
            return Err(self.src.error(
                p.name_span,
                "the section of an unbounded solid (a halfspace) is unbounded",
                "csgrt extrudes bounded shapes: expected bounded children (a halfspace met with a box)",
            ));
        }
        if b.min.z > 0.0 || b.max.z < 0.0 || b.min.x > b.max.x || b.min.y > b.max.y {
            return Ok(None);
        }
        let node = self.b.csg.add_section(child, xf, prims, sections);
        let size = DVec3::new(b.max.x - b.min.x, b.max.y - b.min.y, 1.0);
        let lo = DVec3::new(b.min.x, b.min.y, 0.0);
        let cap =
            frame * DAffine3::from_scale_rotation_translation(size, glam::DQuat::IDENTITY, lo);
        let caps = self.leaf(p, Shape::Cuboid(Cuboid { centered: false }), cap, mat)?;
        Ok(self.op(Op::Intersection, vec![Some(node), caps]))
    }

    /// `linear_extrude(height, center, convexity, twist, slices, scale)`.
    pub(super) fn linear_extrude(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        let a = Args::bind(
            self.src,
            s,
            &[
                "height",
                "center",
                "convexity",
                "twist",
                "slices",
                "scale",
                "file",
                "layer",
                "origin",
                "timestamp",
            ],
        )?;
        let legacy = file_child(s, &a);
        let h = a.number("height")?.unwrap_or(100.0);
        let center = a.boolean("center")?.unwrap_or(false);
        let twist_deg = a.number("twist")?.unwrap_or(0.0);
        let twist = twist_deg.to_radians();
        let slices = a.number("slices")?;
        let scale = if a.is_number("scale") {
            let k = a.number("scale")?.unwrap_or(1.0);
            DVec2::splat(k)
        } else {
            a.numbers("scale", &[2])?
                .map_or(DVec2::ONE, |v| DVec2::new(v[0], v[1]))
        }
        .max(DVec2::ZERO);
        let mark = self.plane_notes.len();
        let Some(f) = self.extruded(s, legacy, depth)? else {
            return Ok(None);
        };
        if h <= 0.0 {
            return self.empty(s, "its height is zero or negative");
        }
        let faceted =
            self.facets == super::super::Facets::OpenScad && (twist != 0.0 || scale.x != scale.y);
        let one_polygon = match &f {
            Figure::Polygon(o) if !o.curved() => Some(o),
            _ => None,
        };
        if faceted && one_polygon.is_none() {
            self.facets_drawn_exact(
                s,
                "twisting or unevenly scaling a 2-D combination or curves",
            );
        }
        if let (true, Some(o)) = (faceted, one_polygon) {
            let cut = Cut {
                h,
                center,
                twist: twist_deg,
                scale,
                slices,
            };
            return self.extruded_facets(s, &a, o, &cut, xf, mat);
        }
        let sweep = Sweep {
            top: scale,
            twist,
            centered: center,
        };
        let node = self.linear(s, &f, xf, mat, h, sweep)?;
        // A point of the plane moves by the taper's scale at most.
        self.placed_plane_notes(mark, node, stretch(&xf) * scale.max_element().max(1.0));
        Ok(node)
    }

    /// `rotate_extrude(angle, convexity)`.
    pub(super) fn rotate_extrude(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        let a = Args::bind(
            self.src,
            s,
            &[
                "angle",
                "convexity",
                "file",
                "layer",
                "origin",
                "scale",
                "timestamp",
            ],
        )?;
        let legacy = file_child(s, &a);
        let mut angle = a.number("angle")?.unwrap_or(360.0);
        if angle <= -360.0 || angle > 360.0 {
            angle = 360.0;
        }
        let mark = self.plane_notes.len();
        let Some(f) = self.extruded(s, legacy, depth)? else {
            return Ok(None);
        };
        if angle == 0.0 {
            return self.empty(s, "its angle is zero");
        }
        let f = if f.section().is_some() {
            match self.flat_for(s, &f, true, "a turn of a projection", "turned")? {
                Some(g) => g,
                None => return Ok(None),
            }
        } else {
            f
        };
        let (mut lo, mut hi) = f.x_range();
        // What a combination leaves may lie on one side though its parts
        // reach across (a circle across the axis, its right half cut away).
        if lo < 0.0 && hi > 0.0 {
            if f.no_area_beyond_axis(true) {
                hi = 0.0;
            } else if f.no_area_beyond_axis(false) {
                lo = 0.0;
            }
        }
        if lo < 0.0 && hi > 0.0 {
            // OpenSCAD 2021.01 reports this as an error and renders the
            // rest of the model without the extrusion.
            let e = self.src.error(
                s.name_span,
                format!(
                    "all points for rotate_extrude() must have the same X coordinate sign \
                     (range is {lo:.2} -> {hi:.2})"
                ),
                "expected a 2-D shape on one side of the axis x = 0",
            );
            self.go_on(e, "it is left out, as in OpenSCAD")?;
            return Ok(None);
        }
        if self.facets == super::super::Facets::OpenScad && !crate::plane::flat::straight(&f, false)
        {
            self.facets_drawn_exact(s, "turning curves");
        } else if self.facets == super::super::Facets::OpenScad {
            // OpenSCAD's fragments, from the shape's whole x extent (with
            // the axis), a fraction of them for a part turn.
            let n = self.fragments(&a, hi.max(0.0) - lo.min(0.0)).unwrap_or(3);
            let steps = ((n as f64 * angle.abs() / 360.0) as usize).max(1);
            return self.turned_facets(s, &f, angle, steps, xf, mat);
        }
        // A shape at x ≤ 0 turns as its mirror image, half a turn on.
        let (f, flip) = if hi <= 0.0 {
            (f.mirrored_x(), true)
        } else {
            (f, false)
        };
        let Some(body) = self.revolve(s, &f, xf, mat)? else {
            return Ok(None);
        };
        // A turn moves no two points of the plane apart.
        self.placed_plane_notes(mark, Some(body), stretch(&xf));
        if angle == 360.0 {
            return Ok(Some(body));
        }
        // The wedge from 0 to `angle` (from 180° on for a flipped shape):
        // two half-spaces through the axis, met below 180°, joined above.
        let (sa, ca) = sin_cos_deg(angle.abs());
        let sign = if angle < 0.0 { -1.0 } else { 1.0 };
        let turn = if flip { -1.0 } else { 1.0 };
        let normals = [
            DVec3::new(0.0, -sign, 0.0) * turn,
            DVec3::new(-sa, ca * sign, 0.0) * turn,
        ];
        let mut sides = Vec::new();
        for n in normals {
            let local = DAffine3::from_mat3(basis_from_z(n));
            sides.push(self.leaf(s, Shape::Halfspace(Halfspace), xf * local, mat)?);
        }
        let wedge_op = if angle.abs() <= 180.0 {
            Op::Intersection
        } else {
            Op::Union
        };
        let wedge = self.op(wedge_op, sides);
        Ok(self.op(Op::Intersection, vec![Some(body), wedge]))
    }

    /// What extrusion `s` sweeps: its `file` form's drawing ([`file_child`])
    /// or the union of its children.
    fn extruded(
        &mut self,
        s: &Statement,
        legacy: Option<Statement>,
        depth: usize,
    ) -> Result<Option<Figure>> {
        match legacy {
            Some(child) => self.figure(&child, DAffine2::IDENTITY, depth + 1),
            None => self.figure_children(s, Op::Union, DAffine2::IDENTITY, depth),
        }
    }

    /// The full turn of `f` (all of it at x ≥ 0 but for leaves a
    /// combination cuts away).
    fn revolve(
        &mut self,
        s: &Statement,
        f: &Figure,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        match f {
            Figure::Polygon(o) => {
                // A curved outline is wholly on one side of the axis (the
                // rule above), so there is nothing to cut.
                let clipped = if o.curved() { o.clone() } else { clip_right(o) };
                if clipped.loops.is_empty() {
                    return Ok(None);
                }
                let shape = Shape::Lathe(Lathe::new(Arc::new(Region::new(clipped))));
                self.leaf(s, shape, xf, mat)
            }
            Figure::Ellipse(e) => {
                let m = e.matrix2;
                if m.x_axis.y != 0.0 || m.y_axis.x != 0.0 {
                    // A slanted ellipse: the turned ellipse, about its
                    // centre's distance c from the axis, scaled by c.
                    let c = e.translation;
                    let reach = m.row(0).length();
                    // (`Ring::new` takes it wholly right of the axis only.)
                    if let Some(ring) = (c.x > 0.0).then(|| Ring::new(m / c.x)).flatten() {
                        let local = DAffine3::from_scale_rotation_translation(
                            DVec3::splat(c.x),
                            glam::DQuat::IDENTITY,
                            DVec3::new(0.0, 0.0, c.y),
                        );
                        return self.leaf(s, Shape::Ring(ring), xf * local, mat);
                    }
                    if c.x + reach > 0.0 {
                        return self.revolve_flat(
                            s,
                            f,
                            xf,
                            mat,
                            "a turn of a slanted ellipse that reaches the axis",
                        );
                    }
                    return Ok(None);
                }
                let (ra, rz, c) = (m.x_axis.x.abs(), m.y_axis.y.abs(), e.translation);
                if c.x + ra <= 0.0 {
                    return Ok(None);
                }
                if c.x == 0.0 {
                    let local = DAffine3::from_scale_rotation_translation(
                        DVec3::new(ra, ra, rz),
                        glam::DQuat::IDENTITY,
                        DVec3::new(0.0, 0.0, c.y),
                    );
                    return self.leaf(s, Shape::Sphere(Sphere), xf * local, mat);
                }
                // Centred right of the axis and reaching it (a combination
                // cuts the rest away, or the whole shape would have been
                // refused above): the horn or spindle torus's apple, the
                // turn of its part at x ≥ 0. Centred left of the axis and
                // crossing it, its part at x ≥ 0 turns into the lemon.
                if c.x < 0.0 {
                    return self.revolve_flat(
                        s,
                        f,
                        xf,
                        mat,
                        "a turn of a circle centred left of the axis that crosses it",
                    );
                }
                let local = DAffine3::from_scale_rotation_translation(
                    DVec3::new(c.x, c.x, c.x * rz / ra),
                    glam::DQuat::IDENTITY,
                    DVec3::new(0.0, 0.0, c.y),
                );
                let shape = Shape::Torus(Torus { minor: ra / c.x });
                self.leaf(s, shape, xf * local, mat)
            }
            Figure::Section(..) => unreachable!("flattened by rotate_extrude"),
            Figure::Offset(..) => {
                self.revolve_flat(s, f, xf, mat, "a turn of an offset of curved outlines")
            }
            Figure::Hull(_) => self.revolve_flat(s, f, xf, mat, "a turn of a 2-D hull"),
            Figure::Op(op, kids) => {
                let mut parts = Vec::new();
                for k in kids {
                    parts.push(self.revolve(s, k, xf, mat)?);
                }
                Ok(self.op(*op, parts))
            }
        }
    }
}
