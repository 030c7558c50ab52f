//! Binding a statement's arguments to its parameters, with typed getters
//! that report problems at the argument's place in the file.

use crate::error::{Error, Result, Source, TextRange};
use crate::syntax::ast::{Statement, Value, ValueKind};
use crate::syntax::one_of;
use glam::DVec3;

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

    /// Whether the argument was given as a single number.
    pub fn is_number(&self, name: &str) -> bool {
        matches!(self.get(name).map(|v| &v.kind), Some(ValueKind::Number(_)))
    }

    pub fn has(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    fn get(&self, name: &str) -> Option<&'a Value> {
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

    fn wrong_type(&self, name: &str, v: &Value, want: &str) -> Error {
        self.src.error(
            v.span,
            format!("`{name}` of `{}` must be {want}", self.stmt.name),
            format!("expected {want}, found {}", v.kind.type_name()),
        )
    }

    fn finite(&self, name: &str, v: &Value, x: f64) -> Result<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.src.error(
                v.span,
                format!("`{name}` of `{}` must be finite", self.stmt.name),
                "expected a finite number",
            ))
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
                return Err(self.src.error(
                    v.span,
                    format!("`{name}` of `{}` must not be negative", self.stmt.name),
                    "expected a number ≥ 0",
                ));
            }
        }
        Ok(x)
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
