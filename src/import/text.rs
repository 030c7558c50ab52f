//! OpenSCAD's `text()`: a string set in a font, as the glyphs' exact
//! outlines (lines and quadratic or cubic Bézier curves, never flattened).
//!
//! The layout is OpenSCAD 2021.01's (`src/FreetypeRenderer.cc`): the font is
//! sized with FreeType's `FT_Set_Char_Size(face, 0, 1e5, 100, 100)` — 1e5/64
//! points at 100 dpi, so an em is E = round(1e5·100/72) = 138889 units of
//! 1/64 pixel (rounded to a whole number of pixels, 138880, when the font's
//! `head` flags ask for integer ppem, as TrueType fonts' do) — HarfBuzz
//! shapes the string (kerning, ligatures), and a glyph point p (font units,
//! upem to the em) lands at size·(p·E/upem/1e5 + offset + pen), offset and pen (the sum of the earlier glyphs' advances times `spacing`)
//! in 26.6 units divided by 1.024e5 — OpenSCAD's own mixed scale factors,
//! kept "for compatibility". HarfBuzz's positions (advances, kerning) are
//! at the em asked, 138889 units, not the rounded E. Vertical text
//! (`direction` "ttb", "btt") places each glyph by FreeType's synthesized
//! vertical metrics, as HarfBuzz reads them through FreeType
//! (`vertical_position`). `halign` moves the line by its width (the sum
//! of advances times spacing), `valign` by the largest ascent and descent
//! of the glyphs' grid-fitted control boxes. The differences from OpenSCAD
//! are FreeType's: it hints the outline at 2170 ppem and rounds points to
//! 1/64 pixel (both under 2.5e-4 em), and flattens curves into `$fn`
//! pieces; csgrt draws the font's own curves (the smooth limit).
//!
//! Fonts: Liberation Sans 2.1 (Regular, Bold, Italic, Bold Italic) is built
//! in — the default OpenSCAD bundles — so a picture is the same on every
//! machine; other families are looked up among the system's fonts
//! (`fontdb`) when asked for. A family found nowhere falls back to Liberation
//! Sans with a warning, as OpenSCAD's fontconfig falls back to its best
//! match.

use crate::plane::{Ctrl, Outlines};
use glam::DVec2;
use std::sync::OnceLock;

const BUILT_IN: [&[u8]; 4] = [
    include_bytes!("../../fonts/LiberationSans-Regular.ttf"),
    include_bytes!("../../fonts/LiberationSans-Bold.ttf"),
    include_bytes!("../../fonts/LiberationSans-Italic.ttf"),
    include_bytes!("../../fonts/LiberationSans-BoldItalic.ttf"),
];

/// OpenSCAD's default font.
pub const DEFAULT_FAMILY: &str = "Liberation Sans";

/// The longest string `text` lays out (each glyph becomes a solid).
pub const MAX_TEXT_CHARS: usize = 10_000;

/// The arguments of a `text` statement, OpenSCAD's defaults filled in.
#[derive(Clone, Debug)]
pub struct Params<'a> {
    pub text: &'a str,
    pub size: f64,
    pub font: &'a str,
    pub halign: &'a str,
    pub valign: &'a str,
    pub spacing: f64,
    pub direction: &'a str,
    pub language: &'a str,
    pub script: &'a str,
}

/// A laid-out string: one outline set per glyph that has one (a space has
/// none), in OpenSCAD's units, and what to warn about, with the parameter
/// each warning concerns.
#[derive(Debug, Default)]
pub struct Laid {
    pub glyphs: Vec<Outlines>,
    pub warnings: Vec<(&'static str, String)>,
    /// The family and style used, for messages.
    pub face: String,
}

struct Fonts {
    built_in: fontdb::Database,
    system: OnceLock<fontdb::Database>,
}

fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(|| {
        let mut built_in = fontdb::Database::new();
        for data in BUILT_IN {
            built_in.load_font_data(data.to_vec());
        }
        Fonts {
            built_in,
            system: OnceLock::new(),
        }
    })
}

