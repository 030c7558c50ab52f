//! Convex solids known only by their support function: OpenSCAD's `hull()`
//! and `minkowski()` of convex operands, in world space.
//!
//! A [`Convex`] is the Minkowski sum of hulls, each the convex hull of
//! placed solids ([`ConvexPart`]): its support function h(d) = Σ max over a
//! hull's parts of their support, a part's being its solid's own support
//! carried by its transform, M·s(Mᵀd) + t. A line meets it in one span,
//! found by van den Bergen's GJK ray cast ("Ray casting against general
//! convex objects with application to continuous collision detection",
//! 2004): from a point x on the line, the closest point of the set is
//! approached by a simplex of support points; whenever the support point w
//! shows a separating plane (v·(x − w) > 0), x moves along the line to
//! that plane, until x is within the tolerance of the set. The normal there
//! is the last separating direction. The entry is cast from where the line
//! enters the set's box, the exit from where it leaves it, backwards.
//! Converged to 10⁻¹² of the set's size and distance from the origin.

use super::coherence;
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part as SurfacePart, Shape};
use glam::{DAffine3, DVec3};

/// The entry (0) and exit (1) of a line.
const ENTRY: SurfacePart = 0;
const EXIT: SurfacePart = 1;

/// The precision of a span's ends, relative to the set's size: GJK's
/// distances converge to 10⁻¹², its plane bounds to rounding, but a flat
/// face's plane is found from support points whose normal is tilted by
/// GJK's last direction (about √ε).
pub const PRECISION: f64 = 1e-9;

/// The most GJK steps a cast takes.
pub const MAX_ITERATIONS: u32 = 200;

/// A solid placed in the world, by its support function.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPart {
    pub shape: Shape,
    pub to_world: DAffine3,
}

impl ConvexPart {
    /// The placed corners whose hull is the part's hull, where it is a
    /// polytope: a box's eight, a mesh's vertices, a prism of straight
    /// outlines its corners at both ends (the top's scaled by its taper);
    /// `None` for a curved solid.
    pub fn corners(&self) -> Option<Vec<DVec3>> {
        let local: Vec<DVec3> = match &self.shape {
            Shape::Cuboid(c) => {
                let lo = super::cuboid::low(c.centered);
                (0..8)
                    .map(|i| {
                        let pick = |b: usize| if i & b != 0 { 1.0 } else { lo };
                        DVec3::new(pick(1), pick(2), pick(4))
                    })
                    .collect()
            }
            Shape::Mesh(mesh) => mesh.data.verts.clone(),
            Shape::Prism(p) if !p.region.curved() => {
                let z = p.z_lo();
                p.region
                    .outlines
                    .loops
                    .iter()
                    .flatten()
                    .flat_map(|&v| [v.extend(z), (v * p.top).extend(z + 1.0)])
                    .collect()
            }
            _ => return None,
        };
        Some(
            local
                .into_iter()
                .map(|p| self.to_world.transform_point3(p))
                .collect(),
        )
    }

    /// The point of the placed solid farthest along world direction `d`.
    fn support(&self, d: DVec3) -> DVec3 {
        let m = &self.to_world;
        let s = self
            .shape
            .support(m.matrix3.transpose() * d)
            .expect("a bounded solid");
        m.transform_point3(s)
    }
}

/// The Minkowski sum of the hulls of `hulls`' parts where every part is a
/// polytope ([`ConvexPart::corners`]), written out: a sum of polytopes is
/// the hull of the sums of one corner of each, so each hull's corners are
/// hulled (quickhull, planes 10⁻¹⁰ of the points' size thick: every
/// corner within that of the hull), added to every corner of the sum so
/// far and hulled again. `None` when a part is curved, the sum has no
/// volume, or it would take more than
/// [`MAX_SUM_CORNERS`](super::polytope::MAX_SUM_CORNERS) sums.
pub fn polytope_sum(hulls: &[Vec<ConvexPart>]) -> Option<super::Mesh> {
    let sum = super::polytope::corner_sum(
        hulls,
        |h| {
            let mut pts = Vec::new();
            for (k, part) in h.iter().enumerate() {
                // The fault: a hull's last part left out.
                if k > 0 && k + 1 == h.len() && crate::mutant::active("polytope_part_dropped") {
                    continue;
                }
                pts.extend(part.corners().ok_or(())?);
            }
            Ok(pts)
        },
        hull_corners,
        || (),
    )
    .ok()?;
    super::polytope::hull_mesh(&sum)
}

/// The corners of the hull of `pts`; `None` when it has no volume.
fn hull_corners(pts: &[DVec3]) -> Option<Vec<DVec3>> {
    super::quickhull::hull(pts, super::polytope::points_tolerance(pts)).map(|(v, _)| v)
}

/// The Minkowski sum of the convex hulls of `hulls`' parts.
#[derive(Clone, Debug, PartialEq)]
pub struct Convex {
    pub hulls: Vec<Vec<ConvexPart>>,
    /// The box, from the support function along ±x, ±y, ±z.
    bounds: Aabb,
    /// Ten more slabs of supporting planes, along the box's face and
    /// corner diagonals (`DIAGONALS`): with the box, an outer polytope of
    /// 26 planes. A line that misses it never starts GJK; one that meets
    /// it starts where it enters and leaves it.
    slabs: Box<[(f64, f64); 10]>,
    /// The tolerance of a cast: 10⁻¹² of the box's size and distance.
    tol: f64,
    /// The flat ends of a hull's cylinders and frustums whose planes hold
    /// the whole set (at most [`MOST_ENDS`]): a line that crosses one of
    /// them inwards within its disc enters there ([`Convex::end_entry`]).
    ends: Vec<FlatEnd>,
}

/// A flat end of a cylinder or frustum of a hull, in a plane that holds
/// the whole set.
#[derive(Clone, Debug, PartialEq)]
struct FlatEnd {
    /// The plane: its outward unit normal and n·x there.
    normal: DVec3,
    offset: f64,
    /// The part's object space, where the end is the disc x² + y² ≤ r²
    /// at height `z`.
    to_object: DAffine3,
    r2: f64,
}

/// The most flat ends [`Convex::new`] keeps (a hull of many coplanar
/// discs is a face none of them fills).
const MOST_ENDS: usize = 8;

impl Convex {
    /// The set of `hulls` (parts placed in the world), moved so that its
    /// box is centred on the origin — its own coordinates then carry the
    /// precision of its size, not of its distance from the world's origin
    /// — and the translation that puts it back.
    pub fn centred(mut hulls: Vec<Vec<ConvexPart>>) -> (Convex, DVec3) {
        let c = Convex::new(hulls.clone()).bounds.center();
        // A sum moves with any one of its terms: move the first.
        if let Some(h) = hulls.first_mut() {
            for p in h {
                p.to_world = DAffine3::from_translation(-c) * p.to_world;
            }
        }
        (Convex::new(hulls), c)
    }

