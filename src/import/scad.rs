//! `.scad` models: OpenSCAD itself exports them to CSG text (`openscad -o
//! x.csg x.scad`, `-D` definitions passed through), which csgrt then reads
//! as any `.csg`. The export lies in a temporary folder, removed after the
//! render unless a message points into it (then kept and named); files the
//! model names resolve against the model's own folder. Nothing is written
//! beside the model.

use crate::error::{Error, Result, Severity};
use crate::source::Source;
use std::path::{Path, PathBuf};

/// The program run, looked up on PATH.
pub const OPENSCAD: &str = "openscad";

/// `openscad` on PATH, if there is one.
fn find_openscad() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(OPENSCAD))
        .find(|p| p.is_file())
}

/// The variable whose echo reports the view a program sets (`-D` puts its
/// assignment after the program's own).
const VIEW_ECHO: &str = "__csgrt_view";

/// `$vpt`, `$vpr`, `$vpd` and `$vpf` as OpenSCAD has them when a program
/// sets none: what an echoed value is compared with.
const UNSET_VIEW: [f64; 8] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 500.0, 22.5];

/// The view a program sets with `$vpt`, `$vpr` and `$vpd` (each `None`
/// where it keeps OpenSCAD's value). OpenSCAD uses them for its camera
/// unless `--camera` is given.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScadView {
    pub translate: Option<[f64; 3]>,
    pub rotate: Option<[f64; 3]>,
    pub distance: Option<f64>,
}

/// One frame of OpenSCAD's export: its CSG text (named for messages by
/// where it lies, its imports found beside the program) and the view the
/// program sets in it.
#[derive(Clone, Debug)]
pub struct Frame {
    pub source: Source,
    pub view: Option<ScadView>,
}

/// OpenSCAD's export of a program: its frames (one, or one for each `$t`
/// of `--animate`), the files it read, and the folder holding the export,
/// removed when this is dropped unless [`Export::keep`] keeps it.
pub struct Export {
    pub frames: Vec<Frame>,
    pub deps: Vec<PathBuf>,
    folder: tempfile::TempDir,
}

impl Export {
    /// Keeps the export's folder (for a message that points into it).
    pub fn keep(self) -> PathBuf {
        self.folder.keep()
    }
}

/// The CSG text OpenSCAD exports for the program at `path`.
pub fn export(path: &Path, defines: &[String]) -> Result<Export> {
    export_frames(path, defines, None, false)
}

