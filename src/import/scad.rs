//! `.scad` models: OpenSCAD itself exports them to CSG text (`openscad -o
//! x.csg x.scad`, `-D` definitions passed through), which csgrt then reads
//! as any `.csg`. The export is named `x.scad.csg` beside the model, so that
//! files the model names resolve against its folder and a diagnostic's
//! lines are those of `openscad -o x.scad.csg x.scad`; nothing is written
//! there.

use crate::error::{Error, Result};
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

/// The CSG text OpenSCAD exports for the program at `path`.
pub fn export(path: &Path, defines: &[String]) -> Result<Source> {
    export_with(path, defines, false).map(|(src, _)| src)
}

/// [`export`], and with `deps` the files the program read (itself, what it
/// includes and uses, what it imports), from OpenSCAD's `-d` dependency
/// file; empty without.
pub fn export_with(path: &Path, defines: &[String], deps: bool) -> Result<(Source, Vec<PathBuf>)> {
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
    let dir = tempfile::tempdir().map_err(|e| Error::io("<temporary folder>", e))?;
    let out = dir.path().join("export.csg");
    let deps_file = dir.path().join("export.d");
    let mut cmd = std::process::Command::new(&openscad);
    cmd.arg("-o").arg(&out);
    if deps {
        cmd.arg("-d").arg(&deps_file);
    }
    for d in defines {
        cmd.arg("-D").arg(d);
    }
    cmd.arg(path);
    let run = cmd
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(|e| Error::io(&openscad, e))?;
    if !run.status.success() || !out.is_file() {
        let said = String::from_utf8_lossy(&run.stderr);
        return Err(Error::Usage(format!(
            "{}: OpenSCAD could not export it ({}); it said:\n{}",
            path.display(),
            run.status,
            said.trim_end()
        )));
    }
    // OpenSCAD's warnings (its other lines are progress) are passed on.
    for line in String::from_utf8_lossy(&run.stderr).lines() {
        for tag in ["WARNING:", "DEPRECATED:"] {
            if let Some(said) = line.strip_prefix(tag) {
                eprintln!(
                    "warning: {}: OpenSCAD says: {}",
                    path.display(),
                    said.trim()
                );
            }
        }
    }
    let text = crate::source::read_source(&out)?.text;
    let mut name = path.as_os_str().to_owned();
    name.push(".csg");
    let mut files = Vec::new();
    if deps {
        // The program itself, whatever the list says (a missing or
        // unreadable list leaves it alone; a repeat is harmless).
        let said = std::fs::read_to_string(&deps_file).unwrap_or_default();
        files = make_deps(&said);
        files.push(path.to_path_buf());
    }
    Ok((
        Source::new(PathBuf::from(name).display().to_string(), text),
        files,
    ))
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
