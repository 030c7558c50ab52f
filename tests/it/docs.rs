//! The README stands alone: every file it (or docs/) links to or names by
//! a repository path is in the repository, and nothing points outside it.

use std::path::Path;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Relative paths named in `text`: Markdown link targets, and code spans
/// that start with one of the repository's top folders.
fn named_paths(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (i, _) in text.match_indices("](") {
        let rest = &text[i + 2..];
        if let Some(end) = rest.find(')') {
            let target = rest[..end].split('#').next().unwrap_or("");
            if !target.is_empty() && !target.contains("://") {
                out.push(target.to_string());
            }
        }
    }
    for span in text.split('`').skip(1).step_by(2) {
        let first = span.split_whitespace().next().unwrap_or("");
        let tops = [
            "docs/", "tools/", "models/", "tests/", "src/", "grammar/", "bench/", "../",
        ];
        if tops.iter().any(|t| first.starts_with(t))
            && !first.contains(['*', '{', '<', '$'])
            && !first.ends_with('/')
        {
            out.push(first.trim_end_matches([',', '.', ';', ':']).to_string());
        }
    }
    out
}

#[test]
fn the_readme_and_docs_name_only_files_that_are_here() {
    let mut docs = vec![repo().join("README.md")];
    for e in std::fs::read_dir(repo().join("docs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "md") {
            docs.push(p);
        }
    }
    let mut missing = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(doc).unwrap();
        let base = if doc.ends_with("README.md") {
            repo().to_path_buf()
        } else {
            doc.parent().unwrap().to_path_buf()
        };
        for p in named_paths(&text) {
            let outside = p.starts_with("../") && !base.join(&p).starts_with(repo());
            // Code spans name paths from the repository root; links from
            // the document's folder.
            let here = repo().join(&p).exists() || base.join(&p).exists();
            if outside || !here {
                missing.push(format!("{}: {p}", doc.display()));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "named but not in the repository:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_readme_gives_the_language_and_command_line_reference() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    for doc in ["docs/LANGUAGE.md", "docs/CLI.md"] {
        assert!(readme.contains(doc), "README does not point to {doc}");
        assert!(repo().join(doc).is_file());
    }
    for licence in ["LICENSE-MIT", "LICENSE-APACHE"] {
        assert!(repo().join(licence).is_file(), "{licence}");
    }
}
