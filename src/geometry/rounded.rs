//! A convex set written out as the union of exact primitives (a polytope
//! rounded by a ball: `scene/resolve/rounded.rs` finds the pieces), as one
//! solid: the line is taken into its object space once, and each piece
//! from there by its own transform, so that a small set far from the
//! world's origin keeps its own precision — composing each piece's
//! placement with the world's would round it by an ulp of its distance —
//! and its pieces' spans are merged in its own units, not within the
//! coincidence bound of world coordinates that a CSG union applies.

use super::bvh::Bvh;
use super::solid::{Need, Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, Ray, Shape, Transform, NO_PART};
use crate::geometry::convex::ConvexPart as HullPart;
use crate::stats::Stats;
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

    /// The spans of piece `i` (whose box `line` meets) within (tmin,
    /// tmax), pushed onto `all` with their parts numbered as the union's.
    #[inline]
    fn piece_spans(
        &self,
        i: u32,
        line: &Ray,
        tmin: f64,
        tmax: f64,
        st: &mut Stats,
        all: &mut Gathered,
    ) {
        let p = &self.pieces[i as usize];
        st.primitive_tests += 1;
        let (o, d) = p.xf.ray_to_object(line);
        let mut sub = Probe {
            o,
            d,
            tmin,
            tmax,
            st,
            need: Need::Spans,
        };
        let n = self.pieces.len() as Part;
        // Through `dyn`: a piece's spans are not generic in this
        // closure's type (a shape holding shapes would recurse).
        let mut push = |(a, pa, b, pb): RawSpan| all.push((a, pa * n + i, b, pb * n + i));
        p.shape
            .spans(&mut sub, &mut (&mut push as &mut dyn FnMut(RawSpan)));
    }

    /// The scale of `line`'s t about this set: what [`MERGE`] is relative to.
    fn line_scale(&self, line: &Ray) -> f64 {
        let size = (self.bounds.max - self.bounds.min).max_element();
        (line.origin.abs().max_element() + size) / line.dir.length()
    }

    /// Only the union's first boundary after `q.tmin` (a first hit, or a
    /// shadow ray's question) of a union of many pieces (a few are cast
    /// at less cost than ordering them takes): the pieces are taken
    /// nearest box first (`bvh`), and none whose box begins beyond the
    /// first boundary of those taken so far (and the merging distance past
    /// it) is cast — it can neither enter before that boundary nor,
    /// beginning after an exit, join the span that exit ends. Emitted as
    /// [`Mesh`](super::Mesh) does: the boundary, left open on its other
    /// side.
    fn first_spans(
        &self,
        bvh: &Bvh,
        line: &Ray,
        q: &mut Probe,
        all: &mut Gathered,
        emit: &mut impl FnMut(RawSpan),
    ) {
        let (tmin, tmax) = (q.tmin, q.tmax);
        let scale = self.line_scale(line);
        let mut found: Option<RawSpan> = None;
        let take = |i: u32, st: &mut Stats| -> f64 {
            let from = all.len();
            self.piece_spans(i, line, tmin, tmax, st, all);
            // Each new span put in its place by entry, after those with
            // the same entry (as a stable sort of the whole list puts it).
            for k in from..all.len() {
                let s = all[k];
                let at = all[..k].partition_point(|x| x.0 <= s.0);
                all.copy_within(at..k, at + 1);
                all[at] = s;
            }
            found = first_merged(all, scale, tmin);
            match found {
                Some((a, _, b, _)) => {
                    let t = if a > tmin { a } else { b };
                    t + MERGE * (scale + t.abs())
                }
                None => f64::INFINITY,
            }
        };
        bvh.visit_near_first(line, tmin, tmax, q.st, take);
        if let Some((a, pa, b, pb)) = found {
            if a > tmin {
                emit((a, pa, f64::INFINITY, NO_PART));
            } else {
                emit((f64::NEG_INFINITY, NO_PART, b, pb));
            }
        }
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
        let mut all: Gathered = smallvec::SmallVec::new();
        if let Some(b) = self.bvh.as_deref().filter(|_| q.need != Need::Spans) {
            return self.first_spans(b, &line, q, &mut all, emit);
        }
        let mut near: smallvec::SmallVec<[u32; 32]> = smallvec::SmallVec::new();
        match &self.bvh {
            Some(b) => b.visit(&line, q.tmin, q.tmax, q.st, |i| near.push(i)),
            None => near.extend(0..self.pieces.len() as u32),
        }
        // The hierarchy's order is fixed; the spans are sorted below.
        for &i in &near {
            if self.pieces[i as usize].bounds.hit(&line, q.tmin, q.tmax) {
                self.piece_spans(i, &line, q.tmin, q.tmax, q.st, &mut all);
            }
        }
        all.sort_by(|x, y| x.0.total_cmp(&y.0));
        // Merged as they come: each span joins the one before it, or that
        // one is complete.
        let scale = self.line_scale(&line);
        let mut cur: Option<RawSpan> = None;
        for &s in &all {
            if cur.as_mut().is_some_and(|c| joined(c, s, scale)) {
                continue;
            }
            if let Some(c) = cur {
                emit(c);
            }
            cur = Some(s);
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

/// The spans of a union's pieces, gathered before they are merged.
type Gathered = smallvec::SmallVec<[RawSpan; 16]>;

/// Of spans `all`, sorted by entry and merged where one begins before (or
/// within [`MERGE`] of) the end of those before it, the first with a
/// boundary after `tmin` (one that begins after it, or the one it lies
/// in), merged only as far as that.
fn first_merged(all: &[RawSpan], scale: f64, tmin: f64) -> Option<RawSpan> {
    let after = |c: &RawSpan| c.0 > tmin || c.2 > tmin;
    let mut cur: Option<RawSpan> = None;
    for &s in all {
        if cur.as_mut().is_some_and(|c| joined(c, s, scale)) {
            continue;
        }
        if let Some(c) = cur.filter(after) {
            return Some(c);
        }
        cur = Some(s);
    }
    cur.filter(after)
}

/// Whether span `s` (beginning at or after `c`) begins before the end of
/// `c` or within [`MERGE`] of it: then `c` is made to end where the later
/// of the two ends.
fn joined(c: &mut RawSpan, s: RawSpan, scale: f64) -> bool {
    // (A NaN joins nothing, as before.)
    let joins = s.0 <= c.2 + MERGE * (scale + c.2.abs());
    if joins && s.2 > c.2 {
        c.2 = s.2;
        c.3 = s.3;
    }
    joins
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Cuboid, Sphere};

    /// The first boundary after tmin, read as the CSG reads a leaf's list.
    fn read_first(spans: &[RawSpan], tmin: f64) -> Option<(f64, Part)> {
        spans.iter().find_map(|s| {
            if s.0 > tmin {
                Some((s.0, s.1))
            } else if s.2 > tmin {
                Some((s.2, s.3))
            } else {
                None
            }
        })
    }

    /// Asked only for the first boundary (a first hit, a shadow ray), a
    /// union of overlapping balls and boxes gives the one its whole list
    /// of spans gives — the same t and the same piece — from outside and
    /// from inside, with few pieces (all cast) and with many (nearest box
    /// first, through the hierarchy), while casting fewer pieces.
    #[test]
    fn the_first_boundary_alone_is_the_whole_lists() {
        let mut rnd = crate::plane::tests::uniform(67);
        let (mut met, mut inside, mut cast, mut cast_all) = (0, 0, 0u64, 0u64);
        for round in 0..60 {
            let count = if round % 2 == 0 { 6 } else { 40 };
            let parts: Vec<(Shape, DAffine3)> = (0..count)
                .map(|k| {
                    let at = DVec3::new(rnd(), rnd(), rnd()) * 10.0;
                    let size = DVec3::new(0.5 + rnd(), 0.5 + rnd(), 0.5 + rnd()) * 1.5;
                    if k % 2 == 0 {
                        (
                            Shape::Sphere(Sphere),
                            DAffine3::from_scale_rotation_translation(
                                DVec3::splat(size.x),
                                glam::DQuat::IDENTITY,
                                at,
                            ),
                        )
                    } else {
                        (
                            Shape::Cuboid(Cuboid { centered: true }),
                            DAffine3::from_scale_rotation_translation(
                                size,
                                glam::DQuat::from_rotation_z(rnd()),
                                at,
                            ),
                        )
                    }
                })
                .collect();
            let set = Rounded::new(parts, Vec::new()).unwrap();
            for _ in 0..300 {
                let o = DVec3::new(rnd(), rnd(), rnd()) * 30.0 - DVec3::splat(10.0);
                let to = DVec3::new(rnd(), rnd(), rnd()) * 10.0;
                let d = (to - o).normalize();
                let tmin = if rnd() < 0.5 {
                    0.0
                } else {
                    (to - o).length() * rnd()
                };
                let tmax = if rnd() < 0.2 {
                    (to - o).length()
                } else {
                    f64::INFINITY
                };
                // The list asked for `need`, and the pieces cast for it.
                let ask = |need: Need| {
                    let mut st = Stats::default();
                    let mut out = Vec::new();
                    let mut q = Probe {
                        o,
                        d,
                        tmin,
                        tmax,
                        st: &mut st,
                        need,
                    };
                    set.spans(&mut q, &mut |s| out.push(s));
                    (out, st.primitive_tests)
                };
                let (all, n) = ask(Need::Spans);
                cast_all += n;
                let want = read_first(&all, tmin).filter(|b| b.0 < tmax);
                for need in [Need::FirstBoundary, Need::AnyBoundary] {
                    let (first, n) = ask(need);
                    assert!(count <= SCAN_PIECES || first.len() <= 1);
                    let got = read_first(&first, tmin).filter(|b| b.0 < tmax);
                    assert_eq!(got, want, "round {round}: {o} {d} from {tmin}");
                    if need == Need::FirstBoundary {
                        cast += n;
                    }
                }
                met += want.is_some() as u32;
                inside += all.iter().any(|s| s.0 <= tmin && tmin < s.2) as u32;
            }
        }
        assert!(
            met > 4000 && inside > 500,
            "{met} met, {inside} from inside"
        );
        assert!(
            cast < cast_all,
            "{cast} pieces cast for the first boundaries, {cast_all} for the lists"
        );
    }
}
