//! `import()` of an SVG drawing as OpenSCAD 2021.01 reads one
//! (`import_svg.cc` over its own `libsvg/`), with its curves kept exact.
//!
//! What OpenSCAD reads: the `path`, `rect` (round corners as arcs),
//! `circle`, `ellipse`, `line`, `polyline` and `polygon` elements outside
//! `defs`, each under its own `transform` and its groups' (not an
//! `svg`'s; an `svg` inside the drawing as libsvg's stack leaves it, see
//! [`read`]). Fill and stroke colours are not looked at: every closed
//! outline is filled, and an open one — a `line`, a `polyline`, or a
//! path's subpath whose ends lie more than 0.1 apart (when the path never
//! closes with `z`, only those ended by a later `M`) — is stroked instead,
//! by Clipper's offset of the polyline (`stroke-width`, default 1 where it
//! is under 0.01; `stroke-linecap` butt, round or square, default square;
//! `stroke-linejoin` miter with Clipper's limit of 2, round, or bevel read
//! as Clipper's square join), in the element's own coordinates before its
//! transform. One element's outlines are combined by the even-odd rule,
//! the elements by union. `text`, `use`, `image` and the rest draw nothing.
//! The page: `width` and `height` in mm (`px` at 96 per inch, a bare number
//! at `dpi`, default 72), the `viewBox` mapped onto them under
//! `preserveAspectRatio`; without a `viewBox` a user unit is a millimetre
//! (the last `svg` element's page places the drawing).
//! y points down in the file and up in OpenSCAD: a point v of the file
//! lands at (sx·(v.x − vx), sy·(−vy − v.y) + h) less the alignment, or
//! about the centre of the drawing's box with `center`.
//!
//! OpenSCAD cuts curves into 20 pieces, arcs into |Δθ|·10/180 + 4 and
//! circles into 40, and rounds strokes to a 10⁻⁴ grid; csgrt keeps lines,
//! quadratic and cubic Bézier curves, elliptical arcs and ellipses as they
//! are, and strokes as the exact region Clipper's offset approximates. The
//! box that `center` uses is OpenSCAD's own, of its cut-up points, so that
//! a centred drawing lands where OpenSCAD puts it. The XML is read by
//! `roxmltree`, path data, transforms, lengths and view boxes by
//! `svgtypes`.

use glam::{DAffine2, DMat2, DVec2};

/// The farthest a point of a drawing may lie from the origin, placed
/// (csgrt's limit on sizes and positions).
pub const MAX_SVG_COORD: f64 = crate::geometry::transform::MAX_MAGNITUDE;

/// The most elements, and the most path segments, a drawing may have.
pub const MAX_ELEMENTS: usize = 100_000;
pub const MAX_SEGMENTS: usize = 1_000_000;

/// How a stroke ends (Clipper's end types).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cap {
    Butt,
    Round,
    Square,
}

/// How a stroke turns a corner (Clipper's join types; SVG's `bevel` is
/// Clipper's square join in libsvg).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SvgJoin {
    Miter,
    Round,
    Square,
}

/// An open polyline stroked to `width`.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgStroke {
    pub pts: Vec<DVec2>,
    pub width: f64,
    pub cap: Cap,
    pub join: SvgJoin,
}

/// A piece of a stroke's region: a convex polygon or a disc.
#[derive(Clone, Debug, PartialEq)]
pub enum SvgPiece {
    Polygon(Vec<DVec2>),
    Disc(DVec2, f64),
}

