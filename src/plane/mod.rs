//! The plane z = 0, where OpenSCAD's 2-D shapes live until an extrusion
//! lifts them into space.
//!
//! Under a 2-D shape, transforms act in the plane: OpenSCAD keeps of a 4×4
//! matrix only the rows and columns of x, y and the homogeneous part —
//! `[[m00, m01, m03], [m10, m11, m13], [m30, m31, m33]]` — so a
//! `translate([0, 0, 5])` or a turn about x does nothing to a square but
//! what its x and y rows say ([`from_space`]). A region is a set of closed
//! outlines filled by the even-odd rule (a hole is an outline inside
//! another); a line of the plane meets it in sorted spans, found from the
//! crossings of its edges ([`Outlines::spans`]) — what a prism's spans are
//! made of once the slab is clipped.

pub mod cells;
pub mod figure;
pub mod flat;
pub mod hull;
pub mod offset;
pub mod pencil;
pub mod round_offset;
pub mod sites;
pub mod sum;

use crate::math::poly::{self, roots_in, Poly};
use glam::{DAffine2, DAffine3, DMat2, DVec2, DVec3};

/// The plane's part of a space transform, as OpenSCAD applies it to 2-D
/// shapes (`None` when it flattens them: a zero determinant).
pub fn from_space(m: &DAffine3) -> Option<DAffine2> {
    let c = |j: usize| m.matrix3.col(j);
    let a = DMat2::from_cols(c(0).truncate(), c(1).truncate());
    (a.determinant() != 0.0).then(|| DAffine2::from_mat2_translation(a, m.translation.truncate()))
}

/// How an edge runs from its start to the next point of its loop: straight,
/// or a quadratic or cubic Bézier curve with these control points (a font's
/// outline is made of them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ctrl {
    Line,
    Quad(DVec2),
    Cubic(DVec2, DVec2),
}

impl Ctrl {
    /// The control points, mapped by `f`.
    pub fn map(self, f: impl Fn(DVec2) -> DVec2) -> Ctrl {
        match self {
            Ctrl::Line => Ctrl::Line,
            Ctrl::Quad(c) => Ctrl::Quad(f(c)),
            Ctrl::Cubic(c1, c2) => Ctrl::Cubic(f(c1), f(c2)),
        }
    }

    /// The two inner control points of the edge a→b as one cubic Bézier
    /// segment: a line or a quadratic raised to degree 3 exactly (POV-Ray's
    /// `bezier_spline` takes only cubics).
    pub fn cubic(self, a: DVec2, b: DVec2) -> (DVec2, DVec2) {
        match self {
            Ctrl::Line => (a + (b - a) / 3.0, b + (a - b) / 3.0),
            Ctrl::Quad(c) => (a + (c - a) * (2.0 / 3.0), b + (c - b) * (2.0 / 3.0)),
            Ctrl::Cubic(c1, c2) => (c1, c2),
        }
    }

    /// The control points.
    pub fn points(&self) -> impl Iterator<Item = DVec2> {
        let (a, b) = match *self {
            Ctrl::Line => (None, None),
            Ctrl::Quad(c) => (Some(c), None),
            Ctrl::Cubic(c1, c2) => (Some(c1), Some(c2)),
        };
        a.into_iter().chain(b)
    }

    /// The box `(lo, hi)` of the edge from `a` to `b`: its ends' and
    /// control points', which holds a curve (it lies in their hull).
    pub fn bounds(&self, a: DVec2, b: DVec2) -> (DVec2, DVec2) {
        self.points()
            .fold((a.min(b), a.max(b)), |(lo, hi), p| (lo.min(p), hi.max(p)))
    }
}

/// One edge from `a` to `b`: its point at u ∈ [0, 1] is B(u), a polynomial
/// of degree ≤ 3, kept in the power basis about an origin o:
/// `B(u) − o = k[0] + k[1]·u + k[2]·u² + k[3]·u³`.
#[derive(Clone, Copy, Debug)]
pub struct Curve {
    pub k: [DVec2; 4],
    pub degree: usize,
}

impl Curve {
    /// The edge (a, ctrl, b) about origin `o`.
    pub fn new(a: DVec2, ctrl: Ctrl, b: DVec2, o: DVec2) -> Curve {
        let (p0, p3) = (a - o, b - o);
        match ctrl {
            Ctrl::Line => Curve {
                k: [p0, p3 - p0, DVec2::ZERO, DVec2::ZERO],
                degree: 1,
            },
            Ctrl::Quad(c) => {
                let p1 = c - o;
                Curve {
                    k: [p0, 2.0 * (p1 - p0), p0 - 2.0 * p1 + p3, DVec2::ZERO],
                    degree: 2,
                }
            }
            Ctrl::Cubic(c1, c2) => {
                let (p1, p2) = (c1 - o, c2 - o);
                Curve {
                    k: [
                        p0,
                        3.0 * (p1 - p0),
                        3.0 * (p0 - 2.0 * p1 + p2),
                        p3 - 3.0 * p2 + 3.0 * p1 - p0,
                    ],
                    degree: 3,
                }
            }
        }
    }

    /// B(u) − o.
    pub fn at(&self, u: f64) -> DVec2 {
        let k = &self.k;
        ((k[3] * u + k[2]) * u + k[1]) * u + k[0]
    }

    /// B′(u).
    pub fn tangent(&self, u: f64) -> DVec2 {
        let k = &self.k;
        (k[3] * (3.0 * u) + k[2] * 2.0) * u + k[1]
    }

