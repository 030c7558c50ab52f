//! A triangle mesh as an exact leaf: `polyhedron`, and meshes imported
//! from files.
//!
//! A line's spans are read from its sorted crossings with the triangles,
//! by even-odd parity: inside between the first crossing and the second,
//! and so on. Parity needs no orientation, so a closed mesh renders right
//! whichever way its faces are wound (OpenSCAD's clockwise polyhedra,
//! STL's counter-clockwise files, and the many files that mix them); a
//! crossing's normal is turned to face the ray where the line enters and
//! along it where it leaves. An open mesh is closed by the same rule (a
//! line through a hole in it changes side once fewer); the resolver warns
//! with its counts.
//!
//! Crossings come from the watertight ray–triangle test of Woop, Benthin
//! and Wald (JCGT 2013) in f64: the line is sheared so that it runs along
//! z through the origin, and each triangle's three edge functions are
//! computed from its two end points alone, so that a shared edge gets the
//! same value, negated, from both of its triangles. A line exactly on an
//! edge or a vertex (an edge function exactly zero) is given to one
//! triangle only, by the top-left rule of rasterisers applied with each
//! triangle turned counter-clockwise as seen along the line: no crack, no
//! double crossing. Candidate triangles come from a hierarchy over their
//! boxes in object space ([`MeshBvh`]).

use super::mesh_bvh::MeshBvh;
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Need, Part, NO_PART};
use glam::{DAffine3, DVec3};
use smallvec::SmallVec;
use std::sync::Arc;

/// The most triangles a mesh may have: a crossing's part is its triangle
/// and one bit for its normal's side, in 31 bits.
pub const MAX_TRIANGLES: usize = 1 << 28;

/// The vertices, triangles and hierarchy of a mesh, shared by every leaf
/// placing it.
#[derive(Debug)]
pub struct MeshData {
    pub verts: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
    bvh: MeshBvh,
    bounds: Aabb,
    /// Each triangle's corners in `f32`, triangle by triangle, when every
    /// point is exactly an `f32` (a binary STL's always are); empty
    /// otherwise. The triangle tests read a leaf's corners here, in one
    /// place, instead of its triangles' indices and then the shared points
    /// they name (two loads, the second waiting on the first); the values,
    /// and so every answer, are the same.
    flat: Vec<[f32; 9]>,
    /// For a small closed convex mesh ([`face_planes`]): its faces' planes,
    /// against which a line is clipped instead of crossing its triangles;
    /// empty otherwise.
    planes: Vec<FacePlane>,
    /// For a convex mesh ([`MeshData::convex`]): each vertex's neighbours,
    /// so that its support point is found by climbing along edges.
    neighbours: Option<Vec<Vec<u32>>>,
}

impl PartialEq for MeshData {
    fn eq(&self, o: &MeshData) -> bool {
        self.verts == o.verts && self.tris == o.tris
    }
}

impl MeshData {
    /// A mesh of `tris` over `verts` (indices in range, at most
    /// [`MAX_TRIANGLES`]; degenerate triangles are kept and never hit).
    /// Vertices no triangle uses are dropped: they are not in the solid
    /// (its box, its hull).
    pub fn new(verts: Vec<DVec3>, tris: Vec<[u32; 3]>) -> MeshData {
        assert!(tris.len() <= MAX_TRIANGLES);
        let (bvh, order) = MeshBvh::build(&verts, &tris);
        // Triangles in leaf order, then vertices in order of first use, so
        // that a leaf's corners lie close in memory.
        let mut tris: Vec<[u32; 3]> = order.iter().map(|&k| tris[k as usize]).collect();
        drop(order);
        let mut new_index = vec![u32::MAX; verts.len()];
        let mut kept = Vec::new();
        for t in &mut tris {
            for i in t.iter_mut() {
                let k = &mut new_index[*i as usize];
                if *k == u32::MAX {
                    *k = kept.len() as u32;
                    kept.push(verts[*i as usize]);
                }
                *i = *k;
            }
        }
        drop(new_index);
        drop(verts);
        kept.shrink_to_fit();
        let verts = kept;
        let bounds = verts.iter().fold(Aabb::EMPTY, |b, &v| b.include(v));
        let in_f32 = |x: f64| f64::from(x as f32) == x;
        let flat = if verts
            .iter()
            .all(|v| in_f32(v.x) && in_f32(v.y) && in_f32(v.z))
        {
            tris.iter()
                .map(|t| {
                    let [a, b, c] = t.map(|k| verts[k as usize].as_vec3());
                    [a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z]
                })
                .collect()
        } else {
            Vec::new()
        };
        let planes = face_planes(&verts, &tris, &bounds);
        MeshData {
            verts,
            tris,
            bvh,
            bounds,
            flat,
            planes,
            neighbours: None,
        }
    }