impl SvgStroke {
    /// The exact region of Clipper's open offset of the polyline by half
    /// its width, as pieces to unite: the band of each segment, the ends
    /// (square: the band carried on by half the width; round: a disc; butt:
    /// nothing) and at each corner, on its outer side, the join — a disc
    /// (round), the miter kite where the turn is at most 120° (Clipper's
    /// limit, 1 + cos θ ≥ 2/2², for libsvg's default miter limit 2), else
    /// the kite cut square across the corner's bisector at half the width
    /// (Clipper's `DoSquare`, also the `bevel` join libsvg maps to it). A
    /// reversal is squared like an end. None for fewer than two distinct
    /// points.
    pub fn pieces(&self) -> Vec<SvgPiece> {
        let st = self;
        let mut pts: Vec<DVec2> = Vec::with_capacity(st.pts.len());
        for &p in &st.pts {
            if pts.last() != Some(&p) {
                pts.push(p);
            }
        }
        if pts.len() < 2 {
            return Vec::new();
        }
        let r = 0.5 * st.width;
        let poly = SvgPiece::Polygon;
        let mut out = Vec::new();
        let dirs: Vec<DVec2> = pts.windows(2).map(|w| (w[1] - w[0]).normalize()).collect();
        for (w, &t) in pts.windows(2).zip(&dirs) {
            let n = t.perp() * r;
            out.push(poly(vec![w[0] - n, w[1] - n, w[1] + n, w[0] + n]));
        }
        // An end at p, the stroke running away from it along -t.
        let end = |p: DVec2, t: DVec2, out: &mut Vec<SvgPiece>| match st.cap {
            Cap::Butt => {}
            Cap::Round => out.push(SvgPiece::Disc(p, r)),
            Cap::Square => {
                let n = t.perp() * r;
                out.push(poly(vec![p - n, p + t * r - n, p + t * r + n, p + n]));
            }
        };
        end(pts[0], -dirs[0], &mut out);
        end(pts[pts.len() - 1], dirs[dirs.len() - 1], &mut out);
        for (i, w) in dirs.windows(2).enumerate() {
            let (p, t1, t2) = (pts[i + 1], w[0], w[1]);
            let (cross, cos) = (t1.perp_dot(t2), t1.dot(t2));
            if cross == 0.0 && cos > 0.0 {
                continue;
            }
            if st.join == SvgJoin::Round {
                out.push(SvgPiece::Disc(p, r));
                continue;
            }
            if cross == 0.0 {
                // A reversal: squared like an end.
                let n = t1.perp() * r;
                out.push(poly(vec![p - n, p + t1 * r - n, p + t1 * r + n, p + n]));
                continue;
            }
            // The outer side's normals (the side the path turns away from).
            let side = if cross > 0.0 { -1.0 } else { 1.0 };
            let (m1, m2) = (t1.perp() * side, t2.perp() * side);
            // The turn θ between the normals: cos θ = cos of the directions.
            if st.join == SvgJoin::Miter && 1.0 + cos >= 0.5 {
                let miter = p + (m1 + m2) * (r / (1.0 + cos));
                out.push(poly(vec![p, p + m1 * r, miter, p + m2 * r]));
            } else {
                // Cut at distance r along the bisector: r·tan(θ/4) along each
                // offset line past its corner point.
                let s = r * (0.25 * cross.abs().atan2(cos)).tan();
                out.push(poly(vec![
                    p,
                    p + m1 * r,
                    p + m1 * r + t1 * s,
                    p + m2 * r - t2 * s,
                    p + m2 * r,
                ]));
            }
        }
        out
    }
}

/// How an edge of a closed outline runs to the next point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seg {
    Line,
    Quad(DVec2),
    Cubic(DVec2, DVec2),
    /// Along the ellipse (the image of the unit circle), through `mid`, a
    /// point of the arc strictly between its ends.
    Arc {
        ellipse: DAffine2,
        mid: DVec2,
    },
}

/// A closed outline: edge i runs from `pts[i]` to the next point (the last
/// back to the first) as `segs[i]` says.
#[derive(Clone, Debug, PartialEq)]
pub struct Loop {
    pub pts: Vec<DVec2>,
    pub segs: Vec<Seg>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum SvgPart {
    Loop(Loop),
    /// A `circle` or `ellipse`: the image of the unit disc.
    Ellipse(DAffine2),
    Stroke(SvgStroke),
}

/// One element's outlines (even-odd), in its own coordinates, and the
/// transform that places them in the page's user space.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgShape {
    pub element: String,
    pub line: usize,
    pub parts: Vec<SvgPart>,
    pub transform: DAffine2,
}

/// A drawing's shapes and the map from user space to OpenSCAD's plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Svg {
    pub shapes: Vec<SvgShape>,
    pub place: DAffine2,
    /// The elements left out (drawing nothing in OpenSCAD), by name.
    pub skipped: Vec<(String, usize)>,
}

/// What is wrong with a file, and on which line.
#[derive(Clone, Debug, PartialEq)]
pub struct SvgError {
    pub line: Option<usize>,
    pub message: String,
}

fn fail(line: usize, message: impl Into<String>) -> SvgError {
    SvgError {
        line: Some(line),
        message: message.into(),
    }
}

/// libsvg's `parse_double`: the whole text a number, or 0.
fn number(s: &str) -> f64 {
    s.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .unwrap_or(0.0)
}

/// libsvg's `get_style`: the value of `name` in a `style` attribute
/// (`a:b;c:d`, nothing trimmed), or "".
fn style<'a>(style: &'a str, name: &str) -> &'a str {
    for item in style.split(';') {
        let kv: Vec<&str> = item.split(':').collect();
        if kv.len() == 2 && kv[0] == name {
            return kv[1];
        }
    }
    ""
}

/// An attribute, or its value in `style` when absent (libsvg's order).
fn attr_or_style<'a>(n: &roxmltree::Node<'a, 'a>, name: &str) -> &'a str {
    match n.attribute(name) {
        Some(v) if !v.is_empty() => v,
        _ => style(n.attribute("style").unwrap_or(""), name),
    }
}

fn stroke_of(n: &roxmltree::Node, pts: Vec<DVec2>) -> SvgStroke {
    let w = number(attr_or_style(n, "stroke-width"));
    let cap = match attr_or_style(n, "stroke-linecap") {
        "butt" => Cap::Butt,
        "round" => Cap::Round,
        _ => Cap::Square,
    };
    let join = match attr_or_style(n, "stroke-linejoin") {
        "bevel" => SvgJoin::Square,
        "round" => SvgJoin::Round,
        _ => SvgJoin::Miter,
    };
    SvgStroke {
        pts,
        width: if w < 0.01 { 1.0 } else { w },
        cap,
        join,
    }
}

