//! The typed syntax tree of a `.csg` file. Every node keeps its span so that
//! later stages can report problems at their place in the file.

use crate::error::TextRange;

/// OpenSCAD's statement modifiers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Modifiers {
    /// `#`: highlight; rendered as usual.
    pub highlight: bool,
    /// `%`: background; left out of the solid.
    pub background: bool,
    /// `*`: disabled; left out.
    pub disable: bool,
    /// `!`: root; only this subtree is rendered.
    pub root: bool,
}

/// `[modifiers] name(args) body`.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    pub modifiers: Modifiers,
    pub name: String,
    pub name_span: TextRange,
    pub args: Vec<Arg>,
    /// TextRange of the argument list, parentheses included.
    pub args_span: TextRange,
    pub children: Vec<Statement>,
    pub span: TextRange,
}

/// One argument: `key = value` or a positional value.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    pub name: Option<(String, TextRange)>,
    pub value: Value,
    pub span: TextRange,
}

/// A literal value with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    pub kind: ValueKind,
    pub span: TextRange,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ValueKind {
    Number(f64),
    Str(String),
    Bool(bool),
    Undef,
    Vector(Vec<Value>),
}

impl ValueKind {
    /// How the value's type is named in messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            ValueKind::Number(_) => "a number",
            ValueKind::Str(_) => "a string",
            ValueKind::Bool(_) => "a boolean",
            ValueKind::Undef => "`undef`",
            ValueKind::Vector(_) => "a vector",
        }
    }
}
