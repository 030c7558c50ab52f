//! One error type for the whole crate.
//!
//! Problems in a scene file are [`Diagnostic`]s: they carry the file name, the
//! 1-based line and column, the source line and a caret under the offending
//! text, and they print like a compiler message:
//!
//! ```text
//! error: unknown argument `sise` for `cube`
//!  --> part.csg:3:6
//!   |
//! 3 | cube(sise = 2);
//!   |      ^^^^ expected one of `size`, `center`
//! ```

use std::fmt;
use std::path::PathBuf;

/// How many characters of a long source line a diagnostic shows.
pub const WINDOW: usize = 100;

/// A byte range in a source text (named so as not to be confused with
/// `csg::spans::Span`, an interval of a ray parameter).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TextRange {
    pub start: usize,
    pub end: usize,
}

impl TextRange {
    pub fn new(start: usize, end: usize) -> TextRange {
        TextRange { start, end }
    }
}

impl From<pest::Span<'_>> for TextRange {
    fn from(s: pest::Span<'_>) -> TextRange {
        TextRange::new(s.start(), s.end())
    }
}

/// How serious a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
    /// A problem OpenSCAD warns about and renders past: an error where it
    /// is made, which the statement it belongs to turns into a warning
    /// and an empty statement (`--strict` makes every warning an error).
    Lenient,
    /// Not a problem: how csgrt made something (an approximation, with
    /// its error), said once; `--strict` leaves it alone.
    Note,
}

impl Severity {
    /// How a message of this severity begins (`error`, `warning`, `note`).
    pub fn word(self) -> &'static str {
        match self {
            Severity::Error | Severity::Lenient => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

/// A message tied to a place in a source file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub message: String,
    pub file: String,
    pub line: usize,
    pub col: usize,
    pub source_line: String,
    pub caret_len: usize,
    /// Printed after the caret: usually what was expected.
    pub label: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = self.severity.word();
        let num = self.line.to_string();
        let pad = " ".repeat(num.len());
        writeln!(f, "{kind}: {}", printable(&self.message))?;
        writeln!(
            f,
            "{pad}--> {}:{}:{}",
            printable(&self.file),
            self.line,
            self.col
        )?;
        writeln!(f, "{pad} |")?;
        // The characters around the caret as they are shown: a control
        // character escaped (`\x1b`), a tab kept so that the caret lines
        // up under it. (Each shows as one column or more, so no character
        // further than `WINDOW` from the caret can be in the window.)
        let chars: Vec<char> = self.source_line.chars().collect();
        let at = (self.col - 1).min(chars.len());
        let lo = at.saturating_sub(WINDOW);
        let hi = (at + WINDOW).min(chars.len());
        let shown: Vec<String> = chars[lo..hi]
            .iter()
            .map(|&c| match c {
                '\t' => c.to_string(),
                c => printable(c.encode_utf8(&mut [0; 4])).into_owned(),
            })
            .collect();
        let width = |from: usize, to: usize| -> usize {
            shown[from - lo..to - lo]
                .iter()
                .map(|s| s.chars().count())
                .sum()
        };
        // A long line (a polyhedron's points, a machine-written file) is
        // shown as a window of at most `WINDOW` columns around the caret,
        // grown on whichever side of it is narrower.
        let (mut from, mut to) = (at, at);
        loop {
            let right = to < hi && (from == lo || width(at, to) <= width(from, at));
            let (f2, t2) = match (right, from > lo) {
                (true, _) => (from, to + 1),
                (false, true) => (from - 1, to),
                (false, false) => break,
            };
            if width(f2, t2) > WINDOW {
                break;
            }
            (from, to) = (f2, t2);
        }
        let (open, close) = (
            if from > 0 { "…" } else { "" },
            if to < chars.len() { "…" } else { "" },
        );
        writeln!(
            f,
            "{num} | {open}{}{close}",
            shown[from - lo..to - lo].concat()
        )?;
        let lead: String = " ".repeat(open.chars().count())
            + &shown[from - lo..at - lo]
                .iter()
                .map(|s| match s.as_str() {
                    "\t" => s.clone(),
                    s => " ".repeat(s.chars().count()),
                })
                .collect::<String>();
        let under = (at + self.caret_len.max(1)).min(to);
        let carets = "^".repeat(width(at, under).max(1));
        if self.label.is_empty() {
            write!(f, "{pad} | {lead}{carets}")
        } else {
            write!(f, "{pad} | {lead}{carets} {}", printable(&self.label))
        }
    }
}

/// `text` safe to print on a terminal: each control character (an escape
/// sequence's ESC, a bell, a carriage return, a NUL, DEL, C1) and each
/// character that reorders text (Unicode's bidirectional controls) written
/// as an escape (`\x1b`, `\u{202e}`), so a model's bytes never act on the
/// terminal that shows a message quoting them. A newline too: a message
/// of several lines is built with [`printable_lines`].
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    escaped(text, false)
}

/// [`printable`], keeping newlines (a message of several lines, such as
/// OpenSCAD's own words relayed).
pub fn printable_lines(text: &str) -> std::borrow::Cow<'_, str> {
    escaped(text, true)
}

fn escaped(text: &str, newlines: bool) -> std::borrow::Cow<'_, str> {
    let unsafe_char = |c: char| {
        (c.is_control() && !(newlines && c == '\n'))
            || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
    };
    if !text.chars().any(unsafe_char) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if !unsafe_char(c) {
            out.push(c);
        } else if (c as u32) < 0x80 {
            out.push_str(&format!("\\x{:02x}", c as u32));
        } else {
            out.push_str(&format!("\\u{{{:x}}}", c as u32));
        }
    }
    std::borrow::Cow::Owned(out)
}

/// Everything that can go wrong in csgrt.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A problem in a scene or ray file, at a place in it.
    #[error("{0}")]
    Scene(Box<Diagnostic>),
    /// Bad command-line use that clap cannot see (a bad `--size`, say).
    #[error("error: {}", printable_lines(.0))]
    Usage(String),
    /// Reading or writing a file failed.
    #[error("error: {}: {}", printable(&path.display().to_string()), printable(&source.to_string()))]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// Some of several images failed, each already reported; `code` is the
    /// worst of their exit statuses.
    #[error("error: {failed} of {of} images failed (each said why above)")]
    Several { failed: usize, of: usize, code: i32 },
}

impl Error {
    /// The process exit status for this error: 2 for bad input, 1 for I/O.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Scene(_) | Error::Usage(_) => 2,
            Error::Io { .. } => 1,
            Error::Several { code, .. } => *code,
        }
    }

    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Error {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