/// The arc of the SVG endpoint form from `a` to `b` (SVG 1.1 F.6.5, as
/// libsvg's `arc_to`: radii too small for the ends grown to fit), or
/// `None` where the spec draws a line (a zero radius) or nothing (equal
/// ends).
fn arc(a: DVec2, b: DVec2, r: DVec2, rot_deg: f64, large: bool, sweep: bool) -> Option<Seg> {
    let (mut rx, mut ry) = (r.x.abs(), r.y.abs());
    if a == b {
        return None;
    }
    if rx == 0.0 || ry == 0.0 {
        return Some(Seg::Line);
    }
    let rot = DMat2::from_angle(rot_deg.to_radians());
    let p = rot.transpose() * ((a - b) * 0.5);
    let lambda = (p.x * p.x) / (rx * rx) + (p.y * p.y) / (ry * ry);
    if lambda > 1.0 {
        let k = lambda.sqrt();
        rx *= k;
        ry *= k;
    }
    let num = rx * rx * ry * ry - rx * rx * p.y * p.y - ry * ry * p.x * p.x;
    let den = rx * rx * p.y * p.y + ry * ry * p.x * p.x;
    let mut k = (num.max(0.0) / den).sqrt();
    if large == sweep {
        k = -k;
    }
    let c1 = DVec2::new(k * rx * p.y / ry, -k * ry * p.x / rx);
    let center = rot * c1 + (a + b) * 0.5;
    let u = DVec2::new((p.x - c1.x) / rx, (p.y - c1.y) / ry);
    let v = DVec2::new((-p.x - c1.x) / rx, (-p.y - c1.y) / ry);
    let theta = u.y.atan2(u.x);
    let mut delta = v.y.atan2(v.x) - theta;
    if sweep && delta < 0.0 {
        delta += std::f64::consts::TAU;
    } else if !sweep && delta > 0.0 {
        delta -= std::f64::consts::TAU;
    }
    let ellipse =
        DAffine2::from_mat2_translation(rot * DMat2::from_diagonal(DVec2::new(rx, ry)), center);
    let m = theta + 0.5 * delta;
    let mid = ellipse.transform_point2(DVec2::new(m.cos(), m.sin()));
    (ellipse.matrix2.determinant() != 0.0 && mid.is_finite()).then_some(Seg::Arc { ellipse, mid })
}

/// A subpath being read: its points and edges, and whether it ended with
/// `z`.
#[derive(Default)]
struct Sub {
    pts: Vec<DVec2>,
    segs: Vec<Seg>,
}

impl Sub {
    fn to(&mut self, seg: Seg, p: DVec2) {
        self.segs.push(seg);
        self.pts.push(p);
    }
}