    /// The polynomial n·(B(u) − o) − c.
    pub fn along(&self, n: DVec2, c: f64) -> Poly {
        let k = &self.k;
        poly::poly(&[k[0].dot(n) - c, k[1].dot(n), k[2].dot(n), k[3].dot(n)])
    }

    /// Calls `f` with each u in (0, 1) where B′(u)·dir = 0 (where the
    /// curve's extent along dir may be reached between its ends).
    pub fn turning(&self, dir: DVec2, mut f: impl FnMut(f64)) {
        let k = &self.k;
        let d = poly::poly(&[k[1].dot(dir), 2.0 * k[2].dot(dir), 3.0 * k[3].dot(dir)]);
        let mut roots = [0.0; poly::MAX_DEGREE];
        let n = roots_in(&d, self.degree - 1, 0.0, 1.0, &mut roots);
        roots[..n].iter().for_each(|&u| f(u));
    }

    /// The parameter of the point of the curve nearest `p` (a point on it,
    /// up to rounding): among the ends and the parameters where either
    /// coordinate of B equals p's (one of the two is never a double root
    /// but at a cusp), the nearest.
    pub fn param_of(&self, p: DVec2) -> f64 {
        let mut best = (f64::INFINITY, 0.0);
        let mut try_u = |u: f64| {
            let e = (self.at(u) - p).length_squared();
            if e < best.0 {
                best = (e, u);
            }
        };
        try_u(0.0);
        try_u(1.0);
        let mut roots = [0.0; poly::MAX_DEGREE];
        for axis in [DVec2::X, DVec2::Y] {
            let n = roots_in(
                &self.along(axis, p.dot(axis)),
                self.degree,
                0.0,
                1.0,
                &mut roots,
            );
            roots[..n].iter().for_each(|&u| try_u(u));
            // A coordinate's extreme value is a double root of its
            // equation: its critical points are candidates too.
            self.turning(axis, &mut try_u);
        }
        best.1
    }
}

/// Closed outlines in the plane, each a list of at least 3 points joined
/// last to first, filled by the even-odd rule. `ctrl`, when not empty, says
/// how each edge runs (one list per loop, edge i from point i to i + 1);
/// empty, every edge is straight.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outlines {
    pub loops: Vec<Vec<DVec2>>,
    pub ctrl: Vec<Vec<Ctrl>>,
}

impl Outlines {
    /// Its corners (lo, hi) where it is one rectangle with sides along the
    /// axes and of positive size.
    pub fn axis_rectangle(&self) -> Option<(DVec2, DVec2)> {
        let [l] = self.loops.as_slice() else {
            return None;
        };
        if l.len() != 4 || self.curved() {
            return None;
        }
        let (lo, hi) = l
            .iter()
            .fold((l[0], l[0]), |(a, b), &p| (a.min(p), b.max(p)));
        let corner = |p: DVec2| (p.x == lo.x || p.x == hi.x) && (p.y == lo.y || p.y == hi.y);
        let sides = (0..4).all(|i| {
            let (p, q) = (l[i], l[(i + 1) % 4]);
            (p.x == q.x) != (p.y == q.y)
        });
        (sides && l.iter().all(|&p| corner(p)) && lo.x < hi.x && lo.y < hi.y).then_some((lo, hi))
    }

    /// Straight-edged outlines.
    pub fn polygons(loops: Vec<Vec<DVec2>>) -> Outlines {
        Outlines {
            loops,
            ctrl: Vec::new(),
        }
    }

    /// Whether any edge is curved.
    pub fn curved(&self) -> bool {
        self.ctrl.iter().flatten().any(|c| *c != Ctrl::Line)
    }

    /// The same outlines with every point (and control point) mapped by `f`.
    pub fn map(&self, f: impl Fn(DVec2) -> DVec2 + Copy) -> Outlines {
        Outlines {
            loops: self
                .loops
                .iter()
                .map(|l| l.iter().map(|&p| f(p)).collect())
                .collect(),
            ctrl: self
                .ctrl
                .iter()
                .map(|l| l.iter().map(|c| c.map(f)).collect())
                .collect(),
        }
    }

    /// The range of p·axis over the region (exact: a curve's extreme
    /// values are at its ends or where its derivative along `axis` is 0).
    pub fn extent(&self, axis: DVec2) -> (f64, f64) {
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        let mut add = |v: f64| r = (r.0.min(v), r.1.max(v));
        for (a, c, b) in self.edges() {
            add(a.dot(axis));
            if c != Ctrl::Line {
                let curve = Curve::new(a, c, b, DVec2::ZERO);
                curve.turning(axis, |u| add(curve.at(u).dot(axis)));
            }
        }
        r
    }

    /// Every edge as (start, how it runs, end).
    pub fn edges(&self) -> impl Iterator<Item = (DVec2, Ctrl, DVec2)> + '_ {
        self.loops.iter().enumerate().flat_map(move |(j, l)| {
            (0..l.len()).map(move |i| {
                let c = self.ctrl.get(j).map_or(Ctrl::Line, |c| c[i]);
                (l[i], c, l[(i + 1) % l.len()])
            })
        })
    }

    /// Whether point `p` is inside (even-odd; on an edge counts as either):
    /// the crossings of the line through p along +x beyond p, half-open in
    /// y so that a vertex on it is counted once.
    pub fn contains(&self, p: DVec2) -> bool {
        inside_by(numbered(self.edges()), p)
    }

    /// The sorted spans `(s_in, s_out)` of the line `o + s·d` inside the
    /// region: the parameters where it crosses an edge, paired in order
    /// (even-odd). An edge counts when its ends lie on either side of the
    /// line, one strictly to the left and the other not, so a line through
    /// a vertex counts it once, and a line along an edge holds it when the
    /// region lies to the line's left. A curve counts where it passes from
    /// one side to the other.
    pub fn spans(&self, o: DVec2, d: DVec2) -> Vec<(f64, f64)> {
        sorted_crossings(numbered(self.edges()), o, d)
            .chunks_exact(2)
            .map(|c| (c[0].0, c[1].0))
            .filter(|(s0, s1)| s0 < s1)
            .collect()
    }
}

