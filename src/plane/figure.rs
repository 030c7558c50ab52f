//! A region of the plane as a tree ([`Figure`]): polygons and ellipses
//! combined by the set operations, hulls, exact round offsets, and
//! projections of solids (by the number of their statement; the scene
//! reads those). OpenSCAD's 2-D operations ([`super::offset`],
//! [`super::sum`], [`super::hull`]) map figures to figures; the
//! extrusions lift them into space.

use super::round_offset::RoundOffset;
use super::Outlines;
use crate::math::boolean::Op;
use glam::{DAffine2, DVec2};
use std::sync::Arc;

/// A region of the plane, as a tree.
#[derive(Clone, Debug)]
pub enum Figure {
    /// Outlines filled by the even-odd rule, in the plane's coordinates.
    Polygon(Outlines),
    /// The image of the unit disc.
    Ellipse(DAffine2),
    /// `projection(cut)`: the slice z = 0 of its children (cut = true) or
    /// their shadow on it, moved in the plane by the transform. The
    /// statement is the resolver's, by this number: its children are read
    /// only when the tree is extruded, in the extrusion's frame.
    Section(u32, DAffine2),
    Op(Op, Vec<Figure>),
    /// `hull()` of 2-D shapes: extruded, the hull of their extrusions.
    Hull(Vec<Figure>),
    /// Curved outlines offset with round joins, in their own frame, placed
    /// in the plane by the map (an offset is not one after any map).
    Offset(Arc<RoundOffset>, DAffine2),
}

