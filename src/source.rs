//! Model files read into text: the size limit, UTF-8 with the place of the
//! first bad byte, missing files and folders in plain words, and the named
//! [`Source`] that turns byte ranges into file:line:column diagnostics.

use crate::error::{Diagnostic, Error, Result, Severity, TextRange};
use std::path::Path;

/// A named source text, able to turn byte spans into diagnostics.
#[derive(Clone, Debug)]
pub struct Source {
    pub name: String,
    pub text: String,
    /// Where the files the text names are found, when not in the folder
    /// of `name` (OpenSCAD's export of a `.scad` program: the program's).
    pub folder: Option<std::path::PathBuf>,
}

impl Source {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Source {
        Source {
            name: name.into(),
            text: text.into(),
            folder: None,
        }
    }

    /// The source with the files it names found in `folder`.
    pub fn with_folder(mut self, folder: &Path) -> Source {
        self.folder = Some(folder.to_path_buf());
        self
    }

    /// Where a file the model names (an `import`, a `surface`) lies: an
    /// absolute path as it is, a relative one against the model's own
    /// folder (or [`Source::folder`]), as OpenSCAD resolves them.
    pub fn beside(&self, file: &str) -> std::path::PathBuf {
        let file = std::path::Path::new(file);
        if file.is_absolute() {
            return file.to_path_buf();
        }
        let folder = match &self.folder {
            Some(f) => f.as_path(),
            None => std::path::Path::new(&self.name)
                .parent()
                .unwrap_or(std::path::Path::new("")),
        };
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

    /// An error OpenSCAD only warns about ([`Severity::Lenient`]): the
    /// statement it is in renders empty, with it as a warning.
    pub fn lenient(
        &self,
        span: TextRange,
        message: impl Into<String>,
        label: impl Into<String>,
    ) -> Error {
        leniently(self.error(span, message, label))
    }
}

/// `e`, a problem in a file, made one OpenSCAD only warns about
/// ([`Source::lenient`]); any other error as it is.
pub fn leniently(e: Error) -> Error {
    match e {
        Error::Scene(mut d) => {
            d.severity = Severity::Lenient;
            Error::Scene(d)
        }
        e => e,
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// The largest scene or ray file read, checked before reading it. Reading
/// takes about 44 bytes of memory a byte of text at the peak (a people's
/// model of 110 MB, mostly polyhedron points: 4.8 GB, 25 s), so 256 MiB
/// asks for about 11 GiB.
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// Reads a model file into a named source.
pub fn read_source(path: &Path) -> Result<Source> {
    let meta = model_file(path)?;
    if meta.len() > MAX_FILE_BYTES {
        return Err(Error::Usage(format!(
            "{}: the file has {} bytes; the limit is {} MiB",
            path.display(),
            meta.len(),
            MAX_FILE_BYTES >> 20
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| unreadable(path, e))?;
    let name = path.display().to_string();
    match String::from_utf8(bytes) {
        Ok(text) => match text.find('\0') {
            // Text never holds a NUL: this is a binary file.
            Some(at) => Err(Source::new(name, text).error(
                TextRange::new(at, at + 1),
                "byte 0x00 (NUL) in the file: it is not text",
                "expected a model's text (`.csg`, `.ray` or `.scad`), not a binary file",
            )),
            None => Ok(Source::new(name, text)),
        },
        Err(e) => {
            // The place of the first byte that is not UTF-8, in the text
            // as far as it is (the same bytes in its lossy reading).
            let at = e.utf8_error().valid_up_to();
            let byte = e.as_bytes()[at];
            let src = Source::new(name, String::from_utf8_lossy(e.as_bytes()).into_owned());
            Err(src.error(
                TextRange::new(at, at + 1),
                format!("byte 0x{byte:02X} is not UTF-8 text"),
                "expected a file saved as UTF-8 (as OpenSCAD writes it)",
            ))
        }
    }
}

/// The metadata of a model or ray file, or why it is none: missing, not
/// readable or a folder, in plain words (see [`unreadable`]).
pub fn model_file(path: &Path) -> Result<std::fs::Metadata> {
    let meta = std::fs::metadata(path).map_err(|e| unreadable(path, e))?;
    if meta.is_dir() {
        return Err(Error::Usage(format!(
            "{}: is a folder, not a file",
            path.display()
        )));
    }
    Ok(meta)
}

/// A model or ray file that cannot be read, in plain words: missing, a
/// folder, or not readable are the user's to fix (exit 2); anything else
/// is the system's (exit 1).
fn unreadable(path: &Path, e: std::io::Error) -> Error {
    use std::io::ErrorKind;
    let why = match e.kind() {
        ErrorKind::NotFound => "no such file",
        ErrorKind::PermissionDenied => "permission denied: this user may not read it",
        _ => return Error::io(path, e),
    };
    Error::Usage(format!("{}: {why}", path.display()))
}

/// `path`'s extension in lower case, if it has one.
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// Whether `path` names an OpenSCAD program (`.scad`).
pub fn is_scad(path: &Path) -> bool {
    extension(path).as_deref() == Some("scad")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::WINDOW;

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
            std::path::Path::new("a.stl")
        );
        assert_eq!(
            Source::new("/tmp/e/x.csg", "")
                .with_folder(std::path::Path::new("m"))
                .beside("a.stl"),
            std::path::Path::new("m/a.stl")
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