/// The parts of a `path`'s data (see the module comment for what is
/// stroked).
fn path_parts(
    n: &roxmltree::Node,
    d: &str,
    line: usize,
    segments: &mut usize,
) -> Result<Vec<SvgPart>, SvgError> {
    use svgtypes::PathSegment as P;
    let mut parts = Vec::new();
    let mut subs: Vec<(Sub, bool)> = Vec::new();
    let mut cur = Sub::default();
    let (mut x, mut start) = (DVec2::ZERO, DVec2::ZERO);
    // The last control point, for the smooth forms (S after C or S, T
    // after Q or T).
    let (mut last_cubic, mut last_quad): (Option<DVec2>, Option<DVec2>) = (None, None);
    let mut closed_any = false;
    let flush = |cur: &mut Sub, subs: &mut Vec<(Sub, bool)>, closed: bool| {
        let s = std::mem::take(cur);
        if !s.pts.is_empty() {
            subs.push((s, closed));
        }
    };
    for seg in svgtypes::PathParser::from(d) {
        let seg = seg.map_err(|e| fail(line, format!("`path` data: {e}")))?;
        *segments += 1;
        if *segments > MAX_SEGMENTS {
            return Err(fail(
                line,
                format!("more than {MAX_SEGMENTS} path segments"),
            ));
        }
        let at = |abs: bool, px: f64, py: f64| {
            if abs {
                DVec2::new(px, py)
            } else {
                x + DVec2::new(px, py)
            }
        };
        if cur.pts.is_empty() && !matches!(seg, P::MoveTo { .. }) {
            // A subpath goes on from the current point (after `z`, the
            // start of the one it closed).
            cur.pts.push(x);
        }
        let (mut cubic, mut quad) = (None, None);
        match seg {
            P::MoveTo { abs, x: px, y: py } => {
                flush(&mut cur, &mut subs, false);
                x = at(abs, px, py);
                start = x;
                cur.pts.push(x);
            }
            P::LineTo { abs, x: px, y: py } => {
                x = at(abs, px, py);
                cur.to(Seg::Line, x);
            }
            P::HorizontalLineTo { abs, x: px } => {
                x = DVec2::new(if abs { px } else { x.x + px }, x.y);
                cur.to(Seg::Line, x);
            }
            P::VerticalLineTo { abs, y: py } => {
                x = DVec2::new(x.x, if abs { py } else { x.y + py });
                cur.to(Seg::Line, x);
            }
            P::CurveTo {
                abs,
                x1,
                y1,
                x2,
                y2,
                x: px,
                y: py,
            } => {
                let (c1, c2) = (at(abs, x1, y1), at(abs, x2, y2));
                x = at(abs, px, py);
                cur.to(Seg::Cubic(c1, c2), x);
                cubic = Some(c2);
            }
            P::SmoothCurveTo {
                abs,
                x2,
                y2,
                x: px,
                y: py,
            } => {
                let c1 = last_cubic.map_or(x, |c| x + (x - c));
                let c2 = at(abs, x2, y2);
                x = at(abs, px, py);
                cur.to(Seg::Cubic(c1, c2), x);
                cubic = Some(c2);
            }
            P::Quadratic {
                abs,
                x1,
                y1,
                x: px,
                y: py,
            } => {
                let c = at(abs, x1, y1);
                x = at(abs, px, py);
                cur.to(Seg::Quad(c), x);
                quad = Some(c);
            }
            P::SmoothQuadratic { abs, x: px, y: py } => {
                let c = last_quad.map_or(x, |q| x + (x - q));
                x = at(abs, px, py);
                cur.to(Seg::Quad(c), x);
                quad = Some(c);
            }
            P::EllipticalArc {
                abs,
                rx,
                ry,
                x_axis_rotation,
                large_arc,
                sweep,
                x: px,
                y: py,
            } => {
                let b = at(abs, px, py);
                if let Some(s) = arc(x, b, DVec2::new(rx, ry), x_axis_rotation, large_arc, sweep) {
                    cur.to(s, b);
                }
                x = b;
            }
            P::ClosePath { .. } => {
                x = start;
                closed_any = true;
                flush(&mut cur, &mut subs, true);
            }
        }
        last_cubic = cubic;
        last_quad = quad;
    }
    flush(&mut cur, &mut subs, false);
    let last = subs.len();
    for (i, (s, closed)) in subs.into_iter().enumerate() {
        let (a, b) = (s.pts[0], *s.pts.last().unwrap());
        // libsvg strokes a subpath whose ends lie apart, but the last one
        // only in a path that never closes.
        let open = !closed && (a - b).length() > 0.1 && (i + 1 < last || !closed_any);
        if open {
            // libsvg strokes the line through its points of the curves
            // (OpenSCAD's own stroke: its faceting is the meaning).
            let mut pts = vec![s.pts[0]];
            for (i, seg) in s.segs.iter().enumerate() {
                if crate::mutant::active("svg_stroke_chords") {
                    pts.push(s.pts[i + 1]);
                } else {
                    libsvg_steps(s.pts[i], *seg, s.pts[i + 1], &mut pts);
                }
            }
            parts.push(SvgPart::Stroke(stroke_of(n, pts)));
            continue;
        }
        // Closed: the last point back to the first by a straight edge
        // (none where they meet).
        let (mut pts, mut segs) = (s.pts, s.segs);
        if pts.len() > 1 && pts[0] == *pts.last().unwrap() {
            pts.pop();
        } else {
            segs.push(Seg::Line);
        }
        if !pts.is_empty() {
            parts.push(SvgPart::Loop(Loop { pts, segs }));
        }
    }
    Ok(parts)
}

/// The points of a `points` attribute (pairs of numbers; an odd last one
/// dropped).
fn points(s: &str) -> Vec<DVec2> {
    let nums: Vec<f64> = s
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(number)
        .collect();
    nums.chunks_exact(2)
        .map(|c| DVec2::new(c[0], c[1]))
        .collect()
}

/// A `rect`'s outline: a square-cornered loop, or libsvg's path of four
/// quarter arcs (rx, ry filled in from each other and capped at half the
/// sides).
fn rect_parts(
    n: &roxmltree::Node,
    line: usize,
    segments: &mut usize,
) -> Result<Vec<SvgPart>, SvgError> {
    let g = |k: &str| number(n.attribute(k).unwrap_or(""));
    let (x, y, w, h) = (g("x"), g("y"), g("width"), g("height"));
    let (mut rx, mut ry) = (g("rx"), g("ry"));
    let (has_rx, has_ry) = (rx.abs() >= 1e-8, ry.abs() >= 1e-8);
    if has_rx || has_ry {
        if !has_rx {
            rx = ry;
        } else if !has_ry {
            ry = rx;
        }
        rx = rx.min(w / 2.0);
        ry = ry.min(h / 2.0);
        let d = format!(
            "M {} {} H {} A {rx} {ry} 0 0 1 {} {} V {} A {rx} {ry} 0 0 1 {} {} H {} A {rx} {ry} 0 0 1 {} {} V {} A {rx} {ry} 0 0 1 {} {} z",
            x + rx, y, x + w - rx, x + w, y + ry, y + h - ry, x + w - rx, y + h, x + rx, x, y + h - ry, y + ry, x + rx, y
        );
        return path_parts(n, &d, line, segments);
    }
    let pts = vec![
        DVec2::new(x, y),
        DVec2::new(x + w, y),
        DVec2::new(x + w, y + h),
        DVec2::new(x, y + h),
    ];
    Ok(vec![SvgPart::Loop(Loop {
        segs: vec![Seg::Line; 4],
        pts,
    })])
}

