//! `.scad` models: OpenSCAD itself exports them to CSG text (`openscad -o
//! x.csg x.scad`, `-D` definitions passed through), which csgrt then reads
//! as any `.csg`. The export is named `x.scad.csg` beside the model, so that
//! files the model names resolve against its folder and a diagnostic's
//! lines are those of `openscad -o x.scad.csg x.scad`; nothing is written
//! there.

use crate::error::{Error, Result, Source};
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
    crate::cli::model_file(path)?;
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
    let mut cmd = std::process::Command::new(&openscad);
    cmd.arg("-o").arg(&out);
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
    let text = crate::cli::read_source(&out)?.text;
    let mut name = path.as_os_str().to_owned();
    name.push(".csg");
    Ok(Source::new(PathBuf::from(name).display().to_string(), text))
}