    /// A convex closed mesh (a hull): as [`MeshData::new`], with each
    /// vertex's neighbours kept. On a convex polytope a vertex no
    /// neighbour of which lies farther along a direction is the farthest
    /// of all (a linear function has no other local maximum there), so its
    /// support point is found by climbing, not by reading every vertex.
    pub fn convex(verts: Vec<DVec3>, tris: Vec<[u32; 3]>) -> MeshData {
        let mut m = MeshData::new(verts, tris);
        let mut nb = vec![Vec::new(); m.verts.len()];
        for t in &m.tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if !nb[a as usize].contains(&b) {
                    nb[a as usize].push(b);
                    nb[b as usize].push(a);
                }
            }
        }
        m.neighbours = Some(nb);
        m
    }

    /// The vertex farthest along `d` (any of them where several).
    pub fn farthest(&self, d: DVec3) -> Option<DVec3> {
        let Some(nb) = &self.neighbours else {
            return self
                .verts
                .iter()
                .copied()
                .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)));
        };
        let mut at = 0usize;
        let mut best = self.verts.first()?.dot(d);
        loop {
            let next = nb[at]
                .iter()
                .map(|&k| (k as usize, self.verts[k as usize].dot(d)))
                .max_by(|a, b| a.1.total_cmp(&b.1));
            match next {
                // The fault: the climb stops after its first step.
                Some((k, v)) if v > best && !(at != 0 && crate::mutant::active("climb_once")) => {
                    at = k;
                    best = v;
                }
                _ => return Some(self.verts[at]),
            }
        }
    }

    /// Whether the triangles' corners are also kept flat in `f32`.
    #[cfg(test)]
    fn has_flat_corners(&self) -> bool {
        !self.flat.is_empty()
    }

    /// Triangle `i`'s corners.
    #[inline(always)]
    fn corners(&self, i: u32) -> [DVec3; 3] {
        match self.flat.get(i as usize) {
            Some(c) => unflatten(c),
            None => self.corner_refs(i).map(|v| *v),
        }
    }

    #[inline]
    fn corner_refs(&self, i: u32) -> [&DVec3; 3] {
        let t = self.tris[i as usize];
        [
            &self.verts[t[0] as usize],
            &self.verts[t[1] as usize],
            &self.verts[t[2] as usize],
        ]
    }

    /// The crossing `(t, triangle, its normal faces along d)` of the sheared
    /// line `w` with triangle `i`, if any.
    #[inline(always)]
    fn cross(&self, w: &Watertight, i: u32) -> Option<(f64, u32, bool)> {
        // The shared points by reference where there are no flat corners
        // (copied through `[_; 3]::map`, they were not made inline).
        let hit = match self.flat.get(i as usize) {
            Some(c) => {
                let [a, b, c] = unflatten(c);
                w.hit([&a, &b, &c])
            }
            None => w.hit(self.corner_refs(i)),
        };
        hit.map(|(t, along)| (t, i, along))
    }

    /// The crossings `(t, triangle, the triangle's normal faces along d)`
    /// of the line `o + t·d` in triangles whose boxes it meets in [t0,
    /// t1], at most t1 (none is dropped for lying a rounding before t0),
    /// sorted by t.
    pub fn crossings(
        &self,
        o: DVec3,
        d: DVec3,
        t0: f64,
        t1: f64,
        st: &mut crate::stats::Stats,
    ) -> SmallVec<[(f64, u32, bool); 16]> {
        let mut out: SmallVec<[(f64, u32, bool); 16]> = SmallVec::new();
        // The sheared line is set up at the first leaf met (most lines
        // that look for crossings before their start meet none).
        let mut w = Lazy::new(o, d);
        let mut tested = 0;
        self.bvh.visit(&self.bounds, o, d, t0, t1, st, |first, n| {
            let Some(w) = w.get() else { return true };
            tested += u64::from(n);
            for i in first..first + n {
                if let Some(x) = self.cross(w, i) {
                    if x.0 <= t1 {
                        out.push(x);
                    }
                }
            }
            false
        });
        st.triangle_tests += tested;
        out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }

    /// Some crossing `(t, triangle, its normal faces along d)` with tmin <
    /// t < tmax, the first met in the hierarchy's fixed order (a shadow
    /// ray's question: is there one).
    pub fn any(
        &self,
        o: DVec3,
        d: DVec3,
        tmin: f64,
        tmax: f64,
        st: &mut crate::stats::Stats,
    ) -> Option<(f64, u32, bool)> {
        let mut w = Lazy::new(o, d);
        let mut found = None;
        let mut tested = 0;
        self.bvh
            .visit(&self.bounds, o, d, tmin, tmax, st, |first, n| {
                let Some(w) = w.get() else { return true };
                for i in first..first + n {
                    tested += 1;
                    if let Some(x) = self.cross(w, i) {
                        if x.0 > tmin && x.0 < tmax {
                            found = Some(x);
                            return true;
                        }
                    }
                }
                false
            });
        st.triangle_tests += tested;
        found
    }

    /// The nearest crossing `(t, triangle, its normal faces along d)` with
    /// tmin < t < tmax, boxes opened nearest first and skipped once they
    /// begin beyond the best so far.
    pub fn nearest(
        &self,
        o: DVec3,
        d: DVec3,
        tmin: f64,
        tmax: f64,
        st: &mut crate::stats::Stats,
    ) -> Option<(f64, u32, bool)> {
        self.nearest_and_before(o, d, tmin, tmax, st).0
    }

    /// [`nearest`](Self::nearest), and whether the line may meet the
    /// mesh's box at or before tmin (`false` when it has no crossing in
    /// (tmin, tmax)): if not, no crossing lies before tmin.
    pub fn nearest_and_before(
        &self,
        o: DVec3,
        d: DVec3,
        tmin: f64,
        tmax: f64,
        st: &mut crate::stats::Stats,
    ) -> (Option<(f64, u32, bool)>, bool) {
        let mut w = Lazy::new(o, d);
        let mut best: Option<(f64, u32, bool)> = None;
        let mut tested = 0;
        let before = self
            .bvh
            .visit_near_first(&self.bounds, o, d, tmin, tmax, st, |first, n| {
                let Some(w) = w.get() else {
                    return f64::INFINITY;
                };
                tested += u64::from(n);
                for i in first..first + n {
                    if let Some((t, i, along)) = self.cross(w, i) {
                        // Ties go to the lower triangle, whatever the order
                        // of visits.
                        let better = best.map_or(true, |b| t < b.0 || (t == b.0 && i < b.1));
                        if t > tmin && t < tmax && better {
                            best = Some((t, i, along));
                        }
                    }
                }
                best.map_or(f64::INFINITY, |b| b.0)
            });
        st.triangle_tests += tested;
        (best, before && best.is_some())
    }
}

