//! Deliberately wrong builds, so that the oracle and the accuracy tool can
//! show that they catch real faults (`tools/oracle/mutants.py`, run by `.ci/run`).
//!
//! Only a build with `--features mutants` has them; there
//! `CSGRT_MUTANT=NAME` switches on the one fault NAME (see [`NAMES`]). In a
//! normal build [`active`] is the constant `false` and every hook compiles
//! away.

/// The faults a mutant build can carry, each a place in the code.
pub const NAMES: &[&str] = &[
    "rotate_ignored",
    "normals_inward",
    "sphere_small",
    "compose_reversed",
    "scale_ignored",
    "difference_unflipped",
    "color_ignored",
    "outer_color_wins",
    "fov_vertical",
    "cylinder_center_ignored",
    "curves_as_chords",
    "kerning_ignored",
    "twist_reversed",
    "dxf_ellipses_dropped",
    "dxf_fine_grid",
    "dxf_union_fill",
    "framing_loose",
    "dimensions_mixed",
    "offset_miter_squared",
    "sum_circle_dropped",
    "section_unflattened",
    "resize_auto_ignored",
    "ellipse_turned_back",
    "svg_arcs_as_chords",
    "hull_gjk_normals",
    "minkowski_moved_twice",
    "offset_one_side",
    "hull_arc_caps_dropped",
    "outline_first_loop_only",
    "offset_arcs_unswept",
    "pieces_uncut",
    "facets_coarse",
    "climb_once",
    "lenient_refused",
    "spindle_lemon_kept",
    "svg_stroke_chords",
    "ring_unslanted",
    "nef3_holes_dropped",
    "flat_coarse",
    "offset_wedge_widest",
    "sum_edges_skipped",
    "turn_wedges_coarse",
    "twist_pieces_reversed",
    "mesh_hulled",
    "svg_nested_popped",
    "section_uncut",
    "crossing_half_stroked",
    "off_w_ignored",
    "sites_xor_united",
    "shadow_upright_alone",
    "trapezoids_top_dropped",
    "polytope_part_dropped",
    "convex_slab_shrunk",
    "coaxial_axis_dropped",
    "twist_reach_shrunk",
    "twist_discs_unturned",
    "pieces_last_dropped",
    "merge_empty_kept",
    "trig_roots_early",
    "twist_far_point_untwisted",
    "disc_push_short",
    "disc_hull_frustum_thin",
    "ball_chain_untangent",
    "distribute_cut_dropped",
    "rounded_lathe_torus_thin",
    "hull_parts_coarse",
    "pov_clearance_wide",
    "srgb_skipped",
    "fill_shadowed",
    "pov_shadows_kept",
];

/// Whether the fault `name` is switched on.
#[cfg(feature = "mutants")]
pub fn active(name: &str) -> bool {
    use std::sync::OnceLock;
    static CHOSEN: OnceLock<String> = OnceLock::new();
    debug_assert!(NAMES.contains(&name), "unknown mutant {name}");
    CHOSEN.get_or_init(|| std::env::var("CSGRT_MUTANT").unwrap_or_default()) == name
}

/// Whether the fault `name` is switched on: never, in a normal build.
#[cfg(not(feature = "mutants"))]
#[inline(always)]
pub fn active(_name: &str) -> bool {
    false
}
