//! Triangulation: a polygonal face in space by ear clipping across its
//! Newell normal ([`triangulate`]: polyhedron and mesh-file faces), and
//! the even-odd region of loops in the plane ([`cap`]: each outer loop
//! with the holes directly inside it joined to it by bridges, as OpenSCAD
//! meshes 2-D shapes), with the tests of a loop's area, winding and
//! nesting it rests on.

use glam::{DVec2, DVec3};

/// A face of `points` (indices, in order, at least 3) as triangles over
/// the same indices: consecutive repeats dropped, then ear clipping in the
/// plane across the face's Newell normal (robust to non-planar and
/// non-convex faces; a face whose outline crosses itself is finished as a
/// fan once no ear is left). A face with no area gives no triangle.
pub fn triangulate(points: &[DVec3], face: &[u32]) -> Vec<[u32; 3]> {
    let mut out = Vec::new();
    triangulate_into(points, face, &mut out);
    out
}

/// [`triangulate`], the triangles added to `out`; a triangle (the common
/// face) with no allocation: itself, unless two of its corners are one.
pub fn triangulate_into(points: &[DVec3], face: &[u32], out: &mut Vec<[u32; 3]>) {
    if let [a, b, c] = *face {
        if a != b && b != c && c != a {
            out.push([a, b, c]);
        }
        return;
    }
    let mut f: Vec<u32> = Vec::with_capacity(face.len());
    for &i in face {
        if f.last() != Some(&i) {
            f.push(i);
        }
    }
    while f.len() > 1 && f.first() == f.last() {
        f.pop();
    }
    if f.len() < 3 {
        return;
    }
    if f.len() == 3 {
        out.push([f[0], f[1], f[2]]);
        return;
    }
    // Newell's normal: the face's mean plane, whatever its shape.
    let mut n = DVec3::ZERO;
    for k in 0..f.len() {
        let (a, b) = (points[f[k] as usize], points[f[(k + 1) % f.len()] as usize]);
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let a = n.abs();
    let (i, j) = if a.z >= a.x && a.z >= a.y {
        (0, 1)
    } else if a.x >= a.y {
        (1, 2)
    } else {
        (2, 0)
    };
    // Seen from the side n points to, the face turns counter-clockwise.
    let sign = if n[3 - i - j] >= 0.0 { 1.0 } else { -1.0 };
    let p2 = |k: u32| {
        let p = points[k as usize];
        (p[i], p[j])
    };
    let cross = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        sign * ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0))
    };
    out.reserve(f.len() - 2);
    let mut ring = f;
    while ring.len() > 3 {
        let m = ring.len();
        let ear = (0..m).find(|&k| {
            let (pa, pb, pc) = (ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
            let (a, b, c) = (p2(pa), p2(pb), p2(pc));
            if cross(a, b, c) <= 0.0 {
                return false;
            }
            // No other vertex inside or on the ear.
            ring.iter().all(|&q| {
                if q == pa || q == pb || q == pc {
                    return true;
                }
                let x = p2(q);
                !(cross(a, b, x) >= 0.0 && cross(b, c, x) >= 0.0 && cross(c, a, x) >= 0.0)
            })
        });
        let Some(k) = ear else {
            break;
        };
        out.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
        ring.remove(k);
    }
    // What is left: a triangle, or a knot with no ear (a fan of it).
    for k in 1..ring.len() - 1 {
        out.push([ring[0], ring[k], ring[k + 1]]);
    }
}

/// Twice the signed area of a loop (positive counter-clockwise).
pub fn signed_area(l: &[DVec2]) -> f64 {
    (0..l.len())
        .map(|i| l[i].perp_dot(l[(i + 1) % l.len()]))
        .sum()
}