/// A triangle's flat `f32` corners as the `f64` points they are.
#[inline(always)]
fn unflatten(c: &[f32; 9]) -> [DVec3; 3] {
    let v = |k: usize| DVec3::new(f64::from(c[k]), f64::from(c[k + 1]), f64::from(c[k + 2]));
    [v(0), v(3), v(6)]
}

/// A line's [`Watertight`] set-up, made when first asked for (a line
/// that meets no leaf's box needs none).
struct Lazy {
    o: DVec3,
    d: DVec3,
    w: Option<Option<Watertight>>,
}

impl Lazy {
    fn new(o: DVec3, d: DVec3) -> Lazy {
        Lazy { o, d, w: None }
    }

    /// The set-up, `None` for a direction it cannot take (zero or not
    /// finite: then no walk reaches a leaf either).
    #[inline(always)]
    fn get(&mut self) -> Option<&Watertight> {
        let (o, d) = (self.o, self.d);
        self.w.get_or_insert_with(|| Watertight::new(o, d)).as_ref()
    }
}

/// A line sheared to run along +z through the origin (Woop, Benthin and
/// Wald's set-up, once a line).
///
/// The line's t is measured along `d / p`, `p` the power of two of d's
/// largest component, and divided by `p` at the end: every intermediate of
/// the test then stays in f64's normal range however long `d` is (with
/// 1 / d itself, a direction of length 1e295 made the crossings' products
/// subnormal, t good to 8 digits, and the nearest of two crossings
/// 1e-9 apart came out wrong). For a normal `d` the results are the same
/// bits: every step is the same rounding scaled by a power of two.
struct Watertight {
    o: DVec3,
    k: [usize; 3],
    s: DVec3,
    p: f64,
}