/// A fontconfig name, `Family[,Family…]:style=Bold Italic` (or `:bold`,
/// `:italic`, `:weight=…`): the families, the weight and the slant asked.
fn parse_font_name(name: &str) -> (Vec<String>, fontdb::Weight, fontdb::Style) {
    let mut parts = name.split(':');
    let families: Vec<String> = parts
        .next()
        .unwrap_or("")
        .split(',')
        .map(|f| f.replace('\\', "").trim().to_string())
        .filter(|f| !f.is_empty())
        .collect();
    let mut weight = fontdb::Weight::NORMAL;
    let mut style = fontdb::Style::Normal;
    for prop in parts {
        let value = prop
            .split_once('=')
            .map_or(prop, |(_, v)| v)
            .to_ascii_lowercase();
        let words = value.replace(['-', '_'], "");
        for (key, w) in [
            ("thin", 100),
            ("extralight", 200),
            ("ultralight", 200),
            ("light", 300),
            ("medium", 500),
            ("semibold", 600),
            ("demibold", 600),
            ("extrabold", 800),
            ("ultrabold", 800),
            ("black", 900),
            ("heavy", 900),
        ] {
            if words.contains(key) {
                weight = fontdb::Weight(w);
            }
        }
        if words.split_whitespace().any(|w| w == "bold") || words == "bold" {
            weight = fontdb::Weight::BOLD;
        }
        if words.contains("italic") {
            style = fontdb::Style::Italic;
        } else if words.contains("oblique") {
            style = fontdb::Style::Oblique;
        }
    }
    (families, weight, style)
}

/// The face for a fontconfig name: in the built-in fonts, else among the
/// system's; a warning when no family asked for is found.
fn find_face(name: &str) -> (&'static fontdb::Database, fontdb::ID, Option<String>) {
    let f = fonts();
    let trimmed = name.trim();
    let (families, weight, style) = parse_font_name(if trimmed.is_empty() {
        "Liberation Sans:style=Regular"
    } else {
        trimmed
    });
    let lookup = |db: &'static fontdb::Database, family: &str| {
        // fontconfig matches family names without regard to case.
        let canonical = db
            .faces()
            .flat_map(|face| face.families.iter())
            .find(|(n, _)| n.eq_ignore_ascii_case(family))
            .map(|(n, _)| n.clone())?;
        let query = fontdb::Query {
            families: &[fontdb::Family::Name(&canonical)],
            weight,
            stretch: fontdb::Stretch::Normal,
            style,
        };
        db.query(&query).map(|id| (db, id))
    };
    for family in &families {
        if let Some((db, id)) = lookup(&f.built_in, family) {
            return (db, id, None);
        }
        let system = f.system.get_or_init(|| {
            let mut db = fontdb::Database::new();
            db.load_system_fonts();
            db
        });
        if let Some((db, id)) = lookup(system, family) {
            return (db, id, None);
        }
    }
    let (db, id) = lookup(&f.built_in, DEFAULT_FAMILY).expect("the built-in font is present");
    let warning = format!(
        "font `{}` is not installed; using {}",
        families.join(","),
        db.face(id).map_or(String::new(), describe)
    );
    (db, id, Some(warning))
}

fn describe(face: &fontdb::FaceInfo) -> String {
    let family = face.families.first().map_or("?", |(n, _)| n.as_str());
    let bold = face.weight.0 >= 600;
    let italic = face.style != fontdb::Style::Normal;
    let style = match (bold, italic) {
        (false, false) => "Regular",
        (true, false) => "Bold",
        (false, true) => "Italic",
        (true, true) => "Bold Italic",
    };
    format!("{family}:style={style}")
}

/// A glyph's contours, in font units.
#[derive(Default)]
struct Contours {
    loops: Vec<Vec<DVec2>>,
    ctrl: Vec<Vec<Ctrl>>,
    start: DVec2,
    open: bool,
}

impl Contours {
    fn to(&mut self, c: Ctrl, p: DVec2) {
        let l = self.loops.last_mut().expect("a contour is open");
        let last = *l.last().expect("a contour has a start");
        if c == Ctrl::Line && p == last {
            return;
        }
        l.push(p);
        self.ctrl.last_mut().expect("a contour is open").push(c);
    }

    fn finish(&mut self) {
        if !self.open {
            return;
        }
        self.open = false;
        let (l, c) = (
            self.loops.last_mut().unwrap(),
            self.ctrl.last_mut().unwrap(),
        );
        if l.len() > 1 && *l.last().unwrap() == self.start {
            // The last edge ends at the start: it closes the loop.
            l.pop();
        } else {
            c.push(Ctrl::Line);
        }
        let curved = c.iter().any(|k| *k != Ctrl::Line);
        if l.len() < 2 || l.len() == 2 && !curved {
            self.loops.pop();
            self.ctrl.pop();
        }
    }
}

