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
use smallvec::SmallVec;

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
                let c = self.shade(ray, &b, depth, weight, None, st);
                (c.clamp(DVec3::ZERO, DVec3::ONE), c)
            }
            None => (self.scene.background, self.scene.background),
        }
    }

    /// The colour of boundary `b` of `ray`; `ahead`, when known, the
    /// boundaries after it along the same line ([`Ahead`]).
    fn shade(
        &self,
        ray: &Ray,
        b: &Boundary,
        depth: u32,
        weight: f64,
        ahead: Option<Ahead>,
        st: &mut Stats,
    ) -> DVec3 {
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
                st.refracted_rays += 1;
                let (depth, weight) = (depth + 1, weight * m.kt);
                color += m.kt
                    * if m.ior == 1.0 {
                        self.straight_on(ray, hit.t + err, depth, weight, ahead, st)
                    } else {
                        let t = refract(ray.dir, n, m.ior);
                        self.trace(&Ray::new(offset_origin(p, n, err, t), t), depth, weight, st)
                    };
            }
        }
        color
    }

    /// The colour seen along `ray`'s own line beyond `after` (past a
    /// surface of index 1, which the light crosses unbent: OpenSCAD's
    /// `color` with an alpha), clamped to [0, 1]; the background where
    /// nothing lies beyond. The next boundary is `ahead`'s first beyond
    /// `after` while `ahead` holds one; otherwise one query finds the
    /// line's boundaries beyond `after` ([`Shader::boundaries_beyond`]), and the
    /// surfaces seen through this one take theirs from the same list
    /// instead of casting a ray each.
    fn straight_on(
        &self,
        ray: &Ray,
        after: f64,
        depth: u32,
        weight: f64,
        ahead: Option<Ahead>,
        st: &mut Stats,
    ) -> DVec3 {
        let found;
        let a = match ahead {
            Some(a) if a.complete || a.list.last().is_some_and(|b| b.t > after) => a,
            _ => {
                found = self.boundaries_beyond(ray, after, st);
                Ahead {
                    list: &found.0,
                    complete: found.1,
                }
            }
        };
        let Some(k) = a.list.iter().position(|b| b.t > after) else {
            return self.scene.background;
        };
        let rest = Ahead {
            list: &a.list[k + 1..],
            complete: a.complete,
        };
        let c = self.shade(ray, &a.list[k], depth, weight, Some(rest), st);
        c.clamp(DVec3::ZERO, DVec3::ONE)
    }

    /// The surface boundaries of `ray`'s line beyond `after`, in order,
    /// up to and including the first whose material does not pass the
    /// line on unbent (opaque, or of another index), from one query of
    /// the tree's list ([`Csg::spans_until`], which it is good up to);
    /// at most [`AHEAD`] of them, and whether they are all there are up to
    /// there (not cut at [`AHEAD`]).
    fn boundaries_beyond(
        &self,
        ray: &Ray,
        after: f64,
        st: &mut Stats,
    ) -> (SmallVec<[Boundary; AHEAD]>, bool) {
        let stops = |b: &Boundary| {
            let m = self.material(b.prim);
            m.kt <= 0.0 || m.ior != 1.0
        };
        self.csg
            .spans_until(ray, after, f64::INFINITY, st, stops, |spans| {
                let mut list = SmallVec::new();
                for b in spans.iter().flat_map(|s| [s.enter, s.exit]) {
                    if b.t <= after || !b.is_surface() {
                        continue;
                    }
                    if list.len() == AHEAD {
                        return (list, false);
                    }
                    list.push(b);
                    if stops(&b) {
                        break;
                    }
                }
                (list, true)
            })
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

/// The boundaries a line crosses beyond a surface it passes unbent, of
/// the list found once for the surfaces after it
/// ([`Shader::boundaries_beyond`]); `complete` when they are all there
/// are up to the first that stops the line (or to the scene's end), not
/// cut at [`AHEAD`].
#[derive(Clone, Copy)]
struct Ahead<'a> {
    list: &'a [Boundary],
    complete: bool,
}