impl Watertight {
    fn new(o: DVec3, d: DVec3) -> Option<Watertight> {
        let a = d.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        if d[kz] == 0.0 || !d[kz].is_finite() {
            return None;
        }
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let p = super::mesh_bvh::pow2_floor(a[kz]);
        Some(Watertight {
            o,
            k: [kx, ky, kz],
            s: DVec3::new(d[kx] / d[kz], d[ky] / d[kz], 1.0 / (d[kz] / p)),
            p,
        })
    }

    /// `(t, whether the triangle's normal (b − a) × (c − a) faces along
    /// d)` where the line crosses it, if it does (by the rules above).
    #[inline(always)]
    fn hit(&self, p: [&DVec3; 3]) -> Option<(f64, bool)> {
        let [kx, ky, kz] = self.k;
        let s = self.s;
        let o: &[f64; 3] = self.o.as_ref();
        // Coordinates read by index from memory, not from registers (and
        // not through `[_; 3]::map`, which was not made inline here).
        let at = |v: &DVec3| {
            let v: &[f64; 3] = v.as_ref();
            let rz = v[kz] - o[kz];
            (
                (v[kx] - o[kx]) - s.x * rz,
                (v[ky] - o[ky]) - s.y * rz,
                s.z * rz,
            )
        };
        let (a, b, c) = (at(p[0]), at(p[1]), at(p[2]));
        // Edge functions: u of edge b→c, v of c→a, w of a→b.
        let mut u = c.0 * b.1 - c.1 * b.0;
        let mut v = a.0 * c.1 - a.1 * c.0;
        // Of two signs, outside whichever way the triangle turns (the
        // common case, decided before the rules for zeros below).
        if (u < 0.0 && v > 0.0) || (u > 0.0 && v < 0.0) {
            return None;
        }
        let mut w = b.0 * a.1 - b.1 * a.0;
        if (w < 0.0 && (u > 0.0 || v > 0.0)) || (w > 0.0 && (u < 0.0 || v < 0.0)) {
            return None;
        }
        let mut det = u + v + w;
        if det == 0.0 || det.is_nan() {
            return None;
        }
        // Seen along the line the triangle turns clockwise when det < 0:
        // its normal faces along d. Turned counter-clockwise, its edges
        // run the other way.
        let along = det < 0.0;
        let (mut e_bc, mut e_ca, mut e_ab) = (
            (c.0 - b.0, c.1 - b.1),
            (a.0 - c.0, a.1 - c.1),
            (b.0 - a.0, b.1 - a.1),
        );
        if along {
            u = -u;
            v = -v;
            w = -w;
            det = -det;
            e_bc = (-e_bc.0, -e_bc.1);
            e_ca = (-e_ca.0, -e_ca.1);
            e_ab = (-e_ab.0, -e_ab.1);
        }
        // Top-left: an edge owns the line on it when it runs down, or
        // along +x.
        let owns = |e: (f64, f64)| e.1 < 0.0 || (e.1 == 0.0 && e.0 > 0.0);
        let inside = |f: f64, e| f > 0.0 || (f == 0.0 && owns(e));
        if !(inside(u, e_bc) && inside(v, e_ca) && inside(w, e_ab)) {
            return None;
        }
        // Turning negated the edge functions and their sum alike.
        let t = u * a.2 + v * b.2 + w * c.2;
        Some((t / det / self.p, along))
    }
}

/// A crossing's part: its triangle, and whether its normal is to be turned
/// (an entry faces against d, an exit along it).
fn part_of((_, i, along): (f64, u32, bool), entering: bool) -> Part {
    (i << 1) | u32::from(along == entering)
}

/// The most triangles of a mesh clipped by its faces' planes rather than
/// crossed triangle by triangle through its hierarchy (a gear's tooth, a
/// hand-written wedge); a larger convex mesh (a hull of many points)
/// keeps the hierarchy, which tests only the triangles near the line.
pub const PLANES_MAX_TRIANGLES: usize = 64;

/// A face's plane: inside where `n·x ≤ h`, `n` the outward normal that
/// `part`'s triangle gives ([`Mesh::normal`]), not unit.
#[derive(Clone, Copy, Debug)]
struct FacePlane {
    n: DVec3,
    h: f64,
    part: Part,
}

