//! Parsing: source text → typed syntax tree ([`ast`]), with spans kept.
//!
//! The grammar lives in `grammar/csg.pest`; this module has one function per
//! rule that produces a node, and turns pest's syntax errors into csgrt's
//! [`Diagnostic`](crate::error::Diagnostic)s, naming what was expected in words.

pub mod ast;
pub mod ray;

use crate::error::{Error, Result, TextRange};
use crate::source::Source;
use ast::{Arg, Modifiers, Statement, Value, ValueKind};
use pest::iterators::Pair;
use pest::Parser;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/csg.pest"]
struct CsgParser;

/// The deepest nesting of statements and vectors accepted (people's models
/// nest a few hundred deep: a recursive module's export). Deeper input is
/// an error, not a stack overflow in the stages that walk the tree (the
/// CLI runs them on threads with [`MAIN_STACK`] and [`WORKER_STACK`]).
pub const MAX_NESTING: usize = 4096;

/// The stack of the CLI's thread that reads, resolves and writes a model
/// (address space reserved; only what the model's depth uses is touched):
/// enough for [`MAX_NESTING`] levels of each stage's recursion.
pub const MAIN_STACK: usize = 1 << 30;

/// The stack of each rendering thread (which reads an animation's frames
/// too, and casts the framing's rays).
pub const WORKER_STACK: usize = 256 << 20;

/// Parses a whole `.csg` file into its top-level statements.
pub fn parse_csg(src: &Source) -> Result<Vec<Statement>> {
    let mut pairs = CsgParser::parse(Rule::file, &src.text).map_err(|e| syntax_error(src, e))?;
    let file = pairs.next().expect("the file rule always yields one pair");
    let mut out = Vec::new();
    for pair in file.into_inner() {
        if pair.as_rule() == Rule::statement {
            out.push(statement(src, pair, 1)?);
        }
    }
    Ok(out)
}

fn too_deep(src: &Source, span: TextRange) -> Error {
    src.error(
        span,
        format!("nesting deeper than {MAX_NESTING} levels"),
        "the limit is reached here",
    )
}

fn statement(src: &Source, pair: Pair<'_, Rule>, depth: usize) -> Result<Statement> {
    let span = TextRange::from(pair.as_span());
    if depth > MAX_NESTING {
        // Point at the statement's name, not at everything it holds.
        let at = pair
            .clone()
            .into_inner()
            .find(|p| p.as_rule() == Rule::name)
            .map_or(span, |p| p.as_span().into());
        return Err(too_deep(src, at));
    }
    let mut modifiers = Modifiers::default();
    let mut name = String::new();
    let mut name_span = span;
    let mut args = Vec::new();
    let mut args_span = span;
    let mut children = Vec::new();
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::modifier => match p.as_str() {
                "#" => modifiers.highlight = true,
                "%" => modifiers.background = true,
                "*" => modifiers.disable = true,
                _ => modifiers.root = true,
            },
            Rule::name => {
                name = p.as_str().to_string();
                name_span = p.as_span().into();
            }
            Rule::arg_list => {
                args_span = p.as_span().into();
                for a in p.into_inner() {
                    if a.as_rule() == Rule::argument {
                        // Vectors nest on their own count, from 1.
                        args.push(argument(src, a)?);
                    }
                }
            }
            Rule::block => {
                for s in p.into_inner() {
                    if s.as_rule() == Rule::statement {
                        children.push(statement(src, s, depth + 1)?);
                    }
                }
            }
            Rule::statement => children.push(statement(src, p, depth + 1)?),
            _ => {}
        }
    }
    Ok(Statement {
        modifiers,
        name,
        name_span,
        args,
        args_span,
        children,
        span,
    })
}

fn argument(src: &Source, pair: Pair<'_, Rule>) -> Result<Arg> {
    let span = TextRange::from(pair.as_span());
    let mut name = None;
    let mut value = None;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::name => name = Some((p.as_str().to_string(), p.as_span().into())),
            Rule::equals => {}
            _ => value = Some(self::value(src, p, 1)?),
        }
    }
    let value = value.expect("the grammar gives every argument a value");
    Ok(Arg { name, value, span })
}

