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

use glam::{DAffine2, DAffine3, DMat2, DVec2};

/// The plane's part of a space transform, as OpenSCAD applies it to 2-D
/// shapes (`None` when it flattens them: a zero determinant).
pub fn from_space(m: &DAffine3) -> Option<DAffine2> {
    let c = |j: usize| m.matrix3.col(j);
    let a = DMat2::from_cols(c(0).truncate(), c(1).truncate());
    (a.determinant() != 0.0).then(|| DAffine2::from_mat2_translation(a, m.translation.truncate()))
}

/// Closed outlines in the plane, each a list of at least 3 points joined
/// last to first, filled by the even-odd rule.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outlines {
    pub loops: Vec<Vec<DVec2>>,
}

impl Outlines {
    /// Every edge as (start, end).
    pub fn edges(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        self.loops
            .iter()
            .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
    }

    /// Whether point `p` is inside (even-odd; on an edge counts as either).
    pub fn contains(&self, p: DVec2) -> bool {
        let mut inside = false;
        for (a, b) in self.edges() {
            // Half-open in y, so a vertex on the ray is counted once.
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// The sorted spans `(s_in, s_out)` of the line `o + s·d` inside the
    /// region: the parameters where it crosses an edge, paired in order
    /// (even-odd). An edge counts when its ends lie on either side of the
    /// line, one strictly to the left and the other not, so a line through
    /// a vertex counts it once, and a line along an edge holds it when the
    /// region lies to the line's left.
    pub fn spans(&self, o: DVec2, d: DVec2) -> Vec<(f64, f64)> {
        crossings(self.edges(), o, d)
            .chunks_exact(2)
            .map(|c| (c[0].0, c[1].0))
            .filter(|(s0, s1)| s0 < s1)
            .collect()
    }
}

/// Outlines made ready for ray queries: their edges, each with its unit
/// outward normal (the side the region is not on, found once at its
/// middle), and their box.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub outlines: Outlines,
    pub edges: Vec<(DVec2, DVec2)>,
    pub normals: Vec<DVec2>,
    pub lo: DVec2,
    pub hi: DVec2,
}

impl Region {
    pub fn new(outlines: Outlines) -> Region {
        let edges: Vec<(DVec2, DVec2)> = outlines.edges().collect();
        let size = edges
            .iter()
            .map(|(a, b)| a.abs().max(b.abs()).max_element())
            .fold(1e-300, f64::max);
        let normals = edges
            .iter()
            .map(|&(a, b)| {
                let n = (b - a).perp().normalize_or_zero() * -1.0;
                let mid = (a + b) * 0.5;
                // The region lies on one side of a simple edge: the normal
                // points to the other.
                if outlines.contains(mid + n * (1e-9 * size)) {
                    -n
                } else {
                    n
                }
            })
            .collect();
        let (lo, hi) = edges.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), (a, _)| (lo.min(*a), hi.max(*a)),
        );
        Region {
            outlines,
            edges,
            normals,
            lo,
            hi,
        }
    }

    /// Where the line `o + s·d` crosses edges, sorted: `(s, edge)`, by the
    /// rule of [`Outlines::spans`].
    pub fn crossings(&self, o: DVec2, d: DVec2) -> Vec<(f64, u32)> {
        crossings(self.edges.iter().copied(), o, d)
    }
}

/// Where the line `o + s·d` crosses `edges`, sorted: `(s, edge index)`. An
/// edge counts when one end lies strictly left of the line and the other
/// not (see [`Outlines::spans`]).
fn crossings(edges: impl Iterator<Item = (DVec2, DVec2)>, o: DVec2, d: DVec2) -> Vec<(f64, u32)> {
    let n = d.perp(); // the side of the line a point is on: (p − o)·n
    let mut cuts: Vec<(f64, u32)> = Vec::new();
    for (k, (a, b)) in edges.enumerate() {
        let (sa, sb) = ((a - o).dot(n), (b - o).dot(n));
        if (sa > 0.0) == (sb > 0.0) {
            continue;
        }
        // The crossing point of the edge, then its parameter on the line.
        let p = a + (b - a) * (sa / (sa - sb));
        cuts.push(((p - o).dot(d) / d.length_squared(), k as u32));
    }
    cuts.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    cuts
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn square_with_hole() -> Outlines {
        let sq = |c: f64, h: f64| {
            vec![
                DVec2::new(c - h, c - h),
                DVec2::new(c + h, c - h),
                DVec2::new(c + h, c + h),
                DVec2::new(c - h, c + h),
            ]
        };
        Outlines {
            loops: vec![sq(0.0, 2.0), sq(0.0, 1.0)],
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
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
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