/// The planes of a closed convex mesh of at most [`PLANES_MAX_TRIANGLES`]
/// triangles, one a face (its first triangle's), or none. Closed: every
/// edge joins exactly two triangles ([`edge_use`], as the warning about
/// open meshes counts them). Convex: every vertex lies inside
/// every triangle's plane, oriented away from the vertices' centroid, or
/// within 10⁻⁹ of the box's diagonal of it (and the rounding of points at
/// the box's distance from the origin: 64 ε of it), and the centroid
/// farther than that inside; a hull made with a coarser thickness far
/// from the origin keeps its triangles;
/// such a closed surface bounds exactly the intersection of the planes'
/// half-spaces, so parity and clipping agree. Triangles without area are
/// never crossed and give no plane.
fn face_planes(verts: &[DVec3], tris: &[[u32; 3]], bounds: &Aabb) -> Vec<FacePlane> {
    if tris.len() > PLANES_MAX_TRIANGLES || tris.len() < 4 {
        return Vec::new();
    }
    if edge_use(tris) != (0, 0) {
        return Vec::new();
    }
    let far = bounds.min.abs().max(bounds.max.abs()).max_element();
    let tol = 1e-9 * (bounds.max - bounds.min).length() + 64.0 * f64::EPSILON * far;
    let centroid = verts.iter().sum::<DVec3>() / verts.len() as f64;
    let mut planes: Vec<FacePlane> = Vec::new();
    for (i, t) in tris.iter().enumerate() {
        let [a, b, c] = t.map(|k| verts[k as usize]);
        let raw = (b - a).cross(c - a);
        let len = raw.length();
        if len == 0.0 || !len.is_finite() {
            continue;
        }
        // Outward: away from the centroid (`Mesh::normal` flips the
        // triangle's normal for a part whose low bit is set).
        let inward = raw.dot(centroid - a) > 0.0;
        let n = if inward { -raw } else { raw };
        let h = n.dot(a);
        let unit = n / len;
        if unit.dot(centroid) - h / len > -tol || verts.iter().any(|v| unit.dot(*v) - h / len > tol)
        {
            return Vec::new();
        }
        let same = |p: &FacePlane| {
            let l = p.n.length();
            (p.n / l - unit).length() < 1e-12 && (p.h / l - h / len).abs() < tol
        };
        if !planes.iter().any(same) {
            planes.push(FacePlane {
                n,
                h,
                part: ((i as u32) << 1) | u32::from(inward),
            });
        }
    }
    planes
}

/// The line `o + t·d` clipped by `planes`: the one span inside them all,
/// entered through the last plane it crosses inwards and left through the
/// first it crosses outwards; none where it runs along or outside one.
fn clip(planes: &[FacePlane], o: DVec3, d: DVec3, emit: &mut impl FnMut(RawSpan)) {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut p0, mut p1) = (NO_PART, NO_PART);
    for p in planes {
        let (along, gap) = (p.n.dot(d), p.h - p.n.dot(o));
        if along == 0.0 {
            if gap <= 0.0 {
                return;
            }
            continue;
        }
        let t = gap / along;
        if along < 0.0 {
            if t > t0 {
                t0 = t;
                p0 = p.part;
            }
        } else if t < t1 {
            t1 = t;
            p1 = p.part;
        }
    }
    if t0 < t1 {
        emit((t0, p0, t1, p1));
    }
}

/// The line along which a point's inside is counted, and POV-Ray's
/// `inside_vector` for the same parity: no special direction.
const INSIDE: DVec3 = DVec3::new(0.573_462_1, 0.614_379_3, 0.542_058_7);

/// A mesh placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    pub data: Arc<MeshData>,
}

