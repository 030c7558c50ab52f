//! Replays the fuzzer's kept corpus (`fuzz/corpus/scene`, minimised) and
//! every input it ever crashed on (`fuzz/regressions`) through the same
//! harness, on stable, in the normal test line.

use std::path::Path;

fn inputs(dir: &str) -> Vec<std::path::PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let mut v: Vec<_> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

fn replay(dir: &str, at_least: usize) {
    let files = inputs(dir);
    assert!(files.len() >= at_least, "{dir}: {} inputs", files.len());
    for f in files {
        let data = std::fs::read(&f).unwrap();
        if std::panic::catch_unwind(|| csgrt::harness::exercise(&data)).is_err() {
            panic!("{} fails the harness", f.display());
        }
    }
}

#[test]
fn the_kept_fuzz_corpus_passes_the_harness() {
    replay("fuzz/corpus/scene", 100);
}

#[test]
fn the_readers_corpus_passes_their_harness() {
    // DXF drawings (whole and cut short) through the drawing and font
    // readers (`fuzz/fuzz_targets/readers.rs`).
    let files = inputs("fuzz/corpus/readers");
    assert!(files.len() >= 3);
    for f in files {
        let data = std::fs::read(&f).unwrap();
        if std::panic::catch_unwind(|| csgrt::harness::exercise_readers(&data)).is_err() {
            panic!("{} fails the readers' harness", f.display());
        }
    }
}

#[test]
fn inputs_that_once_crashed_pass_the_harness() {
    replay("fuzz/regressions", 1);
}

#[test]
fn the_mesh_corpora_pass_the_mesh_harness() {
    // Each mesh reader's corpus (`fuzz/fuzz_targets/mesh_*.rs`): files
    // whole, cut short and malformed.
    for &(dir, ext) in csgrt::harness::MESH_TARGETS {
        let files = inputs(&format!("fuzz/corpus/mesh_{dir}"));
        assert!(!files.is_empty(), "{dir}");
        for f in files {
            let data = std::fs::read(&f).unwrap();
            if std::panic::catch_unwind(|| csgrt::harness::exercise_mesh(ext, &data)).is_err() {
                panic!("{} fails the mesh harness", f.display());
            }
        }
    }
}

#[test]
fn the_svg_corpus_passes_the_svg_harness() {
    // SVG drawings (the test drawings, whole, cut short and with bytes
    // changed) imported and rendered (`fuzz/fuzz_targets/svg.rs`).
    let files = inputs("fuzz/corpus/svg");
    assert!(files.len() >= 3);
    for f in files {
        let data = std::fs::read(&f).unwrap();
        if std::panic::catch_unwind(|| csgrt::harness::exercise_svg(&data)).is_err() {
            panic!("{} fails the SVG harness", f.display());
        }
    }
}
