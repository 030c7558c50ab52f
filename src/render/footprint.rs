//! The pixels whose camera rays may meet a box: the box's eight corners
//! projected onto the image, and their hull cut along each row of pixels.
//! A camera sample outside it, by a margin far wider than any rounding of
//! the rays or of the box test, misses the box; where the box is the
//! scene's, it sees the background, and no ray need be cast for it.

use super::camera::Camera;
use crate::geometry::Aabb;
use glam::{DVec2, DVec3};
use std::ops::Range;

/// How far (in pixels) outside the projected hull a sample must lie to be
/// counted a miss. A sample lies within half a pixel of its pixel's
/// centre; the rest is the margin, where a pixel subtends some 10⁻³ of a
/// radian and the rays and the box test round by some 10⁻¹⁵.
pub const FOOTPRINT_MARGIN: f64 = 2.0;

/// Beyond this many pixels from the image, a projected corner is taken to
/// lie too near the plane of the eye for its projection to be trusted.
const FOOTPRINT_REACH: f64 = 1e6;

/// A box's corners on the image, in pixels from the top left (`None`: an
/// empty box, seen nowhere).
#[derive(Clone, Debug, PartialEq)]
pub struct Footprint {
    corners: Option<[DVec2; 8]>,
}

impl Footprint {
    /// The footprint of `b` seen by `cam` on a `w`×`h` image, or `None`
    /// where it cannot rule pixels out safely: a box unbounded, not wholly
    /// ahead of the rays' origins, or reaching far outside the image. An
    /// empty box has an empty footprint.
    pub fn of(cam: &Camera, b: &Aabb, w: u32, h: u32) -> Option<Footprint> {
        if b.is_empty() {
            return Some(Footprint { corners: None });
        }
        if !b.is_bounded() {
            return None;
        }
        let reach = FOOTPRINT_REACH + w.max(h) as f64;
        let mut corners = [DVec2::ZERO; 8];
        for (k, c) in corners.iter_mut().enumerate() {
            let p = DVec3::new(
                if k & 1 == 0 { b.min.x } else { b.max.x },
                if k & 2 == 0 { b.min.y } else { b.max.y },
                if k & 4 == 0 { b.min.z } else { b.max.z },
            );
            let (x, y, ahead) = cam.project(p);
            // `!(a > 0)` also refuses NaN.
            if !(ahead > 0.0 && x.abs() < reach && y.abs() < reach) {
                return None;
            }
            *c = DVec2::new(x, y);
        }
        Some(Footprint {
            corners: Some(corners),
        })
    }

    /// The columns of row `y` (of a `w`-pixel row) whose samples may meet
    /// the box: every pixel whose square, grown by the margin, meets the
    /// hull of the corners. Empty when none does.
    pub fn columns(&self, y: u32, w: u32) -> Range<u32> {
        let Some(corners) = &self.corners else {
            return 0..0;
        };
        let (lo, hi) = (
            y as f64 - FOOTPRINT_MARGIN,
            y as f64 + 1.0 + FOOTPRINT_MARGIN,
        );
        // The hull's cut by the band lo ≤ y ≤ hi reaches, in x, exactly as
        // far as its corners inside the band and its edges' crossings of
        // the band's sides do; every segment between two corners lies in
        // the hull, and every edge of the hull is one.
        let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut take = |x: f64| {
            left = left.min(x);
            right = right.max(x);
        };
        for (i, p) in corners.iter().enumerate() {
            if p.y >= lo && p.y <= hi {
                take(p.x);
            }
            for q in &corners[i + 1..] {
                if p.y == q.y {
                    continue;
                }
                for side in [lo, hi] {
                    let s = (side - p.y) / (q.y - p.y);
                    if (0.0..=1.0).contains(&s) {
                        take(p.x + s * (q.x - p.x));
                    }
                }
            }
        }
        if left > right {
            return 0..0;
        }
        let first = (left - FOOTPRINT_MARGIN - 1.0).ceil().max(0.0);
        let last = (right + FOOTPRINT_MARGIN).floor().min(w as f64 - 1.0);
        if first > last {
            return 0..0;
        }
        first as u32..last as u32 + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, Projection};

