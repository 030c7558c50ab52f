//! The scene written out for other programs: `--dump-scene` JSON
//! ([`dump`], each leaf's fields from `Solid::params`) and POV-Ray scene
//! language ([`pov`], each leaf's object from `Solid::pov`).

pub mod dump;
pub mod pov;