    pub fn new(hulls: Vec<Vec<ConvexPart>>) -> Convex {
        let mut c = Convex {
            hulls,
            bounds: Aabb::EMPTY,
            slabs: Box::new([(0.0, 0.0); 10]),
            tol: 0.0,
            ends: Vec::new(),
        };
        let axis = |i: usize| DVec3::AXES[i];
        let (mut lo, mut hi) = (DVec3::ZERO, DVec3::ZERO);
        for i in 0..3 {
            hi[i] = c.support_point(axis(i))[i];
            lo[i] = c.support_point(-axis(i))[i];
        }
        c.bounds = Aabb::new(lo, hi);
        for (i, d) in DIAGONALS.into_iter().enumerate() {
            let d = DVec3::from(d);
            let (a, mut b) = (d.dot(c.support_point(-d)), d.dot(c.support_point(d)));
            if crate::mutant::active("convex_slab_shrunk") {
                b -= 0.01 * (b - a);
            }
            c.slabs[i] = (a, b);
        }
        c.tol = 1e-12
            * (hi - lo)
                .max_element()
                .max(lo.abs().max(hi.abs()).max_element());
        c.ends = c.flat_ends();
        c
    }

    /// The ends for [`Convex::ends`]: of a hull (a sum's face is not one
    /// part's), each end of positive radius of a cylinder or frustum whose
    /// plane holds the set within the tolerance.
    fn flat_ends(&self) -> Vec<FlatEnd> {
        let [parts] = self.hulls.as_slice() else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for part in parts {
            let Shape::Cone(c) = &part.shape else {
                continue;
            };
            let m = part.to_world;
            if m.matrix3.determinant() == 0.0 {
                continue;
            }
            let to_object = m.inverse();
            let z0 = super::cone::bottom(c.centered);
            for (up, z, r) in [(1.0, z0 + 1.0, c.r1), (-1.0, z0, c.r0)] {
                if r <= 0.0 || out.len() == MOST_ENDS {
                    continue;
                }
                let Some(normal) = (to_object.matrix3.transpose() * DVec3::Z * up).try_normalize()
                else {
                    continue;
                };
                let offset = normal.dot(m.transform_point3(DVec3::Z * z));
                // The one support query: whether the plane holds the set.
                if normal.dot(self.support_point(normal)) <= offset + self.tol {
                    out.push(FlatEnd {
                        normal,
                        offset,
                        to_object,
                        r2: r * r,
                    });
                }
            }
        }
        out
    }

    /// Where the line s + λr (λ in [0, lmax]) enters through one of the
    /// flat ends, and that end's normal: proved without a step, for the
    /// set lies behind the end's plane and the point where the line
    /// crosses it inwards lies on the end's disc, in the set. (A flat end
    /// has no atom along its axis, so Newton's method proves nothing
    /// there, and GJK took all its steps.)
    fn end_entry(&self, s: DVec3, r: DVec3, lmax: f64) -> Option<(f64, DVec3)> {
        self.ends.iter().find_map(|e| {
            let nr = e.normal.dot(r);
            let lambda = (e.offset - e.normal.dot(s)) / nr;
            // (NaN fails each test.)
            if !(nr < 0.0 && lambda >= 0.0 && lambda <= lmax) {
                return None;
            }
            let local = e.to_object.transform_point3(s + r * lambda);
            (local.truncate().length_squared() <= e.r2).then_some((lambda, e.normal))
        })
    }

