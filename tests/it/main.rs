//! The integration tests, one crate (one link instead of one per file:
//! a minute of CI), a module per file.

mod approximation;
mod batch;
mod bvh;
mod camera;
mod cli;
mod common;
mod csg_properties;
mod default_look;
mod docs;
mod facets;
mod formats;
mod framing;
mod fuzz_corpus;
mod layers;
mod limits;
mod meshes;
mod openscad;
mod plane_hull;
mod plane_offset;
mod plane_sites;
mod plane_sum;
mod primitives;
mod projection;
mod robustness;
mod sampling;
mod self_intersection;
mod skip_work;
mod sphere_image;
mod stability;
mod vertical_text;
mod view;
mod watch;
