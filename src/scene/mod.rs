//! The resolved scene: camera, lights, materials and the CSG tree, with
//! every default applied. Built from the syntax tree by [`resolve`].

pub mod args;
pub mod builder;
pub mod defaults;
mod display_list;
pub mod openscad_view;
mod resolve;

pub use display_list::resolve_ray;
pub use resolve::{later_statements, resolve, resolve_with};

/// How `$fn`, `$fa` and `$fs` are read (`--facets`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Facets {
    /// An explicit `$fn` of 3 to 8 on `circle`, `cylinder` and `sphere` is
    /// a shape (OpenSCAD's polygon, prism or ring polyhedron); anything
    /// else is the exact smooth surface.
    #[default]
    Shapes,
    /// Every `$fn` ignored: the exact smooth surfaces.
    Exact,
    /// OpenSCAD's own fragment rule (`Calc::get_fragments_from_r`) on
    /// every circle, cylinder and sphere: the solid OpenSCAD would export.
    OpenScad,
}

use crate::csg::Csg;
use crate::error::Diagnostic;
use crate::geometry::Aabb;
use crate::math::srgb;
use glam::DVec3;
use std::borrow::Cow;

/// The seed's Surface model (slide 24).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// As the file gives it (sRGB) while the scene is built; linear in a
    /// finished [`Scene`].
    pub color: DVec3,
    /// Ambient, diffuse and specular coefficients.
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    /// Phong exponent.
    pub ns: f64,
    /// Reflectance and transmission.
    pub kr: f64,
    pub kt: f64,
    /// Index of refraction.
    pub ior: f64,
    /// The colour is the colour scheme's: no `color` or material colour
    /// was given (`--colorscheme` may change it).
    pub scheme_color: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    Ambient {
        color: DVec3,
    },
    /// `direction` is the unit direction the light travels in; without
    /// `shadows` it reaches every face turned to it (a fill light).
    Directional {
        color: DVec3,
        direction: DVec3,
        shadows: bool,
    },
    Point {
        color: DVec3,
        position: DVec3,
    },
}

impl Light {
    /// For a directional light, the direction of every shadow ray it
    /// asks for (towards it): one place, so that a render's line families
    /// ([`Csg::viewed`](crate::csg::Csg::viewed)) are the shadow rays'
    /// own to the bit.
    pub fn shadow_direction(&self) -> Option<DVec3> {
        match *self {
            Light::Directional {
                direction,
                shadows: true,
                ..
            } => Some(Light::towards(direction)),
            _ => None,
        }
    }

    /// The way towards a directional light travelling along `direction`.
    pub fn towards(direction: DVec3) -> DVec3 {
        -direction
    }
}

/// The seed's pinhole camera (slide 6); `fov` is the horizontal angle in
/// degrees. Orthographic, it shows the same rectangle of the plane through
/// `lookat` square to the view, with parallel rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    pub eye: DVec3,
    pub lookat: DVec3,
    pub up: DVec3,
    pub fov: f64,
    pub projection: Projection,
}

/// How a camera projects (`--projection`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Projection {
    #[default]
    Perspective,
    /// Parallel rays along `lookat − eye`, as OpenSCAD's `--projection=ortho`.
    Orthographic,
}

#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The camera the file asked for; `None` frames the scene's bounds.
    pub camera: Option<CameraSpec>,
    /// Linear, as every colour of the scene (decoded from the sRGB values
    /// the file gives).
    pub background: DVec3,
    /// The file gave the background (`--colorscheme` keeps it).
    pub background_given: bool,
    /// The file's lights; none: csgrt's rig, turned with the camera
    /// ([`Scene::lights_seen_by`]).
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub csg: Csg,
    pub warnings: Vec<Diagnostic>,
    /// The model is 2-D at the top level: each of its shapes is shown as
    /// a slab (see `resolve::extrude`), and OpenSCAD's box of it is flat.
    pub planar: bool,
    /// The nodes made by the certified approximation (a hull or Minkowski
    /// sum of an intersection or a difference).
    pub approximations: Vec<Approximation>,
    /// The box the default camera frames, once [`Scene::fix_framing`] has
    /// found it (finding it casts rays); `None`: found at each view.
    pub framed: Option<Aabb>,
    /// The view a `.scad` program sets with `$vpt`, `$vpr`, `$vpd`: the
    /// camera unless the file's own or `--camera` replaces it.
    pub scad_view: Option<openscad_view::Viewpoint>,
}