/// Whether `p` is inside the loop `l` by the even-odd rule.
pub fn inside_loop(l: &[DVec2], p: DVec2) -> bool {
    let mut inside = false;
    for i in 0..l.len() {
        let (a, b) = (l[i], l[(i + 1) % l.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// How many of the other loops each loop lies in (by its first point): an
/// even count is an outer loop, an odd one a hole.
pub fn depths(loops: &[Vec<DVec2>]) -> Vec<usize> {
    (0..loops.len())
        .map(|k| {
            (0..loops.len())
                .filter(|&m| m != k && inside_loop(&loops[m], loops[k][0]))
                .count()
        })
        .collect()
}

/// The triangles `[(loop, vertex); 3]` covering the region of `loops`
/// (each of at least 3 points) once, wound counter-clockwise.
pub fn cap(loops: &[Vec<DVec2>]) -> Vec<[(usize, usize); 3]> {
    let depth = depths(loops);
    // Each loop as (loop, vertex) places, outer ones counter-clockwise,
    // holes clockwise.
    let ring_of = |k: usize, ccw: bool| -> Vec<(usize, usize)> {
        let mut r: Vec<(usize, usize)> = (0..loops[k].len()).map(|i| (k, i)).collect();
        if (signed_area(&loops[k]) > 0.0) != ccw {
            r.reverse();
        }
        r
    };
    let at = |p: (usize, usize)| loops[p.0][p.1];
    let mut out = Vec::new();
    for outer in (0..loops.len()).filter(|&k| depth[k] % 2 == 0) {
        let mut ring = ring_of(outer, true);
        // Its holes: one level deeper and inside it, rightmost first.
        let mut holes: Vec<usize> = (0..loops.len())
            .filter(|&h| depth[h] == depth[outer] + 1 && inside_loop(&loops[outer], loops[h][0]))
            .collect();
        let right = |h: usize| {
            loops[h]
                .iter()
                .map(|p| p.x)
                .fold(f64::NEG_INFINITY, f64::max)
        };
        holes.sort_by(|&a, &b| right(b).total_cmp(&right(a)).then(a.cmp(&b)));
        for h in holes {
            let hr = ring_of(h, false);
            let start = (0..hr.len())
                .max_by(|&a, &b| at(hr[a]).x.total_cmp(&at(hr[b]).x).then(b.cmp(&a)))
                .unwrap_or(0);
            let Some(m) = bridge(&ring, at, at(hr[start])) else {
                continue;
            };
            // ring[..=m], the hole from its rightmost point round to it
            // again, then ring[m..].
            let mut joined = ring[..=m].to_vec();
            joined.extend((0..=hr.len()).map(|j| hr[(start + j) % hr.len()]));
            joined.extend_from_slice(&ring[m..]);
            ring = joined;
        }
        // Ear clipping over the places, by a numbering of its own.
        let pts: Vec<DVec3> = ring.iter().map(|&p| at(p).extend(0.0)).collect();
        let mut id: Vec<u32> = Vec::with_capacity(ring.len());
        for (j, p) in ring.iter().enumerate() {
            // A place met twice (a bridge's ends) keeps one number.
            let first = ring[..j].iter().position(|q| q == p).unwrap_or(j);
            id.push(first as u32);
        }
        for t in triangulate(&pts, &id) {
            out.push(t.map(|i| ring[i as usize]));
        }
    }
    out
}

/// The place in `ring` that the point `p` (inside it, the rightmost of a
/// hole) is joined to: the nearer end of the first edge met going +x from
/// `p`, or the ring's reflex vertex inside the triangle that would cut
/// that bridge at the least angle from +x.
fn bridge(
    ring: &[(usize, usize)],
    at: impl Fn((usize, usize)) -> DVec2,
    p: DVec2,
) -> Option<usize> {
    let n = ring.len();
    let mut best: Option<(f64, usize)> = None;
    for i in 0..n {
        let (a, b) = (at(ring[i]), at(ring[(i + 1) % n]));
        // Edges that reach the line y = p.y, not along it.
        if (a.y - p.y) * (b.y - p.y) > 0.0 || a.y == b.y {
            continue;
        }
        let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
        if x < p.x {
            continue;
        }
        // The end with the larger x (on the ray, the one hit exactly).
        let m = if a.y == p.y && a.x >= p.x {
            i
        } else if b.y == p.y && b.x >= p.x {
            (i + 1) % n
        } else if a.x > b.x {
            i
        } else {
            (i + 1) % n
        };
        if best.map_or(true, |(bx, _)| x < bx) {
            best = Some((x, m));
        }
    }
    let (x, m) = best?;
    let hit = DVec2::new(x, p.y);
    let mp = at(ring[m]);
    if mp == hit {
        return Some(m);
    }
    // A reflex vertex inside the triangle (p, hit, mp) hides mp: take the
    // one at the least angle from +x (then the nearest).
    let inside = |q: DVec2| {
        let c = |a: DVec2, b: DVec2| (b - a).perp_dot(q - a);
        let (d1, d2, d3) = (c(p, hit), c(hit, mp), c(mp, p));
        (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0)
    };
    let mut pick = (m, f64::INFINITY, (mp - p).length());
    for j in 0..n {
        let q = at(ring[j]);
        if j == m || q == p || !inside(q) {
            continue;
        }
        let (prev, next) = (at(ring[(j + n - 1) % n]), at(ring[(j + 1) % n]));
        let reflex = (q - prev).perp_dot(next - q) < 0.0;
        if !reflex {
            continue;
        }
        let v = q - p;
        let tan = v.y.abs() / v.x.max(f64::MIN_POSITIVE);
        let d = v.length();
        if tan < pick.1 || (tan == pick.1 && d < pick.2) {
            pick = (j, tan, d);
        }
    }
    Some(pick.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(loops: &[Vec<DVec2>], tris: &[[(usize, usize); 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|p| loops[p.0][p.1]);
                (b - a).perp_dot(c - a) / 2.0
            })
            .sum()
    }

    #[test]
    fn a_square_with_two_holes_is_covered_once() {
        let sq = |x: f64, y: f64, s: f64| {
            vec![
                DVec2::new(x, y),
                DVec2::new(x + s, y),
                DVec2::new(x + s, y + s),
                DVec2::new(x, y + s),
            ]
        };
        // Holes wound either way, an island in a hole.
        let mut hole = sq(1.0, 1.0, 3.0);
        hole.reverse();
        let loops = vec![
            sq(0.0, 0.0, 10.0),
            hole,
            sq(6.0, 2.0, 2.0),
            sq(2.0, 2.0, 1.0),
        ];
        let tris = cap(&loops);
        // 100 − 9 − 4 + 1, every triangle counter-clockwise.
        assert!(
            (area(&loops, &tris) - 88.0).abs() < 1e-9,
            "{}",
            area(&loops, &tris)
        );
        for t in &tris {
            let [a, b, c] = t.map(|p| loops[p.0][p.1]);
            assert!((b - a).perp_dot(c - a) >= 0.0);
        }
        // And no point of a hole is covered: a grid of points, by parity
        // of the triangles against the region's own even-odd rule.
        for i in 0..40 {
            for j in 0..40 {
                let q = DVec2::new(0.13 + i as f64 * 0.25, 0.11 + j as f64 * 0.25);
                let covered = tris
                    .iter()
                    .filter(|t| {
                        let [a, b, c] = t.map(|p| loops[p.0][p.1]);
                        let s = |u: DVec2, v: DVec2| (v - u).perp_dot(q - u) > 0.0;
                        s(a, b) && s(b, c) && s(c, a)
                    })
                    .count();
                let want = loops.iter().filter(|l| inside_loop(l, q)).count() % 2;
                assert_eq!(covered, want, "{q}");
            }
        }
    }
}
