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
            Severity::Error => "error",
            Severity::Warning => "warning",
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

/// A named source text, able to turn byte spans into diagnostics.
#[derive(Clone, Debug)]
pub struct Source {
    pub name: String,
    pub text: String,
}

impl Source {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Source {
        Source {
            name: name.into(),
            text: text.into(),
        }
    }

    /// Where a file the model names (an `import`, a `surface`) lies: an
    /// absolute path as it is, a relative one against the model's own
    /// folder, as OpenSCAD resolves them.
    pub fn beside(&self, file: &str) -> std::path::PathBuf {
        let file = std::path::Path::new(file);
        if file.is_absolute() {
            return file.to_path_buf();
        }
        let folder = std::path::Path::new(&self.name)
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        folder.join(file)
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = floor_char_boundary(&self.text, offset.min(self.text.len()));
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let col = self.text[line_start..offset].chars().count() + 1;
        (line, col)
    }

    /// A diagnostic of the given severity pointing at `span`.
    pub fn diagnostic(
        &self,
        severity: Severity,
        span: TextRange,
        message: impl Into<String>,
        label: impl Into<String>,
    ) -> Diagnostic {
        let start = floor_char_boundary(&self.text, span.start.min(self.text.len()));
        let (line, col) = self.line_col(start);
        let line_start = self.text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |i| start + i);
        let source_line = self.text[line_start..line_end].trim_end_matches('\r');
        let end = floor_char_boundary(&self.text, span.end.clamp(start, line_end));
        let caret_len = self.text[start..end].chars().count().max(1);
        Diagnostic {
            severity,
            message: message.into(),
            file: self.name.clone(),
            line,
            col,
            source_line: source_line.to_string(),
            caret_len,
            label: label.into(),
        }
    }

    /// An error pointing at `span`.
    pub fn error(
        &self,
        span: TextRange,
        message: impl Into<String>,
        label: impl Into<String>,
    ) -> Error {
        Error::Scene(Box::new(self.diagnostic(
            Severity::Error,
            span,
            message,
            label,
        )))
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_a_model_names_lie_beside_it() {
        let src = Source::new("parts/bracket.csg", "");
        assert_eq!(
            src.beside("logo.stl"),
            std::path::Path::new("parts/logo.stl")
        );
        assert_eq!(
            src.beside("../m/a.dat"),
            std::path::Path::new("parts/../m/a.dat")
        );
        assert_eq!(src.beside("/abs/a.stl"), std::path::Path::new("/abs/a.stl"));
        assert_eq!(
            Source::new("x.csg", "").beside("a.stl"),
            std::path::Path::new("./a.stl")
        );
    }

    #[test]
    fn diagnostic_points_at_the_span_with_a_caret() {
        let src = Source::new("a.csg", "sphere(1);\ncube(sise = 2);\n");
        let d = src.diagnostic(
            Severity::Error,
            TextRange::new(16, 20),
            "unknown argument `sise` for `cube`",
            "expected one of `size`, `center`",
        );
        assert_eq!(
            d.to_string(),
            "error: unknown argument `sise` for `cube`\n --> a.csg:2:6\n  |\n2 | cube(sise = 2);\n  |      ^^^^ expected one of `size`, `center`"
        );
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_caret() {
        let line = format!(
            "{}sphere(r = x);{}",
            "cube(1); ".repeat(30),
            " cube(2);".repeat(30)
        );
        let src = Source::new("l.csg", line.clone());
        let at = line.find('x').unwrap();
        let d = src.diagnostic(Severity::Error, TextRange::new(at, at + 1), "bad", "here");
        let text = d.to_string();
        let lines: Vec<&str> = text.lines().collect();
        let shown = lines[3].strip_prefix("1 | ").unwrap();
        assert!(shown.starts_with('…') && shown.ends_with('…'), "{shown}");
        assert_eq!(shown.chars().count(), WINDOW + 2);
        let caret = lines[4].strip_prefix("  | ").unwrap();
        let col = caret.find('^').unwrap();
        assert_eq!(
            shown.chars().nth(caret[..col].chars().count()),
            Some('x'),
            "{text}"
        );
    }

    #[test]
    fn line_col_counts_characters_not_bytes() {
        let src = Source::new("u.csg", "// é\nx");
        assert_eq!(src.line_col(6), (2, 1));
        assert_eq!(src.line_col(5), (1, 5));
    }
}