fn value(src: &Source, pair: Pair<'_, Rule>, depth: usize) -> Result<Value> {
    let span = TextRange::from(pair.as_span());
    if depth > MAX_NESTING {
        return Err(too_deep(src, span));
    }
    let kind = match pair.as_rule() {
        Rule::number => ValueKind::Number(parse_number(pair.as_str())),
        Rule::string => {
            let body = pair.into_inner().next().map_or("", |p| p.as_str());
            ValueKind::Str(unescape(body))
        }
        Rule::boolean => ValueKind::Bool(pair.as_str() == "true"),
        Rule::undef => ValueKind::Undef,
        Rule::vector => {
            let mut items = Vec::new();
            for p in pair.into_inner() {
                match p.as_rule() {
                    Rule::open_bracket | Rule::close_bracket | Rule::comma => {}
                    _ => items.push(self::value(src, p, depth + 1)?),
                }
            }
            ValueKind::Vector(items)
        }
        r => unreachable!("value rule {r:?}"),
    };
    Ok(Value { kind, span })
}

/// Numbers as OpenSCAD prints them; `inf` and `nan` are accepted here and
/// rejected later wherever a finite value is needed.
fn parse_number(text: &str) -> f64 {
    let (sign, body) = match text.as_bytes()[0] {
        b'-' => (-1.0, &text[1..]),
        b'+' => (1.0, &text[1..]),
        _ => (1.0, text),
    };
    let magnitude = match body {
        "inf" => f64::INFINITY,
        "nan" => f64::NAN,
        _ => body
            .parse::<f64>()
            .expect("the grammar only admits numbers Rust can read"),
    };
    sign * magnitude
}

fn unescape(body: &str) -> String {
    let mut out = String::with_capacity(body.len());
    let mut chars = body.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some('n') => out.push('\n'),
                Some('t') => out.push('\t'),
                Some('r') => out.push('\r'),
                Some(other) => out.push(other),
                None => {}
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// How a rule is named when the parser says what it expected.
fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::statement => "a statement",
        Rule::modifier => "a modifier",
        Rule::name => "a name",
        Rule::arg_list | Rule::open_paren => "`(`",
        Rule::close_paren => "`)`",
        Rule::open_brace | Rule::block => "`{`",
        Rule::close_brace => "`}`",
        Rule::open_bracket | Rule::vector => "a vector",
        Rule::close_bracket => "`]`",
        Rule::comma => "`,`",
        Rule::equals => "`=`",
        Rule::terminator => "`;`",
        Rule::argument => "an argument",
        Rule::number => "a number",
        Rule::string | Rule::string_body => "a string",
        Rule::boolean => "`true` or `false`",
        Rule::undef => "`undef`",
        Rule::EOI => "the end of the file",
        // A file that fails at its first token.
        Rule::file => "a statement or the end of the file",
        _ => "more input",
    }
}

/// Joins names as "a, b or c".
pub(crate) fn one_of(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!("{} or {}", init.join(", "), last),
    }
}

fn syntax_error(src: &Source, e: pest::error::Error<Rule>) -> Error {
    use pest::error::{ErrorVariant, InputLocation};
    let pos = match e.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let found = describe_found(&src.text[pos.min(src.text.len())..]);
    let (message, span_len) = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } if !positives.is_empty() => {
            // Sorted, so that messages do not depend on the grammar's order.
            let mut names: Vec<&str> = positives.iter().map(|r| rule_name(*r)).collect();
            names.sort_unstable();
            names.dedup();
            (
                format!("expected {}, found {}", one_of(&names), found.0),
                found.1,
            )
        }
        ErrorVariant::ParsingError { .. } => (format!("unexpected {}", found.0), found.1),
        // pest's own guards against deep recursion.
        ErrorVariant::CustomError { message } if message.contains("limit reached") => {
            ("the file nests too deeply to be parsed".to_string(), 1)
        }
        ErrorVariant::CustomError { message } => (message.clone(), 1),
    };
    let label = if message.starts_with("expected") {
        ""
    } else {
        "the parser stopped here"
    };
    src.error(TextRange::new(pos, pos + span_len), message, label)
}