/// A node csgrt approximates: where it is, its world box and its error (a
/// distance in world units, the Hausdorff distance's bound).
#[derive(Clone, Debug)]
pub struct Approximation {
    pub note: Diagnostic,
    pub bounds: Aabb,
    pub eps: f64,
}

impl Approximation {
    /// The error in pixels of a `width`-wide picture taken by `cam`, at
    /// the box's point nearest the eye (the largest there).
    pub fn pixels(&self, cam: &CameraSpec, width: u32) -> f64 {
        let look = cam.lookat - cam.eye;
        let focal = width as f64 / (2.0 * (0.5 * cam.fov).to_radians().tan());
        let distance = match cam.projection {
            Projection::Orthographic => look.length(),
            Projection::Perspective => {
                let nearest = cam.eye.clamp(self.bounds.min, self.bounds.max);
                (nearest - cam.eye).length()
            }
        };
        self.eps * focal / distance
    }
}

impl Scene {
    /// Whether a warning or note of the scene points into the file `name`
    /// (a `.scad` model's export, kept then for the message).
    pub fn mentions(&self, name: &str) -> bool {
        self.warnings
            .iter()
            .chain(self.approximations.iter().map(|a| &a.note))
            .any(|d| d.file == name)
    }

    /// OpenSCAD's colour scheme `scheme` where the file says nothing: its
    /// background, and its face colour on every solid without a colour.
    pub fn apply_color_scheme(&mut self, scheme: &defaults::ColorScheme) {
        if !self.background_given {
            self.background = srgb::decode3(scheme.background);
        }
        for m in self.materials.iter_mut().filter(|m| m.scheme_color) {
            m.color = srgb::decode3(scheme.face);
        }
    }

    /// The lights of a picture taken by `cam`: the file's, or without any
    /// the default rig placed about that camera.
    pub fn lights_seen_by(&self, cam: &CameraSpec) -> Cow<'_, [Light]> {
        if self.lights.is_empty() {
            Cow::Owned(defaults::lights(cam))
        } else {
            Cow::Borrowed(&self.lights)
        }
    }

    /// The camera to render with at `width`×`height`.
    pub fn view(&self, width: u32, height: u32) -> CameraSpec {
        if let (None, Some(v)) = (self.camera, self.scad_view) {
            let opts = openscad_view::ViewOptions {
                camera: Some(v),
                ..Default::default()
            };
            // (No `--viewall` here: the box is not needed.)
            return openscad_view::camera(&opts, &Aabb::EMPTY, width, height);
        }
        self.camera
            .unwrap_or_else(|| defaults::framing_camera(&self.framing_bounds(), width, height))
    }

    /// What OpenSCAD's `--viewall` frames: [`Scene::framing_bounds`], flat
    /// for a 2-D model when the tree is bounded.
    pub fn result_bounds(&self) -> Aabb {
        let mut t = self.framing_bounds();
        if !self.csg.bounds().is_bounded() {
            return t;
        }
        if self.planar && !crate::mutant::active("framing_loose") {
            // In the slabs' middle plane, as OpenSCAD's 2-D box (z = 0).
            let mid = 0.5 * (t.min.z + t.max.z);
            (t.min.z, t.max.z) = (mid, mid);
        }
        t
    }

    /// Finds the box the default camera frames once, for every later view
    /// of this scene (whose tree must not change after).
    pub fn fix_framing(&mut self) {
        if self.camera.is_none() && self.scad_view.is_none() && self.framed.is_none() {
            self.framed = Some(self.framing_bounds());
        }
    }

    /// What the default camera frames: the box of the result itself
    /// ([`crate::csg::Csg::tight_bounds`]: what is left after differences,
    /// intersections and partial turns, not their parts' boxes) if the tree
    /// is bounded, else the box of its bounded primitives (a halfspace
    /// floor is drawn but not framed).
    pub fn framing_bounds(&self) -> Aabb {
        if let Some(b) = self.framed {
            return b;
        }
        let b = self.csg.bounds();
        if b.is_empty() {
            return b;
        }
        if b.is_bounded() {
            return self.csg.tight_bounds();
        }
        self.csg
            .prims
            .iter()
            .filter(|p| p.bounds.is_bounded())
            .fold(Aabb::EMPTY, |a, p| a.union(&p.bounds))
    }
}