    /// The point of the set farthest along `d` (any of them where several).
    pub fn support_point(&self, d: DVec3) -> DVec3 {
        self.hulls
            .iter()
            .map(|parts| {
                parts
                    .iter()
                    .map(|p| p.support(d))
                    .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))
                    .expect("a hull of something")
            })
            .sum()
    }

    /// GJK's ray cast from `s` along `r` up to λ = `lmax`: the first λ
    /// where s + λr is in the set (0 when s is), with the separating
    /// direction there (the outward normal; zero when s is inside), and the
    /// steps taken.
    pub fn cast(&self, s: DVec3, r: DVec3, lmax: f64) -> (Option<(f64, DVec3)>, u32) {
        let mut lambda = 0.0;
        let mut x = s;
        let mut n = DVec3::ZERO;
        let mut simplex = Simplex::default();
        let p0 = self.support_point(-r);
        simplex.add(p0);
        let mut v = x - p0;
        let tol2 = self.tol * self.tol;
        let loose = LOOSE * (self.bounds.max - self.bounds.min).max_element();
        let mut tried = false;
        let mut it = 0;
        while it < MAX_ITERATIONS {
            it += 1;
            if v.length_squared() <= tol2 {
                break;
            }
            // Close: Newton's method from here, when its plane is proved
            // to touch the set where it meets the line.
            if !tried && n != DVec3::ZERO && v.length_squared() <= loose * loose {
                tried = true;
                let (hit, steps) = self.refine(s, r, lambda, n.normalize());
                it += steps;
                if let Some(hit) = hit {
                    return (Some(hit), it);
                }
            }
            let p = self.support_point(v);
            let w = x - p;
            let vw = v.dot(w);
            let before = v.length_squared();
            let moved = vw > 0.0;
            if moved {
                let vr = v.dot(r);
                if vr >= 0.0 {
                    return (None, it);
                }
                lambda -= vw / vr;
                if lambda > lmax {
                    return (None, it);
                }
                x = s + r * lambda;
                n = v;
            }
            simplex.add(p);
            match simplex.closest(x) {
                Some(c) => v = -c,
                // x in the simplex's hull: inside the set (on its surface
                // when the cast has moved).
                None => {
                    return match n.try_normalize() {
                        Some(unit) if !tried => match self.refine(s, r, lambda, unit) {
                            (Some(hit), steps) => (Some(hit), it + steps),
                            (None, steps) => (Some((lambda, n)), it + steps),
                        },
                        _ => (Some((lambda, n)), it),
                    }
                }
            }
            // The floating point allows no closer approach.
            if !moved && v.length_squared() >= before * (1.0 - 1e-12) {
                break;
            }
        }
        let (hit, probes) = self.polish(s, r, lambda, n, v, &simplex);
        (hit.filter(|h| h.0 <= lmax), it + probes)
    }

    /// The best of the lower bounds on the entry that supporting planes
    /// give, once GJK has come as close as the floating point lets it:
    /// GJK's own, the plane of the last direction v (right to second order
    /// on a curved surface), and the planes through three of the simplex's
    /// points and of the support points of directions tilted from v by
    /// 10⁻⁶ (a flat face's own plane, where v is tilted by rounding and
    /// its support jumps between the face's corners). Each plane holds the
    /// set on one side, so the line enters the set no earlier than the
    /// plane: the largest such λ is still a lower bound, and exact when the
    /// plane touches the set at the hit. A plane the line's point lies
    /// beyond while the line runs parallel or away shows a miss.
    fn polish(
        &self,
        s: DVec3,
        r: DVec3,
        lambda: f64,
        n: DVec3,
        v: DVec3,
        simplex: &Simplex,
    ) -> (Option<(f64, DVec3)>, u32) {
        let Some(vh) = v.try_normalize() else {
            return (Some((lambda, n)), 0);
        };
        let mut pts: smallvec::SmallVec<[DVec3; 8]> = simplex.pts.iter().copied().collect();
        let u1 = if pts.len() >= 2 {
            (pts[1] - pts[0]).reject_from(vh).try_normalize()
        } else {
            None
        }
        .unwrap_or_else(|| vh.any_orthonormal_vector());
        let u2 = vh.cross(u1);
        for u in [u1, -u1, u2, -u2] {
            let p = self.support_point(vh + u * 1e-6);
            if !pts.contains(&p) {
                pts.push(p);
            }
        }
        let mut normals: smallvec::SmallVec<[DVec3; 24]> = smallvec::smallvec![vh];
        for i in 0..pts.len() {
            for j in i + 1..pts.len() {
                for k in j + 1..pts.len() {
                    let c = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
                    if let Some(c) = c.try_normalize() {
                        normals.push(if c.dot(vh) < 0.0 { -c } else { c });
                    }
                }
            }
        }
        let (mut best, mut best_n) = (lambda, n);
        let x = s + r * lambda;
        let mut probes = 4;
        for m in normals {
            probes += 1;
            let h = m.dot(self.support_point(m));
            let mr = m.dot(r);
            if mr < 0.0 {
                let l = (h - m.dot(s)) / mr;
                if l > best {
                    best = l;
                    best_n = m;
                }
            } else if m.dot(x) > h + self.tol {
                return (None, probes);
            }
        }
        let Some(unit) = best_n.try_normalize() else {
            return (Some((best, best_n)), probes);
        };
        match self.refine(s, r, best, unit) {
            (Some(hit), steps) => (Some(hit), probes + steps),
            (None, steps) => (Some((best, best_n)), probes + steps),
        }
    }

    /// The point of the set closest to `q` (GJK's distance query), and the
    /// steps taken; q itself when inside.
    pub fn closest(&self, q: DVec3) -> (DVec3, u32) {
        let mut simplex = Simplex::default();
        let p0 = self.support_point(q - self.bounds.center());
        simplex.add(p0);
        let mut v = q - p0;
        for it in 1..=MAX_ITERATIONS {
            let p = self.support_point(v);
            let vw = v.dot(q - p);
            // v is the shortest, to the rounding: q's closest point is q − v.
            if v.length_squared() - vw <= 1e-28 * v.length_squared() {
                return (q - v, it);
            }
            simplex.add(p);
            match simplex.closest(q) {
                Some(c) => {
                    let before = v.length_squared();
                    v = -c;
                    if v.length_squared() >= before * (1.0 - 1e-14) {
                        return (q - v, it);
                    }
                }
                None => return (q, it),
            }
        }
        (q - v, MAX_ITERATIONS)
    }

    /// The line o + t·d inside the outer polytope (the box and the
    /// diagonal slabs), as a range of t.
    fn clip(&self, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        let mut narrow = |od: f64, dd: f64, a: f64, b: f64| {
            if dd == 0.0 {
                return od >= a && od <= b;
            }
            let (t0, t1) = ((a - od) / dd, (b - od) / dd);
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
            true
        };
        for i in 0..3 {
            if !narrow(o[i], d[i], self.bounds.min[i], self.bounds.max[i]) {
                return None;
            }
        }
        for (&(a, b), dir) in self.slabs.iter().zip(DIAGONALS) {
            let dir = DVec3::from(dir);
            if !narrow(dir.dot(o), dir.dot(d), a, b) {
                return None;
            }
        }
        // Widened a little, so that the casts start outside.
        let pad = 1e-9 * (hi - lo).abs().max(1.0);
        (lo <= hi).then_some((lo - pad, hi + pad))
    }

    /// [`Convex::cast`], started where it can be from the normal a cast
    /// along nearly `r` found last ([`coherence::recall`]; `slot` 0 for an
    /// entry, 1 for an exit): Newton's method from the plane of that
    /// normal ([`Convex::refine`]), whose answer is proved as ever; GJK's
    /// cast when it proves none. What it finds is remembered.
    fn warm_cast(&self, s: DVec3, r: DVec3, lmax: f64, slot: u8) -> (Option<(f64, DVec3)>, u32) {
        let key = self as *const Convex as usize;
        if let Some(hit) = self.end_entry(s, r, lmax) {
            coherence::remember(key, slot, r, hit.1);
            return (Some(hit), 0);
        }
        let mut steps = 0;
        if let Some(n) = coherence::recall(key, slot, r) {
            let nr = n.dot(r);
            if nr < 0.0 {
                let h = n.dot(self.support_point(n));
                let (hit, k) = self.refine(s, r, ((h - n.dot(s)) / nr).max(0.0), n);
                steps += k;
                if let Some(hit) = hit.filter(|h| h.0 <= lmax) {
                    coherence::remember(key, slot, r, hit.1);
                    return (Some(hit), steps);
                }
            }
        }
        let (hit, k) = self.cast(s, r, lmax);
        if let Some(n) = hit.and_then(|h| h.1.try_normalize()) {
            coherence::remember(key, slot, r, n);
        }
        (hit, steps + k)
    }

    /// The span of the line, and the steps both casts took.
    fn span(&self, o: DVec3, d: DVec3) -> (Option<(f64, DVec3, f64, DVec3)>, u32) {
        let Some((a, b)) = self.clip(o, d) else {
            return (None, 0);
        };
        let (fwd, i0) = self.warm_cast(o + d * a, d, b - a, 0);
        let Some((l0, n0)) = fwd else {
            return (None, i0);
        };
        let (back, i1) = self.warm_cast(o + d * b, -d, b - a, 1);
        let Some((l1, n1)) = back else {
            return (None, i0 + i1);
        };
        let (t0, t1) = (a + l0, b - l1);
        ((t0 < t1).then_some((t0, n0, t1, n1)), i0 + i1)
    }
}

impl Solid for Convex {
    const NAME: &'static str = "hull";

