//! The library's layers (docs/ARCHITECTURE.md): every `crate::…` path in
//! `src/` (and every `super::` that climbs to the crate's root) names a
//! module of a lower layer or its own module, and the command line is the
//! binary's alone. Read from the source text, not from the compiler, so
//! that the rule is the one the architecture document states.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The library's top-level modules from the bottom up; a module may use
/// those on earlier lines and its own. `(root)` is `src/lib.rs`'s own
/// items (the API that loads a model by its extension).
const LAYERS: &[&[&str]] = &[
    &["error", "stats", "mutant"],
    &["source"],
    &["math"],
    &["plane"],
    &["geometry"],
    &["csg"],
    &["syntax"],
    &["import"],
    &["scene"],
    &["render"],
    &["export"],
    &["(root)"],
    &["harness"],
];

fn level(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The module path of a file under `src/` (`geometry/mesh.rs` →
/// `[geometry, mesh]`; `lib.rs` → `[]`).
fn module_path(rel: &str) -> Vec<String> {
    let stem = rel.trim_end_matches(".rs");
    let mut parts: Vec<String> = stem.split('/').map(str::to_string).collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    if parts == ["lib"] {
        parts.clear();
    }
    parts
}

/// The text with comments and string literals blanked (a path in a doc
/// comment or a message is not an import).
fn code_only(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            '"' => {
                out.push('"');
                let mut escaped = false;
                for c in chars.by_ref() {
                    if escaped {
                        escaped = false;
                    } else if c == '\\' {
                        escaped = true;
                    } else if c == '"' {
                        break;
                    }
                }
                out.push('"');
            }
            '\'' => {
                // A char literal ('x', '\n', '"') or a lifetime ('a).
                let rest: String = chars.clone().take(4).collect();
                let lit = if let Some(esc) = rest.strip_prefix('\\') {
                    esc.find('\'').map(|i| i + 2)
                } else {
                    rest.char_indices()
                        .nth(1)
                        .filter(|&(_, c)| c == '\'')
                        .map(|(i, _)| i + 1)
                };
                out.push('\'');
                if let Some(n) = lit {
                    for _ in 0..n {
                        chars.next();
                    }
                }
            }
            c => out.push(c),
        }
    }
    out
}

fn ident_at(s: &str) -> Option<&str> {
    let s = s.trim_start();
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    (end > 0).then(|| &s[..end])
}

/// The first names of the paths below the crate's root that `code` uses:
/// `crate::a::…`, each item of `crate::{a, b::c}`, and `super::…` chains
/// that climb from `path` to the root.
fn root_names(code: &str, path: &[String]) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().last();
        rest = &rest[i + "crate::".len()..];
        if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(inner) = rest.strip_prefix('{') {
            let (mut depth, mut item) = (1, String::new());
            for c in inner.chars() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
                if depth == 0 || (depth == 1 && c == ',') {
                    if let Some(n) = ident_at(&item) {
                        out.insert(n.to_string());
                    }
                    item.clear();
                    if depth == 0 {
                        break;
                    }
                } else {
                    item.push(c);
                }
            }
        } else if let Some(n) = ident_at(rest) {
            out.insert(n.to_string());
        }
    }
    let inline = inline_modules(code);
    let mut from = 0;
    while let Some(i) = code[from..].find("super::").map(|i| i + from) {
        let before = code[..i].chars().last();
        let mut climbs = 0;
        let mut at = &code[i..];
        while let Some(r) = at.strip_prefix("super::") {
            climbs += 1;
            at = r;
        }
        from = code.len() - at.len();
        if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        // Inside `mod tests { … }` a `super` climbs to the file's module.
        let depth = path.len() + inline.iter().filter(|r| r.contains(&i)).count();
        if climbs >= depth {
            if let Some(n) = ident_at(at) {
                out.insert(n.to_string());
            }
        }
    }
    out
}

/// The byte ranges of the modules written inline (`mod tests { … }`).
fn inline_modules(code: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(i) = code[from..].find("mod ").map(|i| i + from) {
        from = i + 4;
        if code[..i]
            .chars()
            .last()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            continue;
        }
        let Some(name) = ident_at(&code[from..]) else {
            continue;
        };
        let after = code[from..].trim_start()[name.len()..].trim_start();
        if !after.starts_with('{') {
            continue;
        }
        let open = code.len() - after.len();
        let mut depth = 0;
        for (j, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                out.push(open..open + j);
                break;
            }
        }
    }
    out
}

/// `lib.rs`'s re-exports: an item named at the root → its module.
fn reexports(lib: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for line in lib.lines() {
        let Some(rest) = line.trim().strip_prefix("pub use ") else {
            continue;
        };
        let rest = rest.trim_end_matches(';');
        let Some((module, items)) = rest.split_once("::") else {
            continue;
        };
        for item in items.trim_matches(|c| c == '{' || c == '}').split(',') {
            let item = item.trim();
            let name = item.rsplit("::").next().unwrap_or(item);
            out.insert(name.to_string(), module.to_string());
        }
    }
    out
}

