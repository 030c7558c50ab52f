//! Convex hulls in the plane: of points (Andrew's monotone chain), of
//! discs and of [`Site`]s (points, discs and arcs), and whether a loop is
//! convex.

use super::figure::Figure;
use super::sites::{sites, Site};
use super::Outlines;
use crate::math::boolean::Op;
use glam::DVec2;

/// The most points, discs or sites whose hull is found (a 3-D hull by
/// every triple: n⁴ tests).
pub const MAX_HULL_POINTS: usize = 48;

/// The indices of the corners of the convex hull of `q`, counter-clockwise
/// (Andrew's monotone chain from the lowest x, then y); points on an edge
/// (within `tol` of its length) and repeats are left out.
pub fn hull_indices_2d(q: &[DVec2], tol: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..q.len()).collect();
    order.sort_by(|&a, &b| q[a].x.total_cmp(&q[b].x).then(q[a].y.total_cmp(&q[b].y)));
    order.dedup_by(|a, b| q[*a] == q[*b]);
    let turn = |a: usize, b: usize, c: usize| {
        let (e, f) = (q[b] - q[a], q[c] - q[a]);
        e.perp_dot(f) > tol * e.length().max(f.length())
    };
    let mut hull: Vec<usize> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &usize>> = if pass == 0 {
            Box::new(order.iter())
        } else {
            Box::new(order.iter().rev())
        };
        for &i in iter {
            while hull.len() >= start + 2 && !turn(hull[hull.len() - 2], hull[hull.len() - 1], i) {
                hull.pop();
            }
            hull.push(i);
        }
        hull.pop();
    }
    hull
}

/// The convex hull of discs (radius zero: points) in the plane: its
/// polygon through the tangent points, counter-clockwise, and the discs on
/// its boundary — the hull is that polygon with those discs. `None` for a
/// hull with no area (points on a line), or past [`MAX_HULL_POINTS`] discs.
pub fn disc_hull(discs: &[(DVec2, f64)]) -> Option<(Vec<DVec2>, Vec<usize>)> {
    let sites: Vec<Site> = discs.iter().map(|&(c, r)| Site::disc(c, r)).collect();
    arc_hull(&sites)
}

/// The convex hull of [`Site`]s, points, discs and arcs: its polygon
/// through the points where the boundary leaves and meets the discs and
/// arcs, counter-clockwise, and the sites on its boundary. The hull is that
/// polygon with those sites' caps (see [`super::sites`]). `None` for a hull
/// with no area (points on a line), or past [`MAX_HULL_POINTS`] sites once
/// those inside a disc, and points inside the other points' hull, are
/// left out.
pub fn arc_hull(sites: &[Site]) -> Option<(Vec<DVec2>, Vec<usize>)> {
    if sites.len() > 64 * MAX_HULL_POINTS {
        return None;
    }
    let scale = sites
        .iter()
        .fold(0.0f64, |a, s| a.max(s.c.abs().max_element() + s.r));
    let tol = 1e-12 * scale;
    // Points inside the hull of the points add nothing.
    let points: Vec<usize> = (0..sites.len()).filter(|&i| sites[i].r == 0.0).collect();
    let q: Vec<DVec2> = points.iter().map(|&i| sites[i].c).collect();
    let mut corner = vec![q.len() < 3; sites.len()];
    for k in hull_indices_2d(&q, 0.0) {
        corner[points[k]] = true;
    }
    let candidates: Vec<usize> = (0..sites.len())
        .filter(|&i| sites[i].r > 0.0 || corner[i])
        .collect();
    // Sites inside a whole disc add nothing.
    let keep: Vec<usize> = candidates
        .iter()
        .copied()
        .filter(|&i| {
            !candidates.iter().any(|&j| {
                let (si, sj) = (sites[i], sites[j]);
                j != i
                    && sj.arc.is_none()
                    && (si.c - sj.c).length() + si.r <= sj.r
                    && (si.r < sj.r
                        || (si.r == sj.r && si.c == sj.c && si.arc.is_some())
                        || (si == sj && j < i))
            })
        })
        .collect();
    if keep.len() > MAX_HULL_POINTS {
        return None;
    }
    if let [one] = keep[..] {
        return (sites[one].r > 0.0 && sites[one].arc.is_none()).then(|| (Vec::new(), vec![one]));
    }
    // Each outer common tangent with every site on its inner side: an edge
    // from site i to site j, the outward normal n at angle φ past the
    // right of i → j with sin φ = (rᵢ − rⱼ)/|cⱼ − cᵢ|, where both sites
    // have that normal (an arc, only its own).
    let atol = 1e-12;
    let mut edges: Vec<(f64, usize, usize, DVec2)> = Vec::new();
    for &i in &keep {
        for &j in &keep {
            let (si, sj) = (sites[i], sites[j]);
            let d = sj.c - si.c;
            let l = d.length();
            if i == j || l == 0.0 {
                continue;
            }
            let sin = (si.r - sj.r) / l;
            if sin.abs() >= 1.0 {
                continue;
            }
            let (along, right) = (d / l, DVec2::new(d.y, -d.x) / l);
            let n = right * (1.0 - sin * sin).sqrt() + along * sin;
            let angle = n.y.atan2(n.x);
            if !si.faces(angle, atol) || !sj.faces(angle, atol) {
                continue;
            }
            let h = n.dot(si.c) + si.r;
            if keep.iter().all(|&k| {
                let sk = sites[k];
                !sk.faces(angle, -atol) || n.dot(sk.c) + sk.r <= h + tol
            }) {
                edges.push((angle, i, j, n));
            }
        }
    }
    edges.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut poly: Vec<DVec2> = Vec::new();
    let mut on: Vec<usize> = Vec::new();
    for &(_, i, j, n) in &edges {
        for k in [i, j] {
            let p = sites[k].c + n * sites[k].r;
            if poly.last().map_or(true, |q| (*q - p).length() > tol) {
                poly.push(p);
            }
            if sites[k].r > 0.0 && !on.contains(&k) {
                on.push(k);
            }
        }
    }
    while poly.len() > 1 && (poly[0] - poly[poly.len() - 1]).length() <= tol {
        poly.pop();
    }
    // Points where the boundary runs straight on are not corners.
    let mut corners = Vec::new();
    for k in 0..poly.len() {
        let (a, b, c) = (
            poly[(k + poly.len() - 1) % poly.len()],
            poly[k],
            poly[(k + 1) % poly.len()],
        );
        if (b - a).perp_dot(c - b) > tol * (b - a).length().max((c - b).length()) {
            corners.push(b);
        }
    }
    if corners.len() < 3 {
        corners.clear();
    }
    // An arc the boundary follows from one of its own ends to the other
    // meets no tangent: it is on the hull where it leaves the polygon.
    for &k in &keep {
        if sites[k].arc.is_some() && !on.contains(&k) && leaves(&sites[k], &corners, tol) {
            on.push(k);
        }
    }
    if corners.is_empty() && on.is_empty() {
        return None;
    }
    Some((corners, on))
}

