//! Binding a statement's arguments to its parameters, with typed getters
//! that report problems at the argument's place in the file.

use crate::error::{Error, Result, TextRange};
use crate::source::Source;
use crate::syntax::ast::{Statement, Value, ValueKind};
use crate::syntax::one_of;
use glam::DVec3;

/// The largest explicit `$fn` read as a shape (a hexagon nut) rather than a
/// smoothness setting.
pub const MAX_SHAPE_FACETS: usize = 8;

/// One list of `faces` or `paths` as written: its numbers with their
/// places, and its own place.
pub struct NumberList {
    pub span: TextRange,
    pub items: Vec<(f64, TextRange)>,
}

/// csgrt's scene statements (the camera and lights), at the top level.
pub const SCENE: &[&str] = &[
    "camera",
    "background",
    "ambient_light",
    "directional_light",
    "point_light",
];

/// csgrt's own statements besides [`SCENE`]: OpenSCAD has no leniency to
/// copy for them, so a bad number in one stays an error.
const OWN: &[&str] = &["material", "torus", "halfspace"];

pub struct Args<'a> {
    src: &'a Source,
    stmt: &'a Statement,
    params: &'static [&'static str],
    values: Vec<Option<&'a Value>>,
}

fn quoted(names: &[&str]) -> String {
    let q: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    let q: Vec<&str> = q.iter().map(|s| s.as_str()).collect();
    one_of(&q)
}

