//! Vertical text (`direction = "ttb"` or `"btt"`) against OpenSCAD 2021.01's
//! own layout: `tests/text/vertical.dxf` is `openscad -o vertical.dxf
//! vertical.scad` (Liberation Sans installed, as Debian's fonts-liberation
//! gives it). Each line of the file is laid out by csgrt and compared both
//! ways with OpenSCAD's outline: every point of csgrt's outlines (the
//! glyphs' on-curve points) has a vertex of OpenSCAD's near it, and every
//! vertex of OpenSCAD's (its flattened curves' points too) lies near
//! csgrt's exact outline. "Near" is FreeType's own rounding: OpenSCAD
//! hints each outline at 2170 ppem and rounds its points to 1/64 pixel;
//! measured, csgrt's points are within 1.0e-4 of the size of OpenSCAD's
//! (each glyph shifted by a few 1e-5 as a whole), so 2e-4 of the size is
//! allowed. A layout off by FreeType's rounded em in its advances (8 units
//! of 26.6 a glyph) fails it after five glyphs. The last line is
//! horizontal, laid out by the same rules.

use csgrt::import::text::{layout, Params};
use csgrt::plane::Curve;
use glam::DVec2;

/// The LINE entities of a DXF drawing, as (start, end).
fn dxf_lines(text: &str) -> Vec<(DVec2, DVec2)> {
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let mut out = Vec::new();
    let (mut a, mut b) = (DVec2::ZERO, DVec2::ZERO);
    let mut in_line = false;
    for pair in lines.chunks_exact(2) {
        let (code, value) = (pair[0], pair[1]);
        let num = || value.parse::<f64>().unwrap();
        match code {
            "0" => {
                if in_line {
                    out.push((a, b));
                }
                in_line = value == "LINE";
            }
            "10" => a.x = num(),
            "20" => a.y = num(),
            "11" => b.x = num(),
            "21" => b.y = num(),
            _ => {}
        }
    }
    out
}

fn params<'a>(text: &'a str, size: f64, direction: &'a str) -> Params<'a> {
    Params {
        text,
        size,
        font: "",
        halign: "left",
        valign: "baseline",
        spacing: 1.0,
        direction,
        language: "en",
        script: "",
    }
}

fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let u = if ab == DVec2::ZERO {
        0.0
    } else {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    };
    (p - a - ab * u).length()
}

#[test]
fn vertical_text_lands_where_openscad_puts_it() {
    let dxf = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/text/vertical.dxf"),
    )
    .unwrap();
    let lines = dxf_lines(&dxf);
    assert!(lines.len() > 500, "{}", lines.len());
    // Each vertical line stands within 30 of its x; the horizontal one
    // below y = -120.
    let lines_of = |dx: f64| -> Vec<(DVec2, DVec2)> {
        lines
            .iter()
            .filter(|(a, _)| {
                if dx < 0.0 {
                    a.y < -120.0
                } else {
                    (a.x - dx).abs() < 30.0 && a.y > -120.0
                }
            })
            .map(|&(a, b)| {
                let at = if dx < 0.0 {
                    DVec2::new(0.0, -150.0)
                } else {
                    DVec2::new(dx, 0.0)
                };
                (a - at, b - at)
            })
            .collect()
    };
    let bold = "Liberation Sans:style=Bold";
    let cases = [
        (0.0, params("AgW", 10.0, "ttb")),
        (60.0, params("AgW", 10.0, "btt")),
        (
            120.0,
            Params {
                halign: "center",
                valign: "center",
                ..params("AgW", 10.0, "ttb")
            },
        ),
        (
            180.0,
            Params {
                halign: "right",
                valign: "top",
                spacing: 1.3,
                ..params("Hi! 7", 8.0, "ttb")
            },
        ),
        (
            240.0,
            Params {
                valign: "bottom",
                font: bold,
                ..params("fjord", 12.0, "ttb")
            },
        ),
        (-1.0, params("The quick brown fox jumps over", 10.0, "ltr")),
    ];
    for (dx, p) in cases {
        let tol = 2e-4 * p.size;
        let laid = layout(&p);
        assert!(laid.warnings.is_empty(), "{:?}", laid.warnings);
        let theirs = lines_of(dx);
        assert!(!theirs.is_empty());
        // csgrt's edges, curves sampled finely (their chords within 1e-7).
        let mut ours: Vec<(DVec2, DVec2)> = Vec::new();
        let mut points = Vec::new();
        for o in &laid.glyphs {
            for (a, c, b) in o.edges() {
                points.push(a);
                let curve = Curve::new(a, c, b, DVec2::ZERO);
                let steps = if curve.degree == 1 { 1 } else { 400 };
                for i in 0..steps {
                    let (u0, u1) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
                    ours.push((curve.at(u0), curve.at(u1)));
                }
            }
        }
        let mut worst: f64 = 0.0;
        for q in &points {
            let d = theirs
                .iter()
                .map(|(a, b)| (*q - *a).length().min((*q - *b).length()))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
            assert!(d <= tol, "{p:?}: csgrt's point {q} is {d} from OpenSCAD's");
        }
        for (a, _) in &theirs {
            let d = ours
                .iter()
                .map(|(u, v)| segment_distance(*a, *u, *v))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
            assert!(
                d <= tol,
                "{p:?}: OpenSCAD's point {a} is {d} from csgrt's outline"
            );
        }
        eprintln!(
            "{} {}: worst {worst:.3e} of size {}",
            p.text, p.direction, p.size
        );
    }
}
