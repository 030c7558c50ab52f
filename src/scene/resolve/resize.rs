//! `resize(newsize, auto)`: a scale about the origin, from the extent of
//! the children, as OpenSCAD 2021.01 computes it (`CGAL_Nef_polyhedron::
//! resize` in 3-D, `Polygon2d::resize` in 2-D) but from the exact extent
//! of the exact solid, not of its mesh.
//!
//! The extent along an axis is exact where it can be shown to be: a
//! leaf's from its support point; a union's the largest of its
//! children's; an intersection's the smallest, when that child's extreme
//! point lies in every other; a difference's its first operand's, when
//! that extreme point lies in no subtracted solid. Anything else (an
//! unbounded or twisted leaf, a slice, an extreme point cut away) is "not
//! supported yet", never a guess.

use super::{Resolver, APPEARANCE, TRANSFORMS};
use crate::error::Result;
use crate::math::boolean::Op;
use crate::plane::figure::Figure;
use crate::scene::args::Args;
use crate::scene::Material;
use crate::syntax::ast::{Statement, ValueKind};
use glam::{DAffine2, DAffine3, DVec2, DVec3};

/// `newsize` (0 for axes not given) and `auto` of a resize.
fn sizes(a: &Args) -> Result<([f64; 3], [bool; 3])> {
    let mut size = [0.0; 3];
    if let Some(v) = a.numbers("newsize", &[1, 2, 3])? {
        size[..v.len()].copy_from_slice(&v);
    }
    let mut auto = [false; 3];
    if let Some(v) = a.get("auto") {
        match &v.kind {
            ValueKind::Vector(items) if items.len() <= 3 => {
                for (i, it) in items.iter().enumerate() {
                    auto[i] = match it.kind {
                        ValueKind::Bool(b) => b,
                        ValueKind::Number(x) => x != 0.0,
                        _ => return Err(a.wrong_type("auto", it, "`true` or `false`")),
                    };
                }
            }
            _ => auto = [a.boolean("auto")?.unwrap_or(false); 3],
        }
    }
    if crate::mutant::active("resize_auto_ignored") {
        auto = [false; 3];
    }
    Ok((size, auto))
}

const PARAMS: &[&str] = &["newsize", "auto", "convexity"];

/// Whether OpenSCAD 2021.01 hands `resize` these children as a CGAL Nef
/// polyhedron — a union of two or more, the result of a CSG operation on
/// two or more, `render`, `minkowski` — rather than as a PolySet (a
/// primitive, an extrusion, a mesh, a hull, under any transforms). Only
/// `CGAL_Nef_polyhedron::resize` takes a size below 0 (a mirror);
/// `PolySet::resize` leaves that axis as it is.
fn nef_result(children: &[Statement]) -> bool {
    let live: Vec<&Statement> = children
        .iter()
        .filter(|c| !super::skipped(c) && c.name != "echo")
        .collect();
    match live[..] {
        [] => false,
        [one] => match one.name.as_str() {
            "render" | "minkowski" => true,
            n if TRANSFORMS.contains(&n)
                || APPEARANCE.contains(&n)
                || ["group", "union", "difference", "intersection"].contains(&n) =>
            {
                nef_result(&one.children)
            }
            _ => false,
        },
        _ => true,
    }
}

/// Whether a statement makes a 2-D shape (its first live child decides
/// for transforms and operations, as OpenSCAD's dimension rule).
pub(super) fn is_planar(s: &Statement) -> bool {
    dimension(s) == Some(true)
}

