//! Any bytes as a .nef3 mesh (CGAL's Nef complex) (`csgrt::harness::exercise_mesh`): the reader
//! answers a mesh or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| csgrt::harness::exercise_mesh("nef3", data));
