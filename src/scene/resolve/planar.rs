//! OpenSCAD's 2-D statements read into figures.
//!
//! Below `linear_extrude` and `rotate_extrude` the statements live in the
//! plane: [`Resolver::figure`] reads them into a [`Figure`] tree — polygons
//! and ellipses (a circle under the plane's part of its transforms, see
//! [`plane::from_space`]) combined by the 2-D `union`, `intersection` and
//! `difference`, offsets, hulls, sums, imported drawings and text. The
//! extrusions ([`super::extrude`]) lift the tree into space.

use super::Resolver;
use crate::error::Result;
use crate::import::dxf_figure;
use crate::math::boolean::{combine_parts, Op};
use crate::plane::figure::{is_circle, Figure};
use crate::plane::offset::Join;
use crate::plane::sum;
use crate::plane::{self, Outlines};
use crate::scene::args::Args;
use crate::syntax::ast::Statement;
use glam::{DAffine2, DVec2};

/// The 2-D primitives.
pub(super) const SHAPES_2D: &[&str] = &["square", "circle", "polygon", "text"];

impl Resolver<'_> {
    /// A 2-D statement under the plane transform `m`; `None` when empty.
    pub(super) fn figure(
        &mut self,
        s: &Statement,
        m: DAffine2,
        depth: usize,
    ) -> Result<Option<Figure>> {
        let r = self.figure_of(s, m, depth);
        self.rendered_past(s, r)
    }

    /// [`Resolver::figure`] before OpenSCAD's leniency.
    fn figure_of(&mut self, s: &Statement, m: DAffine2, depth: usize) -> Result<Option<Figure>> {
        if super::skipped(s) {
            return Ok(None);
        }
        if super::resize::dimension(s) == Some(false) && !crate::mutant::active("dimensions_mixed")
        {
            // GeometryEvaluator::collectChildren2D.
            self.left_out(s, false);
            return Ok(None);
        }
        let name = s.name.as_str();
        if SHAPES_2D.contains(&name) {
            self.no_children(s)?;
            return self.figure_shape(s, m);
        }
        if super::TRANSFORMS.contains(&name) {
            let local = self.transform(s)?;
            let Some(l2) = plane::from_space(&local) else {
                self.warn(
                    s.name_span,
                    &format!("this `{name}` flattens its 2-D children"),
                    "they have no area and are left out, as in OpenSCAD",
                );
                return Ok(None);
            };
            return self.figure_children(s, Op::Union, m * l2, depth);
        }
        if name == "offset" {
            return self.offset(s, m, depth);
        }
        if name == "import" {
            self.no_children(s)?;
            return self.import(s, m);
        }
        if name == "resize" {
            return self.resize_figure(s, m, depth);
        }
        if name == "projection" {
            let a = Args::bind(self.src, s, &["cut", "convexity"])?;
            a.boolean("cut")?;
            if s.children.iter().all(super::skipped) {
                return Ok(None);
            }
            let id = self.projections.len() as u32;
            self.projections.push(s.clone());
            return Ok(Some(Figure::Section(id, m)));
        }
        if super::APPEARANCE.contains(&name) {
            // An extrusion is one new solid: colours below it are dropped,
            // as in OpenSCAD; the arguments are still checked.
            self.appearance(s, crate::scene::defaults::MATERIAL)?;
            return self.figure_children(s, Op::Union, m, depth);
        }
        if super::OPERATIONS.contains(&name) {
            let params: &'static [&'static str] = if name == "render" {
                &["convexity"]
            } else {
                &[]
            };
            Args::bind(self.src, s, params)?;
            let op = match name {
                "intersection" => Op::Intersection,
                "difference" => Op::Difference,
                _ => Op::Union,
            };
            return self.figure_children(s, op, m, depth);
        }
        if name == "hull" {
            Args::bind(self.src, s, &[])?;
            let mut kids = Vec::new();
            for c in s.children.iter().filter(|c| !super::skipped(c)) {
                kids.extend(self.figure(c, m, depth + 1)?);
            }
            if kids.is_empty() {
                return Ok(None);
            }
            return Ok(Some(crate::plane::hull::hull_of_figures(kids)));
        }
        if name == "minkowski" {
            // Summed in its own frame, then placed: m(A ⊕ B) is m's image
            // of the sum (the sum moves once).
            Args::bind(self.src, s, &["convexity"])?;
            let mut ops = Vec::new();
            for c in s.children.iter().filter(|c| !super::skipped(c)) {
                ops.push(self.figure(c, DAffine2::IDENTITY, depth + 1)?);
            }
            // An empty operand makes the sum empty (Clipper's sum with no
            // paths, as OpenSCAD calls it).
            let Some(ops) = ops.into_iter().collect::<Option<Vec<Figure>>>() else {
                return Ok(None);
            };
            if ops.is_empty() {
                return Ok(None);
            }
            let circles = ops
                .iter()
                .any(|f| matches!(f, Figure::Ellipse(e) if is_circle(e.matrix2)));
            if circles {
                self.facets_drawn_exact(s, "minkowski() with a circle");
            }
            let found = match sum::minkowski(ops.clone()) {
                // Where the flat sum fails too, its reason is the one left.
                Err(why) => self
                    .flat_sum(s, ops)
                    .map_err(|e| if e.is_empty() { why } else { e }),
                exact => exact,
            };
            return match found {
                Ok(f) => Ok(f.map(|f| f.moved(m))),
                Err(why) => Err(self.src.error(
                    s.name_span,
                    why,
                    "csgrt sums convex 2-D shapes and their unions, any shape with circles (its offset), and a polygon with convex ones exactly, and the rest flattened to straight polygons",
                )),
            };
        }
        if super::solids::binder(name) == Some(None) {
            return Err(self.unknown_to_openscad(s));
        }
        let (message, label) = if super::solids::binder(name).is_some() {
            (
                format!("`{name}` is a 3-D solid and cannot stand in a 2-D shape"),
                "expected a 2-D shape (square, circle, polygon) or a 2-D operation",
            )
        } else {
            (
                format!("`{name}` cannot stand in a 2-D shape"),
                "expected a 2-D shape (square, circle, polygon), a transform or a 2-D operation",
            )
        };
        Err(self.src.error(s.name_span, message, label))
    }

    /// The 2-D `minkowski()` of `ops` with no exact form here: each
    /// operand but a circle flattened to straight polygons, then summed
    /// exactly ([`sum::convolved`]); the notes taken back if it fails.
    fn flat_sum(
        &mut self,
        s: &Statement,
        ops: Vec<Figure>,
    ) -> std::result::Result<Option<Figure>, String> {
        self.noted_if_done(|r| {
            let mut flat = Vec::new();
            for f in ops {
                if matches!(&f, Figure::Ellipse(e) if is_circle(e.matrix2)) {
                    flat.push(f);
                    continue;
                }
                let what = "a 2-D `minkowski` of shapes that are not convex";
                match r.flat_figure(s, &f, false, what)? {
                    Some(g) => flat.push(g),
                    None => return Ok(None),
                }
            }
            sum::convolved(flat)
        })
    }

    pub(super) fn figure_children(
        &mut self,
        s: &Statement,
        op: Op,
        m: DAffine2,
        depth: usize,
    ) -> Result<Option<Figure>> {
        let mut parts = Vec::new();
        for c in s.children.iter().filter(|c| !super::skipped(c)) {
            parts.push(self.figure(c, m, depth + 1)?);
        }
        Ok(combine_parts(op, parts, Figure::Op))
    }

    /// `square`, `circle` or `polygon` under `m`.
    pub(super) fn figure_shape(&mut self, s: &Statement, m: DAffine2) -> Result<Option<Figure>> {
        let moved = |o: Outlines| o.map(|p| m.transform_point2(p));
        match s.name.as_str() {
            "square" => {
                let a = Args::bind(self.src, s, &["size", "center"])?;
                let size = if a.is_number("size") {
                    DVec2::splat(a.number("size")?.unwrap_or(1.0))
                } else {
                    a.numbers("size", &[2])?
                        .map_or(DVec2::ONE, |v| DVec2::new(v[0], v[1]))
                };
                if size.min_element() <= 0.0 {
                    self.empty(s, "a size is zero or negative")?;
                    return Ok(None);
                }
                let lo = if a.boolean("center")?.unwrap_or(false) {
                    -0.5 * size
                } else {
                    DVec2::ZERO
                };
                let hi = lo + size;
                let pts = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
                Ok(Some(Figure::Polygon(moved(Outlines::polygons(vec![pts])))))
            }
            "circle" => {
                let a = Args::bind(self.src, s, &["r", "d"])?;
                let r = match (a.number("r")?, a.number("d")?) {
                    (_, Some(d)) => d / 2.0,
                    (Some(r), None) => r,
                    (None, None) => 1.0,
                };
                if r <= 0.0 {
                    self.empty(s, "its radius is zero or negative")?;
                    return Ok(None);
                }
                Ok(Some(match self.fragments(&a, r) {
                    Some(n) => Figure::Polygon(moved(super::facet_mesh::regular_polygon(n, r))),
                    None => Figure::Ellipse(m * DAffine2::from_scale(DVec2::splat(r))),
                }))
            }
            "text" => self.text(s, m),
            _ => Ok(self.polygon(s)?.map(|o| Figure::Polygon(moved(o)))),
        }
    }

    /// `polygon(points, paths)` read as OpenSCAD 2021.01 reads it
    /// (`PolygonNode`): a polygon it cannot read is left out of the model
    /// and the rest rendered, so here too, with a warning at the place. No
    /// points (`undef`) or fewer than 3, or a point that is not 2 numbers
    /// (OpenSCAD's error "Unable to convert points[i]"), leave the whole
    /// polygon out; an index out of range is dropped from its path
    /// (OpenSCAD's warning "Point index is out of bounds"), a fraction cut
    /// to a whole number as OpenSCAD's `size_t` does, and a path left with
    /// fewer than 3 points, which has no area, adds nothing.
    fn polygon(&mut self, s: &Statement) -> Result<Option<Outlines>> {
        let a = Args::bind(self.src, s, &["points", "paths", "convexity"])?;
        let pts = match a.points("points", &[2], 0) {
            Ok(Some(p)) => p,
            Ok(None) => {
                self.empty(s, "it has no `points` (as in OpenSCAD, it is left out)")?;
                return Ok(None);
            }
            Err(e) => {
                self.go_on(e, "the polygon is left out, as in OpenSCAD")?;
                return Ok(None);
            }
        };
        // No paths, or an empty list of them: all points, in order.
        let paths = match a.number_lists("paths")?.filter(|l| !l.is_empty()) {
            Some(lists) => lists,
            None if pts.len() < 3 => {
                let found = format!("expected 3 or more points, found {}", pts.len());
                self.warn(
                    a.span_of("points"),
                    "a polygon needs at least 3 points",
                    &found,
                );
                return Ok(None);
            }
            None => {
                let path: Vec<DVec2> = pts.iter().map(|p| p.truncate()).collect();
                if on_one_line(&path) {
                    self.empty(s, "its points lie on one line")?;
                    return Ok(None);
                }
                return Ok(Some(Outlines::polygons(vec![path])));
            }
        };
        let mut loops = Vec::new();
        for l in paths {
            let mut path = Vec::with_capacity(l.items.len());
            for (n, span) in l.items {
                let i = n.trunc();
                if !(i >= 0.0 && i < pts.len() as f64) {
                    let e = a.index_range("paths", n, span, pts.len());
                    self.go_on(e, "it is dropped from its path, as in OpenSCAD")?;
                    continue;
                }
                path.push(pts[i as usize].truncate());
            }
            if path.len() < 3 {
                let found = format!("expected 3 or more points, found {}", path.len());
                self.warn(l.span, "a path of fewer than 3 points adds nothing", &found);
                continue;
            }
            if on_one_line(&path) {
                self.warn(
                    l.span,
                    "a path whose points lie on one line adds nothing",
                    "it has no area",
                );
                continue;
            }
            loops.push(path);
        }
        if loops.is_empty() {
            return Ok(None);
        }
        Ok(Some(Outlines::polygons(loops)))
    }

    /// `text` under `m`: the union of its glyphs.
    fn text(&mut self, s: &Statement, m: DAffine2) -> Result<Option<Figure>> {
        self.facets_drawn_exact(s, "text");
        const PARAMS: &[&str] = &[
            "text",
            "size",
            "font",
            "halign",
            "valign",
            "spacing",
            "direction",
            "language",
            "script",
        ];
        let a = Args::bind(self.src, s, PARAMS)?;
        let text = a.string("text")?.unwrap_or("");
        if text.chars().count() > crate::import::text::MAX_TEXT_CHARS {
            return Err(a.error(
                a.span_of("text"),
                "this text is too long",
                format!(
                    "expected at most {} characters",
                    crate::import::text::MAX_TEXT_CHARS
                ),
            ));
        }
        let p = crate::import::text::Params {
            text,
            size: a.number("size")?.unwrap_or(10.0),
            font: a.string("font")?.unwrap_or(""),
            halign: a.string("halign")?.unwrap_or("left"),
            valign: a.string("valign")?.unwrap_or("baseline"),
            spacing: a.number("spacing")?.unwrap_or(1.0),
            direction: a.string("direction")?.unwrap_or(""),
            language: a.string("language")?.unwrap_or("en"),
            script: a.string("script")?.unwrap_or(""),
        };
        let laid = crate::import::text::layout(&p);
        for (param, w) in &laid.warnings {
            let place = if a.has(param) {
                a.span_of(param)
            } else {
                s.args_span
            };
            let label = if *param == "font" {
                "expected an installed family (Liberation Sans is built in)"
            } else {
                "OpenSCAD reads it so too"
            };
            self.warn(place, w, label);
        }
        let glyphs: Vec<Option<Figure>> = laid
            .glyphs
            .into_iter()
            .map(|o| Some(Figure::Polygon(o.map(|p| m.transform_point2(p)))))
            .collect();
        Ok(combine_parts(Op::Union, glyphs, Figure::Op))
    }

    /// `offset(r | delta, chamfer)` of its children's union, computed in
    /// its own frame, then placed by `m`.
    fn offset(&mut self, s: &Statement, m: DAffine2, depth: usize) -> Result<Option<Figure>> {
        let a = Args::bind(self.src, s, &["r", "delta", "chamfer"])?;
        // As OpenSCAD: r beats delta; no argument at all is r = 1.
        let (join, d) = match (a.number("r")?, a.number("delta")?) {
            (Some(r), _) => (Join::Round, r),
            (None, Some(d)) if a.boolean("chamfer")?.unwrap_or(false) => (Join::Square, d),
            (None, Some(d)) => (Join::Miter, d),
            (None, None) => (Join::Round, 1.0),
        };
        if join == Join::Round {
            self.facets_drawn_exact(s, "offset(r)");
        }
        let Some(f) = self.figure_children(s, Op::Union, DAffine2::IDENTITY, depth)? else {
            return Ok(None);
        };
        // What has no exact offset is offset flattened to straight
        // polygons and circles (the certified approximation).
        let found = match crate::plane::offset::offset(f.clone(), join, d) {
            Err(why) => {
                let what = "an `offset` of curves, ellipses, hulls or projections";
                self.noted_if_done(|r| match r.flat_figure(s, &f, true, what)? {
                    Some(flat) => crate::plane::offset::offset(flat, join, d),
                    None => Ok(None),
                })
                .map_err(|e| if e.is_empty() { why } else { e })
            }
            exact => exact,
        };
        match found {
            Ok(f) => Ok(f.map(|f| f.moved(m))),
            Err(why) => Err(self.src.error(
                s.name_span,
                why,
                "csgrt offsets polygons, circles and curved outlines (text) exactly, and the rest flattened to straight polygons",
            )),
        }
    }

    /// The file `import` names: (its name, the argument's place, its
    /// extension in lower case, its path beside the scene).
    pub(super) fn import_file<'b>(
        &self,
        a: &Args<'b>,
    ) -> Result<(&'b str, crate::error::TextRange, String, std::path::PathBuf)> {
        let file = match (a.string("file")?, a.string("filename")?) {
            (Some(f), _) | (None, Some(f)) => f,
            (None, None) => {
                // OpenSCAD: "Unsupported file format", and nothing.
                return Err(self.src.lenient(
                    a.list_span(),
                    "`import` needs a `file`",
                    "expected file = \"name.dxf\" or \"name.stl\"",
                ));
            }
        };
        let span = if a.has("file") {
            a.span_of("file")
        } else {
            a.span_of("filename")
        };
        let ext = std::path::Path::new(file)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        Ok((file, span, ext, self.src.beside(file)))
    }

    /// `import()` of a drawing (DXF or SVG), under `m`.
    pub(super) fn import(&mut self, s: &Statement, m: DAffine2) -> Result<Option<Figure>> {
        let a = Args::bind(self.src, s, super::solids::IMPORT_PARAMS)?;
        let (_, span, ext, path) = self.import_file(&a)?;
        if ext == "svg" {
            return self.import_svg(s, &a, span, &path, m);
        }
        if ext != "dxf" {
            let (message, label) = if crate::import::meshfile::FORMATS.contains(&ext.as_str()) {
                (
                    format!("a `.{ext}` mesh is a solid and cannot stand in a 2-D shape"),
                    "expected a DXF or SVG drawing here",
                )
            } else {
                (
                    format!(
                        "cannot import `{}`: not a drawing or mesh file",
                        path.display()
                    ),
                    "csgrt imports DXF and SVG drawings and STL, OFF, OBJ, 3MF, AMF and NEF3 meshes",
                )
            };
            // OpenSCAD: "Unsupported file format" (or a 3-D child of a 2-D
            // operation), and the import is empty.
            return Err(self.src.lenient(span, message, label));
        }
        let layer = match (a.string("layer")?, a.string("layername")?) {
            (Some(l), _) | (None, Some(l)) => l,
            _ => "",
        };
        let origin = a
            .numbers("origin", &[2])?
            .map_or(DVec2::ZERO, |v| DVec2::new(v[0], v[1]));
        let scale = a.number("scale")?.unwrap_or(1.0);
        let bytes = self.read_named(
            span,
            &path,
            "drawing",
            "expected a DXF file beside the scene",
        )?;
        let cut = |r: f64| self.fragments(&a, r);
        let d = crate::import::dxf::read(&bytes, layer, origin, scale, &cut).map_err(|e| {
            self.src.lenient(
                span,
                format!(
                    "`{}` is not a DXF drawing csgrt can read: {e}",
                    path.display()
                ),
                "expected a DXF file",
            )
        })?;
        if !d.skipped.is_empty() {
            let what: Vec<String> = d.skipped.iter().map(|(k, n)| format!("{n} {k}")).collect();
            self.warn(
                span,
                &format!("entities of the drawing left out: {}", what.join(", ")),
                "OpenSCAD leaves them out too",
            );
        }
        if d.open_paths > 0 {
            self.warn(
                span,
                &format!(
                    "{} path(s) of the drawing do not close: each is closed by a straight edge",
                    d.open_paths
                ),
                "as OpenSCAD closes them",
            );
        }
        Ok(dxf_figure::from_drawing(&d).map(|f| f.moved(m)))
    }

    /// `import()` of an SVG drawing (`dpi`, `center`; OpenSCAD reads no
    /// `origin`, `scale` or layer of one), under `m`.
    fn import_svg(
        &mut self,
        s: &Statement,
        a: &Args,
        span: crate::error::TextRange,
        path: &std::path::Path,
        m: DAffine2,
    ) -> Result<Option<Figure>> {
        self.facets_drawn_exact(s, "a drawing's curves");
        let mut dpi = a.number("dpi")?.unwrap_or(72.0);
        if dpi < 0.001 {
            self.warn(
                a.span_of("dpi"),
                "the dpi must be at least 0.001: the default of 72 is used",
                "as OpenSCAD does",
            );
            dpi = 72.0;
        }
        let center = a.boolean("center")?.unwrap_or(false);
        let bytes = self.read_named(
            span,
            path,
            "drawing",
            "expected an SVG file beside the scene",
        )?;
        let d = crate::import::svg::read(&bytes, dpi, center).map_err(|e| {
            let at = e.line.map_or(String::new(), |l| format!(", line {l}"));
            self.src.error(
                span,
                format!("`{}`{at}: {}", path.display(), e.message),
                "expected an SVG drawing csgrt can read",
            )
        })?;
        if !d.skipped.is_empty() {
            let what: Vec<String> = d
                .skipped
                .iter()
                .map(|(k, n)| format!("{n} `{k}`"))
                .collect();
            self.warn(
                span,
                &format!("elements of the drawing left out: {}", what.join(", ")),
                "OpenSCAD leaves them out too",
            );
        }
        Ok(crate::import::svg_figure::from_svg(&d).map(|f| f.moved(m)))
    }
}

