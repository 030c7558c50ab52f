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
                // OpenSCAD's affine transform of any 4 rows: all divided
                // by the last number, the rest of the last row ignored.
                let mut w = 1.0;
                if m.len() == 4 && m[3] != [0.0, 0.0, 0.0, 1.0] {
                    w = m[3][3];
                    let span = a.span_of("m");
                    let message = "the last row of a multmatrix is not [0, 0, 0, 1]";
                    if w == 0.0 {
                        return Err(self.src.lenient(
                            span,
                            message,
                            "its last number is 0: OpenSCAD's matrix is not finite",
                        ));
                    }
                    self.warn(
                        span,
                        message,
                        "as OpenSCAD, the matrix is divided by its last number and the rest of that row is ignored",
                    );
                }
                let col = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]) / w;
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

/// OpenSCAD 2021.01's `sin_degrees` and `cos_degrees` (`degree_trig.cc`),
/// which its primitives place their facets' points with: the angle folded
/// into [0°, 90°], exact at multiples of 30° and 45°, and the sine of the
/// complement above 45°. (csgrt's own rotations keep [`sin_cos_deg`].)
pub(super) fn facet_sin_cos(deg: f64) -> (f64, f64) {
    const HUGE: f64 = (1u64 << 26) as f64 * 360.0 * (1u64 << 26) as f64;
    let mut x = deg;
    if !(0.0..360.0).contains(&x) {
        if x < HUGE && x > -HUGE {
            x -= 360.0 * (x / 360.0).floor();
        } else {
            return (f64::NAN, f64::NAN);
        }
    }
    #[allow(clippy::excessive_precision)]
    let sqrt3_4 = 0.866_025_403_784_438_596_59; // M_SQRT3_4, √3/2
    let sqrt1_2 = std::f64::consts::FRAC_1_SQRT_2;
    // sin_degrees
    let mut a = x;
    let oppose = a >= 180.0;
    if oppose {
        a -= 180.0;
    }
    if a > 90.0 {
        a = 180.0 - a;
    }
    let sin = if a < 45.0 {
        if a == 30.0 {
            0.5
        } else {
            deg2rad(a).sin()
        }
    } else if a == 45.0 {
        sqrt1_2
    } else if a == 60.0 {
        sqrt3_4
    } else {
        deg2rad(90.0 - a).cos()
    };
    let sin = if oppose { -sin } else { sin };
    // cos_degrees
    let mut a = x;
    let mut oppose = a >= 180.0;
    if oppose {
        a -= 180.0;
    }
    if a > 90.0 {
        a = 180.0 - a;
        oppose = !oppose;
    }
    let cos = if a > 45.0 {
        if a == 60.0 {
            0.5
        } else {
            deg2rad(90.0 - a).sin()
        }
    } else if a == 45.0 {
        sqrt1_2
    } else if a == 30.0 {
        sqrt3_4
    } else {
        deg2rad(a).cos()
    };
    (sin, if oppose { -cos } else { cos })
}

/// Degrees to radians as OpenSCAD's `deg2rad`: `x * M_DEG2RAD`.
pub(super) fn deg2rad(x: f64) -> f64 {
    #[allow(clippy::excessive_precision)]
    const M_DEG2RAD: f64 = 0.017_453_292_519_943_295_769;
    x * M_DEG2RAD
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