/// The element's own `transform` (identity when absent or malformed, as
/// libsvg leaves a list it cannot read).
fn transform_of(n: &roxmltree::Node, line: usize) -> Result<DAffine2, SvgError> {
    let Some(t) = n.attribute("transform") else {
        return Ok(DAffine2::IDENTITY);
    };
    let t: svgtypes::Transform = t
        .parse()
        .map_err(|e| fail(line, format!("`transform`: {e}")))?;
    Ok(DAffine2::from_cols_array(&[t.a, t.b, t.c, t.d, t.e, t.f]))
}

/// libsvg's `to_mm` of a page length.
fn to_mm(l: Option<svgtypes::Length>, viewbox: Option<f64>, dpi: f64) -> f64 {
    use svgtypes::LengthUnit as U;
    const INCH: f64 = 25.4;
    match l {
        None => viewbox.map_or(0.0, |v| INCH * v / dpi),
        Some(l) => match l.unit {
            U::None => INCH * l.number / dpi,
            U::Px => INCH * l.number / 96.0,
            U::Pt => INCH * l.number / 72.0,
            U::Pc => INCH * l.number / 6.0,
            U::In => INCH * l.number,
            U::Cm => 10.0 * l.number,
            U::Mm => l.number,
            _ => viewbox.unwrap_or(0.0),
        },
    }
}

/// OpenSCAD's points of a part, cut up as libsvg cuts them (for the box
/// that `center` takes): 20 steps a curve, |Δθ|·10/180 + 4 an arc, 40 an
/// ellipse; a stroke by its pieces' corners and its discs' points every
/// half degree (Clipper cuts them into hundreds of pieces).
fn openscad_points(p: &SvgPart, out: &mut Vec<DVec2>) {
    match p {
        SvgPart::Ellipse(e) => (1..=40).for_each(|i| {
            let a = (i as f64 * 9.0).to_radians();
            out.push(e.transform_point2(DVec2::new(a.cos(), a.sin())));
        }),
        SvgPart::Loop(l) => {
            for (i, seg) in l.segs.iter().enumerate() {
                let (a, b) = (l.pts[i], l.pts[(i + 1) % l.pts.len()]);
                out.push(a);
                libsvg_steps(a, *seg, b, out);
            }
        }
        SvgPart::Stroke(s) => {
            for piece in s.pieces() {
                match piece {
                    SvgPiece::Polygon(v) => out.extend(v),
                    // Clipper's round parts are within 10⁻⁴ of the circle:
                    // points every half degree are too.
                    SvgPiece::Disc(c, r) => out.extend((0..720).map(|i| {
                        let (sn, cs) = (i as f64 * 0.5).to_radians().sin_cos();
                        c + DVec2::new(cs, sn) * r
                    })),
                }
            }
        }
    }
}

/// The points after `a` up to `b` of the edge `seg` from `a` to `b`, as
/// libsvg cuts it up: 20 steps a curve, |Δθ|·10/180 + 4 an arc, none a line
/// (`b` alone).
fn libsvg_steps(a: DVec2, seg: Seg, b: DVec2, out: &mut Vec<DVec2>) {
    match seg {
        Seg::Line => out.push(b),
        Seg::Quad(c) => (1..=20).for_each(|k| {
            let u = k as f64 / 20.0;
            out.push(a * (1.0 - u).powi(2) + c * 2.0 * (1.0 - u) * u + b * u * u);
        }),
        Seg::Cubic(c1, c2) => (1..=20).for_each(|k| {
            let u = k as f64 / 20.0;
            let v = 1.0 - u;
            out.push(a * v * v * v + c1 * 3.0 * v * v * u + c2 * 3.0 * v * u * u + b * u * u * u);
        }),
        Seg::Arc { ellipse, mid } => {
            let inv = ellipse.inverse();
            let ang = |p: DVec2| {
                let q = inv.transform_point2(p);
                q.y.atan2(q.x)
            };
            let (t0, tm, t1) = (ang(a), ang(mid), ang(b));
            // The sweep from t0 through tm to t1.
            let tau = std::f64::consts::TAU;
            let fwd = (t1 - t0).rem_euclid(tau);
            let delta = if (tm - t0).rem_euclid(tau) < fwd {
                fwd
            } else {
                fwd - tau
            };
            let steps = (delta.abs().to_degrees() * 10.0 / 180.0 + 4.0) as usize;
            for k in 1..=steps {
                let t = t0 + delta * k as f64 / steps as f64;
                out.push(ellipse.transform_point2(DVec2::new(t.cos(), t.sin())));
            }
        }
    }
}