/// Names what stands at the error position, and how many bytes to underline.
fn describe_found(rest: &str) -> (String, usize) {
    let Some(c) = rest.chars().next() else {
        return ("the end of the file".to_string(), 0);
    };
    if c.is_ascii_alphanumeric() || c == '_' || c == '$' {
        let word: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '$' || *c == '.')
            .collect();
        let len = word.len();
        (format!("`{word}`"), len)
    } else if c == '\n' || c == '\r' {
        ("the end of the line".to_string(), 1)
    } else {
        (format!("`{c}`"), c.len_utf8())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<Statement>> {
        parse_csg(&Source::new("t.csg", text))
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn reads_every_lexical_form() {
        let s = parse(
            "/* block */ group() {\n\t// line\n\t#%*!multmatrix([[1, 0, 0, -0], [0, 1, 0, 1e+06], [0, 0, 1, -2.65809e-06], [0, 0, 0, 1]]) cube(size = [1, 2, 3], center = true, $fn = 0);\n  text(text = \"a \\\"q\\\"\", b = undef, c = false, d = inf, e = -inf, f = .5,);\n}\nsphere(1);",
        )
        .unwrap();
        assert_eq!(s.len(), 2);
        let g = &s[0];
        assert_eq!(g.name, "group");
        assert_eq!(g.children.len(), 2);
        let m = &g.children[0];
        assert!(m.modifiers.highlight && m.modifiers.background);
        assert!(m.modifiers.disable && m.modifiers.root);
        assert_eq!(m.children[0].name, "cube");
        let ValueKind::Vector(rows) = &m.args[0].value.kind else {
            panic!()
        };
        let ValueKind::Vector(r1) = &rows[1].kind else {
            panic!()
        };
        assert_eq!(r1[3].kind, ValueKind::Number(1e6));
        let t = &g.children[1];
        assert_eq!(t.args[0].value.kind, ValueKind::Str("a \"q\"".into()));
        assert_eq!(t.args[1].value.kind, ValueKind::Undef);
        assert_eq!(t.args[2].value.kind, ValueKind::Bool(false));
        assert_eq!(t.args[3].value.kind, ValueKind::Number(f64::INFINITY));
        assert_eq!(t.args[4].value.kind, ValueKind::Number(f64::NEG_INFINITY));
        assert_eq!(t.args[5].value.kind, ValueKind::Number(0.5));
        assert_eq!(s[1].args[0].name, None);
    }

    #[test]
    fn empty_statements_are_allowed_as_in_openscad() {
        let s = parse(";\ngroup() { cube(); ; };\n;").unwrap();
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].children.len(), 1);
    }

    #[test]
    fn negative_zero_keeps_its_sign() {
        let s = parse("translate([-0, 0, 0]) cube();").unwrap();
        let ValueKind::Vector(v) = &s[0].args[0].value.kind else {
            panic!()
        };
        let ValueKind::Number(x) = v[0].kind else {
            panic!()
        };
        assert!(x == 0.0 && x.is_sign_negative());
    }

    #[test]
    fn a_missing_semicolon_names_what_was_expected() {
        assert_eq!(
            err("cube(1)\n"),
            "error: expected `;`, `{` or a statement, found the end of the file\n --> t.csg:2:1\n  |\n2 | \n  | ^"
        );
    }

    #[test]
    fn an_unclosed_argument_list_points_at_the_stray_token() {
        assert_eq!(
            err("sphere(r = 1;\n"),
            "error: expected `)` or `,`, found `;`\n --> t.csg:1:13\n  |\n1 | sphere(r = 1;\n  |             ^"
        );
    }

    #[test]
    fn nesting_past_the_limit_is_an_error_not_a_crash() {
        // On a thread with the CLI's stack, as the CLI parses.
        let depth = MAX_NESTING + 1;
        let text = "group() {".repeat(depth) + &"}".repeat(depth);
        let e = std::thread::Builder::new()
            .stack_size(MAIN_STACK)
            .spawn(move || err(&text))
            .unwrap()
            .join()
            .unwrap();
        assert!(
            e.starts_with("error: nesting deeper than 4096 levels\n"),
            "{e}"
        );
    }
}
