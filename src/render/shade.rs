//! The seed's Whitted shading (slides 13, 25–29), recursively.
//!
//! For a hit with material (C, ka, kd, ks, ns, kr, kt, ior):
//! * ambient: `ka·Ia·C`;
//! * each directional or point light with `N·L > 0` that is not blocked
//!   (a directional light without shadows is never blocked):
//!   `kd·(N·L)·C·Il + ks·(V·R)^ns·Il`, `R = 2(N·L)N − L`, only if `V·R > 0`;
//!   a blocker dims the light by its transmission `kt` (slide 27's note),
//!   an opaque one (kt = 0) blocks it;
//! * reflection: `kr·I(reflected ray)`, the background on a miss;
//! * transmission: `kt·I(refracted ray)` by Snell's law (slide 15), total
//!   internal reflection sending the ray back in; entering or leaving is
//!   decided by the outward normal.
//!
//! Colours are linear (the scene decoded them from sRGB).
//! Each channel is clamped to [0, 1] at every level, as slide 29 does (the
//! camera ray's own radiance is also kept unclamped, for HDR and EXR). A
//! secondary ray is cast only while the ray tree is shallower than
//! `max_depth` and its weight (the product of kr/kt along the path) is at
//! least 1/512: below that it cannot change an 8-bit pixel by ½.
//!
//! Phong terms use the normal turned towards the viewer, so the inside of
//! a transparent solid is lit too.

use crate::csg::spans::Boundary;
use crate::csg::Csg;
use crate::geometry::Ray;
use crate::math::robust::{offset_origin, point_error};
use crate::scene::{Light, Material, Scene};
use crate::stats::Stats;
use glam::DVec3;

/// Secondary rays below this weight are not cast.
pub const MIN_WEIGHT: f64 = 1.0 / 512.0;

pub struct Shader<'a> {
    pub scene: &'a Scene,
    /// The scene's tree, or the copy of it prepared for this view
    /// ([`Csg::viewed`]).
    pub csg: &'a Csg,
    /// The lights of this view ([`Scene::lights_seen_by`]).
    pub lights: &'a [Light],
    pub max_depth: u32,
    /// Whether any material transmits: if none does, shadow rays need only
    /// find a blocker, not multiply transmissions.
    any_transparent: bool,
}

