//! The shadow of triangles swept from z = 0 to 1: `projection(cut =
//! false)` of a mesh, extruded, in object space.
//!
//! The shadow of a closed solid made of triangles is the union of its
//! triangles' shadows: a point of the plane has a vertical line through the
//! solid exactly where that line meets the boundary. A line of the plane
//! meets a triangle in one interval, cut by its three edges' half-planes,
//! and the union of those intervals is the shadow's, merged where they
//! touch. An edge two triangles share is crossed at the same parameter by
//! both (each computes it from the edge's ends taken in one order), and
//! ends closer than the coincidence bound (`math::robust`) meet. A box
//! tree over the triangles ([`EdgeTree`]) keeps the search to those near
//! the line. Parts: 0 the bottom, 1 the top, 2 + 3·k + j the side over edge
//! j of triangle k.

use super::prism::{clip, slab};
use super::solid::{Param, Probe, RawSpan, Solid};
use super::{Aabb, Part};
use crate::math::robust::coincidence;
use crate::plane::EdgeTree;
use glam::{DVec2, DVec3};
use std::sync::Arc;

const BOTTOM: Part = 0;
const TOP: Part = 1;
const SIDE: Part = 2;

/// Past this many triangles a soup drops those inside its full cells
/// ([`pruned`]).
const PRUNE_TRIANGLES: usize = 4096;

/// The most cells across the grid [`pruned`] lays over a soup.
const PRUNE_CELLS: usize = 512;

/// Whether counter-clockwise triangle `t` holds `p` (its edges count).
fn holds(t: [DVec2; 3], p: DVec2) -> bool {
    (0..3).all(|j| (t[(j + 1) % 3] - t[j]).perp_dot(p - t[j]) >= 0.0)
}