    /// Every sample a pixel can take (its corners, its centre and random
    /// points in it) whose ray meets the box by the renderer's own box
    /// test lies in a column the footprint keeps: 400 random boxes (thin,
    /// flat, large, beside and around the eye) and views, both
    /// projections.
    #[test]
    fn a_sample_whose_ray_meets_the_box_is_kept() {
        let mut rnd = crate::plane::tests::uniform(11);
        let v = |r: &mut dyn FnMut() -> f64| DVec3::new(r() - 0.5, r() - 0.5, r() - 0.5);
        let (w, h) = (48u32, 36u32);
        let (mut kept, mut dropped, mut refused) = (0u64, 0u64, 0);
        for case in 0..400 {
            let spec = CameraSpec {
                eye: v(&mut rnd) * 40.0,
                lookat: v(&mut rnd) * 4.0,
                up: v(&mut rnd),
                fov: 10.0 + 80.0 * rnd(),
                projection: if case % 3 == 0 {
                    Projection::Orthographic
                } else {
                    Projection::Perspective
                },
            };
            let cam = Camera::new(&spec, w, h);
            let mut size = v(&mut rnd).abs() * 20.0 * rnd();
            if case % 5 == 0 {
                size.x = 0.0;
            }
            let lo = v(&mut rnd) * 30.0;
            let b = Aabb::new(lo, lo + size);
            let Some(f) = Footprint::of(&cam, &b, w, h) else {
                refused += 1;
                continue;
            };
            for y in 0..h {
                let cols = f.columns(y, w);
                for x in 0..w {
                    let mut at = vec![(0.5, 0.5), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];
                    at.extend((0..4).map(|_| (rnd(), rnd())));
                    let met = at.iter().any(|&(ox, oy)| {
                        b.hit(&cam.ray(x as f64 + ox, y as f64 + oy), 0.0, f64::INFINITY)
                    });
                    if cols.contains(&x) {
                        kept += 1;
                    } else {
                        dropped += 1;
                        assert!(!met, "case {case}: pixel ({x}, {y}) meets {b:?}, dropped");
                    }
                }
            }
        }
        // The test means something: most views rule out pixels.
        assert!(dropped > kept, "{dropped} dropped, {kept} kept");
        assert!(refused < 200, "{refused} of 400 refused");
    }

    /// A box wholly or partly behind the eye, or unbounded, rules nothing
    /// out; an empty one rules out everything.
    #[test]
    fn a_box_behind_the_eye_rules_nothing_out() {
        let spec = CameraSpec {
            eye: DVec3::new(0.0, -10.0, 0.0),
            lookat: DVec3::ZERO,
            up: DVec3::Z,
            fov: 30.0,
            projection: Projection::Perspective,
        };
        let cam = Camera::new(&spec, 40, 30);
        let behind = Aabb::new(DVec3::new(-1.0, -12.0, -1.0), DVec3::new(1.0, -11.0, 1.0));
        assert_eq!(Footprint::of(&cam, &behind, 40, 30), None);
        let across = Aabb::new(DVec3::new(-1.0, -12.0, -1.0), DVec3::new(1.0, 1.0, 1.0));
        assert_eq!(Footprint::of(&cam, &across, 40, 30), None);
        assert_eq!(Footprint::of(&cam, &Aabb::EVERYTHING, 40, 30), None);
        let empty = Footprint::of(&cam, &Aabb::EMPTY, 40, 30).unwrap();
        assert!((0..30).all(|y| empty.columns(y, 40).is_empty()));
        let ahead = Aabb::new(DVec3::splat(-1.0), DVec3::splat(1.0));
        let f = Footprint::of(&cam, &ahead, 40, 30).unwrap();
        assert!(f.columns(15, 40).contains(&20) && f.columns(0, 40).is_empty());
    }
}
