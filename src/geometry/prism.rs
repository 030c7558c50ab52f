//! A prism: a plane region swept from z = 0 to z = 1 — OpenSCAD's
//! `linear_extrude` without twist, in object space (the height is the
//! transform's) — its section at height z the region scaled by
//! s(z) = 1 + (top − 1)·z about the axis (`top` = 1: no taper). It carries
//! its region by reference, shared by every leaf made from it.
//!
//! Without taper a line meets it where its projection on the plane is
//! inside the region (the region's own line spans, [`Region::crossings`],
//! paired even-odd) and where it is inside the slab. A uniform taper is the
//! projective map (x, y, z) ↦ (x, y, z)/s(z), under which the prism is
//! straight and the line is still a line: in homogeneous coordinates the
//! line's image through the plane is ℓ = (o_xy, s(o)) × (d_xy, s′·d_z), each
//! edge is crossed where its ends lie on either side of ℓ, and the side over
//! edge (a, b) is the plane cross(b − a, p_xy) = s(z)·cross(b − a, a), met
//! at one t. Parts: 0 the bottom cap, 1 the top cap, 2 + k the side over
//! edge k.

use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part, NO_PART};
use crate::plane::pencil::Pencil;
use crate::plane::{side_changes, Ctrl, Curve, Cuts, Region};
use glam::{DVec2, DVec3};
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

#[derive(Clone, Debug, PartialEq)]
pub struct Prism {
    pub region: Arc<Region>,
    /// The scale of the top section (≥ 0; 1 for a straight prism).
    pub top: f64,
    /// From z = −1/2 to 1/2 rather than 0 to 1 (OpenSCAD's `center`): kept
    /// here, not in the transform, so that a small part far from the origin
    /// keeps its own precision (the half height is not rounded into a
    /// translation of the world's size).
    pub centered: bool,
    /// The line families of the view being rendered (its eye's, its
    /// directional lights'), each with the edges its lines may cross: see
    /// [`Csg::viewed`](crate::csg::Csg::viewed). Empty outside a render.
    pub views: Vec<Pencil>,
}

impl Prism {
    /// The region swept up by the taper `top`, from z = 0 (or −1/2 when
    /// `centered`), with no view's line families yet.
    pub fn new(region: Arc<Region>, top: f64, centered: bool) -> Prism {
        Prism {
            region,
            top,
            centered,
            views: Vec::new(),
        }
    }

    /// The bottom's height.
    pub fn z_lo(&self) -> f64 {
        super::cone::bottom(self.centered)
    }

    /// The section's scale s(z) at height z (from the bottom).
    fn scale_at(&self, z: f64) -> f64 {
        1.0 + (self.top - 1.0) * z
    }

    /// The spans of a tapered prism inside the slab (t0, p0)–(t1, p1).
    fn tapered(&self, o: DVec3, d: DVec3, slab: RawSpan, emit: &mut impl FnMut(RawSpan)) {
        let (z0, _, z1, _) = slab;
        let k = self.top - 1.0;
        let (w0, wd) = (1.0 + k * o.z, k * d.z);
        let (o2, d2) = (o.truncate(), d.truncate());
        let h0 = DVec3::new(o2.x, o2.y, w0);
        let hd = DVec3::new(d2.x, d2.y, wd);
        let line = h0.cross(hd);
        if line == DVec3::ZERO {
            // The line's image is one point: inside everywhere or nowhere.
            let tm = if z0.is_finite() && z1.is_finite() {
                0.5 * (z0 + z1)
            } else {
                0.0
            };
            let w = w0 + tm * wd;
            if w > 0.0 && self.region.contains((o2 + tm * d2) / w) {
                emit(slab);
            }
            return;
        }
        let mut cuts: smallvec::SmallVec<[(f64, Part); 16]> = smallvec::SmallVec::new();
        for (e, a, ctrl, b) in self.region.edges_meeting(line) {
            let (sa, sb) = (line.dot(a.extend(1.0)), line.dot(b.extend(1.0)));
            if ctrl != Ctrl::Line {
                // The curve's points on the image ℓ·(q, 1) = 0, each met
                // where o_xy + t·d_xy = w(t)·q: t by least squares along
                // v = d_xy − w_d·q (the two equations agree up to rounding).
                let curve = Curve::new(a, ctrl, b, DVec2::ZERO);
                let f = curve.along(line.truncate(), -line.z);
                side_changes(sa, sb, &f, curve.degree, |u| {
                    let q = match u {
                        0.0 => a,
                        1.0 => b,
                        _ => curve.at(u),
                    };
                    let v = d2 - wd * q;
                    let t = (w0 * q - o2).dot(v) / v.length_squared();
                    if v != DVec2::ZERO && w0 + t * wd > 0.0 {
                        cuts.push((t, SIDE + e as Part));
                    }
                });
                continue;
            }
            if (sa > 0.0) == (sb > 0.0) {
                continue;
            }
            let ed = b - a;
            let c = ed.perp_dot(a);
            let f0 = ed.perp_dot(o2) - w0 * c;
            let f1 = ed.perp_dot(d2) - wd * c;
            if f1 == 0.0 {
                continue;
            }
            let t = -f0 / f1;
            if w0 + t * wd > 0.0 {
                cuts.push((t, SIDE + e as Part));
            }
        }
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        // Outside at the image's far end (the points where s → 0⁺): an odd
        // crossing pairs with the vanishing point, at the other end.
        if cuts.len() % 2 == 1 {
            if wd >= 0.0 {
                cuts.push((f64::INFINITY, NO_PART));
            } else {
                cuts.insert(0, (f64::NEG_INFINITY, NO_PART));
            }
        }
        for pair in cuts.chunks_exact(2) {
            clip(slab, (pair[0].0, pair[0].1, pair[1].0, pair[1].1), emit);
        }
    }
}

