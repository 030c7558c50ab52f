//! The one way a [`Scene`] is built, whatever file it comes from: the
//! `.csg` resolver and the `.ray` loader both add leaves, combine them and
//! finish here, so that material sharing, the empty-scene warning and every
//! default (material, background) and the decoding of sRGB colours are
//! applied in one place.

use super::{defaults, CameraSpec, Light, Material, Scene};
use crate::csg::{Csg, Primitive};
use crate::error::{Diagnostic, Severity, TextRange};
use crate::geometry::{Shape, Transform};
use crate::math::boolean::Op;
use crate::math::srgb;
use crate::source::Source;

#[derive(Default)]
pub struct SceneBuilder {
    pub csg: Csg,
    materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub camera: Option<CameraSpec>,
    pub background: Option<glam::DVec3>,
    pub warnings: Vec<Diagnostic>,
    pub approximations: Vec<super::Approximation>,
}

impl SceneBuilder {
    pub fn new() -> SceneBuilder {
        SceneBuilder::default()
    }

    /// The id of material `m`, shared by every leaf with the same one.
    pub fn material_id(&mut self, m: Material) -> u32 {
        match self.materials.iter().position(|x| *x == m) {
            Some(i) => i as u32,
            None => {
                self.materials.push(m);
                self.materials.len() as u32 - 1
            }
        }
    }

    /// Adds a leaf; its node id.
    pub fn leaf(&mut self, shape: Shape, xf: Transform, material: u32) -> u32 {
        self.csg.add_prim(Primitive::new(shape, xf, material))
    }

    /// The union of `ids`: nothing, the one, or a new node.
    pub fn union(&mut self, ids: Vec<u32>) -> Option<u32> {
        match ids.len() {
            0 => None,
            1 => Some(ids[0]),
            _ => Some(self.csg.add_op(Op::Union, ids)),
        }
    }

    pub fn warn(&mut self, src: &Source, place: TextRange, message: &str, label: &str) {
        let d = src.diagnostic(Severity::Warning, place, message, label);
        self.warnings.push(d);
    }

    /// The scene with `root` as its tree: a warning at `place` if it has
    /// no solids, and the defaults for whatever the file left unsaid.
    pub fn finish(
        mut self,
        src: &Source,
        root: Option<u32>,
        place: TextRange,
        background: glam::DVec3,
    ) -> Scene {
        self.csg.root = root;
        self.csg.index_unions();
        if root.is_none() {
            self.warn(
                src,
                place,
                "the scene has no solids",
                "only the background will show",
            );
        }
        if self.materials.is_empty() {
            self.materials.push(defaults::MATERIAL);
        }
        // Light adds up in linear values: the colours written in sRGB are
        // decoded here, once.
        for m in &mut self.materials {
            m.color = srgb::decode3(m.color);
        }
        Scene {
            camera: self.camera,
            background: srgb::decode3(self.background.unwrap_or(background)),
            background_given: self.background.is_some(),
            lights: self.lights,
            materials: self.materials,
            csg: self.csg,
            warnings: self.warnings,
            planar: false,
            approximations: self.approximations,
            framed: None,
            scad_view: None,
        }
    }
}