/// Whether any of an arc is outside the convex polygon `poly`
/// (counter-clockwise; any, when it has no corners) by more than `tol`.
fn leaves(site: &Site, poly: &[DVec2], tol: f64) -> bool {
    let Some((from, span)) = site.arc else {
        return true;
    };
    if poly.is_empty() {
        return true;
    }
    let ends = [site.at(from), site.at(from + span)];
    (0..poly.len()).any(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let m = DVec2::new(b.y - a.y, a.x - b.x).normalize();
        let far = if site.faces(m.y.atan2(m.x), 0.0) {
            m.dot(site.c) + site.r
        } else {
            m.dot(ends[0]).max(m.dot(ends[1]))
        };
        far > m.dot(a) + tol
    })
}

/// Whether a simple loop turns one way only.
pub fn convex_polygon(l: &[DVec2]) -> bool {
    let n = l.len();
    let (mut pos, mut neg) = (false, false);
    for i in 0..n {
        let (a, b, c) = (l[i], l[(i + 1) % n], l[(i + 2) % n]);
        let x = (b - a).perp_dot(c - b);
        pos |= x > 0.0;
        neg |= x < 0.0;
    }
    !(pos && neg)
}

/// OpenSCAD's 2-D `hull()` of figures. Circles, polygons and their
/// combinations: the polygon through the tangent points with the circles
/// and arcs on it, exact and an ordinary 2-D tree; anything else (an
/// offset of curved outlines, a projection) is kept as [`Figure::Hull`],
/// for the extrusion to take the hull of its parts' extrusions.
pub fn hull_of_figures(kids: Vec<Figure>) -> Figure {
    let mut found = Vec::new();
    if kids.iter().all(|k| sites(k, &mut found)) {
        if let Some((poly, on)) = arc_hull(&found) {
            let mut parts: Vec<Figure> = on
                .into_iter()
                .filter(|&i| {
                    found[i].arc.is_none() || !crate::mutant::active("hull_arc_caps_dropped")
                })
                .map(|i| found[i].cap())
                .collect();
            if poly.len() >= 3 {
                parts.push(Figure::Polygon(Outlines::polygons(vec![poly])));
            }
            return if parts.len() == 1 {
                parts.pop().expect("one")
            } else {
                Figure::Op(Op::Union, parts)
            };
        }
    }
    Figure::Hull(kids)
}