    /// A span that ends within the set's precision (10⁻⁹ of its size)
    /// after the query's start is a ray leaving the surface it starts on
    /// (a shadow or reflected ray), not a surface ahead of it: dropped. One
    /// that starts within it is a ray going in from its surface (out of a
    /// difference's cut): it starts at the query's start.
    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (span, steps) = self.span(q.o, q.d);
        q.st.convex_steps += steps as u64;
        if let Some((mut t0, _, t1, _)) = span {
            if q.tmin.is_finite() {
                let size = (self.bounds.max - self.bounds.min).max_element();
                let near = q.tmin + PRECISION * size / q.d.length();
                if t1 <= near {
                    return;
                }
                if t0 <= near {
                    t0 = t0.min(q.tmin);
                }
            }
            emit((t0, ENTRY, t1, EXIT));
        }
    }

    /// Not known from the point alone: see [`Solid::normal_on`].
    fn normal(&self, p: DVec3, _part: SurfacePart) -> DVec3 {
        // Away from the set's middle: right for a ball, and a direction
        // outwards for any convex set.
        p - self.bounds.center()
    }

    /// The last separating direction of the cast that found the point.
    fn normal_on(&self, o: DVec3, d: DVec3, _t: f64, part: SurfacePart) -> DVec3 {
        // Only the cast from the end the point is on.
        let cast = self.clip(o, d).and_then(|(a, b)| {
            if part == EXIT {
                self.cast(o + d * b, -d, b - a).0
            } else {
                self.cast(o + d * a, d, b - a).0
            }
        });
        match cast {
            Some((_, n)) if n != DVec3::ZERO => n,
            _ => self.normal(o, part),
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        matches!(self.cast(p, DVec3::X, 0.0).0, Some((l, _)) if l == 0.0)
    }

    fn object_bounds(&self) -> Aabb {
        self.bounds
    }

    /// The exact box: the support points along the world's axes, carried
    /// carried by `m` (world direction d is Mᵀd in object space).
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        let t = m.matrix3.transpose();
        let (mut lo, mut hi) = (DVec3::ZERO, DVec3::ZERO);
        for i in 0..3 {
            let e = DVec3::AXES[i];
            hi[i] = m.transform_point3(self.support_point(t * e))[i];
            lo[i] = m.transform_point3(self.support_point(-(t * e)))[i];
        }
        Aabb::new(lo, hi)
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        Some(self.support_point(d))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("sum_of", Param::Num(self.hulls.len() as f64)),
            (
                "parts",
                Param::Num(self.hulls.iter().map(|h| h.len()).sum::<usize>() as f64),
            ),
        ]
    }

    /// POV-Ray has no hull: the export stops POV-Ray with the reason.
    fn pov(&self) -> String {
        "#error \"csgrt: hull() and minkowski() have no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0"
            .to_string()
    }
}

/// A piece of a part whose support moves smoothly with the direction, or
/// not at all: the unknowns of [`Convex::refine`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Atom {
    /// A vertex of a polytope part (a cube, a mesh, a polygon's prism).
    Point(DVec3),
    /// A ball part (an ellipsoid once placed): hull, part.
    Ball(usize, usize),
    /// An end circle of a cylinder or cone part: hull, part, whether the top.
    Rim(usize, usize, bool),
}

/// How far the directions that find the active atoms are tilted from the
/// cast's last one (radians): well beyond GJK's √ε error in it.
const ACTIVE_TILT: f64 = 1e-5;

/// How close (relative to the set's size) GJK brings the line's point
/// before Newton's method is tried.
const LOOSE: f64 = 1e-6;

/// The directions of [`Convex`]'s diagonal slabs: the box's face
/// diagonals and corner diagonals, unit length.
const DIAGONALS: [[f64; 3]; 10] = {
    const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
    const T: f64 = 0.577_350_269_189_625_8;
    [
        [H, H, 0.0],
        [H, -H, 0.0],
        [0.0, H, H],
        [0.0, H, -H],
        [H, 0.0, H],
        [-H, 0.0, H],
        [T, T, T],
        [T, T, -T],
        [T, -T, T],
        [-T, T, T],
    ]
};

/// The most changes of the active atoms a refinement makes.
const ACTIVE_ROUNDS: usize = 4;

/// The most Newton steps a round of refinement takes.
const NEWTON_ITERATIONS: u32 = 12;

/// The last Newton step (radians) that counts as converged: the one after
/// it is below the rounding.
const NEWTON_CONVERGED: f64 = 1e-10;

/// The most unknowns: the normal's two angles, the ray's t, and two
/// weights (a point on a face spanned by three atoms).
const MAX_UNKNOWNS: usize = 5;

impl Convex {
    /// The atom of hull `j` that gives its support along `d`; `None` for a
    /// part with neither (a torus, a curved outline) or along a flat end
    /// circle's axis.
    fn atom(&self, j: usize, d: DVec3) -> Option<Atom> {
        let parts = &self.hulls[j];
        let (i, p) = parts
            .iter()
            .map(|p| p.support(d))
            .enumerate()
            .max_by(|a, b| a.1.dot(d).total_cmp(&b.1.dot(d)))?;
        let part = &parts[i];
        match &part.shape {
            Shape::Sphere(_) => Some(Atom::Ball(j, i)),
            Shape::Cuboid(_) | Shape::Mesh(_) => Some(Atom::Point(p)),
            Shape::Prism(q) if !q.region.curved() => Some(Atom::Point(p)),
            Shape::Cone(c) => {
                let local = part.to_world.matrix3.transpose() * d;
                if local.truncate() == glam::DVec2::ZERO {
                    return None;
                }
                let top = rim(c, true, local).dot(local) > rim(c, false, local).dot(local);
                if (if top { c.r1 } else { c.r0 }) == 0.0 {
                    Some(Atom::Point(p))
                } else {
                    Some(Atom::Rim(j, i, top))
                }
            }
            _ => None,
        }
    }

    /// An atom's support point along `d`.
    fn atom_support(&self, a: Atom, d: DVec3) -> DVec3 {
        match a {
            Atom::Point(p) => p,
            Atom::Ball(j, i) => self.hulls[j][i].support(d),
            Atom::Rim(j, i, top) => {
                let (part, c) = self.rim_part(j, i);
                let local = part.to_world.matrix3.transpose() * d;
                part.to_world.transform_point3(rim(c, top, local))
            }
        }
    }

    /// The part of hull `j` a rim atom belongs to, and its cone.
    fn rim_part(&self, j: usize, i: usize) -> (&ConvexPart, &super::Cone) {
        let part = &self.hulls[j][i];
        let Shape::Cone(c) = &part.shape else {
            unreachable!("a rim of a cone")
        };
        (part, c)
    }