impl ttf_parser::OutlineBuilder for Contours {
    fn move_to(&mut self, x: f32, y: f32) {
        self.finish();
        self.start = DVec2::new(x as f64, y as f64);
        self.loops.push(vec![self.start]);
        self.ctrl.push(Vec::new());
        self.open = true;
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.to(Ctrl::Line, DVec2::new(x as f64, y as f64));
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let c = DVec2::new(x1 as f64, y1 as f64);
        self.to(Ctrl::Quad(c), DVec2::new(x as f64, y as f64));
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        let (c1, c2) = (
            DVec2::new(x1 as f64, y1 as f64),
            DVec2::new(x2 as f64, y2 as f64),
        );
        self.to(Ctrl::Cubic(c1, c2), DVec2::new(x as f64, y as f64));
    }
    fn close(&mut self) {
        self.finish();
    }
}

/// The em asked of FreeType, in 26.6 units: 1e5/64 points at 100 dpi.
const NOMINAL_EM: f64 = 138_889.0;

/// The em in 26.6 units FreeType sizes the face to (see the module's
/// comment): `head` flag bit 3 rounds the ppem to a whole number.
fn em_26_6(face: &ttf_parser::Face) -> f64 {
    let nominal = NOMINAL_EM;
    let integer_ppem = face
        .raw_face()
        .table(ttf_parser::Tag::from_bytes(b"head"))
        .and_then(|h| h.get(16..18))
        .is_some_and(|f| u16::from_be_bytes([f[0], f[1]]) & 8 != 0);
    if integer_ppem {
        ((nominal + 32.0) / 64.0).floor() * 64.0
    } else {
        nominal
    }
}

/// Where OpenSCAD 2021.01 places a glyph in vertical text, and how far the
/// pen moves: (offset, advance) in 26.6 units. HarfBuzz, through FreeType
/// (`hb_ft_font_create`, unhinted loads), moves each glyph by minus its
/// vertical origin — (horiBearingX − vertBearingX, horiBearingY +
/// vertBearingY) — and advances by minus its vertical advance. A font
/// without `vmtx` (Liberation Sans has none) gets FreeType's own
/// (`ttgload.c`): vertBearingX = horiBearingX − horiAdvance/2, the advance
/// A = sTypoAscender − sTypoDescender (else hhea's) and the top bearing
/// (A − height)/2 in font units, C's integer division, then scaled. Each
/// scaling rounds to the nearest 26.6 unit, as FT_MulFix does; `s` is 26.6
/// units a font unit, `y_lo` and `y_hi` the outline's extent in y. The
/// advance alone is scaled by the size asked (`FT_Get_Advance` takes the
/// face's requested scale, 1e5·100/72 units an em, not the TrueType
/// driver's whole-pixel one): measured against OpenSCAD's own layout, the
/// rounded scale leaves 8 units of drift a glyph.
fn vertical_position(
    face: &rustybuzz::Face,
    gid: ttf_parser::GlyphId,
    s: f64,
    y_lo: f64,
    y_hi: f64,
) -> (DVec2, DVec2) {
    let scaled = |v: f64| (v * s).round();
    let h_advance = scaled(face.glyph_hor_advance(gid).unwrap_or(0) as f64);
    let (asc, desc) = match (face.typographic_ascender(), face.typographic_descender()) {
        (Some(a), Some(d)) => (a, d),
        _ => (face.ascender(), face.descender()),
    };
    let v_advance = asc as f64 - desc as f64;
    let top_of_box = scaled(y_hi);
    let height = ((top_of_box - scaled(y_lo)) / s).round();
    let top = ((v_advance - height) / 2.0).trunc();
    let origin = DVec2::new((h_advance / 2.0).floor(), top_of_box + scaled(top));
    let requested = NOMINAL_EM / face.units_per_em() as f64;
    (-origin, DVec2::new(0.0, -(v_advance * requested).round()))
}