/// The most boundaries [`Shader::boundaries_beyond`] keeps: more than the default
/// ray tree's depth passes through.
const AHEAD: usize = 12;

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
    use crate::math::srgb;

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

    fn rendered(text: &str, w: u32, h: u32, max_depth: u32) -> Vec<u8> {
        let src = crate::Source::new("t.csg", text.to_string());
        let ast = crate::syntax::parse_csg(&src).unwrap();
        let scene = crate::scene::resolve_with(&src, &ast, Default::default()).unwrap();
        let s = crate::render::Settings {
            width: w,
            height: h,
            max_depth,
            ..Default::default()
        };
        crate::render::render(&scene, &s, &|_| {}).rgb
    }

    /// Seen straight down through `n` translucent slabs (alpha `a`) under
    /// ambient light alone, a pixel is the closed form of the seed's
    /// recursion over the 2n faces: each face ka·C plus kt times what lies
    /// beyond it (clamped), while the tree is shallower than `max_depth`
    /// and the path's weight kt^(k+1) is at least 1/512; the background
    /// past the last face. Found once for all faces ahead, more than a
    /// list holds ([`AHEAD`]), and at the depth and weight limits.
    #[test]
    fn faces_seen_through_unbent_are_the_closed_form() {
        let (ka, c, bg) = (0.2, [0.9, 0.5, 0.1], [0.2, 0.3, 0.4]);
        for (n, a, max_depth) in [
            (2, 0.5, 5),
            (3, 0.5, 5),
            (3, 0.7, 30),
            (10, 0.5, 30),
            (10, 0.1, 60),
            (40, 0.05, 90),
        ] {
            let kt: f64 = 1.0 - a;
            let slabs: String = (0..n)
                .map(|i| {
                    format!(
                        "color([{}, {}, {}, {a}]) translate([-50, -50, {}]) cube([100, 100, 1]);\n",
                        c[0],
                        c[1],
                        c[2],
                        -3.0 * i as f64
                    )
                })
                .collect();
            let text = format!(
                "camera(eye = [0, 0, 50], lookat = [0, 0, 0], up = [0, 1, 0], fov = 10);\n\
                 background([{}, {}, {}]);\nambient_light([1, 1, 1]);\n{slabs}",
                bg[0], bg[1], bg[2]
            );
            let got = rendered(&text, 8, 6, max_depth);
            for ch in 0..3 {
                let local = ka * srgb::decode(c[ch]);
                // Face k of 2n, at depth k with weight kt^k.
                let mut beyond = srgb::decode(bg[ch]);
                for k in (0..2 * n).rev() {
                    let on = k < max_depth as usize && kt.powi(k as i32 + 1) >= MIN_WEIGHT;
                    if k > max_depth as usize {
                        continue;
                    }
                    beyond = local + if on { kt * beyond.clamp(0.0, 1.0) } else { 0.0 };
                }
                let want = srgb::byte(beyond.clamp(0.0, 1.0)) as i32;
                for px in got.chunks(3) {
                    assert!(
                        (px[ch] as i32 - want).abs() <= 1,
                        "{n} slabs, alpha {a}, depth {max_depth}: {} against {want}",
                        px[ch]
                    );
                }
            }
        }
    }

    /// A transparent solid of index 1 and one of index 1 + 10⁻¹⁰ (whose
    /// rays are cast one by one, bent by Snell's law) show the same
    /// picture to a level: overlapping translucent balls, a hollow
    /// translucent box and an opaque floor, under lights with shadows.
    #[test]
    fn faces_seen_through_unbent_are_those_cast_one_by_one() {
        let scene = |ior: &str| {
            format!(
                "camera(eye = [30, -40, 25], lookat = [0, 0, 0], fov = 40);\n\
                 directional_light([0.8, 0.8, 0.8], [-1, 1.5, -2]);\n\
                 point_light([0.3, 0.3, 0.3], [10, -10, 30]);\nambient_light([0.2, 0.2, 0.2]);\n\
                 material(color = [0.9, 0.3, 0.2], kt = 0.6, ior = {ior}) {{\n\
                 sphere(6); translate([5, 0, 0]) sphere(5); translate([-4, 3, 2]) sphere(4);\n\
                 difference() {{ translate([0, -4, 0]) cube(9, center = true); cube(7, center = true); }}\n\
                 }}\n\
                 material(color = [0.2, 0.7, 0.3], kt = 0.3, ior = {ior}) translate([0, 0, -3]) cylinder(h = 12, r = 2);\n\
                 translate([-30, -30, -12]) cube([60, 60, 1]);\n"
            )
        };
        for depth in [2, 5, 12] {
            let (a, b) = (
                rendered(&scene("1"), 64, 48, depth),
                rendered(&scene("1.0000000001"), 64, 48, depth),
            );
            let worst = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).max();
            assert!(worst <= Some(1), "depth {depth}: {worst:?} levels apart");
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