/// OpenSCAD's export of the program at `path`, with `-D` `defines`: with
/// `frames` N, the N frames of `openscad --animate N` (`$t` = i/N, set as
/// OpenSCAD sets it, before the program's own assignments); with `deps`,
/// the files the program read (itself, what it includes and uses, what it
/// imports), from OpenSCAD's `-d` dependency file.
///
/// OpenSCAD's messages are passed on: those that name a line of a file
/// are placed there (OpenSCAD gives no column); an error that stops the
/// export is the error. `$vp*` are read through an echo that `-D` adds
/// after the program, and `--viewall`, which OpenSCAD turns off with a
/// warning exactly when the program sets one of them.
pub fn export_frames(
    path: &Path,
    defines: &[String],
    frames: Option<u32>,
    deps: bool,
) -> Result<Export> {
    crate::source::model_file(path)?;
    for d in defines {
        if !d
            .split_once('=')
            .is_some_and(|(name, _)| !name.trim().is_empty())
        {
            return Err(Error::Usage(format!(
                "-D {d}: expected NAME=VALUE, as in -D width=20"
            )));
        }
    }
    let Some(openscad) = find_openscad() else {
        return Err(Error::Usage(format!(
            "{}: reading a .scad program needs OpenSCAD, and `{OPENSCAD}` is not on PATH; \
             install it (Debian and Ubuntu: apt-get install -y openscad) or export the model \
             yourself (openscad -o part.csg part.scad) and render the .csg",
            path.display()
        )));
    };
    let folder = tempfile::Builder::new()
        .prefix("csgrt-export-")
        .tempdir()
        .map_err(|e| Error::io("<temporary folder>", e))?;
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let out = folder.path().join(format!("{stem}.csg"));
    let deps_file = folder.path().join(format!("{stem}.d"));
    let mut cmd = std::process::Command::new(&openscad);
    cmd.arg("-o").arg(&out);
    if deps {
        cmd.arg("-d").arg(&deps_file);
    }
    if let Some(n) = frames {
        cmd.arg(format!("--animate={n}"));
    }
    cmd.arg("--viewall");
    for d in defines {
        cmd.arg("-D").arg(d);
    }
    cmd.arg("-D").arg(format!(
        "{VIEW_ECHO}=echo({VIEW_ECHO}=[$vpt,$vpr,$vpd,$vpf]) 0"
    ));
    cmd.arg(path);
    let run = cmd
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(|e| Error::io(&openscad, e))?;
    let said = String::from_utf8_lossy(&run.stderr);
    let files: Vec<PathBuf> = match frames {
        None => vec![out.clone()],
        Some(n) => (0..n)
            .map(|i| folder.path().join(format!("{stem}{i:05}.csg")))
            .collect(),
    };
    let failed = !run.status.success() || !files.iter().all(|f| f.is_file());
    let told = told(path, &said, failed);
    if failed {
        // The first error OpenSCAD placed is the error, after what it
        // said before it; without one, all it said.
        if let Some(i) = told.iter().position(|t| t.stops) {
            let mut told = told;
            for t in &told[..i] {
                eprintln!("{}", t.text);
            }
            let stop = told.swap_remove(i);
            return Err(stop.error.unwrap_or_else(|| {
                Error::Usage(format!("{}: OpenSCAD says: {}", path.display(), stop.said))
            }));
        }
        return Err(Error::Usage(format!(
            "{}: OpenSCAD could not export it ({}); it said:\n{}",
            path.display(),
            run.status,
            said.trim_end()
        )));
    }
    for t in &told {
        eprintln!("{}", t.text);
    }
    let views = said
        .lines()
        .filter_map(|l| l.strip_prefix(&format!("ECHO: {VIEW_ECHO} = ")))
        .map(view_of)
        .collect::<Vec<_>>();
    let sets_view = said.contains("disabled in favor of $vp*");
    let folder_of_model = path.parent().unwrap_or(Path::new(""));
    let mut out_frames = Vec::with_capacity(files.len());
    for (i, f) in files.iter().enumerate() {
        let text = crate::source::read_source(f)?.text;
        let view = if sets_view {
            views.get(i).copied().flatten()
        } else {
            None
        };
        out_frames.push(Frame {
            source: Source::new(f.display().to_string(), text).with_folder(folder_of_model),
            view: view.or(sets_view.then_some(ScadView::default())),
        });
    }
    let mut files = Vec::new();
    if deps {
        // The program itself, whatever the list says (a missing or
        // unreadable list leaves it alone; a repeat is harmless).
        let said = std::fs::read_to_string(&deps_file).unwrap_or_default();
        files = make_deps(&said);
        files.push(path.to_path_buf());
    }
    Ok(Export {
        frames: out_frames,
        deps: files,
        folder,
    })
}

