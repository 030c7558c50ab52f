//! Any bytes → parse → resolve → a tiny render, the mask, the JSON dump and
//! the POV-Ray export (`csgrt::harness::exercise`). Nothing may panic, hang
//! or overflow the stack; every scene error must carry a place in the file.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| csgrt::harness::exercise(data));