impl Solid for Mesh {
    const NAME: &'static str = "polyhedron";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let m = &self.data;
        if !m.planes.is_empty() {
            // A small convex mesh: the line clipped by its faces' planes,
            // one span, whatever the caller reads of it.
            q.st.triangle_tests += m.planes.len() as u64;
            return clip(&m.planes, q.o, q.d, emit);
        }
        if q.need != Need::Spans {
            // Every crossing of a closed mesh is a boundary: the first after
            // tmin is the nearest hit, found nearest first; its side is
            // the parity of the crossings up to tmin (none when the box
            // begins after tmin), asked only for a first hit's normal. A
            // shadow ray takes the first crossing it meets.
            // (A line whose piece in the mesh's box begins after tmin has
            // no crossing before it: no walk for the parity.)
            let (x, before) = if q.need == Need::AnyBoundary {
                (m.any(q.o, q.d, q.tmin, q.tmax, q.st), false)
            } else {
                m.nearest_and_before(q.o, q.d, q.tmin, q.tmax, q.st)
            };
            let Some(x) = x else {
                return;
            };
            let entering = q.need == Need::AnyBoundary
                || !before
                || m.crossings(q.o, q.d, f64::NEG_INFINITY, q.tmin, q.st).len() % 2 == 0;
            let part = part_of(x, entering);
            if entering {
                emit((x.0, part, f64::INFINITY, NO_PART));
            } else {
                emit((f64::NEG_INFINITY, NO_PART, x.0, part));
            }
            return;
        }
        // Outside before the mesh's box: every crossing up to tmax is
        // counted, from the line's start.
        let xs = m.crossings(q.o, q.d, f64::NEG_INFINITY, q.tmax, q.st);
        let mut k = 0;
        while k < xs.len() {
            let a = xs[k];
            match xs.get(k + 1) {
                Some(&b) => {
                    if b.0 > a.0 {
                        emit((a.0, part_of(a, true), b.0, part_of(b, false)));
                    }
                }
                None => emit((a.0, part_of(a, true), f64::INFINITY, NO_PART)),
            }
            k += 2;
        }
    }

    fn normal(&self, _p: DVec3, part: Part) -> DVec3 {
        let [a, b, c] = self.data.corners(part >> 1);
        let n = (b - a).cross(c - a);
        if part & 1 == 1 {
            -n
        } else {
            n
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        let d = INSIDE;
        let mut st = crate::stats::Stats::default();
        let b = &self.data.bounds;
        if p.cmplt(b.min).any() || p.cmpgt(b.max).any() {
            return false;
        }
        self.data
            .crossings(p, d, 0.0, f64::INFINITY, &mut st)
            .iter()
            .filter(|x| x.0 > 0.0)
            .count()
            % 2
            == 1
    }

    fn object_bounds(&self) -> Aabb {
        self.data.bounds
    }

    /// The box of the placed vertices: exact.
    fn world_bounds(&self, m: &DAffine3) -> Aabb {
        self.data
            .verts
            .iter()
            .fold(Aabb::EMPTY, |b, &v| b.include(m.transform_point3(v)))
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        self.data.farthest(d)
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("vertices", Param::Num(self.data.verts.len() as f64)),
            ("triangles", Param::Num(self.data.tris.len() as f64)),
        ]
    }

    /// POV-Ray's `mesh2`: the same vertices and triangles, with an
    /// `inside_vector` so that it is a solid in CSG (POV-Ray counts
    /// crossings along it: the same parity).
    fn pov(&self) -> String {
        let m = &self.data;
        let v: Vec<String> = m
            .verts
            .iter()
            .map(|p| format!("<{:?}, {:?}, {:?}>", p.x, p.y, p.z))
            .collect();
        let f: Vec<String> = m
            .tris
            .iter()
            .map(|t| format!("<{}, {}, {}>", t[0], t[1], t[2]))
            .collect();
        format!(
            "mesh2 {{ vertex_vectors {{ {}, {} }} face_indices {{ {}, {} }} inside_vector <{:?}, {:?}, {:?}>",
            v.len(),
            v.join(", "),
            f.len(),
            f.join(", "),
            INSIDE.x,
            INSIDE.y,
            INSIDE.z
        )
    }
}

/// How a mesh's edges are shared: (edges of one face only, edges of three
/// or more faces), for the warnings about open and non-manifold meshes.
pub fn edge_use(tris: &[[u32; 3]]) -> (usize, usize) {
    // Each edge as one word, its lesser end above.
    let mut edges: Vec<u64> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (u64::from(a.min(b)) << 32) | u64::from(a.max(b)))
        .collect();
    edges.sort_unstable();
    let (mut open, mut many) = (0, 0);
    let mut k = 0;
    while k < edges.len() {
        let mut n = 1;
        while k + n < edges.len() && edges[k + n] == edges[k] {
            n += 1;
        }
        match n {
            1 => open += 1,
            2 => {}
            _ => many += 1,
        }
        k += n;
    }
    (open, many)
}

