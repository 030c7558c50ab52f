//! OpenSCAD's own meshes of extrusions, for `--facets openscad`: a turn
//! (`rotate_extrude`) and a twisted or unevenly scaled `linear_extrude`,
//! as OpenSCAD 2021.01's `GeometryEvaluator.cc` builds them; and the
//! triangles of a 2-D region given by loops (even-odd, as OpenSCAD's
//! outlines), each point of it covered once, for their ends. Each hole is
//! joined to the loop around it by a bridge to a vertex it sees (Eberly's
//! "Triangulation by ear clipping", the method of mapbox's earcut), and
//! each outer loop with its holes is then ear-clipped as one polygon.

use super::transforms::{deg2rad, facet_sin_cos};
use super::{Resolver, GRID_FINE, MAX_FRAGMENTS};
use crate::error::Result;
use crate::geometry::triangulate::{cap, depths, signed_area};
use crate::plane::figure::Figure;
use crate::plane::Outlines;
use crate::scene::args::Args;
use crate::scene::Material;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DVec2, DVec3};

impl Resolver<'_> {
    /// OpenSCAD 2021.01's mesh of a twisted or unevenly scaled
    /// `linear_extrude` (`extrudePolygon` and `add_slice` in
    /// `GeometryEvaluator.cc`), under `--facets openscad`: its slices (the
    /// `slices` given, else `Calc::get_helix_slices`, its conical variant
    /// for an even scale, or `get_diagonal_slices`), each outline's points
    /// at every slice's turn and scale (`Scaling · rotate_degrees(−turn)`),
    /// each quad between two slices split along its shorter diagonal
    /// (`sgn_vdiff`, with OpenSCAD's choice for equal ones: by the
    /// outline's sign and the twist's), the bottom and top capped by each
    /// outline's own triangles. Only one straight polygon `o` (with its
    /// holes): the mesh of a 2-D combination depends on the combined
    /// outline (the caller draws that exact).
    pub(super) fn extruded_facets(
        &mut self,
        s: &Statement,
        a: &Args,
        o: &Outlines,
        cut: &Cut,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        // OpenSCAD's outlines: an outer one counter-clockwise, a hole (in
        // an odd number of others) clockwise.
        let raw: Vec<Vec<DVec2>> = o.loops.iter().filter(|l| l.len() >= 3).cloned().collect();
        let loops: Vec<(Vec<DVec2>, bool)> = raw
            .iter()
            .zip(depths(&raw))
            .map(|(l, depth)| {
                let positive = depth % 2 == 0;
                let mut l = l.clone();
                if (signed_area(&l) > 0.0) != positive {
                    l.reverse();
                }
                (l, positive)
            })
            .collect();
        let (sx, sy) = (cut.scale.x, cut.scale.y);
        let (h1, h2) = if cut.center {
            (-cut.h / 2.0, cut.h / 2.0)
        } else {
            (0.0, cut.h)
        };
        let finite = |name: &str, or: f64| a.special(name).filter(|v| v.is_finite()).unwrap_or(or);
        let (fnv, fa, fs) = (finite("$fn", 0.0), finite("$fa", 12.0), finite("$fs", 2.0));
        let given = cut.slices.filter(|v| v.is_finite()).unwrap_or(0.0) as i64;
        let all = loops.iter().flat_map(|(l, _)| l.iter());
        let slices = if given > 0 {
            given as usize
        } else if cut.twist != 0.0 {
            let r2 = all.fold(0.0f64, |m, v| m.max(v.length_squared()));
            if (sx == 1.0 && sy == 1.0) || sx != sy {
                helix_slices(r2, cut.h, cut.twist, fnv, fs, fa)
            } else {
                conical_helix_slices(r2, cut.h, cut.twist, sx, fnv, fs, fa)
            }
        } else {
            let d2 = all.fold(0.0f64, |m, v| m.max((*v - *v * cut.scale).length_squared()));
            diagonal_slices(d2, cut.h, fnv, fs)
        }
        .min(MAX_FRAGMENTS);
        // Level j (0 to slices), once for every outline: the matrix, the
        // height, the turn and the scale of OpenSCAD's slice boundary j, each
        // point as Eigen computes (S·R)·v.
        let levels: Vec<_> = (0..=slices)
            .map(|j| {
                let rot = cut.twist * j as f64 / slices as f64;
                let k = DVec2::new(
                    1.0 - (1.0 - sx) * j as f64 / slices as f64,
                    1.0 - (1.0 - sy) * j as f64 / slices as f64,
                );
                let (sn, cs) = facet_sin_cos(-rot);
                let m = [[k.x * cs, -k.x * sn], [k.y * sn, k.y * cs]];
                (m, h1 + (h2 - h1) * j as f64 / slices as f64, rot, k)
            })
            .collect();
        let mut pts = Vec::new();
        let mut faces: Vec<Vec<u32>> = Vec::new();
        let mut bases = Vec::new();
        for (l, positive) in &loops {
            let n = l.len();
            let base = pts.len();
            bases.push(base);
            for &(m, z, _, _) in &levels {
                pts.extend(l.iter().map(|v| {
                    DVec3::new(
                        m[0][0] * v.x + m[0][1] * v.y,
                        m[1][0] * v.x + m[1][1] * v.y,
                        z,
                    )
                }));
            }
            let at = |j: usize, i: usize| (base + j * n + i % n) as u32;
            let p2 = |k: u32| pts[k as usize].truncate();
            for j in 0..slices {
                let (_, _, rot1, _) = levels[j];
                let (_, _, rot2, k2) = levels[j + 1];
                let any_zero = k2.x == 0.0 || k2.y == 0.0;
                let any_non_zero = k2.x != 0.0 || k2.y != 0.0;
                let back_twist = rot2 <= rot1;
                let flip = !positive ^ back_twist;
                for i in 1..=n {
                    let (pv1, pv2, cu1, cu2) =
                        (at(j, i - 1), at(j + 1, i - 1), at(j, i), at(j + 1, i));
                    let diff = sgn_vdiff(p2(pv1) - p2(cu2), p2(cu1) - p2(pv2));
                    let split_first = diff == -1 || (diff == 0 && !flip);
                    let second = !any_zero || (any_non_zero && p2(pv2) != p2(cu2));
                    if split_first ^ any_zero {
                        faces.push(vec![pv1, cu2, cu1]);
                        if second {
                            faces.push(vec![cu2, pv1, pv2]);
                        }
                    } else {
                        faces.push(vec![pv1, pv2, cu1]);
                        if second {
                            faces.push(vec![pv2, cu2, cu1]);
                        }
                    }
                }
            }
        }
        // The bottom, and the top unless it has no area: the region once
        // over, holes and all, on the first and last levels' points.
        let ends: &[usize] = if sx > 0.0 && sy > 0.0 {
            &[0, slices]
        } else {
            &[0]
        };
        let shapes: Vec<Vec<DVec2>> = loops.iter().map(|(l, _)| l.clone()).collect();
        end_faces(&shapes, &bases, ends, &mut faces);
        if faces.is_empty() {
            return Ok(None);
        }
        self.mesh_leaf(s, s.name_span, pts, faces, xf, mat)
    }

    /// OpenSCAD 2021.01's mesh of `rotate_extrude` (`rotatePolygon` in
    /// `GeometryEvaluator.cc`), under `--facets openscad`: each outline's
    /// points turned to `steps + 1` rings (a full turn: `steps` rings at
    /// 180° − 360°·j/steps, OpenSCAD's start on −x; a part turn: at
    /// angle·j/steps from +x), neighbouring rings joined by the two
    /// triangles of each planar trapezoid, and a part turn capped at both
    /// ends by the triangles of the region ([`cap`]). A 2-D combination turns as the
    /// same combination of its turned leaves: turning every leaf by the
    /// same rings commutes with union, intersection and difference.
    pub(super) fn turned_facets(
        &mut self,
        s: &Statement,
        f: &Figure,
        angle: f64,
        steps: usize,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        match f {
            Figure::Polygon(o) if !o.curved() => {
                let full = angle == 360.0;
                let rings = if full { steps } else { steps + 1 };
                // Each ring's (sin a, cos a), once for every outline:
                // OpenSCAD's fill_ring angle a puts (x, y) at (x sin a,
                // x cos a, y).
                let trig: Vec<(f64, f64)> = (0..rings)
                    .map(|j| {
                        facet_sin_cos(if full {
                            -90.0 + j as f64 * 360.0 / steps as f64
                        } else {
                            90.0 - j as f64 * angle / steps as f64
                        })
                    })
                    .collect();
                let mut pts = Vec::new();
                let mut faces: Vec<Vec<u32>> = Vec::new();
                let loops: Vec<Vec<DVec2>> =
                    o.loops.iter().filter(|l| l.len() >= 3).cloned().collect();
                let mut bases = Vec::new();
                for l in &loops {
                    let base = pts.len();
                    bases.push(base);
                    for &(sa, ca) in &trig {
                        pts.extend(l.iter().map(|p| DVec3::new(p.x * sa, p.x * ca, p.y)));
                    }
                    let m = l.len();
                    let at = |j: usize, i: usize| (base + (j % rings) * m + i % m) as u32;
                    for j in 0..steps {
                        for i in 0..m {
                            faces.push(vec![at(j, i), at(j + 1, i + 1), at(j, i + 1)]);
                            faces.push(vec![at(j, i), at(j + 1, i), at(j + 1, i + 1)]);
                        }
                    }
                }
                if !full {
                    end_faces(&loops, &bases, &[0, steps], &mut faces);
                }
                if faces.is_empty() {
                    return Ok(None);
                }
                self.mesh_leaf(s, s.name_span, pts, faces, xf, mat)
            }
            Figure::Op(op, kids) => {
                let mut parts = Vec::new();
                for k in kids {
                    parts.push(self.turned_facets(s, k, angle, steps, xf, mat)?);
                }
                Ok(self.op(*op, parts))
            }
            _ => Err(self.src.error(
                s.name_span,
                "OpenSCAD's facets of turned curves are not built (the caller draws them exact)",
                "csgrt builds OpenSCAD's facets of turned polygons and circles",
            )),
        }
    }
}