/// Every import of `files` (path under `src/` → text) against the
/// layers, as messages; empty when they all point down.
fn violations(files: &BTreeMap<String, String>) -> Vec<String> {
    let lib = files.get("lib.rs").map(String::as_str).unwrap_or("");
    let reexported = reexports(lib);
    let mut bad = Vec::new();
    for (rel, text) in files {
        if rel == "main.rs" || rel.starts_with("cli/") {
            continue;
        }
        let code = code_only(text);
        if code.contains("mod cli") {
            bad.push(format!(
                "src/{rel}: declares a `cli` module; only main.rs may"
            ));
        }
        let path = module_path(rel);
        let own = path.first().map_or("(root)", String::as_str);
        let Some(own_level) = level(own) else {
            bad.push(format!("src/{rel}: module `{own}` is in no layer"));
            continue;
        };
        for name in root_names(&code, &path) {
            let target = if name == "cli" {
                bad.push(format!("src/{rel}: uses `cli`, which only main.rs may"));
                continue;
            } else if level(&name).is_some() {
                name.clone()
            } else if let Some(m) = reexported.get(&name) {
                m.clone()
            } else {
                "(root)".to_string()
            };
            if target == own {
                continue;
            }
            match level(&target) {
                Some(l) if l < own_level => {}
                Some(_) => bad.push(format!(
                    "src/{rel}: `{own}` uses `{target}` (via `{name}`), which is not below it"
                )),
                None => bad.push(format!("src/{rel}: `{name}` is in no layer")),
            }
        }
    }
    bad
}

fn read_tree(dir: &Path, base: &Path, out: &mut BTreeMap<String, String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            read_tree(&p, base, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            let rel = p
                .strip_prefix(base)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.insert(rel, std::fs::read_to_string(&p).unwrap());
        }
    }
}

#[test]
fn every_import_points_down() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&src, &src, &mut files);
    assert!(files.len() > 50, "read {} files", files.len());
    // Every top-level module of the library is in a layer.
    let lib = &files["lib.rs"];
    for line in code_only(lib).lines() {
        if let Some(name) = line.trim().strip_prefix("pub mod ") {
            let name = name.trim_end_matches(';');
            assert!(level(name).is_some(), "lib.rs: `{name}` is in no layer");
        }
    }
    let bad = violations(&files);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

fn one(rel: &str, text: &str) -> BTreeMap<String, String> {
    let mut files = BTreeMap::new();
    files.insert(
        "lib.rs".to_string(),
        "pub use scene::Scene;\npub use source::Source;\n".to_string(),
    );
    files.insert(rel.to_string(), text.to_string());
    files
}

#[test]
fn an_upward_import_is_caught() {
    // Each of these is an import against the layers, in one of the forms
    // the reader must see through.
    for (rel, text) in [
        ("geometry/sphere.rs", "use crate::scene::Scene;"),
        ("plane/mod.rs", "use crate::{math::poly, geometry::Aabb};"),
        (
            "csg/spans.rs",
            "fn f() -> crate::render::Settings { todo!() }",
        ),
        ("math/poly.rs", "use crate::Scene;"),
        ("syntax/mod.rs", "use super::scene::args::Args;"),
        ("plane/figure.rs", "use super::super::csg::Csg;"),
        (
            "plane/mod.rs",
            "mod tests {\n    use super::super::super::scene;\n}",
        ),
        (
            "import/svg.rs",
            "use crate::{\n    plane::Outlines,\n    scene::Material,\n};",
        ),
        ("scene/mod.rs", "use crate::cli::Cli;"),
        ("render/mod.rs", "mod cli;"),
        ("render/mod.rs", "use crate::load;"),
    ] {
        assert!(
            !violations(&one(rel, text)).is_empty(),
            "not caught: {rel}: {text}"
        );
    }
    // And these point down, or are no imports at all.
    for (rel, text) in [
        (
            "geometry/sphere.rs",
            "use crate::math::robust;\nuse super::solid::Solid;",
        ),
        (
            "scene/mod.rs",
            "use crate::{csg::Csg, geometry::Shape, Source};",
        ),
        (
            "plane/mod.rs",
            "// see crate::scene::Scene\nconst S: &str = \"crate::render\";",
        ),
        (
            "csg/mod.rs",
            "fn f<'a>(x: &'a str) -> char { 'x' } use crate::geometry::Ray;",
        ),
        ("harness.rs", "use crate::{load, Scene};"),
        ("csg/spans.rs", "mod tests {\n    use super::super::Csg;\n}"),
    ] {
        let v = violations(&one(rel, text));
        assert!(v.is_empty(), "{rel}: {text}: {v:?}");
    }
}
