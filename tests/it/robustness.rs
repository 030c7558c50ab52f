//! Whatever text arrives, parsing and resolving end in a scene or in an
//! error at a place in the file — never in a panic.

use csgrt::error::Error;
use csgrt::{load_csg, Source};
use proptest::prelude::*;
use std::path::Path;

fn corpus() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for dir in ["models", "tests/scenes", "tests/openscad"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().and_then(|x| x.to_str()) == Some("csg") {
                out.push(std::fs::read_to_string(p).unwrap());
            }
        }
    }
    out.sort();
    out
}

/// Ways to damage a text: delete, duplicate, or insert a token at a byte.
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Duplicate(usize, usize),
    Insert(usize, &'static str),
}

const TOKENS: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    ",",
    "=",
    "-",
    "inf",
    "nan",
    "-0",
    "1e308",
    "1e-320",
    "\"",
    "\\",
    "#",
    "%",
    "*",
    "!",
    "$fn",
    "undef",
    "true",
    "cube",
    "sphere(",
    "torus(R = 1, r = 2)",
    "multmatrix([[0,0,0,0],[0,0,0,0],[0,0,0,0],[0,0,0,1]])",
    "scale(0)",
    "rotate(a = 1, v = [0, 0, 0])",
    "camera(eye = [0, 0, 0], lookat = [0, 0, 0])",
    "/*",
    "*/",
    "//",
    "\n",
    "é",
    "\u{0}",
    "9999999999999999999999",
];

fn arb_edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0usize..40).prop_map(|(a, n)| Edit::Delete(a, n)),
        (any::<usize>(), 0usize..40).prop_map(|(a, n)| Edit::Duplicate(a, n)),
        (any::<usize>(), prop::sample::select(TOKENS)).prop_map(|(a, t)| Edit::Insert(a, t)),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut s = text.as_bytes().to_vec();
    for e in edits {
        let at = |a: usize| if s.is_empty() { 0 } else { a % (s.len() + 1) };
        match *e {
            Edit::Delete(a, n) => {
                let a = at(a);
                let b = (a + n).min(s.len());
                s.drain(a..b);
            }
            Edit::Duplicate(a, n) => {
                let a = at(a);
                let b = (a + n).min(s.len());
                let piece = s[a..b].to_vec();
                s.splice(b..b, piece);
            }
            Edit::Insert(a, t) => {
                let a = at(a);
                s.splice(a..a, t.bytes());
            }
        }
    }
    String::from_utf8_lossy(&s).into_owned()
}

fn check(text: &str) -> Result<(), TestCaseError> {
    let src = Source::new("fuzz.csg", text);
    match std::panic::catch_unwind(|| load_csg(&src)) {
        Err(_) => Err(TestCaseError::fail(format!("panic on:\n{text}"))),
        Ok(Ok(_)) => Ok(()),
        Ok(Err(Error::Scene(d))) => {
            prop_assert!(d.line >= 1 && d.col >= 1);
            let place = format!("--> fuzz.csg:{}:{}", d.line, d.col);
            prop_assert!(d.to_string().contains(&place), "no place in {}", d);
            Ok(())
        }
        Ok(Err(e)) => Err(TestCaseError::fail(format!(
            "an error without a place: {e}"
        ))),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8000))]

    #[test]
    fn mutated_models_give_a_scene_or_a_placed_error(pick in any::<prop::sample::Index>(), edits in prop::collection::vec(arb_edit(), 1..6)) {
        let corpus = corpus();
        let text = apply(pick.get(&corpus[..]).as_str(), &edits);
        check(&text)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn random_texts_give_a_scene_or_a_placed_error(text in "[a-z_$(){}\\[\\];,=#%*!\"0-9.e+\\- \n]{0,120}") {
        check(&text)?;
    }
}
