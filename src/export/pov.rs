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
//! * Colours: the scene's linear values (csgrt decodes the sRGB colours a
//!   file gives) under `assumed_gamma 1.0`; POV-Ray encodes its 8-bit
//!   output as sRGB by default, as csgrt does, so its plain command matches
//!   (the file's first lines give it). `max_trace_level`, `adc_bailout
//!   1/512` as csgrt's ray tree.
//! * Lights: the picture's (csgrt's default rig, placed about the camera,
//!   where the file gives none); a light without shadows is `shadowless`.
//! * Coincident faces: where a difference takes away a part whose face lies
//!   on a face of what it is taken from (an extruded ring: two cylinders of
//!   one height), POV-Ray cannot tell which face is in front and draws
//!   either. csgrt decides such faces exactly; the export gives each part
//!   a difference takes away a clearance instead: the part scaled by
//!   1 + 2·[`CLEARANCE`] about its box's centre (a part taken away inside
//!   a part taken away shrinks by as much), written after its matrix as
//!   `translate -c scale k translate c`. Its faces move by at most
//!   [`CLEARANCE`] of its box's diagonal: no pixel of an image under
//!   10,000 pixels across the part.

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

/// How far (a fraction of its box's diagonal) a part that a difference
/// takes away is grown past the faces it may share (see the module's text).
pub const CLEARANCE: f64 = 1e-4;

/// `clear`: +1 for a part a difference takes away (grown by the
/// clearance), −1 for one taken away from such a part (shrunk), 0 else.
fn node(scene: &Scene, csg: &Csg, id: u32, depth: usize, clear: i8, out: &mut String) {
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
            let mut placed = matrix(&prim.xf.to_world);
            if clear != 0 && prim.bounds.is_bounded() && !prim.bounds.is_empty() {
                let c = prim.bounds.center();
                let room = if crate::mutant::active("pov_clearance_wide") {
                    100.0 * CLEARANCE
                } else {
                    CLEARANCE
                };
                let k = 1.0 + 2.0 * room * clear as f64;
                let _ = write!(
                    placed,
                    " translate {} scale {k:?} translate {}",
                    v(-c),
                    v(c)
                );
            }
            let _ = writeln!(
                out,
                "{pad}{solid} {}\n{pad}  texture {{ pigment {{ color rgbt <{:?}, {:?}, {:?}, {:?}> }} finish {{ ambient {:?} diffuse {:?} phong {:?} phong_size {:?} reflection {:?} }} }}{}\n{pad}}}",
                placed,
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
    for (i, &c) in kids.iter().enumerate() {
        let taken = matches!(n.kind, NodeKind::Op(Op::Difference, _)) && i > 0;
        let sign = match (taken, clear) {
            (false, s) => s,
            (true, 0) => 1,
            (true, s) => -s,
        };
        node(scene, csg, c, depth + 1, sign, out);
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
    let lights = scene.lights_seen_by(cam);
    let ambient = lights.iter().fold(DVec3::ZERO, |a, l| match l {
        Light::Ambient { color } => a + *color,
        _ => a,
    });
    let _ = writeln!(
        out,
        "// Written by csgrt --export-pov. To match csgrt's image (colours linear, the PNG sRGB):\n\
         //   povray +IFILE.pov +OFILE.png +W{width} +H{height} +A0.3\n\
         // Parts a difference takes away are scaled by 1 ± {:?} about their box's centre\n\
         // (`translate scale translate` after their matrix), clear of the faces they share.\n\
         #version 3.7;",
        2.0 * CLEARANCE
    );
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
    for l in lights.iter() {
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
            Light::Directional {
                color,
                direction,
                shadows,
            } => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color rgb {} parallel point_at <0, 0, 0>{} }}",
                    v(-direction * far),
                    v(color),
                    if shadows || crate::mutant::active("pov_shadows_kept") {
                        ""
                    } else {
                        " shadowless"
                    }
                );
            }
        }
    }
    if let Some(r) = scene.csg.root {
        node(scene, &scene.csg, r, 0, 0, &mut out);
    }
    out
}