/// Where the line o + t·d is inside the slab 0 ≤ z ≤ 1 (a prism's, in
/// object space): entering and leaving by the bottom (part 0) or top (1)
/// cap, or unbounded along a horizontal line strictly inside (its open
/// ends ±∞ with [`NO_PART`], as a span's are); `None` when it misses.
#[inline]
pub(super) fn slab(o: DVec3, d: DVec3) -> Option<RawSpan> {
    if d.z == 0.0 {
        if o.z <= 0.0 || o.z >= 1.0 {
            return None;
        }
        return Some((f64::NEG_INFINITY, NO_PART, f64::INFINITY, NO_PART));
    }
    let (tb, tt) = (-o.z / d.z, (1.0 - o.z) / d.z);
    Some(if tb < tt {
        (tb, BOTTOM, tt, TOP)
    } else {
        (tt, TOP, tb, BOTTOM)
    })
}

/// The part of span `s` inside the slab, emitted unless it is empty.
#[inline]
pub(super) fn clip(slab: RawSpan, s: RawSpan, emit: &mut impl FnMut(RawSpan)) {
    let ((z0, zp0, z1, zp1), (s0, e0, s1, e1)) = (slab, s);
    let (t0, p0) = if s0 > z0 { (s0, e0) } else { (z0, zp0) };
    let (t1, p1) = if s1 < z1 { (s1, e1) } else { (z1, zp1) };
    if t0 < t1 {
        emit((t0, p0, t1, p1));
    }
}