impl<'a> Args<'a> {
    /// Binds positional arguments in parameter order and named ones by
    /// name. OpenSCAD's special variables (`$fn`, `$fa`, `$fs`, …) are
    /// accepted anywhere and ignored: csgrt renders exact surfaces.
    pub fn bind(
        src: &'a Source,
        stmt: &'a Statement,
        params: &'static [&'static str],
    ) -> Result<Args<'a>> {
        let mut values: Vec<Option<&Value>> = vec![None; params.len()];
        let mut positional = 0;
        for arg in &stmt.args {
            let slot = match &arg.name {
                Some((name, _)) if name.starts_with('$') => continue,
                Some((name, span)) => match params.iter().position(|p| p == name) {
                    Some(i) => i,
                    None => {
                        let label = if params.is_empty() {
                            format!("`{}` takes no arguments", stmt.name)
                        } else {
                            format!("expected {}", quoted(params))
                        };
                        return Err(src.error(
                            *span,
                            format!("unknown argument `{name}` for `{}`", stmt.name),
                            label,
                        ));
                    }
                },
                None => {
                    positional += 1;
                    if positional > params.len() {
                        let label = match params.len() {
                            0 => format!("`{}` takes no arguments", stmt.name),
                            1 => format!("`{}` takes 1 argument", stmt.name),
                            n => format!("`{}` takes at most {n} arguments", stmt.name),
                        };
                        return Err(src.error(
                            arg.span,
                            format!("too many arguments for `{}`", stmt.name),
                            label,
                        ));
                    }
                    positional - 1
                }
            };
            if values[slot].is_some() {
                return Err(src.error(
                    arg.span,
                    format!("argument `{}` given twice", params[slot]),
                    "remove one of them",
                ));
            }
            // `undef` means "not given", as in OpenSCAD.
            if arg.value.kind != ValueKind::Undef {
                values[slot] = Some(&arg.value);
            }
        }
        Ok(Args {
            src,
            stmt,
            params,
            values,
        })
    }

    /// An OpenSCAD special variable given to this statement as a number
    /// (`$fn`, …), finite or not; `None` when absent or not a number.
    pub fn special(&self, name: &str) -> Option<f64> {
        self.stmt
            .args
            .iter()
            .rev()
            .find_map(|a| match (&a.name, &a.value.kind) {
                (Some((n, _)), ValueKind::Number(x)) if n == name => Some(*x),
                _ => None,
            })
    }

    /// OpenSCAD's fragment count when an explicit `$fn` makes a round
    /// solid a polygon with few sides (`$fn` of 3 to 8, a `$fn` in (0, 3)
    /// counting as 3, as OpenSCAD's `get_fragments_from_r`); `None`
    /// otherwise: the exact round surface.
    pub fn few_facets(&self) -> Option<usize> {
        let f = self.special("$fn")?;
        if !f.is_finite() {
            // `get_fragments_from_r`: 3 for an infinite or NaN `$fn`.
            return Some(3);
        }
        if f <= 0.0 {
            return None;
        }
        let n = (f.max(3.0)) as usize;
        (n <= MAX_SHAPE_FACETS).then_some(n)
    }

    /// Whether the argument was given as a single number.
    pub fn is_number(&self, name: &str) -> bool {
        matches!(self.get(name).map(|v| &v.kind), Some(ValueKind::Number(_)))
    }

    pub fn has(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    pub(crate) fn get(&self, name: &str) -> Option<&'a Value> {
        let i = self
            .params
            .iter()
            .position(|p| *p == name)
            .unwrap_or_else(|| panic!("`{name}` is not a parameter of `{}`", self.stmt.name));
        self.values[i]
    }

    /// The span to blame for a missing argument: the argument list.
    pub fn list_span(&self) -> TextRange {
        self.stmt.args_span
    }

    pub fn error(
        &self,
        span: TextRange,
        message: impl Into<String>,
        label: impl Into<String>,
    ) -> Error {
        self.src.error(span, message, label)
    }

    pub(crate) fn wrong_type(&self, name: &str, v: &Value, want: &str) -> Error {
        self.src.error(
            v.span,
            format!("`{name}` of `{}` must be {want}", self.stmt.name),
            format!("expected {want}, found {}", v.kind.type_name()),
        )
    }

    /// `e`, for a statement of OpenSCAD's, made a problem it warns about
    /// and renders past ([`crate::source::leniently`]); for csgrt's own
    /// statements an error as it is.
    fn openscads(&self, e: Error) -> Error {
        let name = self.stmt.name.as_str();
        if SCENE.contains(&name) || OWN.contains(&name) {
            e
        } else {
            crate::source::leniently(e)
        }
    }

    fn finite(&self, name: &str, v: &Value, x: f64) -> Result<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            // OpenSCAD makes nothing of a non-finite size, and removes
            // what a non-finite transform moves.
            Err(self.openscads(self.src.error(
                v.span,
                format!("`{name}` of `{}` must be finite", self.stmt.name),
                "expected a finite number",
            )))
        }
    }

    pub fn number(&self, name: &str) -> Result<Option<f64>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        match v.kind {
            ValueKind::Number(x) => self.finite(name, v, x).map(Some),
            _ => Err(self.wrong_type(name, v, "a number")),
        }
    }

    /// A number that, if given, must be positive (or zero when `zero_ok`).
    pub fn non_negative(&self, name: &str) -> Result<Option<f64>> {
        let x = self.number(name)?;
        if let (Some(x), Some(v)) = (x, self.get(name)) {
            if x < 0.0 {
                // OpenSCAD makes nothing of a negative radius.
                return Err(self.openscads(self.src.error(
                    v.span,
                    format!("`{name}` of `{}` must not be negative", self.stmt.name),
                    "expected a number ≥ 0",
                )));
            }
        }
        Ok(x)
    }

    pub fn string(&self, name: &str) -> Result<Option<&'a str>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        match &v.kind {
            ValueKind::Str(s) => Ok(Some(s.as_str())),
            _ => Err(self.wrong_type(name, v, "a string")),
        }
    }

    pub fn boolean(&self, name: &str) -> Result<Option<bool>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        match v.kind {
            ValueKind::Bool(b) => Ok(Some(b)),
            // OpenSCAD's truthiness for numbers.
            ValueKind::Number(x) => Ok(Some(x != 0.0)),
            _ => Err(self.wrong_type(name, v, "`true` or `false`")),
        }
    }

    /// A vector of numbers with a length in `lens`.
    pub fn numbers(&self, name: &str, lens: &[usize]) -> Result<Option<Vec<f64>>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let want = match lens {
            [n] => format!("a vector of {n} numbers"),
            _ => {
                let n: Vec<String> = lens.iter().map(|n| n.to_string()).collect();
                let n: Vec<&str> = n.iter().map(|s| s.as_str()).collect();
                format!("a vector of {} numbers", one_of(&n))
            }
        };
        let ValueKind::Vector(items) = &v.kind else {
            return Err(self.wrong_type(name, v, &want));
        };
        if !lens.contains(&items.len()) {
            return Err(self.src.error(
                v.span,
                format!("`{name}` of `{}` must be {want}", self.stmt.name),
                format!("expected {want}, found {}", items.len()),
            ));
        }
        let mut out = Vec::with_capacity(items.len());
        for it in items {
            match it.kind {
                ValueKind::Number(x) => out.push(self.finite(name, it, x)?),
                _ => return Err(self.wrong_type(name, it, "a number")),
            }
        }
        Ok(Some(out))
    }

    /// A 3-vector; a 2-vector gets `z_fill` as its z, as in OpenSCAD.
    pub fn vec3(&self, name: &str, z_fill: f64) -> Result<Option<DVec3>> {
        Ok(self
            .numbers(name, &[2, 3])?
            .map(|v| DVec3::new(v[0], v[1], if v.len() == 3 { v[2] } else { z_fill })))
    }

    /// A 3-vector or one number for all three components.
    pub fn scalar_or_vec3(&self, name: &str, z_fill: f64) -> Result<Option<DVec3>> {
        match self.get(name).map(|v| &v.kind) {
            Some(ValueKind::Number(_)) => Ok(self.number(name)?.map(DVec3::splat)),
            _ => self.vec3(name, z_fill),
        }
    }

    /// A matrix given as rows of numbers, each row `cols` long.
    pub fn matrix(&self, name: &str, rows: &[usize], cols: usize) -> Result<Option<Vec<Vec<f64>>>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let want = format!("a matrix of {} rows of {cols} numbers", {
            let n: Vec<String> = rows.iter().map(|n| n.to_string()).collect();
            n.join(" or ")
        });
        let ValueKind::Vector(items) = &v.kind else {
            return Err(self.wrong_type(name, v, &want));
        };
        if !rows.contains(&items.len()) {
            return Err(self.wrong_type(name, v, &want));
        }
        let mut out = Vec::new();
        for row in items {
            let ValueKind::Vector(cells) = &row.kind else {
                return Err(self.wrong_type(name, row, &format!("a row of {cols} numbers")));
            };
            if cells.len() != cols {
                return Err(self.src.error(
                    row.span,
                    format!("`{name}` of `{}` must be {want}", self.stmt.name),
                    format!("expected a row of {cols} numbers, found {}", cells.len()),
                ));
            }
            let mut r = Vec::with_capacity(cols);
            for c in cells {
                match c.kind {
                    ValueKind::Number(x) => r.push(self.finite(name, c, x)?),
                    _ => return Err(self.wrong_type(name, c, "a number")),
                }
            }
            out.push(r);
        }
        Ok(Some(out))
    }

    /// A list of at least `min` points, each a vector of one of `dims`
    /// numbers (OpenSCAD's `points = [[x, y], …]`); a point of 2 numbers
    /// read where 3 are allowed gets z = 0, as in OpenSCAD. Each problem
    /// is reported at the element it is about.
    pub fn points(&self, name: &str, dims: &[usize], min: usize) -> Result<Option<Vec<DVec3>>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let want = format!("a list of points of {} numbers", {
            let n: Vec<String> = dims.iter().map(|n| n.to_string()).collect();
            n.join(" or ")
        });
        let ValueKind::Vector(items) = &v.kind else {
            return Err(self.wrong_type(name, v, &want));
        };
        if items.len() < min {
            return Err(self.src.error(
                v.span,
                format!(
                    "`{name}` of `{}` needs at least {min} points",
                    self.stmt.name
                ),
                format!("expected {min} or more, found {}", items.len()),
            ));
        }
        let mut out = Vec::with_capacity(items.len());
        for it in items {
            // OpenSCAD's "Unable to convert points[i]": the shape is empty.
            let ValueKind::Vector(xs) = &it.kind else {
                let want = format!("a point of {} numbers", dims[0]);
                return Err(self.openscads(self.wrong_type(name, it, &want)));
            };
            if !dims.contains(&xs.len()) {
                return Err(self.openscads(self.src.error(
                    it.span,
                    format!("`{name}` of `{}` must be {want}", self.stmt.name),
                    format!(
                        "expected a point of {} numbers, found {}",
                        dims[0],
                        xs.len()
                    ),
                )));
            }
            let mut p = [0.0; 3];
            for (k, x) in xs.iter().enumerate() {
                match x.kind {
                    ValueKind::Number(n) => p[k] = self.finite(name, x, n)?,
                    _ => return Err(self.openscads(self.wrong_type(name, x, "a number"))),
                }
            }
            out.push(DVec3::from(p));
        }
        Ok(Some(out))
    }

    /// Lists of numbers (OpenSCAD's `faces` or `paths`) as they are
    /// written, each number and each list with its place: only their types
    /// are checked here.
    pub fn number_lists(&self, name: &str) -> Result<Option<Vec<NumberList>>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let ValueKind::Vector(lists) = &v.kind else {
            return Err(self.wrong_type(name, v, "a list of index lists"));
        };
        let mut out = Vec::with_capacity(lists.len());
        for l in lists {
            let ValueKind::Vector(ix) = &l.kind else {
                return Err(self.wrong_type(name, l, "a list of indices"));
            };
            let mut items = Vec::with_capacity(ix.len());
            for i in ix {
                let ValueKind::Number(n) = i.kind else {
                    return Err(self.wrong_type(name, i, "an index"));
                };
                items.push((n, i.span));
            }
            out.push(NumberList {
                span: l.span,
                items,
            });
        }
        Ok(Some(out))
    }

    /// Lists of indices into `count` points (OpenSCAD's `faces` or
    /// `paths`), each at least `min_len` long; an index out of range, not
    /// a whole number, or a list too short is an error at its place.
    pub fn index_lists(
        &self,
        name: &str,
        count: usize,
        min_len: usize,
    ) -> Result<Option<Vec<Vec<u32>>>> {
        let Some(lists) = self.number_lists(name)? else {
            return Ok(None);
        };
        let mut out = Vec::with_capacity(lists.len());
        for l in lists {
            if l.items.len() < min_len {
                return Err(self.src.error(
                    l.span,
                    format!(
                        "a list in `{name}` of `{}` has fewer than {min_len} indices",
                        self.stmt.name
                    ),
                    format!("expected {min_len} or more, found {}", l.items.len()),
                ));
            }
            let mut row = Vec::with_capacity(l.items.len());
            for (n, span) in l.items {
                if n.fract() != 0.0 || n < 0.0 || n >= count as f64 {
                    return Err(self.index_range(name, n, span, count));
                }
                row.push(n as u32);
            }
            out.push(row);
        }
        Ok(Some(out))
    }

    /// The message for index `n` at `span`, not a whole number from 0 to
    /// `count` − 1.
    pub fn index_range(&self, name: &str, n: f64, span: TextRange, count: usize) -> Error {
        self.src.error(
            span,
            format!(
                "index {n} in `{name}` of `{}` is out of range",
                self.stmt.name
            ),
            format!(
                "expected a whole number from 0 to {}",
                count.saturating_sub(1)
            ),
        )
    }

    /// The span of an argument's value (for semantic errors about it).
    pub fn span_of(&self, name: &str) -> TextRange {
        self.get(name).map_or(self.stmt.args_span, |v| v.span)
    }

    /// A required argument: an error at the argument list when missing.
    pub fn require<T>(&self, name: &str, v: Option<T>) -> Result<T> {
        v.ok_or_else(|| {
            self.src.error(
                self.list_span(),
                format!("`{}` needs the argument `{name}`", self.stmt.name),
                format!("expected `{name} = …`"),
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of binding `text`'s first statement with `f`.
    fn run<T>(
        text: &str,
        params: &'static [&'static str],
        f: impl Fn(&Args) -> Result<T>,
    ) -> std::result::Result<T, String> {
        let src = Source::new("t.csg", text);
        let stmts = crate::syntax::parse_csg(&src).unwrap();
        let a = Args::bind(&src, &stmts[0], params).unwrap();
        f(&a).map_err(|e| e.to_string())
    }

    #[test]
    fn points_of_any_length_are_read_with_their_places() {
        let pts = run(
            "polygon(points = [[0, 0], [2, 0], [1, 3.5]]);",
            &["points"],
            |a| a.points("points", &[2], 3),
        )
        .unwrap();
        assert_eq!(
            pts.unwrap(),
            vec![
                DVec3::ZERO,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(1.0, 3.5, 0.0)
            ]
        );
        let e = run("polygon(points = [[0, 0], [2, 0]]);", &["points"], |a| {
            a.points("points", &[2], 3)
        })
        .unwrap_err();
        assert!(
            e.contains("needs at least 3 points") && e.contains("t.csg:1:18"),
            "{e}"
        );
        let e = run(
            "polygon(points = [[0, 0], [2, 0, 1, 4], [1, 1]]);",
            &["points"],
            |a| a.points("points", &[2], 3),
        )
        .unwrap_err();
        assert!(
            e.contains("expected a point of 2 numbers, found 4") && e.contains("t.csg:1:27"),
            "{e}"
        );
    }

    #[test]
    fn index_lists_are_checked_against_the_points() {
        let f = run(
            "polyhedron(faces = [[0, 1, 2], [2, 1, 3]]);",
            &["faces"],
            |a| a.index_lists("faces", 4, 3),
        )
        .unwrap();
        assert_eq!(f.unwrap(), vec![vec![0, 1, 2], vec![2, 1, 3]]);
        let e = run("polyhedron(faces = [[0, 1, 4]]);", &["faces"], |a| {
            a.index_lists("faces", 4, 3)
        })
        .unwrap_err();
        assert!(
            e.contains("index 4 in `faces`")
                && e.contains("t.csg:1:28")
                && e.contains("from 0 to 3"),
            "{e}"
        );
        let e = run("polyhedron(faces = [[0, 1]]);", &["faces"], |a| {
            a.index_lists("faces", 4, 3)
        })
        .unwrap_err();
        assert!(
            e.contains("fewer than 3 indices") && e.contains("t.csg:1:21"),
            "{e}"
        );
        let e = run("polyhedron(faces = [[0, 1.5, 2]]);", &["faces"], |a| {
            a.index_lists("faces", 4, 3)
        })
        .unwrap_err();
        assert!(
            e.contains("out of range") && e.contains("whole number"),
            "{e}"
        );
    }
}