/// The triangles of the region of `loops` ([`cap`]) on each of the
/// `levels` of a mesh whose loop k has its level j at `bases[k] + j·len`.
fn end_faces(loops: &[Vec<DVec2>], bases: &[usize], levels: &[usize], faces: &mut Vec<Vec<u32>>) {
    for t in cap(loops) {
        for &j in levels {
            faces.push(
                t.iter()
                    .map(|&(k, i)| (bases[k] + j * loops[k].len() + i) as u32)
                    .collect(),
            );
        }
    }
}

/// A regular polygon of `n` vertices on the circle of radius r, vertex i
/// at 360°·i/n (OpenSCAD's circle and cylinder at an explicit small `$fn`).
pub(super) fn regular_polygon(n: usize, r: f64) -> Outlines {
    let pts = (0..n)
        .map(|i| {
            let (s, c) = facet_sin_cos(360.0 * i as f64 / n as f64);
            DVec2::new(r * c, r * s)
        })
        .collect();
    Outlines::polygons(vec![pts])
}

/// A twisted or unevenly scaled `linear_extrude` as OpenSCAD slices it.
pub(super) struct Cut {
    pub(super) h: f64,
    pub(super) center: bool,
    /// Degrees.
    pub(super) twist: f64,
    pub(super) scale: DVec2,
    pub(super) slices: Option<f64>,
}

