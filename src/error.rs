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
        let kind = match self.severity {
            Severity::Error | Severity::Lenient => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        };
        let num = self.line.to_string();
        let pad = " ".repeat(num.len());
        writeln!(f, "{kind}: {}", self.message)?;
        writeln!(f, "{pad}--> {}:{}:{}", self.file, self.line, self.col)?;
        writeln!(f, "{pad} |")?;
        // A long line (a polyhedron's points, a machine-written file) is
        // shown as a window of `WINDOW` characters around the caret.
        let chars: Vec<char> = self.source_line.chars().collect();
        let at = (self.col - 1).min(chars.len());
        let (from, to) = if chars.len() <= WINDOW {
            (0, chars.len())
        } else {
            let from = at.saturating_sub(WINDOW / 2).min(chars.len() - WINDOW);
            (from, from + WINDOW)
        };
        let shown: String = chars[from..to].iter().collect();
        let (open, close) = (
            if from > 0 { "…" } else { "" },
            if to < chars.len() { "…" } else { "" },
        );
        writeln!(f, "{num} | {open}{shown}{close}")?;
        // Tabs in the source line are echoed under the caret so it lines up.
        let lead: String = " ".repeat(open.chars().count())
            + &chars[from..at]
                .iter()
                .map(|&c| if c == '\t' { '\t' } else { ' ' })
                .collect::<String>();
        let carets = "^".repeat(self.caret_len.max(1).min(to.saturating_sub(at).max(1)));
        if self.label.is_empty() {
            write!(f, "{pad} | {lead}{carets}")
        } else {
            write!(f, "{pad} | {lead}{carets} {}", self.label)
        }
    }
}

/// Everything that can go wrong in csgrt.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A problem in a scene or ray file, at a place in it.
    #[error("{0}")]
    Scene(Box<Diagnostic>),
    /// Bad command-line use that clap cannot see (a bad `--size`, say).
    #[error("error: {0}")]
    Usage(String),
    /// Reading or writing a file failed.
    #[error("error: {path}: {source}")]
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