/// Counter-clockwise triangles `tris` with the same union and fewer
/// triangles inside it: over a grid of square cells, a cell whose four
/// corners one triangle holds lies in that triangle (it is convex) — a
/// full cell; each row's runs of full cells become rectangles (two
/// triangles each), and a triangle whose box meets only full cells lies in
/// them and is dropped. The union is unchanged: the rectangles lie in it,
/// and what is dropped lies in them. A shadow cast by many stacked pieces
/// (each point under hundreds) keeps only the triangles near its edge,
/// which are all a line's search then meets.
fn pruned(mut pts: Vec<DVec2>, tris: Vec<[u32; 3]>) -> (Vec<DVec2>, Vec<[u32; 3]>) {
    let corners = |t: &[u32; 3]| t.map(|i| pts[i as usize]);
    let boxes: Vec<(DVec2, DVec2)> = tris
        .iter()
        .map(|t| {
            let p = corners(t);
            (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
        })
        .collect();
    let lo = boxes.iter().fold(DVec2::INFINITY, |a, b| a.min(b.0));
    let hi = boxes.iter().fold(DVec2::NEG_INFINITY, |a, b| a.max(b.1));
    let side = (hi - lo).max_element() / PRUNE_CELLS as f64;
    if !(side > 0.0 && side.is_finite()) {
        return (pts, tris);
    }
    let (nx, ny) = (
        (((hi.x - lo.x) / side).ceil() as usize).clamp(1, PRUNE_CELLS),
        (((hi.y - lo.y) / side).ceil() as usize).clamp(1, PRUNE_CELLS),
    );
    let tree = EdgeTree::new(&boxes);
    let corner = |i: usize, j: usize| lo + DVec2::new(i as f64, j as f64) * side;
    let mut full = vec![false; nx * ny];
    // The triangle that held the last full cell: most often it holds the
    // next one too.
    let mut witness: Option<usize> = None;
    for j in 0..ny {
        for i in 0..nx {
            let c = [
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ];
            let within = |k: usize| c.iter().all(|&p| holds(corners(&tris[k]), p));
            let mut found = witness.filter(|&k| within(k));
            if found.is_none() {
                let mid = 0.5 * (c[0] + c[2]);
                let near = |a: DVec2, b: DVec2| {
                    a.x <= mid.x && mid.x <= b.x && a.y <= mid.y && mid.y <= b.y
                };
                tree.visit_boxes(near, &mut |k| {
                    if found.is_none() && within(k as usize) {
                        found = Some(k as usize);
                    }
                });
            }
            if found.is_some() {
                witness = found;
            }
            full[j * nx + i] = found.is_some();
        }
    }
    // Cells not full, summed over the rectangle from the grid's corner.
    let w = nx + 1;
    let mut sum = vec![0u32; w * (ny + 1)];
    for j in 0..ny {
        for i in 0..nx {
            sum[(j + 1) * w + i + 1] =
                u32::from(!full[j * nx + i]) + sum[j * w + i + 1] + sum[(j + 1) * w + i]
                    - sum[j * w + i];
        }
    }
    let cell = |v: f64, n: usize| ((v / side).floor().max(0.0) as usize).min(n - 1);
    let mut kept: Vec<[u32; 3]> = Vec::new();
    for (t, (a, b)) in tris.iter().zip(&boxes) {
        let (i0, i1) = (cell(a.x - lo.x, nx), cell(b.x - lo.x, nx));
        let (j0, j1) = (cell(a.y - lo.y, ny), cell(b.y - lo.y, ny));
        // The box's cells, and one more on each side where it ends on a
        // cell's side (its edge then may lie in the next cell too).
        let (i0, j0) = (i0.saturating_sub(1), j0.saturating_sub(1));
        let (i1, j1) = ((i1 + 1).min(nx - 1), (j1 + 1).min(ny - 1));
        let open = sum[(j1 + 1) * w + i1 + 1] + sum[j0 * w + i0]
            - sum[j0 * w + i1 + 1]
            - sum[(j1 + 1) * w + i0];
        // Kept when it meets a cell that is not full (its box, and none of
        // its edges with the whole cell beyond it).
        let meets = |i: usize, j: usize| {
            let c = [
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ];
            let p = corners(t);
            (0..3).all(|e| {
                let (a, b) = (p[e], p[(e + 1) % 3]);
                c.iter().any(|&q| (b - a).perp_dot(q - a) >= 0.0)
            })
        };
        if open > 0 && (j0..=j1).any(|j| (i0..=i1).any(|i| !full[j * nx + i] && meets(i, j))) {
            kept.push(*t);
        }
    }
    for j in 0..ny {
        let mut i = 0;
        while i < nx {
            if !full[j * nx + i] {
                i += 1;
                continue;
            }
            let start = i;
            while i < nx && full[j * nx + i] {
                i += 1;
            }
            let base = pts.len() as u32;
            pts.extend([
                corner(start, j),
                corner(i, j),
                corner(i, j + 1),
                corner(start, j + 1),
            ]);
            kept.push([base, base + 1, base + 2]);
            kept.push([base, base + 2, base + 3]);
        }
    }
    (pts, kept)
}

/// Triangles of the plane, each counter-clockwise, united.
#[derive(Clone, Debug, PartialEq)]
pub struct Soup {
    pub pts: Vec<DVec2>,
    pub tris: Vec<[u32; 3]>,
    pub lo: DVec2,
    pub hi: DVec2,
    tree: EdgeTree,
}

impl Soup {
    /// The union of the triangles `tris` over `pts` (degenerate ones left
    /// out, the rest turned counter-clockwise), or `None` when none is
    /// left.
    pub fn new(pts: Vec<DVec2>, tris: Vec<[u32; 3]>) -> Option<Soup> {
        let tris: Vec<[u32; 3]> = tris
            .into_iter()
            .filter_map(|[a, b, c]| {
                let (pa, pb, pc) = (pts[a as usize], pts[b as usize], pts[c as usize]);
                let area = (pb - pa).perp_dot(pc - pa);
                if area > 0.0 {
                    Some([a, b, c])
                } else if area < 0.0 {
                    Some([a, c, b])
                } else {
                    None
                }
            })
            .collect();
        if tris.is_empty() {
            return None;
        }
        let (pts, tris) = if tris.len() > PRUNE_TRIANGLES {
            pruned(pts, tris)
        } else {
            (pts, tris)
        };
        let boxes: Vec<(DVec2, DVec2)> = tris
            .iter()
            .map(|t| {
                let p = t.map(|i| pts[i as usize]);
                (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
            })
            .collect();
        let lo = boxes.iter().fold(DVec2::INFINITY, |a, b| a.min(b.0));
        let hi = boxes.iter().fold(DVec2::NEG_INFINITY, |a, b| a.max(b.1));
        let tree = EdgeTree::new(&boxes);
        Some(Soup {
            pts,
            tris,
            lo,
            hi,
            tree,
        })
    }

    /// Edge j of triangle k, from its start to its end.
    fn edge(&self, k: usize, j: usize) -> (DVec2, DVec2) {
        let t = self.tris[k];
        (self.pts[t[j] as usize], self.pts[t[(j + 1) % 3] as usize])
    }

    /// Where the line o + s·d (d ≠ 0) is inside triangle k: (s_in, edge,
    /// s_out, edge), or `None`.
    fn interval(&self, k: usize, o: DVec2, d: DVec2) -> Option<(f64, u32, f64, u32)> {
        let (mut lo, mut hi) = ((f64::NEG_INFINITY, 0), (f64::INFINITY, 0));
        for j in 0..3 {
            let (a, b) = self.edge(k, j);
            // The edge's ends in one order for both triangles that share
            // it: the same parameter from each.
            let (p, q, sign) = if (a.x, a.y) <= (b.x, b.y) {
                (a, b, 1.0)
            } else {
                (b, a, -1.0)
            };
            let e = q - p;
            let (f0, f1) = (e.perp_dot(o - p) * sign, e.perp_dot(d) * sign);
            // Inside the triangle where f0 + s·f1 ≥ 0.
            if f1 == 0.0 {
                if f0 < 0.0 {
                    return None;
                }
                continue;
            }
            let s = -(e.perp_dot(o - p)) / e.perp_dot(d);
            if f1 > 0.0 {
                if s > lo.0 {
                    lo = (s, j as u32);
                }
            } else if s < hi.0 {
                hi = (s, j as u32);
            }
        }
        (lo.0 < hi.0).then_some((lo.0, lo.1, hi.0, hi.1))
    }

    /// The sorted spans `(s_in, part, s_out, part)` of the line o + s·d
    /// (d ≠ 0) inside the union, parts as the module says.
    pub fn spans(&self, o: DVec2, d: DVec2, scale: f64) -> Vec<(f64, Part, f64, Part)> {
        let n = d.perp();
        let mut all = Vec::new();
        self.tree.visit(DVec3::new(n.x, n.y, -o.dot(n)), &mut |k| {
            if let Some((s0, j0, s1, j1)) = self.interval(k as usize, o, d) {
                all.push((s0, SIDE + 3 * k + j0, s1, SIDE + 3 * k + j1));
            }
        });
        all.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        let mut out: Vec<(f64, Part, f64, Part)> = Vec::new();
        // Parameters of the line, in units of |d|: its coincidence bound.
        let len = d.length();
        for s in all {
            match out.last_mut() {
                Some(last) if s.0 <= last.2 + coincidence(last.2 * len, scale) / len => {
                    if s.2 > last.2 {
                        last.2 = s.2;
                        last.3 = s.3;
                    }
                }
                _ => out.push(s),
            }
        }
        out
    }

    /// Whether `p` is in a triangle (its edges count).
    pub fn contains(&self, p: DVec2) -> bool {
        let mut inside = false;
        // Only the triangles whose boxes hold the point.
        let holds = |lo: DVec2, hi: DVec2| lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y;
        self.tree.visit_boxes(holds, &mut |k| {
            inside = inside
                || (0..3).all(|j| {
                    let (a, b) = self.edge(k as usize, j);
                    (b - a).perp_dot(p - a) >= 0.0
                });
        });
        inside
    }

    /// The outward normal of the side over `part` (an edge).
    fn normal(&self, part: Part) -> DVec2 {
        let k = (part - SIDE) as usize;
        let (a, b) = self.edge(k / 3, k % 3);
        let e = b - a;
        DVec2::new(e.y, -e.x)
    }
}

/// A soup's shadow swept from z = 0 to 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Shadow {
    pub soup: Arc<Soup>,
}

impl Solid for Shadow {
    const NAME: &'static str = "projection";

    fn spans(&self, q: &mut Probe, emit: &mut impl FnMut(RawSpan)) {
        let (o, d) = (q.o, q.d);
        let Some((z0, zp0, z1, zp1)) = slab(o, d) else {
            return;
        };
        let (o2, d2) = (o.truncate(), d.truncate());
        if d2 == DVec2::ZERO {
            if self.soup.contains(o2) {
                emit((z0, zp0, z1, zp1));
            }
            return;
        }
        let scale = o.abs().max_element();
        for s in self.soup.spans(o2, d2, scale) {
            clip((z0, zp0, z1, zp1), s, emit);
        }
    }

    fn normal(&self, _p: DVec3, part: Part) -> DVec3 {
        match part {
            BOTTOM => DVec3::NEG_Z,
            TOP => DVec3::Z,
            k => self.soup.normal(k).extend(0.0),
        }
    }

    fn contains(&self, p: DVec3) -> bool {
        (0.0..=1.0).contains(&p.z) && self.soup.contains(p.truncate())
    }

    fn object_bounds(&self) -> Aabb {
        Aabb::new(self.soup.lo.extend(0.0), self.soup.hi.extend(1.0))
    }

    fn support(&self, d: DVec3) -> Option<DVec3> {
        let d2 = d.truncate();
        let p = self
            .soup
            .pts
            .iter()
            .copied()
            .max_by(|a, b| a.dot(d2).total_cmp(&b.dot(d2)))?;
        Some(p.extend(if d.z > 0.0 { 1.0 } else { 0.0 }))
    }

    fn params(&self) -> Vec<(&'static str, Param)> {
        vec![("triangles", Param::Num(self.soup.tris.len() as f64))]
    }

    /// POV-Ray has no solid made from another's shadow: the export stops
    /// POV-Ray with the reason (as for a slice).
    fn pov(&self) -> String {
        "#error \"csgrt: projection(cut = false) has no POV-Ray equivalent\"\nsphere { <0, 0, 0>, 0"
            .to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square of two triangles sharing a diagonal, and a triangle apart.
    fn soup() -> Soup {
        let pts = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(3.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(3.0, 1.0),
        ];
        Soup::new(pts, vec![[0, 1, 2], [0, 3, 2], [4, 5, 6], [0, 1, 3]]).unwrap()
    }

    #[test]
    fn a_line_across_shared_edges_sees_one_span_per_piece() {
        let s = soup();
        // Across the square's diagonal and on to the apart triangle.
        for y in [0.1, 0.25, 0.5, 0.75, 0.9] {
            let sp = s.spans(DVec2::new(-1.0, y), DVec2::X, 1.0);
            assert_eq!(sp.len(), 2, "{y}: {sp:?}");
            assert!((sp[0].0 - 1.0).abs() < 1e-15 && (sp[0].2 - 2.0).abs() < 1e-15);
            assert!((sp[1].0 - 4.0).abs() < 1e-15 && (sp[1].2 - (5.0 - y)).abs() < 1e-15);
        }
        // Along the other diagonal, through two corners and the shared
        // edge's middle: one span.
        let sp = s.spans(DVec2::new(-1.0, 2.0), DVec2::new(1.0, -1.0), 2.0);
        assert_eq!(sp.len(), 1, "{sp:?}");
        assert!(
            (sp[0].0 - 1.0).abs() < 1e-15 && (sp[0].2 - 2.0).abs() < 1e-15,
            "{sp:?}"
        );
    }

    #[test]
    fn inside_is_any_triangle() {
        let s = soup();
        assert!(s.contains(DVec2::new(0.5, 0.5)));
        assert!(s.contains(DVec2::new(3.2, 0.2)));
        assert!(!s.contains(DVec2::new(2.0, 0.5)));
        assert!(!s.contains(DVec2::new(3.9, 0.9)));
    }
}
