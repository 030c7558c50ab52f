//! The seed's display list (`.ray`, `grammar/ray.pest`) → [`Scene`].
//!
//! The format is flat, so it is read straight into a scene (through the one
//! [`SceneBuilder`]): the camera and
//! background statements set the view, `light` adds a light, `surface`
//! sets the material of the spheres after it, `sphere` adds one. All the
//! spheres form a union. Colours and coefficients are in [0, 1] (the
//! lecture's applet divided kr and kt by 255 because its colours were
//! bytes; csgrt's are not).

use crate::error::{Error, Result, TextRange};
use crate::geometry::transform::MAX_MAGNITUDE;
use crate::geometry::{Shape, Transform};
use crate::scene::builder::SceneBuilder;
use crate::scene::{defaults, CameraSpec, Light, Material, Scene};
use crate::source::Source;
use glam::{DAffine3, DVec3};
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

/// Parses a display list into a scene.
pub fn load_ray(src: &Source) -> Result<Scene> {
    let file = RayParser::parse(Rule::file, &src.text)
        .map_err(|e| syntax_error(src, e))?
        .next()
        .expect("the file rule yields one pair");
    let mut cam = CameraSpec {
        eye: DVec3::new(0.0, 0.0, 10.0),
        lookat: DVec3::ZERO,
        up: DVec3::Y,
        fov: 30.0,
        projection: Default::default(),
    };
    let mut b = SceneBuilder::new();
    let mut current: Option<u32> = None;
    let mut spheres = Vec::new();
    let mut camera_span = None;
    for st in file.into_inner() {
        let rule = st.as_rule();
        let span = TextRange::from(st.as_span());
        match rule {
            Rule::eye | Rule::lookat | Rule::up | Rule::fov => {
                camera_span.get_or_insert(span);
                let n = numbers(st);
                match rule {
                    Rule::eye => cam.eye = v3(&n),
                    Rule::lookat => cam.lookat = v3(&n),
                    Rule::up => cam.up = v3(&n),
                    _ => {
                        if !(n[0] > 0.0 && n[0] < 180.0) {
                            return Err(src.error(
                                span,
                                "the field of view is out of range",
                                "expected degrees strictly between 0 and 180",
                            ));
                        }
                        cam.fov = n[0];
                    }
                }
            }
            Rule::background => b.background = Some(v3(&numbers(st))),
            Rule::light => {
                let mut inner = st.into_inner();
                let c: Vec<f64> = inner
                    .by_ref()
                    .take(3)
                    .map(|x| x.as_str().parse().unwrap())
                    .collect();
                let color = v3(&c);
                let kind = inner.next().expect("the grammar gives every light a kind");
                let light = match kind.as_rule() {
                    Rule::ambient => Light::Ambient { color },
                    Rule::directional => {
                        let d = v3(&numbers(kind));
                        if d.length_squared() == 0.0 {
                            return Err(src.error(
                                span,
                                "a light's direction must not be zero",
                                "expected a non-zero direction",
                            ));
                        }
                        Light::Directional {
                            color,
                            direction: d.normalize(),
                        }
                    }
                    _ => Light::Point {
                        color,
                        position: v3(&numbers(kind)),
                    },
                };
                b.lights.push(light);
            }
            Rule::surface => {
                let n = numbers(st);
                if n[3..].iter().any(|x| *x < 0.0) || n[9] == 0.0 {
                    return Err(src.error(
                        span,
                        "a surface's coefficients must not be negative, nor its index zero",
                        "expected `surface r g b ka kd ks ns kr kt nt`",
                    ));
                }
                let m = Material {
                    color: v3(&n),
                    ka: n[3],
                    kd: n[4],
                    ks: n[5],
                    ns: n[6],
                    kr: n[7],
                    kt: n[8],
                    ior: n[9],
                    scheme_color: false,
                };
                current = Some(b.material_id(m));
            }
            Rule::sphere => {
                let n = numbers(st);
                if n[3] <= 0.0 {
                    return Err(src.error(
                        span,
                        "a sphere's radius must be positive",
                        "expected `sphere x y z r` with r > 0",
                    ));
                }
                let material = *current.get_or_insert_with(|| b.material_id(defaults::MATERIAL));
                let r = if crate::mutant::active("sphere_small") {
                    0.97 * n[3]
                } else {
                    n[3]
                };
                let m = DAffine3::from_translation(v3(&n)) * DAffine3::from_scale(DVec3::splat(r));
                let Ok(xf) = Transform::new(m) else {
                    return Err(src.error(
                        span,
                        "this sphere is out of range",
                        format!(
                            "expected a centre within ±{MAX_MAGNITUDE:e} and a radius from {:e} to {MAX_MAGNITUDE:e}",
                            1.0 / MAX_MAGNITUDE
                        ),
                    ));
                };
                spheres.push(b.leaf(Shape::Sphere(crate::geometry::Sphere), xf, material));
            }
            _ => {}
        }
    }
    let look = cam.lookat - cam.eye;
    if look.cross(cam.up).length_squared() == 0.0 {
        return Err(src.error(
            camera_span.unwrap_or_default(),
            "the camera is degenerate",
            "expected `eye` apart from `lookat`, and `up` not along the view",
        ));
    }
    b.camera = Some(cam);
    let root = b.union(spheres);
    // The lecture's display lists have a black background by default.
    Ok(b.finish(src, root, TextRange::default(), DVec3::ZERO))
}
