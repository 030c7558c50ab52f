//! The transforms: `translate`, `scale`, `mirror`, `rotate`, `multmatrix`.

use super::Resolver;
use crate::error::Result;
use crate::mutant;
use crate::scene::args::Args;
use crate::syntax::ast::Statement;
use glam::{DAffine3, DMat3, DVec3};

impl Resolver<'_> {
    pub(super) fn transform(&mut self, s: &Statement) -> Result<DAffine3> {
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
}

/// sin and cos of an angle in degrees, exact at multiples of 90°.
pub(super) fn sin_cos_deg(deg: f64) -> (f64, f64) {
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
pub(super) fn basis_from_z(z: DVec3) -> DMat3 {
    let helper = if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let x = helper.cross(z).normalize();
    let y = z.cross(x);
    DMat3::from_cols(x, y, z)
}
