//! CGAL's `Nef_polyhedron_3` text format (`.nef3`, "Selective Nef
//! Complex"), which OpenSCAD 2021.01 imports with CGAL's own reader: the
//! boundary between the volumes it marks as in and out, as triangles.
//!
//! After the header (`Selective Nef Complex`, `standard`, then the counts
//! of vertices, halfedges, facets, volumes, shalfedges, shalfloops and
//! sfaces) each record is a line `i { … | … } mark`, in that order
//! (CGAL's `SNC_io_parser`). Read here: a vertex's point (homogeneous
//! x y z w, each a number or a fraction n/d), a halfedge's vertex, a
//! facet's twin, its cycles (an shalfedge of each) and its volume, a
//! volume's mark, an shalfedge's source halfedge and its `next` along its
//! facet. A facet whose two sides lie in volumes of different marks is on
//! the boundary: its cycles (outer and holes) are walked by `next`, each
//! shalfedge at its source's vertex, and the region they bound (even-odd)
//! triangulated in the plane across its largest normal component.

use super::meshfile::{FileError, MeshFile};
use glam::{DVec2, DVec3};

/// The most records of one kind a file may hold.
pub const MAX_RECORDS: usize = 1 << 24;

/// The kinds of record, in file order, as the header counts them.
const KINDS: [&str; 7] = [
    "vertices",
    "halfedges",
    "facets",
    "volumes",
    "shalfedges",
    "shalfloops",
    "sfaces",
];

fn fail(line: usize, message: impl Into<String>) -> FileError {
    FileError {
        line: Some(line),
        message: message.into(),
    }
}

/// One record: its fields before `|` split at commas, the numbers after
/// `|` (up to `}`: a point, a direction, a plane, a circle — every one read,
/// as CGAL's reader reads it, so that a broken one is found), and its mark
/// after `}`.
struct Record<'a> {
    line: usize,
    fields: Vec<&'a str>,
    numbers: Vec<f64>,
    mark: bool,
}

fn record(line: usize, text: &str) -> Result<Record<'_>, FileError> {
    let bad = || fail(line, "expected a record `i { … } mark`");
    let open = text.find('{').ok_or_else(bad)?;
    let close = text.rfind('}').ok_or_else(bad)?;
    if close < open {
        return Err(bad());
    }
    let inner = &text[open + 1..close];
    let (before, after) = inner.split_once('|').unwrap_or((inner, ""));
    let mark = match text[close + 1..].trim() {
        "1" => true,
        "0" => false,
        _ => return Err(fail(line, "expected a mark of 0 or 1 after `}`")),
    };
    Ok(Record {
        line,
        fields: before.split(',').collect(),
        numbers: after
            .split_whitespace()
            .map(|w| number(line, w))
            .collect::<Result<_, _>>()?,
        mark,
    })
}

impl Record<'_> {
    /// Field `k` as one index below `count`.
    fn index(&self, k: usize, count: usize, what: &str) -> Result<usize, FileError> {
        let f = self
            .fields
            .get(k)
            .ok_or_else(|| fail(self.line, format!("expected the {what}")))?;
        index(
            self.line,
            f.split_whitespace().next().unwrap_or(""),
            count,
            what,
        )
    }

    /// Field `k` as a list of indices below `count` (an isolated
    /// halfedge's two numbers, a facet's cycles).
    fn indices(&self, k: usize, count: usize, what: &str) -> Result<Vec<usize>, FileError> {
        let f = self
            .fields
            .get(k)
            .ok_or_else(|| fail(self.line, format!("expected the {what}")))?;
        f.split_whitespace()
            .map(|w| index(self.line, w, count, what))
            .collect()
    }
}

fn index(line: usize, w: &str, count: usize, what: &str) -> Result<usize, FileError> {
    match w.parse::<usize>() {
        Ok(i) if i < count => Ok(i),
        _ => Err(fail(
            line,
            format!("`{w}` is not the index of one of the {count} {what}"),
        )),
    }
}