impl Figure {
    /// The exact extent (lo, hi) of a 2-D tree along `axis`, or why not.
    pub fn exact_range(&self, axis: DVec2) -> Result<(f64, f64), &'static str> {
        let f = self;
        match f {
            Figure::Polygon(_) | Figure::Ellipse(_) => Ok(f.range(axis)),
            Figure::Section(..) => Err("the extent of a projection"),
            Figure::Offset(o, _) if o.r > 0.0 => Ok(f.range(axis)),
            Figure::Offset(..) => Err("the extent of curved outlines shrunk by offset"),
            // A hull reaches exactly as far as its farthest part.
            Figure::Op(Op::Union, kids) | Figure::Hull(kids) => {
                let mut r = (f64::INFINITY, f64::NEG_INFINITY);
                for k in kids {
                    let (a, b) = k.exact_range(axis)?;
                    r = (r.0.min(a), r.1.max(b));
                }
                Ok(r)
            }
            // The first operand's, where no subtracted shape's box reaches its
            // far sides.
            Figure::Op(Op::Difference, kids) => {
                let r = kids[0].exact_range(axis)?;
                for k in &kids[1..] {
                    let (a, b) = k.range(axis);
                    if a <= r.0 || b >= r.1 {
                        return Err("the extent of a 2-D difference that cuts its far sides");
                    }
                }
                Ok(r)
            }
            Figure::Op(Op::Intersection, _) => Err("the extent of a 2-D intersection"),
            // Even-odd: a far point that only one operand reaches lies in an odd
            // number of them.
            Figure::Op(Op::Xor, kids) => {
                let r: Vec<(f64, f64)> = kids
                    .iter()
                    .map(|k| k.exact_range(axis))
                    .collect::<Result<_, _>>()?;
                let lo = r.iter().map(|x| x.0).fold(f64::INFINITY, f64::min);
                let hi = r.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
                if r.iter().filter(|x| x.0 == lo).count() > 1
                    || r.iter().filter(|x| x.1 == hi).count() > 1
                {
                    return Err("the extent of a drawing whose paths share a far side");
                }
                Ok((lo, hi))
            }
        }
    }

    /// Whether `f` is proved to have no area where x > 0 (`right`) or
    /// x < 0: its extent says so, or, for a difference, a subtracted convex
    /// shape covers the first operand's box on that side. `false` is no
    /// proof either way.
    pub fn no_area_beyond_axis(&self, right: bool) -> bool {
        let (lo, hi) = self.x_range();
        if (right && hi <= 0.0) || (!right && lo >= 0.0) {
            return true;
        }
        match self {
            Figure::Op(Op::Union, kids) => kids.iter().all(|k| k.no_area_beyond_axis(right)),
            Figure::Op(Op::Intersection, kids) => kids.iter().any(|k| k.no_area_beyond_axis(right)),
            Figure::Op(Op::Difference, kids) if !kids.is_empty() => {
                if kids[0].no_area_beyond_axis(right) {
                    return true;
                }
                // The first operand's box on that side of the axis.
                let (xlo, xhi) = kids[0].x_range();
                let (ylo, yhi) = kids[0].range(DVec2::Y);
                let far = if right { xhi } else { xlo };
                let corners = [
                    DVec2::new(0.0, ylo),
                    DVec2::new(0.0, yhi),
                    DVec2::new(far, ylo),
                    DVec2::new(far, yhi),
                ];
                kids[1..].iter().any(|k| k.covers_convexly(&corners))
            }
            _ => false,
        }
    }

    /// Whether `f` holds the convex hull of `pts`: a leaf that is convex
    /// (an ellipse, a straight convex polygon of one loop) holding each
    /// point, or a union one of whose shapes does.
    fn covers_convexly(&self, pts: &[DVec2]) -> bool {
        match self {
            Figure::Ellipse(e) => {
                let inv = e.inverse();
                pts.iter()
                    .all(|&p| inv.transform_point2(p).length_squared() <= 1.0)
            }
            Figure::Polygon(o) if o.loops.len() == 1 && !o.curved() => {
                let l = &o.loops[0];
                if !super::hull::convex_polygon(l) {
                    return false;
                }
                // Inside or on each edge's line (a point on the boundary is
                // held: the sets are closed), on the side the loop turns.
                let area2: f64 = (0..l.len())
                    .map(|i| l[i].perp_dot(l[(i + 1) % l.len()]))
                    .sum();
                let size = l.iter().fold(0.0f64, |m, p| m.max(p.abs().max_element()));
                let tol = 1e-12 * size * size;
                pts.iter().all(|&p| {
                    (0..l.len()).all(|i| {
                        let (a, b) = (l[i], l[(i + 1) % l.len()]);
                        (b - a).perp_dot(p - a) * area2.signum() >= -tol
                    })
                })
            }
            Figure::Op(Op::Union, kids) => kids.iter().any(|k| k.covers_convexly(pts)),
            _ => false,
        }
    }

    /// The extent in x (exact for leaves; a union or symmetric difference
    /// joins, an intersection meets, a difference keeps its first
    /// operand's).
    pub fn x_range(&self) -> (f64, f64) {
        self.range(DVec2::X)
    }

    /// The extent along `axis`, by the rules of [`Figure::x_range`].
    pub fn range(&self, axis: DVec2) -> (f64, f64) {
        match self {
            Figure::Polygon(o) => o.extent(axis),
            Figure::Ellipse(e) => {
                let h = (e.matrix2.transpose() * axis).length();
                let c = e.translation.dot(axis);
                (c - h, c + h)
            }
            // Not asked: a section is refused before (see `has_section`).
            Figure::Section(..) => (f64::NEG_INFINITY, f64::INFINITY),
            // Along the axis seen in the offset's own frame: R's extent
            // moved out by r when grown (exact), R's own when shrunk (a
            // bound: refused where exactness matters, by resize).
            Figure::Offset(o, m) => {
                let v = m.matrix2.transpose() * axis;
                let c = m.translation.dot(axis);
                let reach = |v: DVec2| {
                    let q = o.region.farthest(v);
                    q.dot(v) + o.r.max(0.0) * v.length()
                };
                (c - reach(-v), c + reach(v))
            }
            // A hull reaches as far as its farthest shape.
            Figure::Hull(kids) => kids
                .iter()
                .map(|k| k.range(axis))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, d)| {
                    (a.min(c), b.max(d))
                }),
            Figure::Op(op, kids) => {
                let rs = kids.iter().map(|k| k.range(axis));
                match op {
                    Op::Union | Op::Xor => rs
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, d)| {
                            (a.min(c), b.max(d))
                        }),
                    Op::Intersection => rs
                        .fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), (c, d)| {
                            (a.max(c), b.min(d))
                        }),
                    Op::Difference => kids[0].range(axis),
                }
            }
        }
    }

    /// The part of `ellipse` (the image of the unit disc) on `mid`'s side
    /// of the chord a–b — the region between an elliptical arc from a to b
    /// through `mid` and its chord: the ellipse met with a rectangle on
    /// that side big enough to hold all of it there.
    pub fn arc_segment(a: DVec2, b: DVec2, ellipse: DAffine2, mid: DVec2) -> Figure {
        let t = (b - a).normalize_or_zero();
        let mut n = t.perp();
        if (mid - a).dot(n) < 0.0 {
            n = -n;
        }
        // Every point of the ellipse lies within d of a.
        let m = ellipse.matrix2;
        let stretch = m.x_axis.length() + m.y_axis.length();
        let d = (ellipse.translation - a).length() + stretch + (b - a).length();
        let rect = vec![a - t * d, b + t * d, b + t * d + n * d, a - t * d + n * d];
        Figure::Op(
            Op::Intersection,
            vec![
                Figure::Ellipse(ellipse),
                Figure::Polygon(Outlines::polygons(vec![rect])),
            ],
        )
    }

    /// The disc of radius r about c.
    pub fn disc(c: DVec2, r: f64) -> Figure {
        Figure::Ellipse(DAffine2::from_scale_angle_translation(
            DVec2::splat(r),
            0.0,
            c,
        ))
    }

    /// The tree moved by `m`.
    pub fn moved(&self, m: DAffine2) -> Figure {
        match self {
            Figure::Polygon(o) => Figure::Polygon(o.map(|p| m.transform_point2(p))),
            Figure::Ellipse(e) => Figure::Ellipse(m * *e),
            Figure::Section(s, at) => Figure::Section(*s, m * *at),
            Figure::Op(op, kids) => Figure::Op(*op, kids.iter().map(|k| k.moved(m)).collect()),
            Figure::Hull(kids) => Figure::Hull(kids.iter().map(|k| k.moved(m)).collect()),
            Figure::Offset(o, at) => Figure::Offset(o.clone(), m * *at),
        }
    }

    /// The mirror image in x = 0.
    pub fn mirrored_x(&self) -> Figure {
        let m = DAffine2::from_scale(DVec2::new(-1.0, 1.0));
        match self {
            Figure::Polygon(o) => Figure::Polygon(o.map(|p| DVec2::new(-p.x, p.y))),
            Figure::Ellipse(e) => Figure::Ellipse(m * *e),
            Figure::Section(s, at) => Figure::Section(*s, m * *at),
            Figure::Op(op, kids) => Figure::Op(*op, kids.iter().map(|k| k.mirrored_x()).collect()),
            Figure::Hull(kids) => Figure::Hull(kids.iter().map(|k| k.mirrored_x()).collect()),
            Figure::Offset(o, at) => Figure::Offset(o.clone(), m * *at),
        }
    }

    /// The number of the first `projection` in the tree, if any.
    pub fn section(&self) -> Option<u32> {
        match self {
            Figure::Section(s, _) => Some(*s),
            Figure::Op(_, kids) | Figure::Hull(kids) => kids.iter().find_map(|k| k.section()),
            _ => None,
        }
    }
}

/// Whether a 2×2 matrix maps the unit circle to a circle.
pub fn is_circle(m: glam::DMat2) -> bool {
    let (x, y) = (m.x_axis, m.y_axis);
    let r2 = x.length_squared();
    x.dot(y).abs() <= 1e-12 * r2 && (y.length_squared() - r2).abs() <= 1e-12 * r2
}

/// Each loop of `o` cut to the half-plane x ≥ 0 (Sutherland–Hodgman: a
/// loop stays one loop, with edges along x = 0 where it was cut).
pub fn clip_right(o: &Outlines) -> Outlines {
    let mut loops = Vec::new();
    for l in &o.loops {
        let mut out: Vec<DVec2> = Vec::new();
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            if a.x >= 0.0 {
                out.push(a);
            }
            if (a.x >= 0.0) != (b.x >= 0.0) {
                let f = a.x / (a.x - b.x);
                out.push(DVec2::new(0.0, a.y + f * (b.y - a.y)));
            }
        }
        out.dedup();
        if out.len() >= 3 {
            loops.push(out);
        }
    }
    Outlines::polygons(loops)
}