/// Outlines made ready for ray queries: their edges, each with its unit
/// outward normal (the side the region is not on, found once at its
/// middle; for a curve, its outward normal there), and their exact box.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub outlines: Outlines,
    pub edges: Vec<(DVec2, DVec2)>,
    pub ctrl: Vec<Ctrl>,
    pub normals: Vec<DVec2>,
    pub lo: DVec2,
    pub hi: DVec2,
    /// Above [`SCAN_EDGES`] edges, the tree over them.
    pub tree: Option<EdgeTree>,
    /// Each edge's chord's nearest and farthest distance from the origin
    /// (of a straight edge, the edge's own: what a twist's path must reach
    /// to cross it), and the least and the greatest of them.
    pub chord_reach: Vec<(f64, f64)>,
    pub chord_range: (f64, f64),
    /// Its cells, for short pieces of lines ([`cells::Cells`]).
    pub cells: cells::CellCache,
}

/// Each edge's box: that of its ends and control points, which holds it.
fn edge_boxes(edges: &[(DVec2, DVec2)], ctrl: &[Ctrl]) -> Vec<(DVec2, DVec2)> {
    (edges.iter().zip(ctrl))
        .map(|(&(a, b), c)| c.bounds(a, b))
        .collect()
}

/// The distance from the origin to the segment a–b.
pub fn segment_distance(a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let u = if e == DVec2::ZERO {
        0.0
    } else {
        (-a.dot(e) / e.length_squared()).clamp(0.0, 1.0)
    };
    (a + e * u).length()
}

