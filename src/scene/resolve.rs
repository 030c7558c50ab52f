//! Syntax tree → [`Scene`]: transforms composed, materials inherited,
//! defaults applied, every problem reported at its place in the file.

use super::args::Args;
use super::{defaults, CameraSpec, Light, Material, Scene};
use crate::csg::spans::Op;
use crate::csg::{Csg, Primitive};
use crate::error::{Diagnostic, Result, Severity, Source, TextRange};
use crate::geometry::transform::{Degenerate, MAX_MAGNITUDE};
use crate::geometry::{Cone, Cuboid, Halfspace, Shape, Sphere, Torus, Transform};
use crate::mutant;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DMat3, DVec3};

const SOLIDS: &[&str] = &["cube", "sphere", "cylinder", "torus", "halfspace"];
const TRANSFORMS: &[&str] = &["multmatrix", "translate", "rotate", "scale", "mirror"];
const OPERATIONS: &[&str] = &["union", "intersection", "difference", "group", "render"];
const APPEARANCE: &[&str] = &["color", "material"];
const SCENE: &[&str] = &[
    "camera",
    "background",
    "ambient_light",
    "directional_light",
    "point_light",
];
/// OpenSCAD nodes csgrt does not render yet: an error, never skipped.
const UNSUPPORTED: &[&str] = &[
    "linear_extrude",
    "rotate_extrude",
    "square",
    "circle",
    "polygon",
    "text",
    "import",
    "surface",
    "projection",
    "offset",
    "hull",
    "minkowski",
    "resize",
    "polyhedron",
    "roof",
    "fill",
];

/// Resolves a parsed `.csg` file into a scene.
pub fn resolve(src: &Source, stmts: &[Statement]) -> Result<Scene> {
    let mut r = Resolver {
        src,
        csg: Csg::default(),
        materials: Vec::new(),
        lights: Vec::new(),
        camera: None,
        background: None,
        warnings: Vec::new(),
    };
    // Scene statements are read first, wherever they stand at the top level.
    for s in stmts {
        if SCENE.contains(&s.name.as_str()) && !skipped(s) {
            r.scene_statement(s)?;
        }
    }
    // `!` makes the first subtree that carries it the whole design.
    let root = find_root(stmts);
    let solids: Vec<&Statement> = match root {
        Some(s) => vec![s],
        None => stmts
            .iter()
            .filter(|s| !SCENE.contains(&s.name.as_str()))
            .collect(),
    };
    let mut ids = Vec::new();
    for s in solids {
        if let Some(id) = r.statement(s, DAffine3::IDENTITY, defaults::MATERIAL, 0)? {
            ids.push(id);
        }
    }
    r.csg.root = r.union(ids);
    if r.csg.root.is_none() {
        let span = stmts.first().map_or(TextRange::default(), |s| s.span);
        r.warn(
            span,
            "the scene has no solids",
            "only the background will show",
        );
    }
    if r.materials.is_empty() {
        r.materials.push(defaults::MATERIAL);
    }
    Ok(Scene {
        camera: r.camera.map(|(c, _)| c),
        background: r.background.unwrap_or(defaults::BACKGROUND),
        lights: if r.lights.is_empty() {
            defaults::lights()
        } else {
            r.lights
        },
        materials: r.materials,
        csg: r.csg,
        warnings: r.warnings,
    })
}

fn skipped(s: &Statement) -> bool {
    s.modifiers.disable || s.modifiers.background
}

fn find_root(stmts: &[Statement]) -> Option<&Statement> {
    for s in stmts {
        if skipped(s) {
            continue;
        }
        if s.modifiers.root {
            return Some(s);
        }
        if let Some(r) = find_root(&s.children) {
            return Some(r);
        }
    }
    None
}

struct Resolver<'a> {
    src: &'a Source,
    csg: Csg,
    materials: Vec<Material>,
    lights: Vec<Light>,
    camera: Option<(CameraSpec, TextRange)>,
    background: Option<DVec3>,
    warnings: Vec<Diagnostic>,
}