/// The elements under (and with) `root` as the tags a stream reader meets:
/// each opened (`true`) in document order and closed (`false`) after its
/// children.
fn tags<'a, 'i>(root: roxmltree::Node<'a, 'i>) -> Vec<(roxmltree::Node<'a, 'i>, bool)> {
    let mut out = Vec::new();
    let mut open: Vec<roxmltree::Node> = Vec::new();
    for n in root.descendants().filter(|n| n.is_element()) {
        while let Some(&top) = open.last() {
            if n.parent() == Some(top) {
                break;
            }
            out.push((top, false));
            open.pop();
        }
        out.push((n, true));
        open.push(n);
    }
    out.extend(open.into_iter().rev().map(|n| (n, false)));
    out
}

/// The page an `svg` element sets in libsvg's reading: its height in mm,
/// and — only where it has a `viewBox`, else those of the one before
/// stay — the scale and origin of the box's units (and the alignment,
/// where `preserveAspectRatio` aligns).
#[derive(Clone, Copy, Debug)]
struct Page {
    height: f64,
    scale: DVec2,
    align: DVec2,
    origin: DVec2,
}

impl Default for Page {
    fn default() -> Self {
        Page {
            height: 0.0,
            scale: DVec2::ONE,
            align: DVec2::ZERO,
            origin: DVec2::ZERO,
        }
    }
}

impl Page {
    /// `import_svg.cc`'s reading of one `svg` element `n` at `dpi`.
    fn set(&mut self, n: &roxmltree::Node, dpi: f64, line: usize) -> Result<(), SvgError> {
        let length = |k: &str| {
            n.attribute(k)
                .and_then(|v| v.parse::<svgtypes::Length>().ok())
        };
        let vb = match n.attribute("viewBox") {
            Some(v) => Some(
                v.parse::<svgtypes::ViewBox>()
                    .map_err(|e| fail(line, format!("`viewBox`: {e}")))?,
            ),
            None => None,
        };
        let width = to_mm(length("width"), vb.map(|v| v.w), dpi);
        let height = to_mm(length("height"), vb.map(|v| v.h), dpi);
        self.height = height;
        let Some(v) = vb else {
            return Ok(());
        };
        self.origin = DVec2::new(v.x, v.y);
        self.scale = DVec2::new(width / v.w, height / v.h);
        let ar: svgtypes::AspectRatio = n
            .attribute("preserveAspectRatio")
            .and_then(|a| a.parse().ok())
            .unwrap_or_default();
        use svgtypes::Align as A;
        let (ax, ay) = match ar.align {
            A::None => return Ok(()),
            A::XMinYMin => (0, 0),
            A::XMidYMin => (1, 0),
            A::XMaxYMin => (2, 0),
            A::XMinYMid => (0, 1),
            A::XMidYMid => (1, 1),
            A::XMaxYMid => (2, 1),
            A::XMinYMax => (0, 2),
            A::XMidYMax => (1, 2),
            A::XMaxYMax => (2, 2),
        };
        let k = if ar.slice {
            self.scale.x.max(self.scale.y)
        } else {
            self.scale.x.min(self.scale.y)
        };
        self.scale = DVec2::splat(k);
        let at = |a: u8, page: f64, vbs: f64| match a {
            1 => page / 2.0 - k * vbs / 2.0,
            2 => page - k * vbs,
            _ => 0.0,
        };
        self.align = DVec2::new(at(ax, width, v.w), at(ay, height, v.h));
        Ok(())
    }
}