impl Region {
    pub fn new(outlines: Outlines) -> Region {
        let all: Vec<(DVec2, Ctrl, DVec2)> = outlines.edges().collect();
        let edges: Vec<(DVec2, DVec2)> = all.iter().map(|&(a, _, b)| (a, b)).collect();
        let ctrl: Vec<Ctrl> = all.iter().map(|&(_, c, _)| c).collect();
        let ((x0, x1), (y0, y1)) = (outlines.extent(DVec2::X), outlines.extent(DVec2::Y));
        let (lo, hi) = (DVec2::new(x0, y0), DVec2::new(x1, y1));
        let size = lo.abs().max(hi.abs()).max_element().max(1e-300);
        let tree = (edges.len() > SCAN_EDGES).then(|| EdgeTree::new(&edge_boxes(&edges, &ctrl)));
        let chord_reach: Vec<(f64, f64)> = edges
            .iter()
            .map(|&(a, b)| (segment_distance(a, b), a.length().max(b.length())))
            .collect();
        let chord_range = chord_reach
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &(r0, r1)| {
                (l.min(r0), h.max(r1))
            });
        let mut region = Region {
            outlines,
            edges,
            ctrl,
            normals: Vec::new(),
            lo,
            hi,
            tree,
            chord_reach,
            chord_range,
            cells: cells::CellCache::default(),
        };
        // Each edge's side by the region's own inside test, through its
        // tree where it has one (the same answers as every edge's, without
        // testing each edge against all: a 3,600-edge outline would take
        // 13 million edge tests).
        region.normals = all
            .iter()
            .map(|&(a, c, b)| {
                let curve = Curve::new(a, c, b, DVec2::ZERO);
                let n = curve.tangent(0.5).perp().normalize_or_zero() * -1.0;
                let mid = curve.at(0.5);
                // The region lies on one side of a simple edge: the normal
                // points to the other.
                if region.contains(mid + n * (1e-9 * size)) {
                    -n
                } else {
                    n
                }
            })
            .collect();
        region
    }

    /// Whether any edge is curved.
    pub fn curved(&self) -> bool {
        self.ctrl.iter().any(|c| *c != Ctrl::Line)
    }

    /// Edge `e` as a curve about origin `o`.
    pub fn curve(&self, e: usize, o: DVec2) -> Curve {
        let (a, b) = self.edges[e];
        Curve::new(a, self.ctrl[e], b, o)
    }

    /// The unit outward normal of edge `e` at its point nearest `p`.
    pub fn normal_at(&self, e: usize, p: DVec2) -> DVec2 {
        if self.ctrl[e] == Ctrl::Line {
            return self.normals[e];
        }
        let c = self.curve(e, DVec2::ZERO);
        let n = c.tangent(c.param_of(p)).perp().normalize_or_zero() * -1.0;
        // The same side as at the middle: the curve does not cross itself.
        let n_mid = c.tangent(0.5).perp() * -1.0;
        if n_mid.dot(self.normals[e]) >= 0.0 {
            n
        } else {
            -n
        }
    }

    /// The point of the outlines farthest along `dir` (exact: a curve's
    /// at its ends or where its derivative along `dir` is 0).
    pub fn farthest(&self, dir: DVec2) -> DVec2 {
        let mut best = (f64::NEG_INFINITY, DVec2::ZERO);
        let mut add = |p: DVec2| {
            if p.dot(dir) > best.0 {
                best = (p.dot(dir), p);
            }
        };
        for e in 0..self.edges.len() {
            add(self.edges[e].0);
            if self.ctrl[e] != Ctrl::Line {
                let curve = self.curve(e, DVec2::ZERO);
                curve.turning(dir, |u| add(curve.at(u)));
            }
        }
        best.1
    }

    /// Whether point `p` is inside.
    pub fn contains(&self, p: DVec2) -> bool {
        match self.tree {
            None => inside_by(self.all_edges(), p),
            Some(_) => inside_by(self.edges_near(p, DVec2::X), p),
        }
    }

    /// Where the line `o + s·d` crosses edges, sorted: `(s, edge)`, by the
    /// rule of [`Outlines::spans`].
    pub fn crossings(&self, o: DVec2, d: DVec2) -> Cuts {
        let mut cuts = Cuts::new();
        let whole = (f64::NEG_INFINITY, f64::INFINITY);
        self.crossings_between(None, o, d, whole, &mut cuts);
        cuts
    }

    /// [`Region::crossings`] with `lo ≤ s ≤ hi` only, pushed onto `cuts`,
    /// and whether those before `lo` are odd in number
    /// ([`window_crossings`]): over the edges `ids` where given, the same
    /// when every edge left out has all its points strictly on one side of
    /// the line (as a [`pencil::Pencil`]'s lists assure).
    pub fn crossings_between(
        &self,
        ids: Option<&[u32]>,
        o: DVec2,
        d: DVec2,
        (lo, hi): (f64, f64),
        cuts: &mut Cuts,
    ) -> bool {
        let start = cuts.len();
        let mut add = |s, k| cuts.push((s, k));
        let odd = match (ids, &self.tree) {
            (Some(ids), _) => {
                let edges = ids.iter().map(|&k| self.edge(k));
                window_crossings(edges, o, d, lo, hi, &mut add)
            }
            (None, None) => window_crossings(self.all_edges(), o, d, lo, hi, &mut add),
            (None, Some(_)) => window_crossings(self.edges_near(o, d), o, d, lo, hi, &mut add),
        };
        cuts[start..].sort_by(by_place);
        odd
    }

    /// Every edge in order, as [`Region::edges_meeting`] gives them: for a
    /// region without a tree, with no list of them made first.
    fn all_edges(&self) -> impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)> + '_ {
        (self.edges.iter().zip(&self.ctrl))
            .enumerate()
            .map(|(k, (&(a, b), &c))| (k as u32, a, c, b))
    }

    /// The edges that may cross the line `o + s·d`: all of them, but for
    /// boxes of the edge tree the line passes clear of.
    fn edges_near(
        &self,
        o: DVec2,
        d: DVec2,
    ) -> impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)> + '_ {
        let n = d.perp();
        self.edges_meeting(DVec3::new(n.x, n.y, -o.dot(n)))
    }

    /// The edges that may meet the line ℓ·(x, y, 1) = 0, as (index, start,
    /// how it runs, end).
    pub fn edges_meeting(
        &self,
        line: DVec3,
    ) -> impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)> + '_ {
        let mut ids: smallvec::SmallVec<[u32; 32]> = smallvec::SmallVec::new();
        match &self.tree {
            None => ids.extend(0..self.edges.len() as u32),
            // In the tree's order: every caller sorts what it finds, or
            // counts it.
            Some(t) => t.visit(line, &mut |k| ids.push(k)),
        }
        ids.into_iter().map(move |k| self.edge(k))
    }

    /// Edge `k` as (index, start, how it runs, end).
    fn edge(&self, k: u32) -> (u32, DVec2, Ctrl, DVec2) {
        let (a, b) = self.edges[k as usize];
        (k, a, self.ctrl[k as usize], b)
    }
}

/// The crossings `(s, edge)` of a line with a region's edges, sorted: on
/// the stack up to 16 (a glyph's or a gear's line meets fewer), so that a
/// prism's test allocates nothing.
pub type Cuts = smallvec::SmallVec<[(f64, u32); 16]>;

/// The most edges a region checks one by one; above, an [`EdgeTree`].
pub const SCAN_EDGES: usize = 32;

/// A bounding-box tree over a region's edges (the box of a curve is that
/// of its control points, which hold it) or any boxes (a shadow's
/// triangles), so that a line is tested against
/// about log(edges) boxes and the edges near it. A box is passed over only
/// when all four corners lie strictly on one side of the line by more than
/// the rounding of the side's value (1e-14 of the terms' magnitude, far
/// above the few ulps either is computed to), so no edge that would have
/// counted is left out: the answers are the same as testing every edge.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeTree {
    nodes: Vec<TreeNode>,
    order: Vec<u32>,
}

#[derive(Clone, Debug, PartialEq)]
struct TreeNode {
    lo: DVec2,
    hi: DVec2,
    /// A leaf: `count` edges of `order` from `first`; else children at
    /// `first` and `first + 1`.
    first: u32,
    count: u32,
}

const TREE_LEAF: usize = 8;

impl EdgeTree {
    pub fn new(boxes: &[(DVec2, DVec2)]) -> EdgeTree {
        let mut t = EdgeTree {
            nodes: Vec::new(),
            order: (0..boxes.len() as u32).collect(),
        };
        t.nodes.push(TreeNode {
            lo: DVec2::ZERO,
            hi: DVec2::ZERO,
            first: 0,
            count: 0,
        });
        t.build(0, 0, boxes.len(), boxes);
        t
    }