/// OpenSCAD's `sgn_vdiff`: which of two vectors is shorter, −1 or 1, or 0
/// within 10 ppm of their mean length.
fn sgn_vdiff(v1: DVec2, v2: DVec2) -> i32 {
    let (l1, l2) = (v1.length(), v2.length());
    let scale = l1 + l2;
    let diff = 2.0 * (l1 - l2).abs() * 1e5;
    if diff > scale {
        if l1 < l2 {
            -1
        } else {
            1
        }
    } else {
        0
    }
}

/// `Calc::get_helix_slices`.
fn helix_slices(r2: f64, h: f64, twist: f64, fnv: f64, fs: f64, fa: f64) -> usize {
    let twist = twist.abs();
    let min = ((twist / 120.0).ceil() as i64).max(1);
    if r2.sqrt() < GRID_FINE || !fnv.is_finite() {
        return min as usize;
    }
    if fnv > 0.0 {
        return ((twist / 360.0 * fnv).ceil() as i64).max(min) as usize;
    }
    let t = deg2rad(twist);
    let c = h / t;
    let length = t * (r2 + c * c).sqrt();
    let fa_slices = (twist / fa).ceil() as i64;
    let fs_slices = (length / fs).ceil() as i64;
    fa_slices.min(fs_slices).max(min) as usize
}

/// `Calc::get_conical_helix_slices` (an even scale ≠ 1 with a twist).
fn conical_helix_slices(
    r2: f64,
    h: f64,
    twist: f64,
    scale: f64,
    fnv: f64,
    fs: f64,
    fa: f64,
) -> usize {
    let twist = twist.abs();
    let r = r2.sqrt();
    let min = ((twist / 120.0).ceil() as i64).max(1);
    if r < GRID_FINE || !fnv.is_finite() {
        return min as usize;
    }
    if fnv > 0.0 {
        return ((twist * fnv / 360.0).ceil() as i64).max(min) as usize;
    }
    let rads = deg2rad(twist);
    let end = if scale > 1.0 {
        rads * scale / (scale - 1.0)
    } else {
        rads / (1.0 - scale)
    };
    let start = end - rads;
    let a = r / end;
    let arch = |t: f64| 0.5 * a * (t * (1.0 + t * t).sqrt() + t.asinh());
    let spiral = arch(end) - arch(start);
    let total = (spiral * spiral + h * h).sqrt();
    let fs_slices = (total / fs).ceil() as i64;
    let fa_slices = (twist / fa).ceil() as i64;
    fa_slices.min(fs_slices).max(min) as usize
}

/// `Calc::get_diagonal_slices` (an uneven scale, no twist).
fn diagonal_slices(d2: f64, h: f64, fnv: f64, fs: f64) -> usize {
    if d2.sqrt() < GRID_FINE || !fnv.is_finite() {
        return 1;
    }
    if fnv > 0.0 {
        return (fnv as i64).max(1) as usize;
    }
    (((d2 + h * h).sqrt() / fs).ceil() as i64).max(1) as usize
}
