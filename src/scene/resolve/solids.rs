//! The solids: each statement's binder, from its arguments to a leaf.

use super::facet_mesh::regular_polygon;
use super::transforms::basis_from_z;
use super::Resolver;
use crate::error::Result;
use crate::geometry::{Cone, Cuboid, Halfspace, Prism, Shape, Sphere, Torus};
use crate::mutant;
use crate::plane::Region;
use crate::scene::args::Args;
use crate::scene::Material;
use crate::syntax::ast::{Statement, ValueKind};
use glam::{DAffine3, DVec3};

/// Binds a solid statement's arguments under the world transform and
/// material: its leaf's id, or `None` when it is empty.
pub(crate) type Binder =
    fn(&mut Resolver, &Statement, DAffine3, Material, usize) -> Result<Option<u32>>;

/// The arguments `import` takes (OpenSCAD's, and the `timestamp` its CSG
/// export adds).
pub(super) const IMPORT_PARAMS: &[&str] = &[
    "file",
    "layer",
    "convexity",
    "origin",
    "scale",
    "width",
    "height",
    "filename",
    "layername",
    "center",
    "dpi",
    "id",
    "timestamp",
];

/// Every OpenSCAD solid statement csgrt knows: its binder (arguments →
/// a leaf, or empty), or `None` for one newer than OpenSCAD 2021.01, which
/// ignores it with a warning, as csgrt does. The resolver, the list of
/// those and its tests all read this table; a new solid is one module in
/// `geometry/` and one line here.
pub(crate) const SOLIDS: &[(&str, Option<Binder>)] = &[
    ("cube", Some(cube)),
    ("sphere", Some(sphere)),
    ("cylinder", Some(cylinder)),
    ("torus", Some(torus)),
    ("halfspace", Some(halfspace)),
    ("linear_extrude", Some(linear_extrude)),
    ("rotate_extrude", Some(rotate_extrude)),
    ("square", Some(slab)),
    ("circle", Some(slab)),
    ("polygon", Some(slab)),
    ("text", Some(slab)),
    ("import", Some(import)),
    ("surface", Some(surface)),
    ("projection", Some(slab)),
    ("offset", Some(slab)),
    ("hull", Some(hull)),
    ("minkowski", Some(minkowski)),
    ("resize", Some(resize)),
    ("polyhedron", Some(polyhedron)),
    ("roof", None),
    ("fill", None),
];

/// The statements of [`SOLIDS`] that take children (2-D shapes to lift).
pub(crate) const WITH_CHILDREN: &[&str] = &[
    "linear_extrude",
    "rotate_extrude",
    "offset",
    "projection",
    "resize",
    "hull",
    "minkowski",
];

/// The solids of later OpenSCAD versions, left out with OpenSCAD
/// 2021.01's warning.
pub fn later_statements() -> impl Iterator<Item = &'static str> {
    SOLIDS.iter().filter(|(_, b)| b.is_none()).map(|(n, _)| *n)
}

/// The binder of a solid statement, if `name` is one (`Some(None)`: known,
/// newer than OpenSCAD 2021.01).
pub(crate) fn binder(name: &str) -> Option<Option<Binder>> {
    SOLIDS.iter().find(|(n, _)| *n == name).map(|(_, b)| *b)
}

fn cube(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, &["size", "center"])?;
    // OpenSCAD takes a number or a vector of three numbers; anything else
    // (`[2, 2]`, a string) it warns about and makes the unit cube.
    let size = match a.get("size") {
        Some(v) if !size_of_cube(&v.kind) => {
            res.warn(
                v.span,
                "`size` of `cube` is neither a number nor a vector of 3 numbers; the cube is 1 × 1 × 1, as in OpenSCAD",
                "expected a number or [x, y, z]",
            );
            DVec3::ONE
        }
        _ => a.scalar_or_vec3("size", 1.0)?.unwrap_or(DVec3::ONE),
    };
    let center = a.boolean("center")?.unwrap_or(false);
    if size.min_element() <= 0.0 {
        return res.empty(s, "a size is zero or negative");
    }
    // Centring is the shape's, so the translation stays exact.
    let scale = if center { 0.5 * size } else { size };
    let shape = Shape::Cuboid(Cuboid { centered: center });
    res.leaf(s, shape, xf * DAffine3::from_scale(scale), mat)
}

