//! Any bytes as a DXF drawing and as a font file
//! (`csgrt::harness::exercise_readers`): the `dxf`, `ttf-parser` and
//! `rustybuzz` paths csgrt uses must never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| csgrt::harness::exercise_readers(data));
