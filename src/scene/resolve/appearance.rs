//! Appearance: `color` and `material`, inherited down the tree.

use super::Resolver;
use crate::error::Result;
use crate::mutant;
use crate::scene::args::Args;
use crate::scene::{defaults, Material};
use crate::syntax::ast::Statement;
use glam::DVec3;

impl Resolver<'_> {
    pub(super) fn appearance(&mut self, s: &Statement, mut m: Material) -> Result<Material> {
        if s.name == "color" {
            let a = Args::bind(self.src, s, &["c", "alpha"])?;
            let c = a.numbers("c", &[3, 4])?;
            let alpha = a.number("alpha")?;
            match c {
                // OpenSCAD writes color([-1, -1, -1, -1]) for "no colour".
                Some(c) if c.iter().any(|x| *x < 0.0) => {}
                _ if mutant::active("color_ignored") => {}
                _ if mutant::active("outer_color_wins") && m.color != defaults::MATERIAL.color => {}
                Some(c) => {
                    m.color = DVec3::new(c[0], c[1], c[2]).clamp(DVec3::ZERO, DVec3::ONE);
                    m.scheme_color = false;
                    let alpha = alpha.or(c.get(3).copied()).unwrap_or(1.0).clamp(0.0, 1.0);
                    if alpha < 1.0 {
                        m.kt = 1.0 - alpha;
                        m.ior = 1.0;
                    }
                }
                None => {}
            }
            return Ok(m);
        }
        let a = Args::bind(
            self.src,
            s,
            &["color", "ka", "kd", "ks", "ns", "kr", "kt", "ior"],
        )?;
        if let Some(c) = a.numbers("color", &[3])? {
            m.color = DVec3::new(c[0], c[1], c[2]);
            m.scheme_color = false;
        }
        let fields: [(&str, &mut f64); 7] = [
            ("ka", &mut m.ka),
            ("kd", &mut m.kd),
            ("ks", &mut m.ks),
            ("ns", &mut m.ns),
            ("kr", &mut m.kr),
            ("kt", &mut m.kt),
            ("ior", &mut m.ior),
        ];
        for (name, field) in fields {
            if let Some(x) = a.non_negative(name)? {
                *field = x;
            }
        }
        if a.has("ior") && m.ior == 0.0 {
            return Err(a.error(
                a.span_of("ior"),
                "`ior` must be positive",
                "expected a number > 0",
            ));
        }
        Ok(m)
    }
}