/// Whether OpenSCAD reads a `cube`'s `size` as one: `undef`, a number or
/// a vector of three numbers.
fn size_of_cube(v: &ValueKind) -> bool {
    match v {
        ValueKind::Undef | ValueKind::Number(_) => true,
        ValueKind::Vector(items) => {
            items.len() == 3 && items.iter().all(|c| matches!(c.kind, ValueKind::Number(_)))
        }
        _ => false,
    }
}

fn sphere(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, &["r", "d"])?;
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
        return res.empty(s, "its radius is zero or negative");
    }
    if let Some(n) = res.fragments(&a, r) {
        let (pts, faces) = ring_sphere(r, n);
        return res.mesh_leaf(s, s.args_span, pts, faces, xf, mat);
    }
    res.leaf(
        s,
        Shape::Sphere(Sphere),
        xf * DAffine3::from_scale(DVec3::splat(r)),
        mat,
    )
}

/// OpenSCAD 2021.01's sphere of n fragments (`primitives.cc`): (n + 1) / 2
/// rings, ring i at φ = 180°·(i + ½)/rings (radius r sin φ, height r cos φ),
/// each the n points at 360°·j/n; the top and bottom rings are faces, and
/// neighbouring rings are joined by two triangles a step (wound as
/// OpenSCAD winds them).
pub(crate) fn ring_sphere(r: f64, n: usize) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    use super::transforms::facet_sin_cos as sin_cos_deg;
    let rings = n.div_ceil(2);
    let mut pts = Vec::with_capacity(rings * n);
    for i in 0..rings {
        let (sp, cp) = sin_cos_deg(180.0 * (i as f64 + 0.5) / rings as f64);
        let (rr, z) = (r * sp, r * cp);
        for j in 0..n {
            let (sa, ca) = sin_cos_deg(360.0 * j as f64 / n as f64);
            pts.push(DVec3::new(rr * ca, rr * sa, z));
        }
    }
    let at = |i: usize, j: usize| (i * n + j % n) as u32;
    let mut faces = vec![(0..n).map(|j| at(0, j)).collect::<Vec<_>>()];
    for i in 0..rings - 1 {
        for j in 0..n {
            faces.push(vec![at(i + 1, j), at(i + 1, j + 1), at(i, j)]);
            faces.push(vec![at(i + 1, j + 1), at(i, j + 1), at(i, j)]);
        }
    }
    faces.push((0..n).rev().map(|j| at(rings - 1, j)).collect());
    (pts, faces)
}

fn cylinder(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(
        res.src,
        s,
        &["h", "r1", "r2", "center", "r", "d", "d1", "d2"],
    )?;
    let h = a.number("h")?.unwrap_or(1.0);
    let center =
        a.boolean("center")?.unwrap_or(false) && !mutant::active("cylinder_center_ignored");
    // As OpenSCAD: a diameter beats a radius, r1/r2 beat r.
    let radius = |d: &str, r: &str| -> Result<Option<f64>> {
        Ok(a.non_negative(d)?.map(|d| d / 2.0).or(a.non_negative(r)?))
    };
    let r = radius("d", "r")?.unwrap_or(1.0);
    let r1 = radius("d1", "r1")?.unwrap_or(r);
    let r2 = radius("d2", "r2")?.unwrap_or(r);
    if h <= 0.0 {
        return res.empty(s, "its height is zero or negative");
    }
    let rmax = r1.max(r2);
    if rmax <= 0.0 {
        return res.empty(s, "both its radii are zero");
    }
    if let Some(n) = res.fragments(&a, rmax) {
        // OpenSCAD's prism (or pyramid, or frustum) over the regular
        // n-gon: the wider end's polygon tapered to the other's, turned
        // end for end when the top is the wider.
        let region = std::sync::Arc::new(Region::new(regular_polygon(n, rmax)));
        let top = r1.min(r2) / rmax;
        // Centred, it is its own mirror image in z = 0.
        let flip = if r1 >= r2 { 1.0 } else { -1.0 };
        let lift = if r1 >= r2 || center { 0.0 } else { h };
        let local = DAffine3::from_translation(DVec3::new(0.0, 0.0, lift))
            * DAffine3::from_scale(DVec3::new(1.0, 1.0, flip * h));
        let prism = Prism::new(region, top, center);
        return res.leaf(s, Shape::Prism(prism), xf * local, mat);
    }
    let shape = Shape::Cone(Cone {
        r0: r1 / rmax,
        r1: r2 / rmax,
        centered: center,
    });
    let local = DAffine3::from_scale(DVec3::new(rmax, rmax, h));
    res.leaf(s, shape, xf * local, mat)
}