    /// How atom `a`'s support point along unit `d` moves as `d` turns by
    /// `e` (d·e = 0), to first order: the derivative of
    /// [`Convex::atom_support`]. A placed ball's point is M·n + t with
    /// n = l/|l|, l = Mᵀd, so it moves by M·(Mᵀe − n(n·Mᵀe))/|l|; a rim's
    /// the same in the end circle's plane (n the unit horizontal part of
    /// l, scaled by the radius); a vertex does not move.
    fn atom_turn(&self, a: Atom, d: DVec3, e: DVec3) -> DVec3 {
        let (part, radius, flat) = match a {
            Atom::Point(_) => return DVec3::ZERO,
            Atom::Ball(j, i) => (&self.hulls[j][i], 1.0, false),
            Atom::Rim(j, i, top) => {
                let (part, c) = self.rim_part(j, i);
                (part, if top { c.r1 } else { c.r0 }, true)
            }
        };
        let m = part.to_world.matrix3;
        let (mut l, mut le) = (m.transpose() * d, m.transpose() * e);
        if flat {
            (l.z, le.z) = (0.0, 0.0);
        }
        let len = l.length();
        if len == 0.0 {
            return DVec3::ZERO;
        }
        let n = l / len;
        m * ((le - n * n.dot(le)) * (radius / len))
    }

    /// The atoms of each hull that support the set along `m` or along
    /// directions tilted from it by [`ACTIVE_TILT`]: the pieces the
    /// surface is made of near the point `m` supports. `None` when a part
    /// has no atoms, or when they span more than a face (more unknowns
    /// than [`MAX_UNKNOWNS`]).
    fn active(&self, m: DVec3) -> Option<Vec<Atoms>> {
        let u1 = m.any_orthonormal_vector();
        let u2 = m.cross(u1);
        let mut out: Vec<Atoms> = vec![smallvec::SmallVec::new(); self.hulls.len()];
        for d in [
            m,
            m + u1 * ACTIVE_TILT,
            m - u1 * ACTIVE_TILT,
            m + u2 * ACTIVE_TILT,
            m - u2 * ACTIVE_TILT,
        ] {
            for (j, atoms) in out.iter_mut().enumerate() {
                let a = self.atom(j, d)?;
                if !atoms.contains(&a) {
                    if atoms.len() == 3 {
                        return None;
                    }
                    atoms.push(a);
                }
            }
        }
        let unknowns = 3 + out.iter().map(|a| a.len() - 1).sum::<usize>();
        (unknowns <= MAX_UNKNOWNS).then_some(out)
    }

    /// The exact supporting plane where the line s + λr enters, from a
    /// normal `m` near it: Newton's method on the conditions that a point
    /// of the face the plane touches — a weighted sum of the active atoms'
    /// support points, each hull's weights summing to one — lies on the
    /// line, and that each hull's active atoms touch the plane together.
    /// Smooth atoms make these smooth in the normal's two angles, so it
    /// converges to the rounding: the normal and the entry of a point on a
    /// ball, on the bridge a hull spans between parts, on an edge rounded by
    /// a sum, on a face. An atom whose weight falls below zero is dropped,
    /// and one that sticks out of the plane is added, until the answer is
    /// proved: the point, a convex combination of support points, is in
    /// the set; the plane through it holds the whole set (the full support
    /// function's value there); and the line crosses the plane inwards —
    /// so the line enters there and nowhere before. `None` when no proof
    /// is found. Returns the entry and normal, and the steps taken.
    fn refine(&self, s: DVec3, r: DVec3, lambda: f64, m: DVec3) -> (Option<(f64, DVec3)>, u32) {
        if crate::mutant::active("hull_gjk_normals") {
            return (None, 0);
        }
        let Some(mut act) = self.active(m) else {
            return (None, 0);
        };
        let mut steps = 0;
        let (mut start, mut t) = (m, lambda);
        for _ in 0..ACTIVE_ROUNDS {
            let (outcome, k) = self.newton(s, r, t, start, &act);
            steps += k;
            match outcome {
                Newton::Plane(t, d) => return (Some((t, d)), steps),
                Newton::Change(next, d, at) => {
                    act = next;
                    start = d;
                    t = at;
                }
                Newton::Failed => break,
            }
        }
        (None, steps)
    }

    /// [`Convex::newton`]'s residual at its unknowns z — the face's point
    /// (each hull's first active atom's support point w₀ plus the others'
    /// differences w − w₀ by their weights) minus the line's, then each
    /// tie d·(w − w₀) — and its Jacobian, given the normal d there and how
    /// it turns with z₀ and z₁ ([`normal_turns`]): the face's point moves
    /// as its atoms' support points do ([`Convex::atom_turn`], weighted),
    /// and with the line's parameter and the weights as the line and the
    /// atoms' differences; each tie as d turns (a support point moves
    /// within its supporting plane, d·(w − w₀)' = d'·(w − w₀)).
    fn linearised(
        &self,
        s: DVec3,
        r: DVec3,
        z: &[f64; MAX_UNKNOWNS],
        (d, e): (DVec3, [DVec3; 2]),
        act: &[Atoms],
    ) -> Linearised {
        let mut f = [0.0; MAX_UNKNOWNS];
        let mut jac = [[0.0; MAX_UNKNOWNS]; MAX_UNKNOWNS];
        let mut p = -(s + r * z[2]);
        let mut moved = [DVec3::ZERO; 2];
        let mut k = 3;
        for atoms in act {
            let w0 = self.atom_support(atoms[0], d);
            p += w0;
            let t0 = e.map(|e| self.atom_turn(atoms[0], d, e));
            moved[0] += t0[0];
            moved[1] += t0[1];
            for &a in &atoms[1..] {
                let w = self.atom_support(a, d) - w0;
                p += w * z[k];
                f[k] = d.dot(w);
                let t = e.map(|e| self.atom_turn(a, d, e));
                for c in 0..2 {
                    let dt = t[c] - t0[c];
                    moved[c] += dt * z[k];
                    jac[k][c] = e[c].dot(w);
                }
                for row in 0..3 {
                    jac[row][k] = w[row];
                }
                k += 1;
            }
        }
        for row in 0..3 {
            f[row] = p[row];
            jac[row][0] = moved[0][row];
            jac[row][1] = moved[1][row];
            jac[row][2] = -r[row];
        }
        (f, jac)
    }

