//! `--dump-scene`: the resolved scene as JSON — camera, lights, materials
//! and the CSG tree with each primitive's world matrix — csgrt's own
//! reading, for a person to inspect. The oracle in `tools/` reads the
//! model file itself; of the dump it takes only the box the default camera
//! framed (`framed`), which it checks against its own mesh's box.

use crate::csg::{Csg, NodeKind};
use crate::geometry::Param;
use crate::scene::{CameraSpec, Light, Scene};
use glam::{DAffine3, DVec3};
use serde_json::{json, Value};

fn v3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// Row-major 4×4.
fn matrix(m: &DAffine3) -> Value {
    let c = |j: usize| m.matrix3.col(j);
    let t = m.translation;
    json!([
        [c(0).x, c(1).x, c(2).x, t.x],
        [c(0).y, c(1).y, c(2).y, t.y],
        [c(0).z, c(1).z, c(2).z, t.z],
        [0.0, 0.0, 0.0, 1.0]
    ])
}

fn node(csg: &Csg, id: u32) -> Value {
    let n = &csg.nodes[id as usize];
    let kids = |ch: &Vec<u32>| Value::Array(ch.iter().map(|&c| node(csg, c)).collect());
    match &n.kind {
        NodeKind::Op(op, ch) => json!({"op": op.name(), "children": kids(ch)}),
        &NodeKind::Section(c, k) => json!({
            "section": k,
            "matrix": matrix(&csg.sections[k as usize].xf.to_world),
            "child": node(csg, c),
        }),
        NodeKind::Leaf(p) => {
            let prim = &csg.prims[*p as usize];
            let mut v = json!({
                "primitive": prim.shape.name(),
                "id": p,
                "matrix": matrix(&prim.xf.to_world),
                "material": prim.material,
            });
            for (key, value) in prim.shape.params() {
                v[key] = match value {
                    Param::Bool(b) => json!(b),
                    Param::Num(x) => json!(x),
                };
            }
            v
        }
    }
}

pub fn scene_json(scene: &Scene, cam: &CameraSpec, width: u32, height: u32) -> Value {
    let lights: Vec<Value> = scene
        .lights_seen_by(cam)
        .iter()
        .map(|l| match *l {
            Light::Ambient { color } => json!({"type": "ambient", "color": v3(color)}),
            Light::Directional {
                color,
                direction,
                shadows,
            } => {
                json!({"type": "directional", "color": v3(color), "direction": v3(direction), "shadows": shadows})
            }
            Light::Point { color, position } => {
                json!({"type": "point", "color": v3(color), "position": v3(position)})
            }
        })
        .collect();
    let materials: Vec<Value> = scene
        .materials
        .iter()
        .map(|m| {
            json!({"color": v3(m.color), "ka": m.ka, "kd": m.kd, "ks": m.ks, "ns": m.ns,
                   "kr": m.kr, "kt": m.kt, "ior": m.ior})
        })
        .collect();
    json!({
        "camera": {"eye": v3(cam.eye), "lookat": v3(cam.lookat), "up": v3(cam.up),
                   "fov": cam.fov, "width": width, "height": height,
                   "projection": match cam.projection {
                       crate::scene::Projection::Perspective => "perspective",
                       crate::scene::Projection::Orthographic => "orthographic",
                   }},
        "framed": scene
            .framed
            .or_else(|| scene.camera.is_none().then(|| scene.framing_bounds()))
            .map_or(Value::Null, |b| json!({"min": v3(b.min), "max": v3(b.max)})),
        "background": v3(scene.background),
        "lights": lights,
        "materials": materials,
        "root": scene.csg.root.map_or(Value::Null, |r| node(&scene.csg, r)),
    })
}
