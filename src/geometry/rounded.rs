//! A convex set written out as the union of exact primitives (a polytope
//! rounded by a ball: `scene/resolve/rounded.rs` finds the pieces), as one
//! solid: the line is taken into its object space once, and each piece
//! from there by its own transform, so that a small set far from the
//! world's origin keeps its own precision — composing each piece's
//! placement with the world's would round it by an ulp of its distance —
//! and its pieces' spans are merged in its own units, not within the
//! coincidence bound of world coordinates that a CSG union applies.

use super::bvh::Bvh;
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, Ray, Shape, Transform};
use crate::geometry::convex::ConvexPart as HullPart;
use glam::{DAffine3, DVec3};

/// One primitive of the union, placed in the set's object space.
#[derive(Clone, Debug, PartialEq)]
pub struct RoundedPiece {
    pub shape: Shape,
    pub xf: Transform,
    /// Its box in the set's object space.
    pub bounds: Aabb,
}

/// The union of `pieces`: the convex set `hulls` describes (kept for a
/// hull or sum that takes this one in; empty for a set that is not
/// convex, a mesh rounded by a ball).
#[derive(Clone, Debug, PartialEq)]
pub struct Rounded {
    pub pieces: Vec<RoundedPiece>,
    pub hulls: Vec<Vec<HullPart>>,
    bounds: Aabb,
    /// Over the pieces, when there are many.
    bvh: Option<Box<Bvh>>,
}

/// The most pieces tested one by one, without a hierarchy.
const SCAN_PIECES: usize = 12;

/// How far apart (relative to the line's and the set's scale, in t) a
/// span's end and the next one's start still overlap: the rounding of
/// crossings computed from the same line.
const MERGE: f64 = 64.0 * f64::EPSILON;

impl Rounded {
    /// The union of `parts` (each a shape and its placement), or why not.
    pub fn new(
        parts: Vec<(Shape, DAffine3)>,
        hulls: Vec<Vec<HullPart>>,
    ) -> Result<Rounded, super::transform::Degenerate> {
        let mut pieces = Vec::with_capacity(parts.len());
        let mut bounds = Aabb::EMPTY;
        for (shape, m) in parts {
            let xf = Transform::new(m)?;
            let b = shape.world_bounds(&m);
            bounds = bounds.union(&b);
            pieces.push(RoundedPiece {
                shape,
                xf,
                bounds: b,
            });
        }
        let bvh = (pieces.len() > SCAN_PIECES).then(|| {
            let items: Vec<(u32, Aabb)> = pieces
                .iter()
                .enumerate()
                .map(|(i, p)| (i as u32, p.bounds))
                .collect();
            Box::new(Bvh::build(&items, 2))
        });
        Ok(Rounded {
            pieces,
            hulls,
            bounds,
            bvh,
        })
    }

    fn piece(&self, part: Part) -> (&RoundedPiece, Part) {
        let n = self.pieces.len() as Part;
        (&self.pieces[(part % n) as usize], part / n)
    }
}

impl Solid for Rounded {
    const NAME: &'static str = "hull";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let line = Ray::new(q.o, q.d);
        let n = self.pieces.len() as Part;
        let mut all: smallvec::SmallVec<[RawSpan; 16]> = smallvec::SmallVec::new();
        let mut near: smallvec::SmallVec<[u32; 32]> = smallvec::SmallVec::new();
        match &self.bvh {
            Some(b) => b.visit(&line, q.tmin, q.tmax, q.st, |i| near.push(i)),
            None => near.extend(0..self.pieces.len() as u32),
        }
        // The hierarchy's order is fixed; the spans are sorted below.
        for &i in &near {
            let p = &self.pieces[i as usize];
            if !p.bounds.hit(&line, q.tmin, q.tmax) {
                continue;
            }
            q.st.primitive_tests += 1;
            let (o, d) = p.xf.ray_to_object(&line);
            let mut sub = Probe {
                o,
                d,
                tmin: q.tmin,
                tmax: q.tmax,
                st: &mut *q.st,
                need: super::Need::Spans,
            };
            // Through `dyn`: a piece's spans are not generic in this
            // closure's type (a shape holding shapes would recurse).
            let mut push = |(a, pa, b, pb): RawSpan| all.push((a, pa * n + i, b, pb * n + i));
            p.shape
                .spans(&mut sub, &mut (&mut push as &mut dyn FnMut(RawSpan)));
        }
        all.sort_by(|x, y| x.0.total_cmp(&y.0));
        let size = (self.bounds.max - self.bounds.min).max_element();
        let scale = (q.o.abs().max_element() + size) / q.d.length();
        let mut cur: Option<RawSpan> = None;
        for s in all {
            match &mut cur {
                Some(c) if s.0 <= c.2 + MERGE * (scale + c.2.abs()) => {
                    if s.2 > c.2 {
                        c.2 = s.2;
                        c.3 = s.3;
                    }
                }
                _ => {
                    if let Some(c) = cur.take() {
                        emit(c);
                    }
                    cur = Some(s);
                }
            }
        }
        if let Some(c) = cur {
            emit(c);
        }
    }

    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        let (piece, sub) = self.piece(part);
        let n = piece.shape.normal(piece.xf.point_to_object(p), sub);
        piece.xf.normal * n
    }

    fn normal_on(&self, o: DVec3, d: DVec3, t: f64, part: Part) -> DVec3 {
        let (piece, sub) = self.piece(part);
        let (po, pd) = piece.xf.ray_to_object(&Ray::new(o, d));
        piece.xf.normal * piece.shape.normal_on(po, pd, t, sub)
    }

    fn contains(&self, p: DVec3) -> bool {
        self.pieces
            .iter()
            .any(|q| q.shape.contains(q.xf.point_to_object(p)))
    }

    fn object_bounds(&self) -> Aabb {
        self.bounds
    }

    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        self.pieces.iter().fold(Aabb::EMPTY, |b, q| {
            b.union(&q.shape.world_bounds(&(*m * q.xf.to_world)))
        })
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        let mut best: Option<DVec3> = None;
        for q in &self.pieces {
            let m = &q.xf.to_world;
            let s = m.transform_point3(q.shape.support(m.matrix3.transpose() * d)?);
            if best.map_or(true, |b| s.dot(d) > b.dot(d)) {
                best = Some(s);
            }
        }
        best
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![("pieces", Param::Num(self.pieces.len() as f64))]
    }

    /// As a hull computed by support functions: the export stops POV-Ray.
    fn pov(&self) -> String {
        "#error \"csgrt: hull() and minkowski() have no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0"
            .to_string()
    }
}
