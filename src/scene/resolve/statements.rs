//! The scene statements: camera, background and lights.

use super::Resolver;
use crate::error::Result;
use crate::scene::args::Args;
use crate::scene::{CameraSpec, Light};
use crate::syntax::ast::Statement;
use glam::DVec3;

impl Resolver<'_> {
    pub(super) fn scene_statement(&mut self, s: &Statement) -> Result<()> {
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
                if let Some(first) = self.camera_at {
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
                self.b.camera = Some(CameraSpec {
                    eye,
                    lookat,
                    up,
                    fov,
                    projection: Default::default(),
                });
                self.camera_at = Some(s.span);
            }
            "background" => {
                let a = Args::bind(self.src, s, &["color"])?;
                let c = a.vec3("color", 0.0)?;
                self.b.background = Some(a.require("color", c)?);
            }
            "ambient_light" => {
                let a = Args::bind(self.src, s, &["color"])?;
                let color = a.scalar_or_vec3("color", 0.0)?.unwrap_or(DVec3::ONE);
                self.b.lights.push(Light::Ambient { color });
            }
            "directional_light" => {
                let a = Args::bind(self.src, s, &["color", "direction", "shadows"])?;
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
                let shadows = a.boolean("shadows")?.unwrap_or(true);
                self.b.lights.push(Light::Directional {
                    color,
                    direction: d.normalize(),
                    shadows,
                });
            }
            "point_light" => {
                let a = Args::bind(self.src, s, &["color", "position"])?;
                let color = a.scalar_or_vec3("color", 0.0)?.unwrap_or(DVec3::ONE);
                let p = a.vec3("position", 0.0)?;
                let position = a.require("position", p)?;
                self.b.lights.push(Light::Point { color, position });
            }
            _ => unreachable!("not a scene statement: {}", s.name),
        }
        Ok(())
    }
}