    /// One round of [`Convex::refine`] with the atoms `act`, and the
    /// steps taken.
    fn newton(&self, s: DVec3, r: DVec3, lambda: f64, m: DVec3, act: &[Atoms]) -> (Newton, u32) {
        let u1 = m.any_orthonormal_vector();
        let u2 = m.cross(u1);
        let n = 3 + act.iter().map(|a| a.len() - 1).sum::<usize>();
        let linearised =
            |z: &[f64; MAX_UNKNOWNS]| self.linearised(s, r, z, normal_turns(m, u1, u2, z), act);
        let mut z = [0.0; MAX_UNKNOWNS];
        z[2] = lambda;
        let mut k = 3;
        for atoms in act {
            for _ in 1..atoms.len() {
                z[k] = 1.0 / atoms.len() as f64;
                k += 1;
            }
        }
        let mut steps = 0;
        let mut last = f64::INFINITY;
        for _ in 0..NEWTON_ITERATIONS {
            steps += 1;
            let (f, jac) = linearised(&z);
            let Some(delta) = solve(jac, f, n) else {
                return (Newton::Failed, steps);
            };
            for i in 0..n {
                z[i] -= delta[i];
            }
            last = delta[0].abs().max(delta[1].abs());
            if last <= NEWTON_CONVERGED {
                break;
            }
        }
        // Not converged: no proof (the line's point is ill-conditioned
        // near a tangent, where a small residual is not a small error).
        if last.is_nan() || last > NEWTON_CONVERGED {
            return (Newton::Failed, steps);
        }
        // Each hull's weights: the first atom's is what the others leave.
        let d = normal_turns(m, u1, u2, &z).0;
        let mut k = 3;
        let mut next = Vec::with_capacity(act.len());
        let mut changed = false;
        for (j, atoms) in act.iter().enumerate() {
            let rest = &z[k..k + atoms.len() - 1];
            k += atoms.len() - 1;
            let first = 1.0 - rest.iter().sum::<f64>();
            let mut kept: Atoms = std::iter::once(first)
                .chain(rest.iter().copied())
                .zip(atoms)
                .filter(|(w, _)| *w >= 0.0)
                .map(|(_, &a)| a)
                .collect();
            changed |= kept.len() < atoms.len();
            // An atom of this hull that reaches beyond the plane.
            let Some(top) = self.atom(j, d) else {
                return (Newton::Failed, steps);
            };
            let h = d.dot(self.atom_support(top, d));
            let here = d.dot(self.atom_support(atoms[0], d));
            if !kept.contains(&top) && h > here + self.tol {
                if kept.len() == 3 {
                    return (Newton::Failed, steps);
                }
                kept.push(top);
                changed = true;
            }
            next.push(kept);
        }
        if changed {
            let unknowns = 3 + next.iter().map(|a| a.len() - 1).sum::<usize>();
            if unknowns > MAX_UNKNOWNS || next.iter().any(|a| a.is_empty()) {
                return (Newton::Failed, steps);
            }
            return (Newton::Change(next, d, z[2]), steps);
        }
        let dr = d.dot(r);
        let f = linearised(&z).0;
        let off = f[..3].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if dr >= 0.0 || dr.is_nan() || off.is_nan() || off > self.tol {
            return (Newton::Failed, steps);
        }
        let x = s + r * z[2];
        let h = d.dot(self.support_point(d));
        if d.dot(x) < h - self.tol {
            return (Newton::Failed, steps);
        }
        (Newton::Plane((h - d.dot(s)) / dr, d), steps)
    }
}

/// The unit normal of [`Convex::newton`]'s unknowns z, the direction
/// m + u1·z₀ + u2·z₁ normalised, and how it moves with z₀ and with z₁:
/// (u − d(d·u))/|m + u1·z₀ + u2·z₁| for u = u1, u2.
fn normal_turns(m: DVec3, u1: DVec3, u2: DVec3, z: &[f64; MAX_UNKNOWNS]) -> (DVec3, [DVec3; 2]) {
    let q = m + u1 * z[0] + u2 * z[1];
    let d = q.normalize();
    let len = q.length();
    (d, [u1, u2].map(|u| (u - d * d.dot(u)) / len))
}

/// A residual of [`Convex::newton`] and its Jacobian.
type Linearised = ([f64; MAX_UNKNOWNS], [[f64; MAX_UNKNOWNS]; MAX_UNKNOWNS]);

/// The active atoms of one hull.
type Atoms = smallvec::SmallVec<[Atom; 3]>;

/// How a round of refinement ended.
enum Newton {
    /// The proved entry and its normal.
    Plane(f64, DVec3),
    /// The atoms to try next (some dropped, some added), and the normal
    /// and the line's parameter to start from.
    Change(Vec<Atoms>, DVec3, f64),
    /// No proof.
    Failed,
}

/// A cone's end circle's support point along object-space `d`.
fn rim(c: &super::Cone, top: bool, d: DVec3) -> DVec3 {
    let z0 = super::cone::bottom(c.centered);
    let dir = d.truncate().normalize_or_zero();
    if top {
        (dir * c.r1).extend(z0 + 1.0)
    } else {
        (dir * c.r0).extend(z0)
    }
}

/// The solution x of J x = f for the first `n` unknowns (Gaussian
/// elimination, partial pivoting); `None` when J is singular.
fn solve(
    mut a: [[f64; MAX_UNKNOWNS]; MAX_UNKNOWNS],
    mut f: [f64; MAX_UNKNOWNS],
    n: usize,
) -> Option<[f64; MAX_UNKNOWNS]> {
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c] == 0.0 || a[p][c].is_nan() {
            return None;
        }
        a.swap(c, p);
        f.swap(c, p);
        let pivot = a[c];
        for row in c + 1..n {
            let k = a[row][c] / pivot[c];
            for (x, &y) in a[row][c..n].iter_mut().zip(&pivot[c..n]) {
                *x -= k * y;
            }
            f[row] -= k * f[c];
        }
    }
    let mut x = [0.0; MAX_UNKNOWNS];
    for c in (0..n).rev() {
        let mut v = f[c];
        for col in c + 1..n {
            v -= a[c][col] * x[col];
        }
        x[c] = v / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Up to four support points; the closest point of their hull to a point
/// (Ericson's Voronoi-region tests), keeping only the points it lies on.
#[derive(Default, Debug)]
struct Simplex {
    pts: smallvec::SmallVec<[DVec3; 4]>,
}

impl Simplex {
    fn add(&mut self, p: DVec3) {
        if !self.pts.contains(&p) {
            self.pts.push(p);
        }
    }

    /// The vector from `x` to the closest point of the hull, the simplex
    /// cut to the points that span that point; `None` when x is inside a
    /// tetrahedron. Computed from the points' offsets from x, each exact
    /// to its own size (a difference rounds relative to its result), so
    /// the answer's rounding shrinks with the simplex's distance from x.
    fn closest(&mut self, x: DVec3) -> Option<DVec3> {
        let q: smallvec::SmallVec<[DVec3; 4]> = self.pts.iter().map(|&p| p - x).collect();
        let (c, keep) = match q.len() {
            1 => (q[0], smallvec::smallvec![0]),
            2 => segment(q[0], q[1]),
            3 => triangle(q[0], q[1], q[2], [0, 1, 2]),
            _ => tetrahedron(q[0], q[1], q[2], q[3])?,
        };
        self.pts = keep.iter().map(|&i| self.pts[i]).collect();
        Some(c)
    }
}

/// The closest point to the origin, and which of the points span it.
type Closest = (DVec3, smallvec::SmallVec<[usize; 4]>);

fn segment(a: DVec3, b: DVec3) -> Closest {
    let ab = b - a;
    let t = -a.dot(ab);
    if t <= 0.0 {
        return (a, smallvec::smallvec![0]);
    }
    let den = ab.length_squared();
    if t >= den {
        return (b, smallvec::smallvec![1]);
    }
    (a + ab * (t / den), smallvec::smallvec![0, 1])
}

/// Ericson's closest point of triangle abc to the origin; `ids` name the
/// three points in the caller's simplex.
fn triangle(a: DVec3, b: DVec3, c: DVec3, ids: [usize; 3]) -> Closest {
    let [ia, ib, ic] = ids;
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, smallvec::smallvec![ia]);
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, smallvec::smallvec![ib]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, smallvec::smallvec![ia, ib]);
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, smallvec::smallvec![ic]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, smallvec::smallvec![ia, ic]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, smallvec::smallvec![ib, ic]);
    }
    if va + vb + vc == 0.0 {
        // A degenerate triangle: its longest edge's closest point.
        return [(a, b, ia, ib), (b, c, ib, ic), (a, c, ia, ic)]
            .into_iter()
            .map(|(p, q, i, j)| {
                let (c, k) = segment(p, q);
                (c, k.iter().map(|&x| [i, j][x]).collect())
            })
            .min_by(|x: &Closest, y: &Closest| {
                x.0.length_squared().total_cmp(&y.0.length_squared())
            })
            .expect("three edges");
    }
    // Inside the face: the origin's foot on its plane, along the plane's
    // normal (a cross product, its direction exact to a few ulps), not from
    // barycentric sums whose rounding is of the points' size.
    let n = ab.cross(ac);
    (
        n * (a.dot(n) / n.length_squared()),
        smallvec::smallvec![ia, ib, ic],
    )
}