impl Solid for Prism {
    const NAME: &'static str = "linear_extrude";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        // Heights from the bottom.
        let (o, d) = (q.o - DVec3::Z * self.z_lo(), q.d);
        // The slab 0 ≤ z ≤ 1.
        let Some((z0, zp0, z1, zp1)) = slab(o, d) else {
            return;
        };
        if self.top != 1.0 {
            return self.tapered(o, d, (z0, zp0, z1, zp1), emit);
        }
        let (o2, d2) = (o.truncate(), d.truncate());
        if d2 == glam::DVec2::ZERO {
            // Along z: inside the slab wherever the point is in the region.
            if self.region.contains(o2) {
                emit((z0, zp0, z1, zp1));
            }
            return;
        }
        let slab = (z0, zp0, z1, zp1);
        // Only the crossings in the slab and the range asked are found
        // (the spans need only be right there): one before them pairs with
        // the first found, its span entering by the cap (any place before
        // the range would), and the same with one beyond them (the
        // crossings are even in number, each outline being closed). None
        // are sought where the slab and the range do not meet.
        let window = (z0.max(q.tmin), z1.min(q.tmax));
        if window.0 > window.1 {
            return;
        }
        // A short piece: its cells' edges; else, a line of a view's family:
        // only the edges its piece lists.
        let mut cuts = Cuts::new();
        let region = &*self.region;
        let short = region.cells.get(region);
        let odd_before =
            match short.and_then(|c| c.crossings_between(region, o2, d2, window, &mut cuts)) {
                Some(inside) => inside,
                None => {
                    let ids = self.views.iter().find_map(|p| p.edges(o2, d2));
                    region.crossings_between(ids, o2, d2, window, &mut cuts)
                }
            };
        // Paired in order, after the one before if there is one.
        let mut open = odd_before.then_some((f64::NEG_INFINITY, 0));
        for &(s1, e1) in &cuts {
            match open.take() {
                Some((s0, e0)) => clip(slab, (s0, SIDE + e0, s1, SIDE + e1), emit),
                None => open = Some((s1, e1)),
            }
        }
        if let Some((s0, e0)) = open {
            clip(slab, (s0, SIDE + e0, f64::INFINITY, SIDE), emit);
        }
    }

    /// A side's normal is its edge's outward normal n in the plane, tilted
    /// by the taper: the side over the point q of the edge is the plane
    /// n·p_xy = s(z)·n·q, with gradient (n, (1 − top)·n·q).
    fn normal(&self, p: DVec3, part: Part) -> DVec3 {
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            k => {
                let e = (k - SIDE) as usize;
                let r = &self.region;
                if r.ctrl[e] == Ctrl::Line {
                    let n = r.normals[e];
                    return n.extend((1.0 - self.top) * n.dot(r.edges[e].0));
                }
                let w = self.scale_at(p.z - self.z_lo());
                let q = if w > 0.0 {
                    p.truncate() / w
                } else {
                    r.edges[e].0
                };
                let c = r.curve(e, DVec2::ZERO);
                let q = c.at(c.param_of(q));
                let n = r.normal_at(e, q);
                n.extend((1.0 - self.top) * n.dot(q))
            }
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        let p = p - DVec3::Z * self.z_lo();
        let w = self.scale_at(p.z);
        (0.0..=1.0).contains(&p.z)
            && (w > 0.0 && self.region.contains(p.truncate() / w)
                || w == 0.0 && p.truncate() == glam::DVec2::ZERO)
    }

    fn object_bounds(&self) -> Aabb {
        let r = &self.region;
        let (lo, hi) = (r.lo.min(r.lo * self.top), r.hi.max(r.hi * self.top));
        let z = self.z_lo();
        Aabb::new(lo.extend(z), hi.extend(z + 1.0))
    }

    /// The farthest point of either cap: the region's farthest point along
    /// d_xy, at scale 1 and at `top`.
    fn support(&self, d: DVec3) -> Option<DVec3> {
        let q = self.region.farthest(d.truncate());
        let z = self.z_lo();
        [q.extend(z), (q * self.top).extend(z + 1.0)]
            .into_iter()
            .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![
            ("edges", Param::Num(self.region.edges.len() as f64)),
            ("scale", Param::Num(self.top)),
            ("center", Param::Bool(self.centered)),
        ]
    }

    /// POV-Ray's prism sweeps along y: a straight one from 0 to 1, a
    /// tapered one as a `conic_sweep` (its section at height y is the
    /// region scaled by y) from `top` to 1, mapped so that it sweeps along
    /// z with s(z) = y, i.e. z = (1 − y)/(1 − top).
    fn pov(&self) -> String {
        let mut pts = Vec::new();
        let pt = |p: DVec2| format!("<{:?}, {:?}>", p.x, p.y);
        let curved = self.region.curved();
        for (j, l) in self.region.outlines.loops.iter().enumerate() {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                if !curved {
                    pts.push(pt(a));
                    continue;
                }
                // Every edge a cubic Bézier segment of four points.
                let (c1, c2) = self.region.outlines.ctrl[j][i].cubic(a, b);
                pts.extend([pt(a), pt(c1), pt(c2), pt(b)]);
            }
            if !curved {
                pts.push(pt(l[0]));
            }
        }
        let spline = if curved {
            "bezier_spline"
        } else {
            "linear_spline"
        };
        let (sweep, h0, h1, m) = if self.top == 1.0 {
            (
                "linear_sweep",
                0.0,
                1.0,
                format!("<1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, {:?}>", self.z_lo()),
            )
        } else {
            let k = 1.0 / (1.0 - self.top);
            (
                "conic_sweep",
                self.top.min(1.0),
                self.top.max(1.0),
                format!(
                    "<1, 0, 0, 0, 0, {:?}, 0, 1, 0, 0, 0, {:?}>",
                    -k,
                    k + self.z_lo()
                ),
            )
        };
        format!(
            "prism {{ {sweep} {spline} {h0:?}, {h1:?}, {}, {} matrix {m}",
            pts.len(),
            pts.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Need;
    use crate::plane::Outlines;
    use crate::stats::Stats;

    /// A line along the slab, inside it, asked over a range that begins
    /// inside the region: its span begins before the range, and its open
    /// end is −∞ with no part, as a span's unbounded ends are (not a
    /// cap's part, which would read as a surface at infinity). Asked over
    /// the whole line, it has the region's two sides.
    #[test]
    fn a_horizontal_line_asked_from_inside_has_an_open_start() {
        let square = Outlines::polygons(vec![vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ]]);
        let prism = Prism::new(Arc::new(Region::new(square)), 1.0, false);
        let spans = |tmin: f64, tmax: f64| {
            let mut st = Stats::default();
            let mut q = Probe {
                o: DVec3::new(-5.0, 0.5, 0.5),
                d: DVec3::X,
                tmin,
                tmax,
                st: &mut st,
                need: Need::Spans,
            };
            let mut out = Vec::new();
            prism.spans(&mut q, &mut |s| out.push(s));
            out
        };
        assert_eq!(spans(f64::NEG_INFINITY, f64::INFINITY).len(), 1);
        let whole = spans(f64::NEG_INFINITY, f64::INFINITY)[0];
        assert_eq!((whole.0, whole.2), (5.0, 6.0));
        assert!(whole.1 >= SIDE && whole.3 >= SIDE, "{whole:?}");
        let from_inside = spans(5.5, 10.0);
        assert_eq!(from_inside.len(), 1, "{from_inside:?}");
        let s = from_inside[0];
        assert_eq!((s.0, s.1), (f64::NEG_INFINITY, NO_PART), "{s:?}");
        assert_eq!(s.2, 6.0);
    }
}