    fn build(&mut self, node: usize, start: usize, end: usize, boxes: &[(DVec2, DVec2)]) {
        let ids = &mut self.order[start..end];
        let (lo, hi) = ids.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &k| (lo.min(boxes[k as usize].0), hi.max(boxes[k as usize].1)),
        );
        self.nodes[node].lo = lo;
        self.nodes[node].hi = hi;
        if end - start <= TREE_LEAF {
            self.nodes[node].first = start as u32;
            self.nodes[node].count = (end - start) as u32;
            return;
        }
        // Split at the median of the box centres along the longer side.
        let axis = if hi.x - lo.x >= hi.y - lo.y { 0 } else { 1 };
        let key = |k: &u32| {
            let (a, b) = boxes[*k as usize];
            (a + b)[axis]
        };
        let mid = (end - start) / 2;
        ids.select_nth_unstable_by(mid, |x, y| key(x).total_cmp(&key(y)).then(x.cmp(y)));
        let first = self.nodes.len();
        for _ in 0..2 {
            self.nodes.push(TreeNode {
                lo: DVec2::ZERO,
                hi: DVec2::ZERO,
                first: 0,
                count: 0,
            });
        }
        self.nodes[node].first = first as u32;
        self.build(first, start, start + mid, boxes);
        self.build(first + 1, start + mid, end, boxes);
    }

    /// Calls `f` with every edge in a box the line ℓ·(x, y, 1) = 0 may meet.
    pub fn visit(&self, line: DVec3, f: &mut impl FnMut(u32)) {
        self.visit_boxes(
            |lo, hi| {
                let (mut pos, mut neg) = (true, true);
                for c in [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)] {
                    let v = line.x * c.x + line.y * c.y + line.z;
                    let tol = 1e-14 * ((line.x * c.x).abs() + (line.y * c.y).abs() + line.z.abs());
                    pos &= v > tol;
                    neg &= v < -tol;
                }
                !(pos || neg)
            },
            f,
        )
    }

    /// Calls `f` with every edge in the boxes `[lo, hi]` for which `meets`
    /// holds, and all of whose enclosing boxes it holds for.
    pub fn visit_boxes(&self, meets: impl Fn(DVec2, DVec2) -> bool, f: &mut impl FnMut(u32)) {
        let mut stack: smallvec::SmallVec<[u32; 32]> = smallvec::SmallVec::new();
        stack.push(0);
        while let Some(i) = stack.pop() {
            let nd = &self.nodes[i as usize];
            if !meets(nd.lo, nd.hi) {
                continue;
            }
            if nd.count > 0 {
                let s = nd.first as usize;
                self.order[s..s + nd.count as usize]
                    .iter()
                    .for_each(|&k| f(k));
            } else {
                stack.push(nd.first);
                stack.push(nd.first + 1);
            }
        }
    }
}

/// Whether `p` is inside `edges` (even-odd): the crossings of the line from
/// p along +x beyond p, by the rule of [`crossings`] (half-open in y).
fn inside_by(edges: impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)>, p: DVec2) -> bool {
    let mut inside = false;
    crossings(edges, p, DVec2::X, |s, _| {
        if s > 0.0 {
            inside = !inside;
        }
    });
    inside
}

/// Edges numbered in order.
fn numbered<'a>(
    edges: impl Iterator<Item = (DVec2, Ctrl, DVec2)> + 'a,
) -> impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)> + 'a {
    edges.enumerate().map(|(k, (a, c, b))| (k as u32, a, c, b))
}

/// [`crossings`], sorted by s (then edge).
fn sorted_crossings(
    edges: impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)>,
    o: DVec2,
    d: DVec2,
) -> Cuts {
    let mut cuts = Cuts::new();
    crossings(edges, o, d, |s, k| cuts.push((s, k)));
    cuts.sort_by(by_place);
    cuts
}

/// The order of crossings: by s, then edge.
fn by_place(x: &(f64, u32), y: &(f64, u32)) -> std::cmp::Ordering {
    x.0.total_cmp(&y.0).then(x.1.cmp(&y.1))
}

/// Each place `(s, edge index)` where the line `o + s·d` crosses `edges`.
/// A point is on the line's left when (p − o)·n > 0, n = d⊥. A straight
/// edge counts when one end lies strictly left and the other not (see
/// [`Outlines::spans`]); a curve counts at each place its side changes:
/// the sides of its ends (computed from the points themselves, as its
/// neighbours do) and of the stretches between the simple roots of
/// n·(B(u) − o) in (0, 1), a change between an end and the next stretch
/// placed at that end.
pub fn crossings(
    edges: impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)>,
    o: DVec2,
    d: DVec2,
    cut: impl FnMut(f64, u32),
) {
    window_crossings(edges, o, d, f64::NEG_INFINITY, f64::INFINITY, cut);
}