/// Reads `bytes` (an SVG file) at `dpi`, centred on its box with `center`.
pub fn read(bytes: &[u8], dpi: f64, center: bool) -> Result<Svg, SvgError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&c| c == b'\n')
            .count()
            + 1;
        fail(line, "the file is not UTF-8 text")
    })?;
    let opts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, opts).map_err(|e| SvgError {
        line: Some(e.pos().row as usize),
        message: e.to_string(),
    })?;
    let root = doc.root_element();
    let line_of = |n: roxmltree::Node| doc.text_pos_at(n.range().start).row as usize;
    if root.tag_name().name() != "svg" {
        return Err(fail(line_of(root), "the root element is not `svg`"));
    }
    // libsvg reads the drawing as a stream of tags, with a stack of
    // containers (`svg`, `g`, `text`, `tspan`) whose transforms a shape
    // takes (an `svg`'s own is none); the end of a `g`, `text` or `tspan`
    // pops the stack's top, whatever it is, and the end of an `svg`
    // nothing — so an `svg` inside the drawing stays on it, and its
    // parent `g`'s end pops it instead. Each `svg`, in document order,
    // sets the page afresh ([`Page::set`]): the last one places the
    // whole drawing (its box for `center` scales each shape by the
    // page set before it).
    let mut page = Page::default();
    let mut stack: Vec<DAffine2> = Vec::new();
    let mut scales: Vec<DVec2> = Vec::new();
    let mut shapes = Vec::new();
    let mut skipped: Vec<(String, usize)> = Vec::new();
    let mut segments = 0usize;
    let mut defs = 0usize;
    for (n, open) in tags(root) {
        let name = n.tag_name().name();
        if name == "defs" {
            if open {
                defs += 1;
            } else {
                defs = defs.saturating_sub(1);
            }
            continue;
        }
        if defs > 0 {
            continue;
        }
        if !open {
            // The fault: a balanced reader's stack.
            if matches!(name, "g" | "text" | "tspan")
                || name == "svg" && crate::mutant::active("svg_nested_popped")
            {
                stack.pop();
            }
            continue;
        }
        let line = line_of(n);
        if shapes.len() >= MAX_ELEMENTS {
            return Err(fail(line, format!("more than {MAX_ELEMENTS} elements")));
        }
        let top = stack.last().copied().unwrap_or(DAffine2::IDENTITY);
        match name {
            "svg" => {
                page.set(&n, dpi, line)?;
                stack.push(top);
                continue;
            }
            "g" | "text" | "tspan" => {
                stack.push(top * transform_of(&n, line)?);
                if name == "g" {
                    continue;
                }
            }
            _ => {}
        }
        let g = |k: &str| number(n.attribute(k).unwrap_or(""));
        let parts = match name {
            "path" => path_parts(&n, n.attribute("d").unwrap_or(""), line, &mut segments)?,
            "rect" => rect_parts(&n, line, &mut segments)?,
            "circle" | "ellipse" => {
                let (rx, ry) = if name == "circle" {
                    (g("r"), g("r"))
                } else {
                    (g("rx"), g("ry"))
                };
                let e = DAffine2::from_mat2_translation(
                    DMat2::from_diagonal(DVec2::new(rx, ry)),
                    DVec2::new(g("cx"), g("cy")),
                );
                if e.matrix2.determinant() == 0.0 {
                    Vec::new()
                } else {
                    vec![SvgPart::Ellipse(e)]
                }
            }
            "line" => vec![SvgPart::Stroke(stroke_of(
                &n,
                vec![DVec2::new(g("x1"), g("y1")), DVec2::new(g("x2"), g("y2"))],
            ))],
            "polyline" => vec![SvgPart::Stroke(stroke_of(
                &n,
                points(n.attribute("points").unwrap_or("")),
            ))],
            "polygon" => {
                let pts = points(n.attribute("points").unwrap_or(""));
                vec![SvgPart::Loop(Loop {
                    segs: vec![Seg::Line; pts.len()],
                    pts,
                })]
            }
            // What draws in an SVG viewer but not in OpenSCAD.
            other @ ("text" | "use" | "image" | "foreignObject") => {
                match skipped.iter_mut().find(|(k, _)| k == other) {
                    Some((_, c)) => *c += 1,
                    None => skipped.push((other.to_string(), 1)),
                }
                continue;
            }
            _ => continue,
        };
        shapes.push(SvgShape {
            element: name.to_string(),
            line,
            parts,
            transform: top * transform_of(&n, line)?,
        });
        scales.push(page.scale);
    }
    let Page {
        height,
        scale,
        align,
        origin,
    } = page;
    // OpenSCAD's placement: its box is of the cut-up points, scaled.
    let (cx, cy) = if center {
        let mut pts = Vec::new();
        for (s, &k) in shapes.iter().zip(&scales) {
            let start = pts.len();
            s.parts.iter().for_each(|p| openscad_points(p, &mut pts));
            pts[start..]
                .iter_mut()
                .for_each(|q| *q = s.transform.transform_point2(*q) * k);
        }
        let lo = pts.iter().fold(DVec2::INFINITY, |a, &b| a.min(b));
        let hi = pts.iter().fold(DVec2::NEG_INFINITY, |a, &b| a.max(b));
        let c = if pts.is_empty() {
            DVec2::ZERO
        } else {
            0.5 * (lo + hi)
        };
        (c.x, c.y)
    } else {
        (-align.x, height - align.y)
    };
    // x' = sx·(x − vx) − cx, y' = sy·(−vy − y) + cy.
    let place = DAffine2::from_mat2_translation(
        DMat2::from_diagonal(DVec2::new(scale.x, -scale.y)),
        DVec2::new(-scale.x * origin.x - cx, -scale.y * origin.y + cy),
    );
    // Every point where OpenSCAD would put it, finite and in range.
    for s in &shapes {
        let mut pts = Vec::new();
        s.parts.iter().for_each(|p| openscad_points(p, &mut pts));
        let m = place * s.transform;
        let far = |q: DVec2| q.is_nan() || q.abs().max_element() > MAX_SVG_COORD;
        if far(m.matrix2.x_axis)
            || far(m.matrix2.y_axis)
            || pts.into_iter().any(|q| far(m.transform_point2(q)))
        {
            return Err(fail(
                s.line,
                format!(
                    "a point of this `{}` lies out of range (beyond ±{MAX_SVG_COORD:e})",
                    s.element
                ),
            ));
        }
    }
    Ok(Svg {
        shapes,
        place,
        skipped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(svg: &str) -> Svg {
        read(svg.as_bytes(), 72.0, false).unwrap()
    }

    #[test]
    fn a_quarter_arc_has_its_centre_and_passes_through_its_middle() {
        // From (1, 0) to (0, 1) on the unit circle about the origin, the
        // short way, counter-clockwise in the file's y-down frame.
        let Some(Seg::Arc { ellipse, mid }) = arc(DVec2::X, DVec2::Y, DVec2::ONE, 0.0, false, true)
        else {
            panic!("an arc")
        };
        assert!(ellipse.translation.length() < 1e-15, "{ellipse:?}");
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((mid - DVec2::splat(h)).length() < 1e-15, "{mid}");
        // The other sweep goes the long way round a circle about (1, 1).
        let Some(Seg::Arc { ellipse, mid }) =
            arc(DVec2::X, DVec2::Y, DVec2::ONE, 0.0, false, false)
        else {
            panic!("an arc")
        };
        assert!((ellipse.translation - DVec2::ONE).length() < 1e-15);
        assert!((mid - DVec2::splat(1.0 - h)).length() < 1e-15, "{mid}");
    }

    #[test]
    fn the_page_maps_millimetres_and_flips_y() {
        // 100 × 50 mm over a 200 × 100 view box: half a millimetre a unit.
        let s = one(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 200 100"><rect x="0" y="0" width="20" height="10"/></svg>"#,
        );
        let p = s.place.transform_point2(DVec2::new(20.0, 10.0));
        assert!((p - DVec2::new(10.0, 45.0)).length() < 1e-12, "{p}");
        // No view box: a user unit is a millimetre; y from the height.
        let s = one(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="72" height="72"><rect width="1" height="1"/></svg>"#,
        );
        let p = s.place.transform_point2(DVec2::new(1.0, 1.0));
        assert!((p - DVec2::new(1.0, 24.4)).length() < 1e-12, "{p}");
    }

    #[test]
    fn open_subpaths_are_stroked_and_closed_ones_filled() {
        let s = one(
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L10 0 M0 5 L10 5 L10 10 z M 20 0 L 30 0" stroke-width="2" style="stroke-linecap:round"/></svg>"#,
        );
        let kinds: Vec<&str> = s.shapes[0]
            .parts
            .iter()
            .map(|p| match p {
                SvgPart::Stroke(_) => "stroke",
                SvgPart::Loop(_) => "loop",
                SvgPart::Ellipse(_) => "ellipse",
            })
            .collect();
        // The last subpath is filled: the path has closed once (libsvg).
        assert_eq!(kinds, ["stroke", "loop", "loop"]);
        let SvgPart::Stroke(st) = &s.shapes[0].parts[0] else {
            unreachable!()
        };
        assert_eq!(
            (st.width, st.cap, st.join),
            (2.0, Cap::Round, SvgJoin::Miter)
        );
    }

    #[test]
    fn transforms_of_groups_apply_outside_the_element_s_own() {
        let s = one(
            r#"<svg xmlns="http://www.w3.org/2000/svg"><g transform="translate(10 0)"><g transform="scale(2)"><rect transform="rotate(90)" width="1" height="1"/></g></g><defs><rect width="5" height="5"/></defs><text>hi</text></svg>"#,
        );
        assert_eq!(s.shapes.len(), 1);
        let p = s.shapes[0].transform.transform_point2(DVec2::new(1.0, 0.0));
        assert!((p - DVec2::new(10.0, 2.0)).length() < 1e-12, "{p}");
        assert_eq!(s.skipped, vec![("text".to_string(), 1)]);
    }

    #[test]
    fn bad_files_are_errors_with_their_line() {
        let e = read(
            b"<svg xmlns='http://www.w3.org/2000/svg'>\n<path d='M 0 0 L x'/></svg>",
            72.0,
            false,
        )
        .unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("path"), "{}", e.message);
        let e = read(b"<svg>\n\n<rect x=1/></svg>", 72.0, false).unwrap_err();
        assert_eq!(e.line, Some(3), "{}", e.message);
        // An open cubic is stroked along libsvg's 20 steps of it.
        let d = read(
            b"<svg xmlns='http://www.w3.org/2000/svg'><path d='M0 0 C 1 1 2 1 3 0'/></svg>",
            72.0,
            false,
        )
        .unwrap();
        let SvgPart::Stroke(st) = &d.shapes[0].parts[0] else {
            panic!("a stroke: {:?}", d.shapes[0].parts[0]);
        };
        assert_eq!(st.pts.len(), 21);
        // The closed form of the cubic at u = 1/2: (1.5, 0.75).
        assert!((st.pts[10] - DVec2::new(1.5, 0.75)).length() < 1e-12);
        let e = read(
            b"<svg xmlns='http://www.w3.org/2000/svg'>\n\n<circle r='1e300'/></svg>",
            72.0,
            true,
        )
        .unwrap_err();
        assert_eq!(e.line, Some(3));
        assert_eq!(
            e.message,
            "a point of this `circle` lies out of range (beyond ±1e15)"
        );
    }
}