impl<'a> Shader<'a> {
    /// A shader of `scene` lit by `lights` that queries `csg`, the
    /// scene's tree prepared for a view.
    pub fn new(scene: &'a Scene, csg: &'a Csg, lights: &'a [Light], max_depth: u32) -> Shader<'a> {
        let any_transparent = scene.materials.iter().any(|m| m.kt > 0.0);
        Shader {
            scene,
            csg,
            lights,
            max_depth,
            any_transparent,
        }
    }

    fn material(&self, prim: u32) -> &Material {
        let id = self.csg.prims[prim as usize].material;
        &self.scene.materials[id as usize]
    }

    /// The colour seen along `ray` (t > 0), clamped to [0, 1].
    pub fn trace(&self, ray: &Ray, depth: u32, weight: f64, st: &mut Stats) -> DVec3 {
        self.unclamped(ray, depth, weight, st).0
    }

    /// For a camera ray: the colour [`Shader::trace`] gives, and the
    /// radiance before its last clamp (every deeper level clamped as
    /// always), for linear HDR and EXR files.
    pub fn primary(&self, ray: &Ray, st: &mut Stats) -> (DVec3, DVec3) {
        self.unclamped(ray, 0, 1.0, st)
    }

    /// The colour along `ray`, clamped to [0, 1] if it hits, and before
    /// that clamp; the background as it is given for a miss.
    fn unclamped(&self, ray: &Ray, depth: u32, weight: f64, st: &mut Stats) -> (DVec3, DVec3) {
        match self.csg.first_boundary(ray, 0.0, f64::INFINITY, st) {
            Some(b) => {
                let c = self.shade(ray, &b, depth, weight, st);
                (c.clamp(DVec3::ZERO, DVec3::ONE), c)
            }
            None => (self.scene.background, self.scene.background),
        }
    }

    fn shade(&self, ray: &Ray, b: &Boundary, depth: u32, weight: f64, st: &mut Stats) -> DVec3 {
        let hit = self.csg.surface(ray, b, st);
        let m = *self.material(hit.prim);
        let p = hit.point;
        let n = hit.normal;
        let v = -ray.dir;
        let ns = if n.dot(v) < 0.0 { -n } else { n };
        let err = point_error(p, ray.origin, hit.t * ray.dir);
        let mut color = DVec3::ZERO;
        for light in self.lights {
            let (l, dist, il, shadows) = match *light {
                Light::Ambient { color: ia } => {
                    color += m.ka * ia * m.color;
                    continue;
                }
                Light::Directional {
                    color,
                    direction,
                    shadows,
                } => (Light::towards(direction), f64::INFINITY, color, shadows),
                Light::Point { color, position } => {
                    let to = position - p;
                    let d = to.length();
                    (to / d, d, color, true)
                }
            };
            let ndl = ns.dot(l);
            if ndl <= 0.0 || (m.kd <= 0.0 && m.ks <= 0.0) {
                continue;
            }
            let pass = if shadows || crate::mutant::active("fill_shadowed") {
                let shadow = Ray::new(offset_origin(p, n, err, l), l);
                st.shadow_rays += 1;
                self.transmittance(&shadow, dist, st)
            } else {
                1.0
            };
            if pass <= 0.0 {
                continue;
            }
            let mut c = m.kd * ndl * m.color * il;
            if m.ks > 0.0 {
                let r = 2.0 * ndl * ns - l;
                let vr = v.dot(r);
                if vr > 0.0 {
                    c += m.ks * specular_power(vr, m.ns) * il;
                }
            }
            color += pass * c;
        }
        if depth < self.max_depth {
            if m.kr > 0.0 && weight * m.kr >= MIN_WEIGHT {
                let r = 2.0 * v.dot(ns) * ns - v;
                let refl = Ray::new(offset_origin(p, n, err, r), r.normalize());
                st.reflected_rays += 1;
                color += m.kr * self.trace(&refl, depth + 1, weight * m.kr, st);
            }
            if m.kt > 0.0 && weight * m.kt >= MIN_WEIGHT {
                let t = refract(ray.dir, n, m.ior);
                let trans = Ray::new(offset_origin(p, n, err, t), t);
                st.refracted_rays += 1;
                color += m.kt * self.trace(&trans, depth + 1, weight * m.kt, st);
            }
        }
        color
    }

    /// The fraction of light that passes along `ray` up to `dist`: the
    /// product of the transmissions of the solids it crosses, 0 at the
    /// first opaque one.
    fn transmittance(&self, ray: &Ray, dist: f64, st: &mut Stats) -> f64 {
        let csg = &self.csg;
        if !self.any_transparent {
            return if csg.occluded(ray, 0.0, dist, st) {
                0.0
            } else {
                1.0
            };
        }
        // Past an opaque solid's surface, nothing matters.
        let opaque = |b: &Boundary| self.material(b.prim).kt <= 0.0;
        csg.spans_until(ray, 0.0, dist, st, opaque, |list| {
            let mut pass = 1.0;
            for s in list {
                if s.exit.t <= 0.0 || s.enter.t >= dist {
                    continue;
                }
                // The solid crossed is named by the surface the ray enters
                // by, or leaves by if it starts inside.
                let face = if s.enter.t > 0.0 && s.enter.is_surface() {
                    s.enter
                } else {
                    s.exit
                };
                pass *= self.material(face.prim).kt;
                if pass <= 0.0 {
                    return 0.0;
                }
            }
            pass
        })
    }
}

/// `x^n` for the specular term: by repeated squaring when `n` is a whole
/// number up to 1024 (csgrt's default 30, and most scenes'), its relative
/// error below n·ε (each squaring doubles the error so far; 3·10⁻¹⁵ at the
/// default, far below a byte's 1/255); `powf`, several times as costly,
/// otherwise.
fn specular_power(x: f64, n: f64) -> f64 {
    if n.fract() == 0.0 && (0.0..=1024.0).contains(&n) {
        x.powi(n as i32)
    } else {
        x.powf(n)
    }
}

/// The refracted direction of unit `dir` at a surface with unit outward
/// normal `n` and index `ior` (slide 15), or the mirror direction under
/// total internal reflection.
pub fn refract(dir: DVec3, n: DVec3, ior: f64) -> DVec3 {
    let i = -dir; // slide 15's I: the negative of the incoming ray
    let (eta, nn) = if dir.dot(n) < 0.0 {
        (1.0 / ior, n)
    } else {
        (ior, -n)
    };
    let cos_i = nn.dot(i);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return (2.0 * cos_i * nn - i).normalize();
    }
    ((eta * cos_i - k.sqrt()) * nn - eta * i).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specular_power_is_powf_within_n_epsilon() {
        for n in [0.0, 1.0, 2.0, 30.0, 100.0, 1024.0, 2.5, 1025.0] {
            for i in 1..=1000 {
                let x = i as f64 / 1000.0;
                let (got, want) = (specular_power(x, n), x.powf(n));
                assert!(
                    (got - want).abs() <= n.max(2.0) * f64::EPSILON * want + 1e-300,
                    "{x}^{n}: {got} against {want}"
                );
            }
        }
    }

    #[test]
    fn refraction_obeys_snells_law() {
        let n = DVec3::Z;
        let dir = DVec3::new(0.6, 0.0, -0.8);
        let t = refract(dir, n, 1.5);
        let sin_i = 0.6;
        let sin_t = t.x / t.length();
        assert!((sin_i / sin_t - 1.5).abs() < 1e-12);
        assert!(t.z < 0.0);
        // Leaving the denser medium at a steep angle: total internal reflection.
        let out = refract(DVec3::new(0.9, 0.0, 0.43588989435406733), n, 1.5);
        assert!(out.z < 0.0);
    }
}