/// The view an echo `[$vpt, $vpr, $vpd, $vpf]` reports: each value that
/// is not OpenSCAD's own when a program sets none. (A program that sets
/// `$vpr` to exactly [0, 0, 0] reads as one that keeps it.)
fn view_of(echo: &str) -> Option<ScadView> {
    let v: Vec<f64> = echo
        .split(['[', ']', ','])
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .map(|p| p.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()?;
    if v.len() != UNSET_VIEW.len() {
        return None;
    }
    let set = |r: std::ops::Range<usize>| v[r.clone()] != UNSET_VIEW[r];
    let three = |i: usize| [v[i], v[i + 1], v[i + 2]];
    Some(ScadView {
        translate: set(0..3).then(|| three(0)),
        rotate: set(3..6).then(|| three(3)),
        distance: (set(6..7) && v[6] > 0.0).then_some(v[6]),
    })
}

/// One thing OpenSCAD said that csgrt passes on: the text to print, and
/// for a message that names a line, the error it is when it stops the
/// export.
struct Told {
    text: String,
    said: String,
    stops: bool,
    error: Option<Error>,
}

/// What OpenSCAD said worth passing on (the program's echoes, OpenSCAD's
/// warnings, errors, traces and deprecations; not its progress, nor
/// csgrt's own echo, nor the viewall
/// notice csgrt's own `--viewall` causes), each placed in the file and
/// line it names when that file can be read. An error stops csgrt only
/// when the export `failed`; after an export that worked (OpenSCAD goes
/// on past a failed `assert` with what it has), it is a warning; a trace is
/// a note.
fn told(path: &Path, said: &str, failed: bool) -> Vec<Told> {
    let mut out = Vec::new();
    for line in said.lines() {
        // The program's own `echo` output, as OpenSCAD prints it (not
        // csgrt's echo of the view).
        if line.starts_with("ECHO: ") && !line.starts_with(&format!("ECHO: {VIEW_ECHO} ")) {
            out.push(Told {
                text: crate::error::printable(line).into_owned(),
                said: line.to_string(),
                stops: false,
                error: None,
            });
            continue;
        }
        let Some((tag, rest)) = ["WARNING:", "DEPRECATED:", "ERROR:", "TRACE:"]
            .iter()
            .find_map(|t| line.strip_prefix(t).map(|r| (*t, r.trim())))
        else {
            continue;
        };
        if rest.contains("disabled in favor of $vp*") {
            continue;
        }
        let stops = failed && tag == "ERROR:";
        let severity = match tag {
            _ if stops => Severity::Error,
            "TRACE:" => Severity::Note,
            _ => Severity::Warning,
        };
        let says = if tag == "ERROR:" && !stops {
            "OpenSCAD reports an error, and renders what it has"
        } else {
            "OpenSCAD says"
        };
        let placed = placed(path, rest, severity, says);
        let text = match &placed {
            Some(e) => e.to_string(),
            None => format!(
                "{}: {}: {says}: {}",
                severity.word(),
                crate::error::printable(&path.display().to_string()),
                crate::error::printable(rest)
            ),
        };
        out.push(Told {
            text,
            said: rest.to_string(),
            stops,
            error: placed,
        });
    }
    out
}

/// OpenSCAD's message `… in file F, line N` as a diagnostic at line N of
/// F (found beside the program, or from the working folder), the whole
/// line under the caret; `None` when it names no line or the file cannot
/// be read.
fn placed(path: &Path, said: &str, severity: Severity, says: &str) -> Option<Error> {
    let (message, place) = said.rsplit_once(" in file ")?;
    let (file, line) = place.rsplit_once(", line ")?;
    let line: usize = line.trim().parse().ok()?;
    let file = file.trim().trim_matches(['"', '\'']);
    let candidates = [
        path.parent().unwrap_or(Path::new(".")).join(file),
        PathBuf::from(file),
    ];
    let found = candidates.iter().find(|p| p.is_file())?;
    let shown = if found.canonicalize().ok()? == path.canonicalize().ok()? {
        path.to_path_buf()
    } else {
        found.clone()
    };
    let src = crate::source::read_source(found).ok()?;
    let src = Source::new(shown.display().to_string(), src.text);
    let start: usize = src
        .text
        .split_inclusive('\n')
        .take(line.checked_sub(1)?)
        .map(str::len)
        .sum();
    let text = src.text.get(start..)?;
    let body = text.split('\n').next().unwrap_or("").trim_end_matches('\r');
    let lead = body.len() - body.trim_start().len();
    let range = crate::error::TextRange::new(start + lead, start + body.trim_end().len());
    Some(Error::Scene(Box::new(src.diagnostic(
        severity,
        range,
        format!("{says}: {message}"),
        "on this line (OpenSCAD gives no column)",
    ))))
}

/// The prerequisites of a Make rule as OpenSCAD writes it (`target: a \
/// b\ c`): backslash-newline continues the line, `\ ` is a space in a
/// name.
pub fn make_deps(text: &str) -> Vec<PathBuf> {
    let joined = text.replace("\\\n", " ").replace("\\\r\n", " ");
    let Some((_, list)) = joined.split_once(": ") else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut chars = list.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&' ') => {
                cur.push(' ');
                chars.next();
            }
            c if c.is_whitespace() => {
                if !cur.is_empty() {
                    out.push(PathBuf::from(std::mem::take(&mut cur)));
                }
            }
            c => cur.push(c),
        }
    }
    if !cur.is_empty() {
        out.push(PathBuf::from(cur));
    }
    out
}

#[cfg(test)]
mod tests {
    /// OpenSCAD 2021.01's `-d` output for a program that includes a file
    /// with a space in its name, verbatim.
    #[test]
    fn make_deps_reads_openscads_list() {
        let said =
            "out.csg: \\\n\t/tmp/dep/other.scad \\\n\t/tmp/dep/lib\\ a.scad \\\n\tmain.scad\n";
        let got = super::make_deps(said);
        let want: Vec<std::path::PathBuf> =
            ["/tmp/dep/other.scad", "/tmp/dep/lib a.scad", "main.scad"]
                .iter()
                .map(Into::into)
                .collect();
        assert_eq!(got, want);
    }
}