/// [`crossings`] with `lo ≤ s ≤ hi` only, the same places by the same
/// arithmetic; of those with s < lo only whether their number is odd (the
/// result), and those with s > hi left out. A curve whose points (ends
/// and control points, whose hull holds it) all lie before `lo`, or all
/// beyond `hi`, by more than the rounding of a crossing's parameter
/// (1e-12 of the points' size, against a few ulps), has its roots left
/// unfound: before `lo` its crossings are as many as its ends' sides say
/// (odd when they differ), beyond `hi` they do not count.
pub fn window_crossings(
    edges: impl Iterator<Item = (u32, DVec2, Ctrl, DVec2)>,
    o: DVec2,
    d: DVec2,
    lo: f64,
    hi: f64,
    mut cut: impl FnMut(f64, u32),
) -> bool {
    // A direction so short (or long) that d·d leaves the normal numbers is
    // scaled by a power of two to about unit length (exactly), and the
    // parameters scaled back (to ±∞ where they overflow: monotone, so a
    // bound scaled back still bounds).
    let (d, back) = unit_scale(d);
    let scaled = |s: f64| s / back.0 / back.1;
    let mut odd_before = false;
    let mut at = |s: f64, k: u32| {
        let s = scaled(s);
        if s < lo {
            odd_before = !odd_before;
        } else if s <= hi || s.is_nan() {
            cut(s, k);
        }
    };
    let n = d.perp();
    let dd = d.length_squared();
    let windowed = lo > f64::NEG_INFINITY || hi < f64::INFINITY;
    let mut odd_unplaced = false;
    for (k, a, c, b) in edges {
        let (sa, sb) = ((a - o).dot(n), (b - o).dot(n));
        if c == Ctrl::Line || crate::mutant::active("curves_as_chords") {
            if (sa > 0.0) == (sb > 0.0) {
                continue;
            }
            // The crossing point of the edge, then its parameter on the line.
            let p = a + (b - a) * (sa / (sa - sb));
            at((p - o).dot(d) / dd, k);
            continue;
        }
        // A curve lies in the hull of its control points: all on one side,
        // it never changes side.
        let mut hull = c.points().map(|p| (p - o).dot(n) > 0.0);
        let left = sa > 0.0;
        if (sb > 0.0) == left && hull.all(|l| l == left) {
            continue;
        }
        if windowed {
            // The points' parameters along the line, widened by the margin.
            let (mut s_lo, mut s_hi, mut size) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
            for q in [a, b].into_iter().chain(c.points()) {
                let s = (q - o).dot(d) / dd;
                (s_lo, s_hi) = (s_lo.min(s), s_hi.max(s));
                size = size.max((q - o).abs().max_element());
            }
            let margin = 1e-12 * size * (d.x.abs() + d.y.abs()) / dd;
            if scaled(s_hi + margin) < lo {
                // (Kept apart from the crossings placed, joined at the end.)
                odd_unplaced ^= (sb > 0.0) != left;
                continue;
            }
            if scaled(s_lo - margin) > hi {
                continue;
            }
        }
        let curve = Curve::new(a, c, b, o);
        side_changes(sa, sb, &curve.along(n, 0.0), curve.degree, |u| {
            let p = match u {
                0.0 => a - o,
                1.0 => b - o,
                _ => curve.at(u),
            };
            at(p.dot(d) / dd, k);
        });
    }
    odd_before != odd_unplaced
}

/// `d` scaled by a power of two to about unit length where its square is
/// far from 1, and the two powers of two it was divided by (one alone may
/// not reach 2¹⁰⁷⁴): a parameter along it divided by both is `d`'s.
fn unit_scale(d: DVec2) -> (DVec2, (f64, f64)) {
    let m = d.x.abs().max(d.y.abs());
    if (1e-150..=1e150).contains(&m) || m == 0.0 || !m.is_finite() {
        return (d, (1.0, 1.0));
    }
    let k = m.log2().floor() as i32;
    let (k1, k2) = (k / 2, k - k / 2);
    let (p1, p2) = (2f64.powi(k1), 2f64.powi(k2));
    (d / p1 / p2, (p1, p2))
}