fn torus(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, &["R", "r"])?;
    let big = a.non_negative("R")?.unwrap_or(2.0);
    let small = a.non_negative("r")?.unwrap_or(0.5);
    if big <= 0.0 || small <= 0.0 {
        return res.empty(s, "a radius is zero");
    }
    if small >= big {
        return Err(a.error(
            a.span_of("r"),
            "the tube radius `r` of a torus must be smaller than `R`",
            format!("expected a number < {big}"),
        ));
    }
    let shape = Shape::Torus(Torus { minor: small / big });
    res.leaf(s, shape, xf * DAffine3::from_scale(DVec3::splat(big)), mat)
}

fn halfspace(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, &["normal", "offset"])?;
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
    res.leaf(s, Shape::Halfspace(Halfspace), xf * local, mat)
}

fn slab(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _: usize,
) -> Result<Option<u32>> {
    res.slab(s, xf, mat)
}

fn linear_extrude(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    depth: usize,
) -> Result<Option<u32>> {
    res.linear_extrude(s, xf, mat, depth)
}

fn rotate_extrude(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    depth: usize,
) -> Result<Option<u32>> {
    res.rotate_extrude(s, xf, mat, depth)
}

fn hull(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    depth: usize,
) -> Result<Option<u32>> {
    res.hull(s, xf, mat, depth)
}

fn minkowski(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    depth: usize,
) -> Result<Option<u32>> {
    res.minkowski(s, xf, mat, depth)
}

fn resize(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    depth: usize,
) -> Result<Option<u32>> {
    res.resize(s, xf, mat, depth)
}

/// `polyhedron(points, faces | triangles, convexity)`: a mesh leaf (see
/// [`crate::geometry::mesh`]); faces of any size, triangulated.
fn polyhedron(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, &["points", "faces", "convexity", "triangles"])?;
    let pts = a.points("points", &[3], 0)?;
    let key = if a.has("faces") { "faces" } else { "triangles" };
    let faces = match pts {
        Some(ref p) => faces(res, &a, key, p.len())?,
        None => None,
    };
    // OpenSCAD makes nothing of a polyhedron without points or faces
    // (`undef`, as a function that found none returns) and goes on.
    match (pts, faces) {
        (Some(pts), Some(faces)) if !pts.is_empty() && !faces.is_empty() => {
            res.mesh_leaf(s, a.span_of(key), pts, faces, xf, mat)
        }
        _ => res.empty(
            s,
            "it has no points or no faces (as in OpenSCAD, it is left out)",
        ),
    }
}

/// A polyhedron's faces read as OpenSCAD 2021.01 reads them: an index
/// out of range is dropped from its face (its warning "Point index is out
/// of bounds"), a fraction cut to a whole number as its `size_t` does, and
/// a face left with fewer than 3 points adds nothing; each a warning at
/// its place.
fn faces(res: &mut Resolver, a: &Args, key: &str, count: usize) -> Result<Option<Vec<Vec<u32>>>> {
    let Some(lists) = a.number_lists(key)? else {
        return Ok(None);
    };
    let mut out = Vec::with_capacity(lists.len());
    for l in lists {
        let mut row = Vec::with_capacity(l.items.len());
        for (n, span) in l.items {
            let i = n.trunc();
            if !(i >= 0.0 && i < count as f64) {
                let e = a.index_range(key, n, span, count);
                res.go_on(e, "it is dropped from its face, as in OpenSCAD")?;
                continue;
            }
            row.push(i as u32);
        }
        if row.len() < 3 {
            let found = format!("expected 3 or more points, found {}", row.len());
            res.warn(l.span, "a face of fewer than 3 points adds nothing", &found);
            continue;
        }
        out.push(row);
    }
    Ok(Some(out))
}

/// `import(file, ...)` where a solid stands: a mesh file, or a drawing
/// shown as OpenSCAD's preview shows 2-D shapes.
fn import(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(res.src, s, IMPORT_PARAMS)?;
    let (_, span, ext, path) = res.import_file(&a)?;
    if !crate::import::meshfile::FORMATS.contains(&ext.as_str()) {
        return res.slab(s, xf, mat);
    }
    let bytes = res.read_named(span, &path, "mesh", "expected a mesh file beside the scene")?;
    // OpenSCAD warns of a file it cannot parse and imports nothing.
    let m = crate::import::meshfile::read(&ext, &bytes).map_err(|e| {
        res.src.lenient(
            span,
            file_message(&path, &e),
            format!("expected a .{ext} mesh"),
        )
    })?;
    drop(bytes);
    res.mesh_leaf(s, span, m.points, m.faces, xf, mat)
}