/// The dimension of what a statement makes, as OpenSCAD 2021.01 reads it
/// (`GeometryEvaluator::applyToChildren`): `Some(true)` for a 2-D shape,
/// `Some(false)` for a solid, `None` for nothing at all (a skipped
/// statement, an empty group, a scene statement, an unknown name).
/// Transforms and operations take the dimension of their first child that
/// has one.
pub(super) fn dimension(s: &Statement) -> Option<bool> {
    if super::skipped(s) {
        return None;
    }
    let name = s.name.as_str();
    if super::planar::SHAPES_2D.contains(&name) || ["offset", "projection"].contains(&name) {
        return Some(true);
    }
    if name == "import" {
        // Drawings are 2-D; meshes (STL, OFF, ...) are solids; what csgrt
        // does not read has no dimension here (its error comes later).
        let file = s.args.iter().find_map(|a| match (&a.name, &a.value.kind) {
            (Some((n, _)), ValueKind::Str(f)) if n == "file" => Some(f.to_lowercase()),
            (None, ValueKind::Str(f)) => Some(f.to_lowercase()),
            _ => None,
        })?;
        let ext = file.rsplit_once('.').map_or("", |(_, e)| e);
        if ["dxf", "svg"].contains(&ext) {
            return Some(true);
        }
        return crate::import::meshfile::FORMATS
            .contains(&ext)
            .then_some(false);
    }
    let passes = TRANSFORMS.contains(&name)
        || super::OPERATIONS.contains(&name)
        || super::APPEARANCE.contains(&name)
        || ["resize", "hull", "minkowski"].contains(&name);
    if passes {
        return s.children.iter().find_map(dimension);
    }
    // A solid csgrt builds; a statement it refuses has its error later.
    matches!(super::solids::binder(name), Some(Some(_))).then_some(false)
}

