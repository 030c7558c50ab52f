//! `--export-pov`: the resolved scene as POV-Ray 3.7 SDL, keeping the CSG
//! tree, so that the two renderers can be compared on the same scene.
//!
//! * Geometry: each primitive is POV's own generic solid (`sphere`, `box`,
//!   `cone`/`cylinder`, `torus` turned from POV's y axis to z, `plane`)
//!   under csgrt's world matrix, written as POV's row-vector `matrix`;
//!   unions, intersections and differences stay CSG.
//! * Camera: POV is left-handed; `right -x*aspect` makes it right-handed
//!   like csgrt, `sky` is csgrt's up, `angle` its horizontal field of view.
//! * Shading: `ambient ka` (against `ambient_light`), `diffuse kd`,
//!   `phong ks phong_size ns`, `reflection kr`; `transmit kt` with an
//!   `interior { ior }`. POV weighs a transmitting surface's own colour by
//!   1 − kt where the lecture's model adds both, so glass differs a little.
//! * `assumed_gamma 1.0` and `max_trace_level`, `adc_bailout 1/512` as
//!   csgrt's ray tree. Render with `+FN +W… +H… File_Gamma=1.0` to match.

use crate::csg::{Csg, NodeKind};
use crate::math::boolean::Op;
use crate::scene::{CameraSpec, Light, Projection, Scene};
use glam::{DAffine3, DVec3};
use std::fmt::Write;

fn v(p: DVec3) -> String {
    format!("<{:?}, {:?}, {:?}>", p.x, p.y, p.z)
}

fn matrix(m: &DAffine3) -> String {
    let c = |j: usize| m.matrix3.col(j);
    let t = m.translation;
    let nums: Vec<String> = [c(0), c(1), c(2), t]
        .iter()
        .flat_map(|r| [r.x, r.y, r.z])
        .map(|x| format!("{x:?}"))
        .collect();
    format!("matrix <{}>", nums.join(", "))
}

/// POV-Ray has no solid made from another's slice: the export stops
/// POV-Ray with the reason.
pub const SECTION_ERROR: &str =
    "#error \"csgrt: projection(cut = true) has no POV-Ray equivalent\"";

/// Nor an even-odd combination of solids (a drawing's arcs, ellipses and
/// strokes by parity with its outlines).
pub const XOR_ERROR: &str =
    "#error \"csgrt: a drawing's outlines combined even-odd have no POV-Ray equivalent\"";

fn node(scene: &Scene, csg: &Csg, id: u32, depth: usize, out: &mut String) {
    let pad = "  ".repeat(depth);
    let n = &csg.nodes[id as usize];
    let (word, kids) = match &n.kind {
        NodeKind::Op(Op::Xor, _) => {
            let _ = writeln!(out, "{pad}{XOR_ERROR}\n{pad}sphere {{ <0, 0, 0>, 0 }}");
            return;
        }
        // POV-Ray's union, intersection and difference mean the same.
        NodeKind::Op(op, ch) => (op.name(), ch),
        NodeKind::Section(..) => {
            let _ = writeln!(out, "{pad}{SECTION_ERROR}\n{pad}sphere {{ <0, 0, 0>, 0 }}");
            return;
        }
        NodeKind::Leaf(p) => {
            let prim = &csg.prims[*p as usize];
            let solid = prim.shape.pov();
            let m = &scene.materials[prim.material as usize];
            let _ = writeln!(
                out,
                "{pad}{solid} {}\n{pad}  texture {{ pigment {{ color rgbt <{:?}, {:?}, {:?}, {:?}> }} finish {{ ambient {:?} diffuse {:?} phong {:?} phong_size {:?} reflection {:?} }} }}{}\n{pad}}}",
                matrix(&prim.xf.to_world),
                m.color.x,
                m.color.y,
                m.color.z,
                m.kt,
                m.ka,
                m.kd,
                m.ks,
                m.ns,
                m.kr,
                if m.kt > 0.0 {
                    format!(" interior {{ ior {:?} }}", m.ior)
                } else {
                    String::new()
                },
            );
            return;
        }
    };
    let _ = writeln!(out, "{pad}{word} {{");
    for &c in kids {
        node(scene, csg, c, depth + 1, out);
    }
    let _ = writeln!(out, "{pad}}}");
}

/// The scene as POV-Ray 3.7 SDL for an image of `width`×`height`.
pub fn scene_sdl(
    scene: &Scene,
    cam: &CameraSpec,
    width: u32,
    height: u32,
    max_depth: u32,
) -> String {
    let mut out = String::new();
    let ambient = scene.lights.iter().fold(DVec3::ZERO, |a, l| match l {
        Light::Ambient { color } => a + *color,
        _ => a,
    });
    let _ = writeln!(out, "// Written by csgrt --export-pov.\n#version 3.7;");
    let _ = writeln!(
        out,
        "global_settings {{ assumed_gamma 1.0 max_trace_level {} adc_bailout 1/512 ambient_light color rgb {} }}",
        max_depth.max(1) + 1,
        v(ambient)
    );
    let _ = writeln!(out, "background {{ color rgb {} }}", v(scene.background));
    match cam.projection {
        Projection::Perspective => {
            let _ = writeln!(
                out,
                "camera {{ perspective location {} sky {} right -x*{:?} up y look_at {} angle {:?} }}",
                v(cam.eye),
                v(cam.up),
                width as f64 / height as f64,
                v(cam.lookat),
                cam.fov
            );
        }
        Projection::Orthographic => {
            // POV-Ray's orthographic rays start on the plane through its
            // location and show `right` × `up` world units: csgrt's.
            let look = cam.lookat - cam.eye;
            let wide = 2.0 * look.length() * (0.5 * cam.fov).to_radians().tan();
            let _ = writeln!(
                out,
                "camera {{ orthographic location {} sky {} right -x*{:?} up y*{:?} look_at {} }}",
                v(cam.eye - crate::render::camera::ORTHO_BACK * look),
                v(cam.up),
                wide,
                wide * height as f64 / width as f64,
                v(cam.lookat)
            );
        }
    }
    let far = {
        // The parts' box (a distance far past the scene; no tighter box needed).
        let mut b = scene.csg.bounds();
        if !b.is_bounded() {
            b = scene.framing_bounds();
        }
        let size = if b.is_bounded() {
            (b.max - b.min).length()
        } else {
            1.0
        };
        (size.max(1.0)) * 1e4
    };
    for l in &scene.lights {
        match *l {
            Light::Ambient { .. } => {}
            Light::Point { color, position } => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color rgb {} }}",
                    v(position),
                    v(color)
                );
            }
            Light::Directional { color, direction } => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color rgb {} parallel point_at <0, 0, 0> }}",
                    v(-direction * far),
                    v(color)
                );
            }
        }
    }
    if let Some(r) = scene.csg.root {
        node(scene, &scene.csg, r, 0, &mut out);
    }
    out
}
