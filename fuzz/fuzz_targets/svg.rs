//! Any bytes as an SVG drawing imported by a scene and rendered small
//! (`csgrt::harness::exercise_svg`): an error at the import, or a picture,
//! never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| csgrt::harness::exercise_svg(data));