/// `surface(file, center, invert, convexity)`: OpenSCAD's solid over a
/// height grid from a `.dat` file or a PNG image (see
/// [`crate::import::meshfile::heights`]), a mesh leaf.
fn surface(
    res: &mut Resolver,
    s: &Statement,
    xf: DAffine3,
    mat: Material,
    _depth: usize,
) -> Result<Option<u32>> {
    let a = Args::bind(
        res.src,
        s,
        &["file", "center", "convexity", "invert", "timestamp"],
    )?;
    let span = a.span_of("file");
    let Some(file) = a.string("file")? else {
        // OpenSCAD: "Can't open DAT file ''", and nothing.
        return Err(res.src.lenient(
            span,
            "`surface` needs a `file`",
            "expected file = \"name.dat\" or \"name.png\"",
        ));
    };
    let center = a.boolean("center")?.unwrap_or(false);
    let invert = a.boolean("invert")?.unwrap_or(false);
    let path = res.src.beside(file);
    let label = "expected a .dat grid or a PNG image beside the scene";
    let bytes = res.read_named(span, &path, "heights", label)?;
    let (h, warning) = crate::import::meshfile::heights(&bytes, invert).map_err(|e| {
        res.src.lenient(
            span,
            file_message(&path, &e),
            "expected a .dat grid or a PNG image",
        )
    })?;
    if let Some(w) = warning {
        res.warn(
            span,
            &file_message(&path, &w),
            "as OpenSCAD, the heights read before it are kept",
        );
    }
    if h.rows < 2 || h.columns < 2 {
        return res.empty(s, "its grid has fewer than 2 rows or columns");
    }
    let m = crate::import::meshfile::surface_mesh(&h, center);
    res.mesh_leaf(s, span, m.points, m.faces, xf, mat)
}

/// "`path`, line N: what" for what is wrong in a file the model names.
fn file_message(path: &std::path::Path, e: &crate::import::meshfile::FileError) -> String {
    let at = e.line.map_or(String::new(), |l| format!(", line {l}"));
    format!("`{}`{at}: {}", path.display(), e.message)
}

impl Resolver<'_> {
    /// A mesh leaf of `faces` over `pts`, triangulated; warnings for an
    /// open or non-manifold mesh at the statement.
    pub(super) fn mesh_leaf(
        &mut self,
        s: &Statement,
        place: crate::error::TextRange,
        pts: Vec<DVec3>,
        faces: Vec<impl AsRef<[u32]>>,
        xf: DAffine3,
        mat: Material,
    ) -> Result<Option<u32>> {
        use crate::geometry::mesh::{edge_use, Mesh, MeshData, MAX_TRIANGLES};
        use crate::geometry::mesh_bvh::{too_far, MAX_COORD};
        use crate::geometry::triangulate::triangulate_into;
        if let Some(p) = too_far(&pts) {
            return Err(self.src.error(
                s.name_span,
                format!("a point of the mesh, {p}, lies too far out"),
                format!("expected coordinates within ±{MAX_COORD:e}"),
            ));
        }
        let mut tris = Vec::with_capacity(faces.len());
        for f in &faces {
            triangulate_into(&pts, f.as_ref(), &mut tris);
            if tris.len() > MAX_TRIANGLES {
                return Err(self.src.error(
                    place,
                    "the mesh has too many triangles",
                    format!("expected at most {MAX_TRIANGLES}"),
                ));
            }
        }
        drop(faces);
        if tris.is_empty() {
            return self.empty(s, "its faces have no area");
        }
        let (open, many) = edge_use(&tris);
        if open > 0 || many > 0 {
            self.warn(
                s.name_span,
                &format!(
                    "this mesh is not closed: {open} edge(s) border one face only, {many} edge(s) three faces or more"
                ),
                "inside is decided by parity: even-odd crossings along each ray; where it is cut into pieces (a hull's, a sum's or a shadow's combination) it is left out, as OpenSCAD's render leaves it out",
            );
        }
        let data = std::sync::Arc::new(MeshData::new(pts, tris));
        self.leaf(s, Shape::Mesh(Mesh { data }), xf, mat)
    }
}