/// Whether the origin and d lie on opposite sides of the plane through
/// a, b, c.
fn outside_plane(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> bool {
    let n = (b - a).cross(c - a);
    let (so, sd) = (-a.dot(n), (d - a).dot(n));
    so * sd < 0.0
}

/// The closest point of tetrahedron abcd to the origin: of the faces the
/// origin lies outside, the nearest; `None` when inside.
fn tetrahedron(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Option<Closest> {
    let p = [a, b, c, d];
    let mut best: Option<(f64, Closest)> = None;
    for [x, y, z, w] in [[0, 1, 2, 3], [0, 2, 3, 1], [0, 3, 1, 2], [1, 3, 2, 0]] {
        if outside_plane(p[x], p[y], p[z], p[w]) {
            let r = triangle(p[x], p[y], p[z], [x, y, z]);
            let dist = r.0.length_squared();
            if best.as_ref().map_or(true, |(b, _)| dist < *b) {
                best = Some((dist, r));
            }
        }
    }
    best.map(|(_, r)| r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Cuboid, Sphere};

    fn ball(c: DVec3, r: f64) -> ConvexPart {
        ConvexPart {
            shape: Shape::Sphere(Sphere),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::splat(r),
                glam::DQuat::IDENTITY,
                c,
            ),
        }
    }

    /// A thin cylinder squashed into an elliptic disc, placed by `m`'s
    /// scale (radius along x, y; height) and height `z`.
    fn disc(rx: f64, ry: f64, h: f64, z: f64) -> ConvexPart {
        ConvexPart {
            shape: Shape::Cone(crate::geometry::Cone {
                r0: 1.0,
                r1: 1.0,
                centered: false,
            }),
            to_world: DAffine3::from_scale_rotation_translation(
                DVec3::new(rx, ry, h),
                glam::DQuat::IDENTITY,
                DVec3::Z * z,
            ),
        }
    }

    /// The hull of two parallel elliptic discs of different shapes (no
    /// exact form: cast by support functions) is entered through its
    /// flat ends where GJK alone enters it, with no step; an end inside
    /// the hull (a disc within the other's shadow under a point above
    /// both) is not an entry; a sum has no ends of its own.
    #[test]
    fn a_line_through_a_flat_end_enters_where_gjk_finds_it() {
        let mut rnd = crate::plane::tests::uniform(73);
        let funnel = Convex::new(vec![vec![
            disc(29.0, 14.5, 0.01, 0.0),
            disc(24.0, 13.2, 0.01, -15.0),
        ]]);
        assert_eq!(
            funnel.ends.len(),
            2,
            "the top of the upper disc, the bottom of the lower"
        );
        let capped = Convex::new(vec![vec![
            disc(5.0, 3.0, 1.0, 0.0),
            ball(DVec3::Z * 9.0, 0.5),
        ]]);
        assert_eq!(
            capped.ends.len(),
            1,
            "the top end lies inside, under the ball"
        );
        let summed = Convex::new(vec![
            vec![disc(5.0, 3.0, 1.0, 0.0)],
            vec![ball(DVec3::ZERO, 1.0)],
        ]);
        assert!(summed.ends.is_empty());
        let mut through = 0;
        for set in [&funnel, &capped] {
            for _ in 0..3000 {
                let at = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd()) * DVec3::new(60.0, 30.0, 40.0)
                    - DVec3::Z * 15.0;
                let r = (DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 2.0).normalize();
                let s = at - r * 100.0;
                let Some((lambda, n)) = set.end_entry(s, r, 200.0) else {
                    continue;
                };
                through += 1;
                let (gjk, _) = set.cast(s, r, 200.0);
                let (want, wn) = gjk.expect("GJK enters where the end is crossed");
                assert!(
                    (lambda - want).abs() <= 1e-9 * 100.0,
                    "{s} {r}: {lambda} against {want}"
                );
                assert!(n.dot(wn.normalize()) > 0.999, "{n} against {wn}");
            }
        }
        assert!(through > 300, "{through} lines through an end");
    }

    /// Newton's Jacobian is the derivative of its residual: against
    /// central differences of the residual (the normal turned by 10⁻⁶,
    /// the weights and the line's parameter moved), on hulls of turned
    /// and squashed balls, elliptic discs and a frustum, at random
    /// normals, weights and parameters, each hull's active atoms as
    /// Newton takes them.
    #[test]
    fn newtons_jacobian_is_its_residuals_derivative() {
        let mut rnd = crate::plane::tests::uniform(29);
        let turned = |mut p: ConvexPart, q: glam::DQuat, squash: DVec3| {
            p.to_world = DAffine3::from_rotation_translation(q, DVec3::ZERO)
                * DAffine3::from_scale(squash)
                * p.to_world;
            p
        };
        let q = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        let mut frustum = disc(2.0, 1.0, 3.0, 1.0);
        frustum.shape = Shape::Cone(crate::geometry::Cone {
            r0: 1.5,
            r1: 0.5,
            centered: true,
        });
        let sets = [
            vec![vec![
                disc(29.0, 14.5, 0.01, 0.0),
                disc(24.0, 13.2, 0.01, -15.0),
            ]],
            vec![vec![
                turned(disc(5.0, 3.0, 1.0, 0.0), q, DVec3::new(1.0, 2.0, 0.5)),
                turned(ball(DVec3::Z * 9.0, 2.5), q, DVec3::new(1.5, 1.0, 1.0)),
            ]],
            vec![
                vec![ball(DVec3::X * 4.0, 1.0), ball(DVec3::ZERO, 2.0)],
                vec![turned(frustum, q, DVec3::ONE)],
            ],
        ];
        let mut checked = [0; 3];
        for set in sets {
            let c = Convex::new(set);
            for _ in 0..400 {
                let m = (DVec3::new(rnd(), rnd(), rnd()) - 0.5).normalize();
                // Each hull's atoms along m and along up to two other
                // directions, at most five unknowns in all.
                let extra = (rnd() * 3.0) as usize;
                let mut act: Vec<Atoms> = vec![Atoms::new(); c.hulls.len()];
                let mut n = 3;
                for (j, atoms) in act.iter_mut().enumerate() {
                    atoms.extend(c.atom(j, m));
                    for _ in 0..extra {
                        let other = (DVec3::new(rnd(), rnd(), rnd()) - 0.5).normalize();
                        match c.atom(j, other) {
                            Some(a) if n < MAX_UNKNOWNS && !atoms.contains(&a) => {
                                atoms.push(a);
                                n += 1;
                            }
                            _ => {}
                        }
                    }
                }
                if act.iter().any(|a| a.is_empty()) {
                    continue;
                }
                checked[n - 3] += 1;
                let (u1, u2) = (
                    m.any_orthonormal_vector(),
                    m.cross(m.any_orthonormal_vector()),
                );
                let (s, r) = (
                    DVec3::new(rnd(), rnd(), rnd()) * 9.0,
                    DVec3::new(0.6, -0.64, 0.48),
                );
                let mut z = [0.0; MAX_UNKNOWNS];
                for (i, v) in z.iter_mut().enumerate().take(n) {
                    *v = if i < 2 { (rnd() - 0.5) * 0.2 } else { rnd() };
                }
                let at = |z: &[f64; MAX_UNKNOWNS]| {
                    c.linearised(s, r, z, normal_turns(m, u1, u2, z), &act)
                };
                let (_, jac) = at(&z);
                for col in 0..n {
                    let h = 1e-6;
                    let (mut hi, mut lo) = (z, z);
                    hi[col] += h;
                    lo[col] -= h;
                    let (fh, fl) = (at(&hi).0, at(&lo).0);
                    for row in 0..n {
                        let want = (fh[row] - fl[row]) / (2.0 * h);
                        assert!(
                            (jac[row][col] - want).abs() <= 1e-5 * (1.0 + want.abs()),
                            "∂f{row}/∂z{col}: {} against {want} ({act:?})",
                            jac[row][col]
                        );
                    }
                }
            }
        }
        assert!(
            checked.iter().all(|&k| k > 20),
            "{checked:?} of 3, 4, 5 unknowns"
        );
    }

    #[test]
    fn the_hull_of_two_balls_is_met_on_their_common_tangent() {
        // Balls of radius 1 at x = 0 and x = 10: a capsule.
        let h = Convex::new(vec![vec![
            ball(DVec3::ZERO, 1.0),
            ball(DVec3::X * 10.0, 1.0),
        ]]);
        let (s, _) = h.span(DVec3::new(5.0, -5.0, 0.5), DVec3::Y);
        let (t0, n0, t1, n1) = s.unwrap();
        let want = 0.75f64.sqrt();
        assert!((t0 - (5.0 - want)).abs() < 1e-10, "{t0}");
        assert!((t1 - (5.0 + want)).abs() < 1e-10, "{t1}");
        assert!(
            (n0.normalize() - DVec3::new(0.0, -want, 0.5)).length() < 1e-6,
            "{n0}"
        );
        assert!(
            (n1.normalize() - DVec3::new(0.0, want, 0.5)).length() < 1e-6,
            "{n1}"
        );
        // Past the end cap: the ball's own chord.
        let (s, _) = h.span(DVec3::new(10.5, -5.0, 0.0), DVec3::Y);
        let (t0, _, t1, _) = s.unwrap();
        assert!(
            (t0 - (5.0 - 0.75f64.sqrt())).abs() < 1e-10
                && (t1 - (5.0 + 0.75f64.sqrt())).abs() < 1e-10
        );
        assert!(h.span(DVec3::new(5.0, -5.0, 1.01), DVec3::Y).0.is_none());
        assert!(h.contains(DVec3::new(3.0, 0.5, 0.5)));
        assert!(!h.contains(DVec3::new(3.0, 1.5, 0.0)));
    }

    #[test]
    fn a_cube_plus_a_ball_is_a_rounded_box() {
        let cube = ConvexPart {
            shape: Shape::Cuboid(Cuboid { centered: false }),
            to_world: DAffine3::from_scale(DVec3::splat(2.0)),
        };
        let m = Convex::new(vec![vec![cube], vec![ball(DVec3::ZERO, 0.5)]]);
        // Across a face: the face pushed out by 0.5.
        let (s, _) = m.span(DVec3::new(1.0, 1.0, -5.0), DVec3::Z);
        let (t0, _, t1, _) = s.unwrap();
        assert!(
            (t0 - 4.5).abs() < 1e-10 && (t1 - 7.5).abs() < 1e-10,
            "{t0} {t1}"
        );
        // Along an edge's rounding: x = 2 + 0.3, the quarter circle.
        let (s, _) = m.span(DVec3::new(2.3, 1.0, -5.0), DVec3::Z);
        let (t0, _, _, _) = s.unwrap();
        let z = -(0.25f64 - 0.09).sqrt();
        assert!((t0 - (5.0 + z)).abs() < 1e-10, "{t0}");
        let b = m.object_bounds();
        assert_eq!((b.min, b.max), (DVec3::splat(-0.5), DVec3::splat(2.5)));
    }

    #[test]
    fn a_centred_sum_is_the_same_set_moved() {
        // Two terms away from the origin: moving each by the centre would
        // move the sum twice.
        let far = vec![
            vec![ball(DVec3::new(18.0, 0.0, 1.0), 1.0)],
            vec![ball(DVec3::new(0.0, 5.0, 0.0), 2.0)],
        ];
        let (c, centre) = Convex::centred(far.clone());
        let whole = Convex::new(far);
        for d in [DVec3::X, -DVec3::Y, DVec3::new(1.0, 2.0, -3.0)] {
            let moved = c.support_point(d) + centre;
            assert!((moved - whole.support_point(d)).length() < 1e-12, "{moved}");
        }
    }
}