/// A coordinate: a decimal number or a fraction n/d.
fn number(line: usize, w: &str) -> Result<f64, FileError> {
    let bad = || fail(line, format!("`{w}` is not a number"));
    let (n, d) = match w.split_once('/') {
        Some((n, d)) => (n, d),
        None => (w, "1"),
    };
    let n: f64 = n.parse().map_err(|_| bad())?;
    let d: f64 = d.parse().map_err(|_| bad())?;
    let x = n / d;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(bad())
    }
}

/// Reads a `.nef3` file.
pub fn read(bytes: &[u8]) -> Result<MeshFile, FileError> {
    let text = std::str::from_utf8(bytes).map_err(|e| fail(1, format!("not text: {e}")))?;
    let last = text.lines().count();
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    let mut next = |what: &str| {
        lines
            .next()
            .ok_or_else(|| fail(last, format!("the file ends before its {what}")))
    };
    let (n, head) = next("header")?;
    if head != "Selective Nef Complex" {
        return Err(fail(n, "expected `Selective Nef Complex`"));
    }
    let (n, kernel) = next("kernel")?;
    if kernel != "standard" {
        return Err(fail(
            n,
            format!("a `{kernel}` Nef complex: expected `standard`"),
        ));
    }
    let mut counts = [0usize; 7];
    for (k, kind) in KINDS.iter().enumerate() {
        let (n, l) = next(kind)?;
        let mut w = l.split_whitespace();
        if w.next() != Some(kind) {
            return Err(fail(n, format!("expected `{kind} N`")));
        }
        counts[k] = match w.next().map(str::parse::<usize>) {
            Some(Ok(c)) if c <= MAX_RECORDS => c,
            _ => {
                return Err(fail(
                    n,
                    format!("expected a count of {kind} up to {MAX_RECORDS}"),
                ))
            }
        };
    }
    let [nv, nh, nf, nvol, nse, _, _] = counts;
    let mut records = Vec::with_capacity(KINDS.len());
    for (k, &c) in counts.iter().enumerate() {
        let mut rs = Vec::with_capacity(c.min(1 << 16));
        for _ in 0..c {
            let (n, l) = next(KINDS[k])?;
            rs.push(record(n, l)?);
        }
        records.push(rs);
    }
    let points = records[0]
        .iter()
        .map(|r| {
            let &[x, y, z, h] = &r.numbers[..] else {
                return Err(fail(r.line, "expected a point `x y z w` after `|`"));
            };
            let p = DVec3::new(x, y, z) / h;
            if p.is_finite() {
                Ok(p)
            } else {
                Err(fail(r.line, "a point with w = 0"))
            }
        })
        .collect::<Result<Vec<DVec3>, FileError>>()?;
    let vertex_of = records[1]
        .iter()
        .map(|r| r.index(1, nv, "vertices"))
        .collect::<Result<Vec<usize>, FileError>>()?;
    let volume_in: Vec<bool> = records[3].iter().map(|r| r.mark).collect();
    // Each shalfedge: (its vertex, the next along its facet).
    let sedges = records[4]
        .iter()
        .map(|r| {
            Ok((
                vertex_of[r.index(3, nh, "halfedges")?],
                r.index(6, nse, "shalfedges")?,
            ))
        })
        .collect::<Result<Vec<(usize, usize)>, FileError>>()?;
    let facets = &records[2];
    let volume = |r: &Record| r.index(r.fields.len().saturating_sub(1), nvol, "volumes");
    let mut faces = Vec::new();
    for (i, r) in facets.iter().enumerate() {
        let twin = r.index(0, nf, "facets")?;
        if twin < i || volume_in[volume(r)?] == volume_in[volume(&facets[twin])?] {
            continue;
        }
        let mut loops: Vec<Vec<usize>> = Vec::new();
        let mut cycles = r.indices(1, nse, "shalfedges")?;
        if crate::mutant::active("nef3_holes_dropped") {
            cycles.truncate(1);
        }
        for start in cycles {
            let mut l = Vec::new();
            let mut e = start;
            loop {
                l.push(sedges[e].0);
                e = sedges[e].1;
                if e == start {
                    break;
                }
                if l.len() > nse {
                    return Err(fail(r.line, "a facet cycle that does not close"));
                }
            }
            split_at_repeats(l, &mut loops);
        }
        // Each loop begun at a point no other loop of the facet shares (the
        // triangulation nests loops by their first points).
        let mut uses = std::collections::HashMap::new();
        for &v in loops.iter().flatten() {
            *uses.entry(v).or_insert(0) += 1;
        }
        for l in &mut loops {
            if let Some(k) = l.iter().position(|v| uses[v] == 1) {
                l.rotate_left(k);
            }
        }
        // The plane's normal: across its largest component.
        let &[a, b, c, _] = &r.numbers[..] else {
            return Err(fail(r.line, "expected a plane `a b c d` after `|`"));
        };
        let n = DVec3::new(a, b, c).abs();
        let k = if n.x >= n.y && n.x >= n.z {
            0
        } else if n.y >= n.z {
            1
        } else {
            2
        };
        let flat = |p: DVec3| match k {
            0 => DVec2::new(p.y, p.z),
            1 => DVec2::new(p.z, p.x),
            _ => DVec2::new(p.x, p.y),
        };
        let plane: Vec<Vec<DVec2>> = loops
            .iter()
            .map(|l| l.iter().map(|&v| flat(points[v])).collect())
            .collect();
        for t in crate::geometry::triangulate::cap(&plane) {
            faces.push(t.iter().map(|&(j, q)| loops[j][q] as u32).collect());
        }
    }
    Ok(MeshFile { points, faces })
}