impl<'a> Params<'a> {
    /// `text` in csgrt's built-in font at `size`, left to right from the
    /// origin on its baseline, in English and Latin script.
    pub fn line(text: &'a str, size: f64) -> Params<'a> {
        Params {
            text,
            size,
            font: DEFAULT_FAMILY,
            halign: "left",
            valign: "baseline",
            spacing: 1.0,
            direction: "ltr",
            language: "en",
            script: "Latn",
        }
    }
}

/// Lays out `p` as OpenSCAD does.
pub fn layout(p: &Params) -> Laid {
    let mut laid = Laid::default();
    let (db, id, warning) = find_face(p.font);
    if let Some(w) = warning {
        laid.warnings.push(("font", w));
    }
    laid.face = db.face(id).map_or(String::new(), describe);
    let found = db.with_face_data(id, |data, index| {
        let face = rustybuzz::Face::from_slice(data, index)?;
        Some(lay_out_with(&face, p, &mut laid.warnings))
    });
    match found.flatten() {
        Some(glyphs) => laid.glyphs = glyphs,
        None => laid
            .warnings
            .push(("font", format!("font {} cannot be read", laid.face))),
    }
    laid
}

/// A layout of `text` (size 10) in the font file `bytes` (for the fuzz
/// harness: a font csgrt did not vet), or `None` when it is no font.
pub fn layout_with_font_bytes(bytes: &[u8], text: &str) -> Option<usize> {
    let face = rustybuzz::Face::from_slice(bytes, 0)?;
    let p = Params {
        text,
        size: 10.0,
        font: "",
        halign: "center",
        valign: "center",
        spacing: 1.0,
        direction: "ltr",
        language: "en",
        script: "Latn",
    };
    Some(lay_out_with(&face, &p, &mut Vec::new()).len())
}

fn lay_out_with(
    face: &rustybuzz::Face,
    p: &Params,
    warnings: &mut Vec<(&'static str, String)>,
) -> Vec<Outlines> {
    let mut buf = rustybuzz::UnicodeBuffer::new();
    buf.push_str(p.text);
    if let Ok(d) = p.direction.parse::<rustybuzz::Direction>() {
        buf.set_direction(d);
    }
    if let Ok(s) = p.script.parse::<rustybuzz::Script>() {
        buf.set_script(s);
    }
    if let Ok(l) = p.language.parse::<rustybuzz::Language>() {
        buf.set_language(l);
    }
    buf.guess_segment_properties();
    let horizontal = matches!(
        buf.direction(),
        rustybuzz::Direction::LeftToRight | rustybuzz::Direction::RightToLeft
    );
    let features: &[rustybuzz::Feature] = if crate::mutant::active("kerning_ignored") {
        &[rustybuzz::Feature::new(
            ttf_parser::Tag::from_bytes(b"kern"),
            0,
            ..,
        )]
    } else {
        &[]
    };
    let shaped = rustybuzz::shape(face, features, buf);
    let upem = face.units_per_em() as f64;
    let em = em_26_6(face);
    // Font units to OpenSCAD's: the outline's (÷1e5, at the em the
    // TrueType driver rounds to whole pixels) and HarfBuzz's positions'
    // (÷1.024e5, at the em asked: hb-ft reads advances through
    // FT_Get_Advance and scales kerning by the face's requested size —
    // measured against OpenSCAD's own layout, tests/it/vertical_text.rs, the
    // rounded em drifts 5e-5 of the size a glyph).
    let (k_outline, k_metric) = (em / upem / 1e5, NOMINAL_EM / upem / 1.024e5);
    struct Glyph {
        contours: Contours,
        offset: DVec2,
        advance: DVec2,
    }
    let mut glyphs = Vec::new();
    let (mut width, mut ascend, mut descend) = (0.0f64, 0.0f64, 0.0f64);
    for (info, pos) in shaped.glyph_infos().iter().zip(shaped.glyph_positions()) {
        let gid = ttf_parser::GlyphId(info.glyph_id as u16);
        let mut contours = Contours::default();
        face.outline_glyph(gid, &mut contours);
        contours.finish();
        // FreeType's control box (font units), then grid-fitted (26.6).
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let ctrl = contours.ctrl.iter().flatten().flat_map(|c| c.points());
        for q in contours.loops.iter().flatten().copied().chain(ctrl) {
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if lo.x > hi.x {
            (lo, hi) = (DVec2::ZERO, DVec2::ZERO);
        }
        let (offset, advance) = if horizontal {
            (
                DVec2::new(pos.x_offset as f64, pos.y_offset as f64) * k_metric,
                DVec2::new(pos.x_advance as f64, pos.y_advance as f64) * k_metric,
            )
        } else {
            let (o, a) = vertical_position(face, gid, em / upem, lo.y, hi.y);
            (o / 1.024e5, a / 1.024e5)
        };
        let (lo, hi) = (
            (lo * (em / upem) / 64.0).floor() * 64.0,
            (hi * (em / upem) / 64.0).ceil() * 64.0,
        );
        if horizontal {
            ascend = ascend.max((hi.y / 1.024e5).max(0.0));
            descend = descend.max((-lo.y / 1.024e5).max(0.0));
            width += advance.x * p.spacing;
        } else {
            width = width.max((hi.x - lo.x) / 1.024e5);
            ascend += advance.y * p.spacing;
        }
        glyphs.push(Glyph {
            contours,
            offset,
            advance,
        });
    }
    let x_offset = match p.halign {
        "right" => -width,
        "center" => -width / 2.0,
        h => {
            if h != "left" {
                warnings.push((
                    "halign",
                    format!(
                        "unknown `halign` \"{h}\" (use \"left\", \"right\" or \"center\"): left"
                    ),
                ));
            }
            0.0
        }
    };
    let y_offset = match p.valign {
        "top" => -ascend,
        "center" => descend / 2.0 - ascend / 2.0,
        "bottom" => descend,
        v => {
            if v != "baseline" {
                warnings.push((
                    "valign",
                    format!(
                        "unknown `valign` \"{v}\" (use \"baseline\", \"bottom\", \"top\" or \"center\"): baseline"
                    ),
                ));
            }
            0.0
        }
    };
    let mut pen = DVec2::ZERO;
    let mut out = Vec::new();
    for g in glyphs {
        let shift = DVec2::new(x_offset, y_offset) + g.offset + pen;
        pen += g.advance * p.spacing;
        if g.contours.loops.is_empty() {
            continue;
        }
        let o = Outlines {
            loops: g.contours.loops,
            ctrl: g.contours.ctrl,
        };
        let size = p.size;
        out.push(o.map(move |q| size * (q * k_outline + shift)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(text: &str) -> Params<'_> {
        Params {
            font: "",
            ..Params::line(text, 10.0)
        }
    }

    #[test]
    fn corrupted_font_files_never_panic() {
        // Single-byte changes all over the built-in font, laid out: a
        // layout or no font, never a panic (ttf-parser and rustybuzz check
        // every table they read).
        let mut seed = 3u64;
        for _ in 0..200 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let mut b = BUILT_IN[0].to_vec();
            for k in 0..8 {
                let i = ((seed >> 16) as usize).wrapping_mul(k + 1) % b.len();
                b[i] = (seed >> (k * 4)) as u8;
            }
            let _ = layout_with_font_bytes(&b, "AVWa fi 0123");
        }
        assert_eq!(layout_with_font_bytes(b"not a font", "a"), None);
    }

    #[test]
    fn font_names_read_as_fontconfig_does() {
        let (f, w, s) = parse_font_name("Liberation Sans:style=Bold Italic");
        assert_eq!(f, vec!["Liberation Sans"]);
        assert_eq!((w, s), (fontdb::Weight::BOLD, fontdb::Style::Italic));
        let (f, w, s) = parse_font_name("DejaVu Sans, Arial:bold");
        assert_eq!(f, vec!["DejaVu Sans", "Arial"]);
        assert_eq!((w, s), (fontdb::Weight::BOLD, fontdb::Style::Normal));
    }

    #[test]
    fn the_built_in_font_answers_the_default_and_its_styles() {
        let laid = layout(&params("H"));
        assert!(laid.warnings.is_empty(), "{:?}", laid.warnings);
        assert_eq!(laid.face, "Liberation Sans:style=Regular");
        let bold = layout(&Params {
            font: "liberation sans:style=Bold",
            ..params("H")
        });
        assert_eq!(bold.face, "Liberation Sans:style=Bold");
        let missing = layout(&Params {
            font: "No Such Family Anywhere",
            ..params("H")
        });
        assert_eq!(missing.face, "Liberation Sans:style=Regular");
        assert_eq!(missing.warnings.len(), 1);
    }
}