impl Resolver<'_> {
    fn warn(&mut self, span: TextRange, message: &str, label: &str) {
        let d = self.src.diagnostic(Severity::Warning, span, message, label);
        self.warnings.push(d);
    }

    fn union(&mut self, ids: Vec<u32>) -> Option<u32> {
        match ids.len() {
            0 => None,
            1 => Some(ids[0]),
            _ => Some(self.csg.add_op(Op::Union, ids)),
        }
    }

    fn children(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Vec<u32>> {
        let mut ids = Vec::new();
        for c in &s.children {
            if let Some(id) = self.statement(c, xf, mat, depth + 1)? {
                ids.push(id);
            }
        }
        Ok(ids)
    }

    fn material_id(&mut self, m: Material) -> u32 {
        match self.materials.iter().position(|x| *x == m) {
            Some(i) => i as u32,
            None => {
                self.materials.push(m);
                self.materials.len() as u32 - 1
            }
        }
    }

    /// One statement under the world transform `xf` and material `mat`;
    /// `None` when it adds no solid.
    fn statement(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        if skipped(s) {
            return Ok(None);
        }
        let name = s.name.as_str();
        if SOLIDS.contains(&name) {
            if let Some(c) = s.children.first() {
                return Err(self.src.error(
                    c.span,
                    format!("`{name}` takes no children"),
                    "a solid stands alone; end it with `;`",
                ));
            }
            return self.solid(s, xf, mat);
        }
        if TRANSFORMS.contains(&name) {
            let local = self.transform(s)?;
            let world = if mutant::active("compose_reversed") {
                local * xf
            } else {
                xf * local
            };
            let ids = self.children(s, world, mat, depth)?;
            return Ok(self.union(ids));
        }
        if APPEARANCE.contains(&name) {
            let m = self.appearance(s, mat)?;
            let ids = self.children(s, xf, m, depth)?;
            return Ok(self.union(ids));
        }
        if OPERATIONS.contains(&name) {
            let params: &'static [&'static str] = if name == "render" {
                &["convexity"]
            } else {
                &[]
            };
            Args::bind(self.src, s, params)?;
            return match name {
                "difference" => self.difference(s, xf, mat, depth),
                "intersection" => {
                    // Every operand is built (so errors in any are reported);
                    // an empty operand makes the intersection empty.
                    let mut ids = Vec::new();
                    let mut empty = false;
                    for c in s.children.iter().filter(|c| !skipped(c)) {
                        match self.statement(c, xf, mat, depth + 1)? {
                            Some(id) => ids.push(id),
                            None => empty = true,
                        }
                    }
                    Ok(match ids.len() {
                        _ if empty => None,
                        0 => None,
                        1 => Some(ids[0]),
                        _ => Some(self.csg.add_op(Op::Intersection, ids)),
                    })
                }
                _ => {
                    let ids = self.children(s, xf, mat, depth)?;
                    Ok(self.union(ids))
                }
            };
        }
        if SCENE.contains(&name) {
            let label = if depth == 0 {
                "a scene statement takes no modifiers here"
            } else {
                "move it to the top level of the file"
            };
            return Err(self.src.error(
                s.name_span,
                format!("`{name}` must stand at the top level"),
                label,
            ));
        }
        if UNSUPPORTED.contains(&name) {
            return Err(self.src.error(
                s.name_span,
                format!("`{name}` is not supported yet"),
                "csgrt renders 3-D CSG of cube, sphere, cylinder, torus and halfspace",
            ));
        }
        Err(self.src.error(
            s.name_span,
            format!("unknown statement `{name}`"),
            "expected a solid, a transform, a CSG operation, color, material or a scene statement",
        ))
    }

    /// The first child minus the union of the others; empty if the first
    /// child is.
    fn difference(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        let mut kids = s.children.iter().filter(|c| !skipped(c));
        let Some(first) = kids.next() else {
            return Ok(None);
        };
        let Some(a) = self.statement(first, xf, mat, depth + 1)? else {
            return Ok(None);
        };
        let mut ids = vec![a];
        for c in kids {
            if let Some(id) = self.statement(c, xf, mat, depth + 1)? {
                ids.push(id);
            }
        }
        Ok(Some(if ids.len() == 1 {
            a
        } else {
            self.csg.add_op(Op::Difference, ids)
        }))
    }

    fn leaf(
        &mut self,
        s: &Statement,
        shape: Shape,
        world: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        let xf = match Transform::new(world) {
            Ok(xf) => xf,
            Err(Degenerate::Flat) => {
                self.warn(
                    s.name_span,
                    &format!("this `{}` is flattened by a singular transform", s.name),
                    "it has no volume and is left out, as in OpenSCAD",
                );
                return Ok(None);
            }
            Err(Degenerate::OutOfRange) => {
                return Err(self.src.error(
                    s.name_span,
                    format!("this `{}` is out of range", s.name),
                    format!("expected sizes and positions within ±{MAX_MAGNITUDE:e}"),
                ));
            }
        };
        let material = self.material_id(mat);
        Ok(Some(self.csg.add_prim(Primitive::new(shape, xf, material))))
    }

    fn empty(&mut self, s: &Statement, why: &str) -> Result<Option<u32>> {
        self.warn(s.args_span, &format!("this `{}` is empty", s.name), why);
        Ok(None)
    }

    fn solid(&mut self, s: &Statement, xf: DAffine3, mat: Material) -> Result<Option<u32>> {
        match s.name.as_str() {
            "cube" => {
                let a = Args::bind(self.src, s, &["size", "center"])?;
                let size = a.scalar_or_vec3("size", 1.0)?.unwrap_or(DVec3::ONE);
                let center = a.boolean("center")?.unwrap_or(false);
                if size.min_element() <= 0.0 {
                    return self.empty(s, "a size is zero or negative");
                }
                // Centring is the shape's, so the translation stays exact.
                let scale = if center { 0.5 * size } else { size };
                let shape = Shape::Cuboid(Cuboid { centered: center });
                self.leaf(s, shape, xf * DAffine3::from_scale(scale), mat)
            }
            "sphere" => {
                let a = Args::bind(self.src, s, &["r", "d"])?;
                let r = match (a.number("r")?, a.number("d")?) {
                    (_, Some(d)) => d / 2.0,
                    (Some(r), None) => r,
                    (None, None) => 1.0,
                };
                let r = if mutant::active("sphere_small") {
                    0.97 * r
                } else {
                    r
                };
                if r <= 0.0 {
                    return self.empty(s, "its radius is zero or negative");
                }
                self.leaf(
                    s,
                    Shape::Sphere(Sphere),
                    xf * DAffine3::from_scale(DVec3::splat(r)),
                    mat,
                )
            }
            "cylinder" => {
                let a = Args::bind(
                    self.src,
                    s,
                    &["h", "r1", "r2", "center", "r", "d", "d1", "d2"],
                )?;
                let h = a.number("h")?.unwrap_or(1.0);
                let center = a.boolean("center")?.unwrap_or(false)
                    && !mutant::active("cylinder_center_ignored");
                // As OpenSCAD: a diameter beats a radius, r1/r2 beat r.
                let radius = |d: &str, r: &str| -> Result<Option<f64>> {
                    Ok(a.non_negative(d)?.map(|d| d / 2.0).or(a.non_negative(r)?))
                };
                let r = radius("d", "r")?.unwrap_or(1.0);
                let r1 = radius("d1", "r1")?.unwrap_or(r);
                let r2 = radius("d2", "r2")?.unwrap_or(r);
                if h <= 0.0 {
                    return self.empty(s, "its height is zero or negative");
                }
                let rmax = r1.max(r2);
                if rmax <= 0.0 {
                    return self.empty(s, "both its radii are zero");
                }
                let shape = Shape::Cone(Cone {
                    r0: r1 / rmax,
                    r1: r2 / rmax,
                    centered: center,
                });
                let local = DAffine3::from_scale(DVec3::new(rmax, rmax, h));
                self.leaf(s, shape, xf * local, mat)
            }
            "torus" => {
                let a = Args::bind(self.src, s, &["R", "r"])?;
                let big = a.non_negative("R")?.unwrap_or(2.0);
                let small = a.non_negative("r")?.unwrap_or(0.5);
                if big <= 0.0 || small <= 0.0 {
                    return self.empty(s, "a radius is zero");
                }
                if small >= big {
                    return Err(a.error(
                        a.span_of("r"),
                        "the tube radius `r` of a torus must be smaller than `R`",
                        format!("expected a number < {big}"),
                    ));
                }
                let shape = Shape::Torus(Torus { minor: small / big });
                self.leaf(s, shape, xf * DAffine3::from_scale(DVec3::splat(big)), mat)
            }
            "halfspace" => {
                let a = Args::bind(self.src, s, &["normal", "offset"])?;
                let n = a.vec3("normal", 0.0)?.unwrap_or(DVec3::Z);
                let offset = a.number("offset")?.unwrap_or(0.0);
                let len = n.length();
                if len == 0.0 {
                    return Err(a.error(
                        a.span_of("normal"),
                        "the normal of a halfspace must not be zero",
                        "expected a non-zero vector",
                    ));
                }
                let z = n / len;
                let local = DAffine3::from_mat3_translation(basis_from_z(z), z * (offset / len));
                self.leaf(s, Shape::Halfspace(Halfspace), xf * local, mat)
            }
            _ => unreachable!("not a solid: {}", s.name),
        }
    }

    fn transform(&mut self, s: &Statement) -> Result<DAffine3> {
        match s.name.as_str() {
            "translate" => {
                let a = Args::bind(self.src, s, &["v"])?;
                Ok(DAffine3::from_translation(
                    a.vec3("v", 0.0)?.unwrap_or(DVec3::ZERO),
                ))
            }
            "scale" => {
                let a = Args::bind(self.src, s, &["v"])?;
                let v = a.scalar_or_vec3("v", 1.0)?.unwrap_or(DVec3::ONE);
                if mutant::active("scale_ignored") {
                    return Ok(DAffine3::IDENTITY);
                }
                Ok(DAffine3::from_scale(v))
            }
            "mirror" => {
                let a = Args::bind(self.src, s, &["v"])?;
                let n = a.vec3("v", 0.0)?.unwrap_or(DVec3::ZERO);
                let l2 = n.length_squared();
                if l2 == 0.0 {
                    return Ok(DAffine3::IDENTITY);
                }
                let m = DMat3::IDENTITY - DMat3::from_cols(n * n.x, n * n.y, n * n.z) * (2.0 / l2);
                Ok(DAffine3::from_mat3(m))
            }
            "rotate" => {
                let a = Args::bind(self.src, s, &["a", "v"])?;
                if let Some(axis) = a.vec3("v", 0.0)? {
                    let deg = a.number("a")?.unwrap_or(0.0);
                    if axis.length_squared() == 0.0 {
                        return Err(a.error(
                            a.span_of("v"),
                            "the axis of a rotation must not be zero",
                            "expected a non-zero vector",
                        ));
                    }
                    return Ok(DAffine3::from_mat3(axis_angle(axis.normalize(), deg)));
                }
                // `rotate(a = deg)` turns about z; `rotate(a = [x, y, z])`
                // turns about x, then y, then z.
                let angles = if a.is_number("a") {
                    DVec3::new(0.0, 0.0, a.number("a")?.unwrap_or(0.0))
                } else {
                    a.vec3("a", 0.0)?.unwrap_or(DVec3::ZERO)
                };
                if mutant::active("rotate_ignored") {
                    return Ok(DAffine3::IDENTITY);
                }
                let m = axis_angle(DVec3::Z, angles.z)
                    * axis_angle(DVec3::Y, angles.y)
                    * axis_angle(DVec3::X, angles.x);
                Ok(DAffine3::from_mat3(m))
            }
            "multmatrix" => {
                let a = Args::bind(self.src, s, &["m"])?;
                let Some(m) = a.matrix("m", &[3, 4], 4)? else {
                    return Ok(DAffine3::IDENTITY);
                };
                if m.len() == 4 && m[3] != [0.0, 0.0, 0.0, 1.0] {
                    let span = a.span_of("m");
                    return Err(a.error(
                        span,
                        "the last row of a multmatrix must be [0, 0, 0, 1]",
                        "csgrt renders affine transforms only",
                    ));
                }
                let col = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
                Ok(DAffine3::from_cols(col(0), col(1), col(2), col(3)))
            }
            _ => unreachable!("not a transform: {}", s.name),
        }
    }

    fn appearance(&mut self, s: &Statement, mut m: Material) -> Result<Material> {
        if s.name == "color" {
            let a = Args::bind(self.src, s, &["c", "alpha"])?;
            let c = a.numbers("c", &[3, 4])?;
            let alpha = a.number("alpha")?;
            match c {
                // OpenSCAD writes color([-1, -1, -1, -1]) for "no colour".
                Some(c) if c.iter().any(|x| *x < 0.0) => {}
                _ if mutant::active("color_ignored") => {}
                _ if mutant::active("outer_color_wins") && m.color != defaults::MATERIAL.color => {}
                Some(c) => {
                    m.color = DVec3::new(c[0], c[1], c[2]).clamp(DVec3::ZERO, DVec3::ONE);
                    let alpha = alpha.or(c.get(3).copied()).unwrap_or(1.0).clamp(0.0, 1.0);
                    if alpha < 1.0 {
                        m.kt = 1.0 - alpha;
                        m.ior = 1.0;
                    }
                }
                None => {}
            }
            return Ok(m);
        }
        let a = Args::bind(
            self.src,
            s,
            &["color", "ka", "kd", "ks", "ns", "kr", "kt", "ior"],
        )?;
        if let Some(c) = a.numbers("color", &[3])? {
            m.color = DVec3::new(c[0], c[1], c[2]);
        }
        let fields: [(&str, &mut f64); 7] = [
            ("ka", &mut m.ka),
            ("kd", &mut m.kd),
            ("ks", &mut m.ks),
            ("ns", &mut m.ns),
            ("kr", &mut m.kr),
            ("kt", &mut m.kt),
            ("ior", &mut m.ior),
        ];
        for (name, field) in fields {
            if let Some(x) = a.non_negative(name)? {
                *field = x;
            }
        }
        if a.has("ior") && m.ior == 0.0 {
            return Err(a.error(
                a.span_of("ior"),
                "`ior` must be positive",
                "expected a number > 0",
            ));
        }
        Ok(m)
    }

    fn scene_statement(&mut self, s: &Statement) -> Result<()> {
        if let Some(c) = s.children.first() {
            return Err(self.src.error(
                c.span,
                format!("`{}` takes no children", s.name),
                "end it with `;`",
            ));
        }
        match s.name.as_str() {
            "camera" => {
                let a = Args::bind(self.src, s, &["eye", "lookat", "up", "fov"])?;
                let eye = a.vec3("eye", 0.0)?;
                let eye = a.require("eye", eye)?;
                let lookat = a.vec3("lookat", 0.0)?;
                let lookat = a.require("lookat", lookat)?;
                let up = a.vec3("up", 0.0)?.unwrap_or(DVec3::Z);
                let fov = a.number("fov")?.unwrap_or(30.0);
                if let Some((_, first)) = self.camera {
                    let (line, _) = self.src.line_col(first.start);
                    return Err(self.src.error(
                        s.name_span,
                        "a second camera",
                        format!("the first is on line {line}"),
                    ));
                }
                let look = lookat - eye;
                if look.length_squared() == 0.0 {
                    return Err(a.error(
                        a.span_of("lookat"),
                        "the camera looks at its own eye",
                        "expected `lookat` to differ from `eye`",
                    ));
                }
                if look.cross(up).length_squared()
                    <= 1e-24 * look.length_squared() * up.length_squared()
                {
                    return Err(a.error(
                        a.span_of("up"),
                        "the camera's `up` is parallel to its view direction",
                        "expected an `up` that is not along `lookat - eye`",
                    ));
                }
                if !(fov > 0.0 && fov < 180.0) {
                    return Err(a.error(
                        a.span_of("fov"),
                        "the camera's field of view is out of range",
                        "expected degrees strictly between 0 and 180",
                    ));
                }
                self.camera = Some((
                    CameraSpec {
                        eye,
                        lookat,
                        up,
                        fov,
                    },
                    s.span,
                ));
            }
            "background" => {
                let a = Args::bind(self.src, s, &["color"])?;
                let c = a.vec3("color", 0.0)?;
                self.background = Some(a.require("color", c)?);
            }
            "ambient_light" => {
                let a = Args::bind(self.src, s, &["color"])?;
                let color = a.scalar_or_vec3("color", 0.0)?.unwrap_or(DVec3::ONE);
                self.lights.push(Light::Ambient { color });
            }
            "directional_light" => {
                let a = Args::bind(self.src, s, &["color", "direction"])?;
                let color = a.scalar_or_vec3("color", 0.0)?.unwrap_or(DVec3::ONE);
                let d = a.vec3("direction", 0.0)?;
                let d = a.require("direction", d)?;
                if d.length_squared() == 0.0 {
                    return Err(a.error(
                        a.span_of("direction"),
                        "a light's direction must not be zero",
                        "expected a non-zero vector",
                    ));
                }
                self.lights.push(Light::Directional {
                    color,
                    direction: d.normalize(),
                });
            }
            "point_light" => {
                let a = Args::bind(self.src, s, &["color", "position"])?;
                let color = a.scalar_or_vec3("color", 0.0)?.unwrap_or(DVec3::ONE);
                let p = a.vec3("position", 0.0)?;
                let position = a.require("position", p)?;
                self.lights.push(Light::Point { color, position });
            }
            _ => unreachable!("not a scene statement: {}", s.name),
        }
        Ok(())
    }
}

/// sin and cos of an angle in degrees, exact at multiples of 90°.
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r % 90.0 == 0.0 {
        match (r / 90.0) as u32 {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        r.to_radians().sin_cos()
    }
}

/// A right-handed rotation by `deg` degrees about the unit `axis`.
fn axis_angle(axis: DVec3, deg: f64) -> DMat3 {
    let (s, c) = sin_cos_deg(deg);
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let t = 1.0 - c;
    DMat3::from_cols(
        DVec3::new(t * x * x + c, t * x * y + s * z, t * x * z - s * y),
        DVec3::new(t * x * y - s * z, t * y * y + c, t * y * z + s * x),
        DVec3::new(t * x * z + s * y, t * y * z - s * x, t * z * z + c),
    )
}

/// A rotation whose third column is the unit vector `z` (right-handed).
fn basis_from_z(z: DVec3) -> DMat3 {
    let helper = if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let x = helper.cross(z).normalize();
    let y = z.cross(x);
    DMat3::from_cols(x, y, z)
}