impl Resolver<'_> {
    /// 3-D `resize`: the children read once in the resize's own frame to
    /// find their extent (and dropped), then again under the scale.
    pub(super) fn resize(
        &mut self,
        s: &Statement,
        xf: DAffine3,
        mat: Material,
        depth: usize,
    ) -> Result<Option<u32>> {
        if is_planar(s) {
            return self.slab(s, xf, mat);
        }
        let a = Args::bind(self.src, s, PARAMS)?;
        let (mut newsize, auto) = sizes(&a)?;
        if !nef_result(&s.children) {
            // `PolySet::resize` takes only sizes above 0.
            newsize = newsize.map(|x| x.max(0.0));
        }
        let mark = self.b.csg.mark();
        let warned = self.b.warnings.len();
        let ids = self.children(s, DAffine3::IDENTITY, mat, depth)?;
        let Some(child) = self.union(ids) else {
            return Ok(None);
        };
        let mut size = [0.0; 3];
        let mut exact = Ok(());
        for (i, e) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
            if newsize[i] == 0.0 && !auto[i] {
                continue;
            }
            let csg = &self.b.csg;
            match (csg.extreme(child, e), csg.extreme(child, -e)) {
                (Ok(hi), Ok(lo)) => size[i] = hi.0 + lo.0,
                (Err(why), _) | (_, Err(why)) => exact = Err(why),
            }
        }
        if let Err(why) = exact {
            // No exact extent: that of the child cut into polytopes, within
            // the certified approximation's distance of it.
            let pieces = self
                .polytopes(s, &[child], xf, false)
                .map_err(|e| self.unmeasured(s, &format!("{why} ({e})")))?;
            let b = pieces
                .iter()
                .fold(crate::geometry::Aabb::EMPTY, |b, p| b.union(&p.bounds));
            size = (b.max - b.min).max(DVec3::ZERO).to_array();
        }
        self.b.csg.rewind(mark);
        self.b.warnings.truncate(warned);
        // CGAL_Nef_polyhedron::resize, line for line.
        let mut scale = [1.0; 3];
        let mut max_at = 0;
        for i in 0..3 {
            if newsize[i] != 0.0 {
                if size[i] == 0.0 {
                    self.warn(
                        s.name_span,
                        "Resize in direction normal to flat object is not implemented",
                        "the children are left as they are, as in OpenSCAD",
                    );
                    let ids = self.children(s, xf, mat, depth)?;
                    return Ok(self.union(ids));
                }
                scale[i] = newsize[i] / size[i];
                if newsize[i] > newsize[max_at] {
                    max_at = i;
                }
            }
        }
        let autoscale = if newsize[max_at] != 0.0 {
            newsize[max_at] / size[max_at]
        } else {
            1.0
        };
        for i in 0..3 {
            if auto[i] && newsize[i] == 0.0 {
                scale[i] = autoscale;
            }
        }
        let local = DAffine3::from_scale(DVec3::from_array(scale));
        let ids = self.children(s, xf * local, mat, depth)?;
        Ok(self.union(ids))
    }

    /// 2-D `resize` under the plane transform `m`.
    pub(super) fn resize_figure(
        &mut self,
        s: &Statement,
        m: DAffine2,
        depth: usize,
    ) -> Result<Option<Figure>> {
        let a = Args::bind(self.src, s, PARAMS)?;
        let (newsize, auto) = sizes(&a)?;
        let Some(f) = self.figure_children(s, Op::Union, DAffine2::IDENTITY, depth)? else {
            return Ok(None);
        };
        let mut size = [0.0; 2];
        let mut measured = None;
        let noted = self.plane_notes.len();
        for (i, e) in [DVec2::X, DVec2::Y].into_iter().enumerate() {
            if newsize[i] > 0.0 || auto[i] {
                let (lo, hi) = match f.exact_range(e) {
                    Ok(r) => r,
                    Err(why) => {
                        // Measured on the loops of its flattened outline
                        // (the certified approximation): within eps.
                        if measured.is_none() {
                            measured = Some(
                                self.flat_outline(s, &f)
                                    .ok_or_else(|| self.unmeasured(s, why))?,
                            );
                        }
                        measured.as_ref().expect("measured").extent(e)
                    }
                };
                size[i] = hi - lo;
            }
        }
        // Polygon2d::resize, line for line.
        let max_at = if newsize[1] != 0.0 && newsize[1] > newsize[0] {
            1
        } else {
            0
        };
        let scale = |i: usize| {
            if newsize[i] > 0.0 {
                newsize[i] / size[i]
            } else {
                1.0
            }
        };
        let autoscale = if newsize[max_at] > 0.0 {
            newsize[max_at] / size[max_at]
        } else {
            1.0
        };
        let pick = |i: usize| {
            if !auto[i] || newsize[i] > 0.0 {
                scale(i)
            } else {
                autoscale
            }
        };
        let local = DAffine2::from_scale(DVec2::new(pick(0), pick(1)));
        // Only the size is approximated: a size off by eps scales the
        // shape about the origin by a factor off by eps/size of itself,
        // moving its points by at most that times the scale times their
        // reach from the origin.
        if let Some(o) = &measured {
            let k = pick(0).abs().max(pick(1).abs());
            let reach = o
                .loops
                .iter()
                .flatten()
                .fold(0.0f64, |r, p| r.max(p.length()));
            let least = size
                .iter()
                .copied()
                .filter(|v| *v > 0.0)
                .fold(f64::INFINITY, f64::min);
            for n in &mut self.plane_notes[noted..] {
                n.1 *= k * (reach + n.1) / (least - n.1).max(f64::MIN_POSITIVE);
            }
        }
        Ok(Some(f.moved(m * local)))
    }

    /// The loops of the outline of `f` flattened to straight polygons, or
    /// `None` (the note taken back).
    fn flat_outline(&mut self, s: &Statement, f: &Figure) -> Option<crate::plane::Outlines> {
        let what = "the size of a `resize`d shape";
        self.noted_if_done(|r| match r.flat_figure(s, f, false, what)? {
            Some(Figure::Polygon(o)) => Ok(o),
            Some(g) => crate::plane::sites::outline(&g).ok_or_else(String::new),
            None => Err(String::new()),
        })
        .ok()
    }

    fn unmeasured(&self, s: &Statement, why: &str) -> crate::error::Error {
        self.src.error(
            s.name_span,
            format!("csgrt cannot measure these children to `resize` them: {why}"),
            "csgrt resizes from an exact extent, or one of convex polytopes or straight polygons within 1/8192 of the children's size (every limit is listed in docs/LANGUAGE.md)",
        )
    }
}
