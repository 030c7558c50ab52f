//! The seed's display list (`.ray`, `grammar/ray.pest`) → a list of
//! [`RayStatement`]s with their places. The scene reads them
//! (`scene::display_list`); nothing here gives them a meaning.

use crate::error::{Error, Result, TextRange};
use crate::source::Source;
use glam::DVec3;
use pest::iterators::Pair;
use pest::Parser;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/ray.pest"]
struct RayParser;

fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::number => "a number",
        Rule::ambient | Rule::directional | Rule::point => {
            "`ambient`, `directional` or `point`"
        }
        Rule::EOI => "the end of the file",
        _ => {
            "a statement (`eye`, `lookat`, `up`, `fov`, `background`, `light`, `surface` or `sphere`)"
        }
    }
}

fn syntax_error(src: &Source, e: pest::error::Error<Rule>) -> Error {
    use pest::error::{ErrorVariant, InputLocation};
    let pos = match e.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let rest = &src.text[pos.min(src.text.len())..];
    let (found, len) = match rest.chars().next() {
        None => ("the end of the file".to_string(), 0),
        Some('\n' | '\r') => ("the end of the line".to_string(), 0),
        Some(_) => {
            let w: String = rest.chars().take_while(|c| !c.is_whitespace()).collect();
            (format!("`{w}`"), w.len())
        }
    };
    let mut names: Vec<&str> = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } => {
            positives.iter().map(|r| rule_name(*r)).collect()
        }
        ErrorVariant::CustomError { .. } => vec![],
    };
    names.sort_unstable();
    names.dedup();
    let expected = if names.is_empty() {
        "a statement".to_string()
    } else {
        super::one_of(&names)
    };
    src.error(
        TextRange::new(pos, pos + len),
        format!("expected {expected}, found {found}"),
        "",
    )
}

fn numbers(p: Pair<'_, Rule>) -> Vec<f64> {
    p.into_inner()
        .filter(|x| x.as_rule() == Rule::number)
        .map(|x| x.as_str().parse().expect("the grammar admits only numbers"))
        .collect()
}

fn v3(n: &[f64]) -> DVec3 {
    DVec3::new(n[0], n[1], n[2])
}

/// One statement of a display list, its numbers as written.
#[derive(Clone, Debug, PartialEq)]
pub enum RayStatement {
    Eye(DVec3),
    Lookat(DVec3),
    Up(DVec3),
    /// The horizontal field of view in degrees.
    Fov(f64),
    Background(DVec3),
    Light {
        color: DVec3,
        kind: RayLight,
    },
    /// `surface r g b ka kd ks ns kr kt nt`.
    Surface([f64; 10]),
    /// `sphere x y z r`.
    Sphere([f64; 4]),
}

/// A display list's light kinds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RayLight {
    Ambient,
    Directional(DVec3),
    Point(DVec3),
}

/// Parses a display list into its statements, each with its place.
pub fn parse_ray(src: &Source) -> Result<Vec<(RayStatement, TextRange)>> {
    let file = RayParser::parse(Rule::file, &src.text)
        .map_err(|e| syntax_error(src, e))?
        .next()
        .expect("the file rule yields one pair");
    let mut out = Vec::new();
    for st in file.into_inner() {
        let rule = st.as_rule();
        let span = TextRange::from(st.as_span());
        let statement = match rule {
            Rule::eye => RayStatement::Eye(v3(&numbers(st))),
            Rule::lookat => RayStatement::Lookat(v3(&numbers(st))),
            Rule::up => RayStatement::Up(v3(&numbers(st))),
            Rule::fov => RayStatement::Fov(numbers(st)[0]),
            Rule::background => RayStatement::Background(v3(&numbers(st))),
            Rule::light => {
                let mut inner = st.into_inner();
                let c: Vec<f64> = inner
                    .by_ref()
                    .take(3)
                    .map(|x| x.as_str().parse().unwrap())
                    .collect();
                let kind = inner.next().expect("the grammar gives every light a kind");
                let kind = match kind.as_rule() {
                    Rule::ambient => RayLight::Ambient,
                    Rule::directional => RayLight::Directional(v3(&numbers(kind))),
                    _ => RayLight::Point(v3(&numbers(kind))),
                };
                RayStatement::Light {
                    color: v3(&c),
                    kind,
                }
            }
            Rule::surface => {
                let n = numbers(st);
                RayStatement::Surface(std::array::from_fn(|i| n[i]))
            }
            Rule::sphere => {
                let n = numbers(st);
                RayStatement::Sphere(std::array::from_fn(|i| n[i]))
            }
            _ => continue,
        };
        out.push((statement, span));
    }
    Ok(out)
}