#[cfg(test)]
mod tests {
    //! The hierarchy's `f32` boxes against no hierarchy at all: every
    //! crossing of every triangle, by the same exact test.
    use super::*;

    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
            xs[(self.next() * xs.len() as f64) as usize % xs.len()]
        }
    }

    fn brute(m: &MeshData, o: DVec3, d: DVec3, t1: f64) -> Vec<(f64, u32, bool)> {
        let Some(w) = Watertight::new(o, d) else {
            return Vec::new();
        };
        let mut out: Vec<_> = (0..m.tris.len() as u32)
            .filter_map(|i| w.hit(m.corner_refs(i)).map(|(t, a)| (t, i, a)))
            .filter(|x| x.0 <= t1)
            .collect();
        out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }

    /// A grid of triangles `step` apart, bent, at `offset` and `scale`
    /// (over decimal steps, no coordinate is an `f32`).
    fn grid(n: usize, offset: DVec3, scale: f64, step: f64) -> MeshData {
        let mut verts = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f64 * step, j as f64 * step);
                let z = if (i + j) % 3 == 0 { step } else { 0.0 };
                verts.push(offset + scale * DVec3::new(x, y, z));
            }
        }
        let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        MeshData::new(verts, tris)
    }

    #[test]
    fn the_hierarchy_drops_no_crossing_the_exact_test_finds() {
        let mut rng = Lcg(7);
        let mut crossings = 0;
        let mut st = crate::stats::Stats::default();
        for (offset, scale, step) in [
            (DVec3::ZERO, 1.0, 0.1),
            (DVec3::new(1e6, -3e5, 7e5), 1.0, 0.1),
            (DVec3::new(0.3, 0.7, -0.1), 1e-7, 0.1),
            (DVec3::new(-2e12, 5e11, 1e12), 3e4, 0.1),
            // Every point an `f32`: the tests read the flat corners (the
            // brute force below still reads the points).
            (DVec3::ZERO, 1.0, 0.125),
            (DVec3::new(1024.0, -512.0, 1000.0), 1.0 / 1024.0, 0.375),
        ] {
            let m = grid(12, offset, scale, step);
            assert_eq!(m.has_flat_corners(), step != 0.1, "{offset} {scale} {step}");
            let pts: Vec<DVec3> = m.verts.clone();
            for k in 0..4000 {
                // Aimed at a vertex, an edge's midpoint or anywhere, from
                // near or far, along an axis (zero components), nearly
                // along one (tiny ones, subnormal too) or in any direction.
                let a = rng.pick(&pts);
                let b = rng.pick(&pts);
                let target = match k % 3 {
                    0 => a,
                    1 => 0.5 * (a + b),
                    _ => a + scale * DVec3::new(rng.next(), rng.next(), rng.next()) * 0.3,
                };
                let mut d = match k % 4 {
                    0 => DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5),
                    1 => [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::Z][k / 4 % 4],
                    2 => DVec3::new(
                        rng.pick(&[1e-25, 1e-313]) * (rng.next() - 0.5),
                        rng.next() - 0.5,
                        1.0,
                    ),
                    _ => b - a + DVec3::new(0.0, 0.0, scale * 0.05),
                };
                if d == DVec3::ZERO {
                    d = DVec3::Z;
                }
                let far = rng.pick(&[1e-3, 1.0, 1e3, 1e9]) * scale;
                let o = target - d.normalize() * far;
                // The direction's length, t's own scale, to subnormal
                // directions (only where the crossings' t stay finite):
                // the walk and the triangle test rescale it by a power of
                // two, the same bits as long as nothing leaves f64's range.
                let k = rng.pick(&[1.0, 1.0, 1e-300, 1e-250, 1e250, 1e300]);
                if (far + 20.0 * scale) / (k * d.length()) < 1e305 {
                    d *= k;
                }
                let want = brute(&m, o, d, f64::INFINITY);
                let got = m.crossings(o, d, f64::NEG_INFINITY, f64::INFINITY, &mut st);
                assert_eq!(got.as_slice(), want.as_slice(), "{o} {d}");
                let first = want.iter().find(|x| x.0 > 0.0).copied();
                assert_eq!(
                    m.nearest(o, d, 0.0, f64::INFINITY, &mut st),
                    first,
                    "{o} {d}"
                );
                // A shadow ray's answer: some crossing of the list, if any.
                let any = m.any(o, d, 0.0, f64::INFINITY, &mut st);
                assert_eq!(any.is_some(), first.is_some(), "{o} {d}");
                assert!(any.map_or(true, |x| want.contains(&x) && x.0 > 0.0));
                crossings += want.len();
            }
        }
        assert!(crossings > 20_000, "{crossings}");
    }

    /// A small convex mesh is clipped by its faces' planes: the same span
    /// as its triangles' crossings (the exact watertight test, brute force,
    /// paired in order), entered and left through faces whose normals are
    /// the crossed triangles' (outward), on random hulls of 4 to 12 random
    /// points (quickhull) at several places and scales, along random lines.
    #[test]
    fn a_small_convex_mesh_is_clipped_as_its_triangles_are_crossed() {
        let mut rng = Lcg(11);
        let (mut checked, mut clipped) = (0, 0);
        for (offset, scale) in [
            (DVec3::ZERO, 1.0),
            (DVec3::new(1353.5, -12.7, 231.0), 10.0),
            (DVec3::new(-3e5, 2e5, 1e5), 1e-3),
        ] {
            for k in 0..200 {
                let n = 4 + k % 9;
                let pts: Vec<DVec3> = (0..n)
                    .map(|_| offset + scale * DVec3::new(rng.next(), rng.next(), rng.next()))
                    .collect();
                let Some(hull) = crate::geometry::polytope::hull_mesh(&pts) else {
                    continue;
                };
                let m = &hull.data;
                if m.tris.len() > PLANES_MAX_TRIANGLES {
                    continue;
                }
                // A hull made convex only within the far place's coarser
                // thickness keeps its triangles.
                if m.planes.is_empty() {
                    continue;
                }
                clipped += 1;
                for _ in 0..50 {
                    let o = offset
                        + scale
                            * DVec3::new(
                                3.0 * rng.next() - 1.0,
                                3.0 * rng.next() - 1.0,
                                3.0 * rng.next() - 1.0,
                            );
                    let target = offset + scale * DVec3::new(rng.next(), rng.next(), rng.next());
                    let d = target - o;
                    let xs = brute(m, o, d, f64::INFINITY);
                    let mut got = Vec::new();
                    clip(&m.planes, o, d, &mut |s| got.push(s));
                    if xs.is_empty() {
                        assert!(got.is_empty(), "{got:?} for no crossing");
                        continue;
                    }
                    assert_eq!(xs.len(), 2, "a line crosses a convex surface twice");
                    assert_eq!(got.len(), 1);
                    let (t0, p0, t1, p1) = got[0];
                    // Rounding at the points' magnitude, along `d`.
                    let room = 2e-9 * scale + 1e-13 * offset.abs().max_element();
                    let tol = room / d.length();
                    assert!(
                        (t0 - xs[0].0).abs() < tol && (t1 - xs[1].0).abs() < tol,
                        "{got:?} {xs:?}"
                    );
                    for (part, x, entering) in [(p0, xs[0], true), (p1, xs[1], false)] {
                        let n = hull.normal(DVec3::ZERO, part).normalize();
                        let want = hull.normal(DVec3::ZERO, part_of(x, entering)).normalize();
                        assert!((n - want).length() < room / scale, "{n} {want}");
                        assert_eq!(n.dot(d) < 0.0, entering, "outward normal");
                    }
                    checked += 1;
                }
            }
        }
        assert!(clipped > 500 && checked > 5000, "{clipped} {checked}");
    }

    /// A mesh that is open, or not convex, keeps its triangles.
    #[test]
    fn an_open_or_concave_mesh_gets_no_planes() {
        let v = DVec3::new;
        // A square pyramid (apex 5) whose base is four triangles meeting
        // at point 4, under the base (a convex bipyramid) or pushed up
        // into the pyramid (a dent: closed, not convex).
        let tris = vec![
            [0, 1, 5],
            [1, 2, 5],
            [2, 3, 5],
            [3, 0, 5],
            [0, 4, 1],
            [1, 4, 2],
            [2, 4, 3],
            [3, 4, 0],
        ];
        let with = |z: f64| {
            vec![
                v(0.0, 0.0, 0.0),
                v(2.0, 0.0, 0.0),
                v(2.0, 2.0, 0.0),
                v(0.0, 2.0, 0.0),
                v(1.0, 1.0, z),
                v(1.0, 1.0, 2.0),
            ]
        };
        assert_eq!(MeshData::new(with(-0.5), tris.clone()).planes.len(), 8);
        assert!(MeshData::new(with(0.5), tris.clone()).planes.is_empty());
        // Flat at 4: the base's four triangles are one face.
        assert_eq!(MeshData::new(with(0.0), tris.clone()).planes.len(), 5);
        // A face missing: open.
        assert!(MeshData::new(with(-0.5), tris[..7].to_vec())
            .planes
            .is_empty());
    }
}
