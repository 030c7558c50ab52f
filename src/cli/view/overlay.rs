//! A broken save's message over the last good picture: the picture
//! dimmed, the message's first lines (what was expected, and the file,
//! line and column) written on it in Liberation Sans — csgrt's own text
//! layout (`import::text`), each glyph's exact outline filled along four
//! lines a pixel row.

use csgrt::import::text::{layout, Params};
use csgrt::plane::Outlines;
use glam::DVec2;

/// The text's size (OpenSCAD's `size`, about its capitals' height), its
/// line pitch and its margin, in pixels.
const TEXT_SIZE: f64 = 13.0;
const LINE: u32 = 21;
const MARGIN: u32 = 10;
/// How many of the message's lines are written, and of how many
/// characters at most (the rest is in the terminal).
pub const MAX_LINES: usize = 3;
pub const MAX_CHARS: usize = 160;
/// Rows of a pixel sampled.
const SUB_ROWS: u32 = 4;

/// `buf` (0RGB, `width`×`height`) dimmed, with `message` written on it.
pub fn draw(buf: &mut [u32], width: u32, height: u32, message: &str) {
    for p in buf.iter_mut() {
        let ch = |s: u32| ((*p >> s & 0xff) * 3 / 10) << s;
        *p = ch(16) | ch(8) | ch(0);
    }
    let room = width.saturating_sub(2 * MARGIN) as f64;
    let lines = message
        .lines()
        .filter(|l| is_said(l))
        .flat_map(|l| wrapped(&l.chars().take(MAX_CHARS).collect::<String>(), room))
        .take(MAX_LINES);
    for (i, glyphs) in lines.enumerate() {
        let baseline = MARGIN + LINE * (i as u32 + 1) - 6;
        write_line(buf, width, height, &glyphs, MARGIN as f64, baseline as f64);
    }
}

/// Whether a line of a message is written: what went wrong and where,
/// not the quoted source under it (`2 | sphere(r=;`, `  |   ^`), which
/// lines up only in a fixed-width font (the terminal has it all).
fn is_said(line: &str) -> bool {
    let t = line.trim_start();
    let quoted = t.starts_with('|')
        || t.split_once(" |")
            .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
    !t.is_empty() && !quoted
}

/// `text` laid out at [`TEXT_SIZE`].
fn laid(text: &str) -> Vec<Outlines> {
    layout(&Params::line(text, TEXT_SIZE)).glyphs
}

/// The right end of laid-out glyphs.
fn right_end(glyphs: &[Outlines]) -> f64 {
    glyphs
        .iter()
        .map(|g| g.extent(DVec2::X).1)
        .fold(0.0, f64::max)
}

/// `line` laid out in lines of at most `room` pixels, broken between
/// words (a word longer than that alone on its line).
fn wrapped(line: &str, room: f64) -> Vec<Vec<Outlines>> {
    let mut out = Vec::new();
    let mut current = String::new();
    for word in line.split(' ') {
        let longer = if current.is_empty() {
            word.to_string()
        } else {
            format!("{current} {word}")
        };
        if !current.is_empty() && right_end(&laid(&longer)) > room {
            out.push(laid(&current));
            current = format!("  {word}");
        } else {
            current = longer;
        }
    }
    out.push(laid(&current));
    out
}

/// The glyphs (y up, the baseline at 0) filled in white with their left
/// end at `x0` and baseline at row `baseline` (y down).
fn write_line(
    buf: &mut [u32],
    width: u32,
    height: u32,
    glyphs: &[Outlines],
    x0: f64,
    baseline: f64,
) {
    let top = (baseline - 2.0 * TEXT_SIZE).max(0.0) as u32;
    let bottom = ((baseline + TEXT_SIZE).ceil() as u32).min(height);
    let ranges: Vec<(f64, f64)> = glyphs.iter().map(|g| g.extent(DVec2::Y)).collect();
    let mut cover = vec![0f64; width as usize];
    for row in top..bottom {
        cover.iter_mut().for_each(|c| *c = 0.0);
        for k in 0..SUB_ROWS {
            let y = baseline - (row as f64 + (k as f64 + 0.5) / SUB_ROWS as f64);
            for (g, &(lo, hi)) in glyphs.iter().zip(&ranges) {
                if y < lo || y > hi {
                    continue;
                }
                for (a, b) in g.spans(DVec2::new(0.0, y), DVec2::X) {
                    add_span(&mut cover, x0 + a, x0 + b, 1.0 / SUB_ROWS as f64);
                }
            }
        }
        let line = &mut buf[(row * width) as usize..((row + 1) * width) as usize];
        for (p, &c) in line.iter_mut().zip(&cover) {
            if c > 0.0 {
                let c = c.min(1.0);
                let ch = |s: u32| {
                    let v = (*p >> s & 0xff) as f64;
                    ((v + (255.0 - v) * c).round() as u32) << s
                };
                *p = ch(16) | ch(8) | ch(0);
            }
        }
    }
}

/// Adds `w` times the part of each pixel [x, x + 1) that [a, b) covers.
fn add_span(cover: &mut [f64], a: f64, b: f64, w: f64) {
    let n = cover.len() as f64;
    let (a, b) = (a.max(0.0), b.min(n));
    if a >= b || a.is_nan() || b.is_nan() {
        return;
    }
    for x in a.floor() as usize..(b.ceil() as usize).min(cover.len()) {
        let (l, r) = (x as f64, x as f64 + 1.0);
        cover[x] += w * (b.min(r) - a.max(l)).max(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message is written: white pixels where there were none, inside
    /// the margin and the lines written; the rest only dimmed.
    #[test]
    fn a_message_is_written_over_the_dimmed_picture() {
        let (w, h) = (320u32, 120u32);
        let mut buf = vec![0x00_80_80_80u32; (w * h) as usize];
        draw(
            &mut buf,
            w,
            h,
            "error: expected a number\n --> part.scad:2:10\n  |\n",
        );
        let lit: Vec<(u32, u32)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| buf[(y * w + x) as usize] == 0x00_ff_ff_ff)
            .collect();
        assert!(lit.len() > 100, "{} white pixels", lit.len());
        assert!(lit
            .iter()
            .all(|&(x, y)| x >= MARGIN - 1 && y < MARGIN + 2 * LINE + 4));
        // Both lines: white pixels on each.
        assert!(lit.iter().any(|&(_, y)| y < MARGIN + LINE));
        assert!(lit.iter().any(|&(_, y)| y > MARGIN + LINE));
        assert_eq!(buf[(h * w - 1) as usize], 0x00_26_26_26);
    }
}