/// The parameters u ∈ [0, 1] where a curve passes from one side of a line
/// to the other, given the sides' measure at its ends (`sa`, `sb`,
/// computed from the end points themselves, as the neighbouring edges do)
/// and along it (`f`, of the given degree): the sides of the ends and of
/// the stretches between the simple roots of f in (0, 1), a change between
/// an end and the next stretch placed at that end. "Left" is f > 0.
pub fn side_changes(sa: f64, sb: f64, f: &Poly, degree: usize, mut at_u: impl FnMut(f64)) {
    let mut roots = [0.0; poly::MAX_DEGREE];
    let nr = roots_in(f, degree, 0.0, 1.0, &mut roots);
    let mut left = sa > 0.0;
    let mut u0 = 0.0;
    for &u in roots[..nr].iter().chain(std::iter::once(&1.0)) {
        // The stretch (u0, u): its side at its middle.
        let l = poly::eval(f, degree, 0.5 * (u0 + u)) > 0.0;
        if l != left {
            at_u(u0);
            left = l;
        }
        u0 = u;
    }
    if (sb > 0.0) != left {
        at_u(1.0);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use glam::DVec3;

    /// Uniform numbers in [0, 1) from a linear congruential generator.
    pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn square_with_hole() -> Outlines {
        let sq = |c: f64, h: f64| {
            vec![
                DVec2::new(c - h, c - h),
                DVec2::new(c + h, c - h),
                DVec2::new(c + h, c + h),
                DVec2::new(c - h, c + h),
            ]
        };
        Outlines::polygons(vec![sq(0.0, 2.0), sq(0.0, 1.0)])
    }

    /// Each edge's normal points out of the region, for outlines of more
    /// edges than are checked one by one (so found through the edge
    /// tree): a star of 240 points with a hole of 60, checked at every
    /// edge's middle against the outlines' own test over every edge.
    #[test]
    fn normals_point_out_of_a_region_with_an_edge_tree() {
        let mut rnd = uniform(7);
        let ring = |n: usize, r0: f64, r1: f64, rnd: &mut dyn FnMut() -> f64| -> Vec<DVec2> {
            (0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * (i as f64 + 0.3 * rnd()) / n as f64;
                    let r = if i % 2 == 0 { r0 } else { r1 } * (1.0 + 0.05 * rnd());
                    DVec2::new(a.cos(), a.sin()) * r
                })
                .collect()
        };
        let outer = ring(240, 10.0, 7.0, &mut rnd);
        let hole = ring(60, 3.0, 2.0, &mut rnd);
        let o = Outlines::polygons(vec![outer, hole]);
        let r = Region::new(o.clone());
        assert!(r.tree.is_some());
        for (k, &(a, b)) in r.edges.iter().enumerate() {
            let (mid, n) = ((a + b) * 0.5, r.normals[k]);
            let eps = 1e-6 * (b - a).length();
            assert!(
                !o.contains(mid + n * eps),
                "edge {k}: outside along its normal"
            );
            assert!(o.contains(mid - n * eps), "edge {k}: inside against it");
        }
    }

    #[test]
    fn openscad_keeps_the_planes_rows_of_a_transform() {
        // A turn of 90° about x sends y to z: in the plane, y collapses.
        let about_x = DAffine3::from_rotation_x(std::f64::consts::FRAC_PI_2);
        let flat = from_space(&about_x);
        assert!(flat.is_none() || flat.unwrap().matrix2.determinant().abs() < 1e-15);
        // A lift along z and a turn about z: the lift goes, the turn stays.
        let m =
            DAffine3::from_translation(DVec3::new(3.0, -1.0, 5.0)) * DAffine3::from_rotation_z(0.5);
        let p = from_space(&m).unwrap();
        let q = p.transform_point2(DVec2::new(1.0, 0.0));
        let want = DVec2::new(3.0 + 0.5f64.cos(), -1.0 + 0.5f64.sin());
        assert!((q - want).length() < 1e-15, "{q:?}");
        assert!(from_space(&DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0))).is_none());
    }

    #[test]
    fn spans_agree_with_the_inside_test() {
        let r = square_with_hole();
        // Along y = 0.5 the line crosses the outer square and the hole.
        let s = r.spans(DVec2::new(-5.0, 0.5), DVec2::new(2.0, 0.0));
        assert_eq!(s, vec![(1.5, 2.0), (3.0, 3.5)]);
        // Many lines, checked on a grid of points between and around cuts.
        let mut next = uniform(12345);
        for _ in 0..500 {
            let o = DVec2::new(next() * 8.0 - 4.0, next() * 8.0 - 4.0);
            let a = next() * std::f64::consts::TAU;
            let d = DVec2::new(a.cos(), a.sin()) * (0.5 + next());
            let spans = r.spans(o, d);
            for k in 0..400 {
                let s = -10.0 + k as f64 * 0.05 + 0.0123;
                let near = spans
                    .iter()
                    .any(|&(a, b)| (a - s).abs() < 1e-9 || (b - s).abs() < 1e-9);
                if near {
                    continue;
                }
                let inside = spans.iter().any(|&(a, b)| a < s && s < b);
                assert_eq!(inside, r.contains(o + d * s), "s = {s} on {o:?} + s {d:?}");
            }
        }
    }

    /// A 240-point wavy ring with a curved hole (a region with an edge
    /// tree), and its outer points.
    pub(crate) fn wavy_ring() -> (Vec<DVec2>, Region) {
        let outer: Vec<DVec2> = (0..240)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 240.0;
                DVec2::new(a.cos(), a.sin()) * (3.0 + 0.4 * (7.0 * a).sin())
            })
            .collect();
        let hole = vec![DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)];
        let mut ctrl = vec![vec![Ctrl::Line; 240]];
        ctrl[0][17] = Ctrl::Quad(DVec2::new(3.5, 1.5));
        ctrl.push(vec![
            Ctrl::Quad(DVec2::new(0.0, -1.5)),
            Ctrl::Cubic(DVec2::new(0.5, 1.5), DVec2::new(-0.5, 1.5)),
        ]);
        let r = Region::new(Outlines {
            loops: vec![outer.clone(), hole],
            ctrl,
        });
        assert!(r.tree.is_some());
        (outer, r)
    }

    /// A flower of 48 curved petals (quadratic tips) with a hole of six
    /// cubic bulges: 54 edges, so an edge tree.
    pub(crate) fn flower() -> Region {
        let petals: Vec<DVec2> = (0..48)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 48.0;
                DVec2::new(a.cos(), a.sin()) * 40.0
            })
            .collect();
        let tips: Vec<Ctrl> = (0..48)
            .map(|i| {
                let a = (i as f64 + 0.5) * std::f64::consts::TAU / 48.0;
                Ctrl::Quad(DVec2::new(a.cos(), a.sin()) * (46.0 + 8.0 * (i % 3) as f64))
            })
            .collect();
        let hole: Vec<DVec2> = (0..6)
            .map(|i| {
                let a = -(i as f64) * std::f64::consts::TAU / 6.0;
                DVec2::new(a.cos(), a.sin()) * 10.0
            })
            .collect();
        let bulges: Vec<Ctrl> = (0..6)
            .map(|i| {
                let a = -(i as f64 + 0.3) * std::f64::consts::TAU / 6.0;
                let b = -(i as f64 + 0.7) * std::f64::consts::TAU / 6.0;
                Ctrl::Cubic(
                    DVec2::new(a.cos(), a.sin()) * 4.0,
                    DVec2::new(b.cos(), b.sin()) * 16.0,
                )
            })
            .collect();
        Region::new(Outlines {
            loops: vec![petals, hole],
            ctrl: vec![tips, bulges],
        })
    }

    /// A line's crossings found only in a window of its parameter are
    /// those of the whole line in the window, to the bit, and the count
    /// before it has the whole line's parity: on a flower of 48 curved
    /// petals with a hole of cubic curves (an edge tree) and on the
    /// wavy ring, for lines at random and through the points that define
    /// the edges, windows at random and ending exactly on a crossing.
    #[test]
    fn crossings_in_a_window_are_the_whole_lines_there() {
        let mut next = uniform(5);
        let flower = flower();
        assert!(flower.tree.is_some() && flower.curved());
        let (_, ring) = wavy_ring();
        let (mut windows, mut odd_seen) = (0, 0);
        for r in [&flower, &ring] {
            let pts: Vec<DVec2> = (r.edges.iter().zip(&r.ctrl))
                .flat_map(|(&(a, _), c)| std::iter::once(a).chain(c.points()))
                .collect();
            let size = r.hi.max_element() - r.lo.min_element();
            for i in 0..3000 {
                let o =
                    r.lo + (r.hi - r.lo) * DVec2::new(next(), next()) * 1.6 - (r.hi - r.lo) * 0.3;
                let through = if i % 2 == 0 {
                    pts[i % pts.len()]
                } else {
                    r.lo + (r.hi - r.lo) * DVec2::new(next(), next())
                };
                let d = (through - o) * (0.01 + 3.0 * next());
                if d == DVec2::ZERO {
                    continue;
                }
                let all = r.crossings(o, d);
                let reach = 2.0 * size / d.length();
                let mut at = || (2.0 * next() - 1.0) * reach;
                let (mut lo, mut hi) = (at(), at());
                if i % 5 == 0 && !all.is_empty() {
                    lo = all[(i / 5) % all.len()].0;
                }
                if i % 7 == 0 && !all.is_empty() {
                    hi = all[(i / 7) % all.len()].0;
                }
                let (lo, hi) = (lo.min(hi), lo.max(hi));
                let mut cuts = Cuts::new();
                let odd = r.crossings_between(None, o, d, (lo, hi), &mut cuts);
                let want: Vec<(f64, u32)> = all
                    .iter()
                    .copied()
                    .filter(|c| lo <= c.0 && c.0 <= hi)
                    .collect();
                let before = all.iter().filter(|c| c.0 < lo).count();
                assert_eq!(
                    cuts.to_vec(),
                    want,
                    "line {i}: o {o:?} d {d:?} in [{lo}, {hi}]"
                );
                assert_eq!(
                    odd,
                    before % 2 == 1,
                    "line {i}: o {o:?} d {d:?} in [{lo}, {hi}]"
                );
                windows += 1;
                odd_seen += odd as usize;
            }
        }
        assert!(
            windows > 5000 && odd_seen > 500,
            "{windows} windows, {odd_seen} odd"
        );
    }

    #[test]
    fn the_edge_tree_finds_every_crossing_testing_all_edges_finds() {
        // The wavy ring: lines at random, lines through vertices and
        // along edges, far away and near.
        let mut next = uniform(99);
        let (outer, r) = wavy_ring();
        let brute = |o: DVec2, d: DVec2| {
            let all = r
                .edges
                .iter()
                .zip(&r.ctrl)
                .enumerate()
                .map(|(k, (&(a, b), &c))| (k as u32, a, c, b));
            sorted_crossings(all, o, d)
        };
        for i in 0..3000 {
            let far = if i % 3 == 0 { 1e6 } else { 1.0 };
            let mut o = DVec2::new(next() * 10.0 - 5.0, next() * 10.0 - 5.0) * far;
            let a = next() * std::f64::consts::TAU;
            let mut d = DVec2::new(a.cos(), a.sin());
            if i % 5 == 1 {
                // Through a vertex.
                o = outer[i % 240];
            } else if i % 5 == 2 {
                // Along an edge.
                o = outer[i % 240];
                d = outer[(i + 1) % 240] - o;
            }
            assert_eq!(r.crossings(o, d), brute(o, d), "o {o:?} d {d:?}");
            let p = DVec2::new(next() * 8.0 - 4.0, next() * 8.0 - 4.0);
            assert_eq!(r.contains(p), r.outlines.contains(p), "{p:?}");
        }
    }

    #[test]
    fn a_line_through_a_vertex_or_along_an_edge_counts_it_right() {
        let r = square_with_hole();
        // Through the outer corners (-2, -2) and (2, 2): it enters at the
        // first, crosses the hole's corners (-1, -1) and (1, 1), leaves at
        // the last.
        let s = r.spans(DVec2::new(-3.0, -3.0), DVec2::new(1.0, 1.0));
        assert_eq!(s, vec![(1.0, 2.0), (4.0, 5.0)]);
        // Along an edge, the half-open rule decides, as a rasteriser's
        // top-left rule does: the side whose inside lies to the line's
        // left holds the edge (the bottom edge, going +x), the other not
        // (the top edge), so two regions sharing an edge never both do.
        let s = r.spans(DVec2::new(-5.0, -2.0), DVec2::new(1.0, 0.0));
        assert_eq!(s, vec![(3.0, 7.0)]);
        let s = r.spans(DVec2::new(-5.0, 2.0), DVec2::new(1.0, 0.0));
        assert_eq!(s, vec![]);
    }
}