/// OpenSCAD's deprecated `file`, `layer` and `origin` of an extrusion
/// (still read by 2021.01, with a deprecation message, and written by its
/// CSG export with a `timestamp`): the drawing as the extrusion's one
/// child, `import(file, layer, origin, convexity)` — its children are
/// ignored, as OpenSCAD ignores them. OpenSCAD scales a linear
/// extrusion's drawing by the first number of its `scale` (`lf.scad`
/// with `scale = [2, 3]`: the bottom twice the drawing, the top [2, 3]
/// times that), and a turned one by its own `scale`.
pub(super) fn file_child(s: &Statement, a: &Args) -> Option<Statement> {
    if !a.has("file") {
        return None;
    }
    // The drawing's own arguments, and OpenSCAD's special variables.
    let mut args: Vec<crate::syntax::ast::Arg> = s
        .args
        .iter()
        .filter(|arg| {
            arg.name.as_ref().is_some_and(|(n, _)| {
                ["file", "layer", "origin", "convexity", "timestamp"].contains(&n.as_str())
                    || n.starts_with('$')
            })
        })
        .cloned()
        .collect();
    if let Some(v) = a.get("scale") {
        let k = match &v.kind {
            crate::syntax::ast::ValueKind::Vector(xs) if !xs.is_empty() => xs[0].clone(),
            _ => v.clone(),
        };
        args.push(crate::syntax::ast::Arg {
            name: Some(("scale".to_string(), k.span)),
            span: k.span,
            value: k,
        });
    }
    Some(Statement {
        modifiers: Default::default(),
        name: "import".to_string(),
        name_span: s.name_span,
        args,
        args_span: s.args_span,
        children: Vec::new(),
        span: s.span,
    })
}

/// Whether every point lies on one line (exactly): a path with no area,
/// which OpenSCAD's sanitizing leaves out.
fn on_one_line(path: &[DVec2]) -> bool {
    let Some(&a) = path.first() else {
        return true;
    };
    let Some(&b) = path.iter().find(|&&p| p != a) else {
        return true;
    };
    path.iter().all(|&p| (b - a).perp_dot(p - a) == 0.0)
}