/// A cycle that passes a vertex twice (a hole touching the outline) as
/// the simple loops it is made of, added to `out`: the even-odd region of
/// those is the cycle's.
fn split_at_repeats(cycle: Vec<usize>, out: &mut Vec<Vec<usize>>) {
    let mut path: Vec<usize> = Vec::with_capacity(cycle.len());
    for v in cycle {
        if let Some(at) = path.iter().position(|&u| u == v) {
            let inner = path.split_off(at + 1);
            if inner.len() >= 2 {
                // Begun after the shared point, which the nesting test of
                // the triangulation would find on the other loop.
                let mut l = inner;
                l.push(v);
                out.push(l);
            }
        } else {
            path.push(v);
        }
    }
    if path.len() >= 3 {
        out.push(path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file of OpenSCAD's suite (`tests/openscad_suite/testdata/nef3/`).
    fn suite_file(name: &str) -> Vec<u8> {
        let dir = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/openscad_suite/testdata/nef3/"
        );
        std::fs::read(format!("{dir}{name}")).unwrap()
    }

    /// A unit cube written as CGAL writes it: the 6 faces of [0, 1]³.
    #[test]
    fn the_suite_cube_is_its_six_faces() {
        let m = read(&suite_file("cube.nef3")).unwrap();
        assert_eq!(m.points.len(), 8);
        assert_eq!(m.faces.len(), 12);
        // Each triangle lies in one face of [-1, 1]³ (the file's cube).
        for f in &m.faces {
            let p: Vec<DVec3> = f.iter().map(|&i| m.points[i as usize]).collect();
            assert!((0..3).any(|k| p.iter().all(|q| q[k] == p[0][k] && q[k].abs() == 1.0)));
        }
    }

    #[test]
    fn a_cycle_touching_itself_is_its_loops() {
        let mut out = Vec::new();
        split_at_repeats(vec![0, 1, 2, 3, 4, 5, 6, 3, 7], &mut out);
        assert_eq!(out, vec![vec![4, 5, 6, 3], vec![0, 1, 2, 3, 7]]);
    }

    #[test]
    fn a_broken_file_is_an_error_at_its_line() {
        let e = read(&suite_file("broken.nef3")).unwrap_err();
        assert_eq!(e.line, Some(20), "{}", e.message);
    }
}
