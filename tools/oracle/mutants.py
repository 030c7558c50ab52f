#!/usr/bin/env python3
"""Deliberately wrong builds of csgrt must fail the oracle and the accuracy
tool; the real build must pass them (that is .ci/run's own oracle line).

The POV-Ray export is read back by tools/oracle/pov_check.py for six of them.

A mutant build (`cargo build --release --features mutants`, its binary
copied to target/mutants/release/csgrt before the real build replaces it:
.ci/run builds it first, so both share their dependencies) carries every
fault of src/mutant.rs, switched on one at a
time by CSGRT_MUTANT=NAME. For each fault this runs the oracle on the
scenes that show it (the oracle's side is computed once a scene and kept),
and the accuracy tool where it applies, OpenSCAD's own suite (tools/oracle/suite.py),
OpenSCAD's own meshes (tools/oracle/openscad_meshes.py), OpenSCAD's own
offsets (tools/oracle/offset_vs_openscad.py) and the certified
approximation's closed forms (tools/oracle/approximation.py) for the faults
they catch,
and requires each to fail. It also
requires the mutant build with no fault switched on to answer exactly as
the real build does on those same scenes and primitives (which the real
build passes: .ci/run's own lines), so a failure means the fault, not the
build.

Usage: mutants.py [--csgrt target/mutants/release/csgrt] [--report FILE]
Exit status 1 unless every mutant is caught.
"""

import argparse
import multiprocessing
import os
import subprocess
import sys

from tools.oracle import oracle  # noqa: E402

from tools import ROOT

# fault -> (scenes for the oracle, the primitives of tools/oracle/accuracy.py that
# must catch it, or none)
MUTANTS = {
    "rotate_ignored": (["models/primitives.csg", "models/csg_ops.csg"], ["cube", "torus"]),
    "normals_inward": (["models/primitives.csg"], ["sphere"]),
    "sphere_small": (["models/seed.ray", "models/mirrors.csg"], ["sphere"]),
    "compose_reversed": (["models/csg_ops.csg"], False),
    "scale_ignored": (["tests/scenes/mirror_scale.csg"], ["cylinder"]),
    "difference_unflipped": (["models/csg_ops.csg"], False),
    "color_ignored": (["models/csg_ops.csg"], False),
    "outer_color_wins": (["tests/scenes/nested_colors.csg"], False),
    "fov_vertical": (["models/csg_ops.csg", "tests/scenes/nested_colors.csg"], False),
    "cylinder_center_ignored": (["models/csg_ops.csg"], False),
    "curves_as_chords": (["tests/openscad/text.csg"], ["glyph", "cubic"]),
    "kerning_ignored": (["tests/openscad/text.csg"], False),
    "twist_reversed": (["tests/openscad/twist.csg"], ["twisted"]),
    "section_unflattened": (["tests/openscad/projection_cut.csg"], False),
    "resize_auto_ignored": (["tests/openscad/resize.csg"], False),
    "ellipse_turned_back": (["tests/openscad/twisted_circles.csg"], ["twisted_ellipse"]),
    "svg_arcs_as_chords": (["tests/openscad/svg.csg"], False),
    "hull_gjk_normals": ([], ["hull_spheres", "rounded_box"]),
    # (caught by pov_check.py alone: POV below)
    "pov_clearance_wide": ([], False),
    "pov_shadows_kept": ([], False),
    "srgb_skipped": (["tests/scenes/cube_on_plate.csg"], False),
    "fill_shadowed": (["tests/scenes/cube_on_plate.csg"], False),
    "minkowski_moved_twice": (["tests/openscad/minkowski.csg"], False),
    "offset_one_side": (["tests/openscad/offset_text.csg"], ["offset_glyph"]),
    "hull_arc_caps_dropped": (["tests/openscad/hull_arcs.csg"], False),
    "outline_first_loop_only": (["tests/openscad/offsets.csg"], False),
    "offset_arcs_unswept": (["tests/openscad/offset_circles.csg"], False),
    "framing_loose": (["tests/scenes/ring_sector.csg"], False),
    "polytope_part_dropped": (["tests/openscad/hull_polytopes.csg"], ["hull_points"]),
    "convex_slab_shrunk": (["tests/openscad/hull.csg"], ["hull_spheres_support"]),
    "coaxial_axis_dropped": (["tests/openscad/hull_coaxial.csg"], False),
    "twist_reach_shrunk": (["tests/openscad/twist.csg"], False),
    "twist_discs_unturned": (["tests/openscad/twist.csg"], ["twisted"]),
    "pieces_last_dropped": (["tests/openscad/candleStand.csg", "models/nameplate.csg"], False),
    "merge_empty_kept": (["models/csg_ops.csg"], False),
    "trig_roots_early": (["tests/openscad/twisted_circles.csg"], ["twisted"]),
    "twist_far_point_untwisted": (["tests/openscad/twist.csg"], False),
    "disc_push_short": (["tests/openscad/hull_discs.csg"], ["lofted_plate"]),
    "disc_hull_frustum_thin": (["tests/openscad/hull_cones.csg"], ["chamfered_plate"]),
    "ball_chain_untangent": (["tests/openscad/hull.csg", "bench/capsule_hull.csg"], ["hull_spheres"]),
    "distribute_cut_dropped": (["models/bracket.csg", "tests/openscad/candleStand.csg"], False),
    "rounded_lathe_torus_thin": (["tests/openscad/rounded_lathes.csg"], False),
}

# fault -> the files of OpenSCAD's own suite (tools/oracle/suite.py --only)
# that must then fail it.
SUITE = {
    "dxf_ellipses_dropped": "dxf/ellipse",
    "dxf_union_fill": "dxf/circle-small,dxf/polygon-holes-touch",
    "framing_loose": "2D/issues/issue666_2D,misc/internal-cavity.csg",
    "dimensions_mixed": "3D/features/2d-3d,2D/features/difference-2d-tests",
    "lenient_refused": "3D/features/primitive-inf-tests,stl/stl-import-unparseable",
    "svg_stroke_chords": "svg/svg-spec/spec-paths-quad01,svg/svg-spec/spec-paths-arcs01",
}

# fault -> scenes of tools/oracle/openscad_meshes.py (OpenSCAD's own meshes)
# that must then fail it.
MESHES = {
    "dxf_fine_grid": "dxf_gaps",
    "spindle_lemon_kept": "turned_across_axis",
    "ring_unslanted": "turned_slanted_ellipses",
    "nef3_holes_dropped": "nef3_import",
    "pieces_uncut": "approximated",
    "climb_once": "approximated_sections",
    "twist_pieces_reversed": "approximated_twisted",
    "mesh_hulled": "approximated_polyhedra",
    "svg_nested_popped": "nested_svg",
    "section_uncut": "approximated_sections",
    "crossing_half_stroked": "offset_self_touching",
    "off_w_ignored": "off_headers",
    "sites_xor_united": "drawing_touching",
    "shadow_upright_alone": "approximated_shadow_met",
    "trapezoids_top_dropped": "approximated_shadow_met",
}

# fault -> arguments of tools/oracle/approximation.py (the certified
# approximation against closed forms) that must then fail it.
APPROXIMATION = {
    "facets_coarse": (),
    "pieces_uncut": (),
    "flat_coarse": (),
    "turn_wedges_coarse": (),
    "hull_parts_coarse": (),
}

# fault -> seeds of tools/oracle/offset_vs_openscad.py (OpenSCAD's own
# offsets) that must then fail.
OFFSETS = {
    "offset_miter_squared": ("5", "1"),
    "sum_circle_dropped": ("18", "1", "--kind", "sum"),
    "offset_wedge_widest": ("1", "1", "--kind", "flat"),
    "sum_edges_skipped": ("9", "1", "--kind", "sum2"),
}

# fault -> a scene tools/oracle/pov_check.py must then reject (the export is read
# back and compared with the file).
POV = {
    "rotate_ignored": "models/primitives.csg",
    "sphere_small": "models/seed.ray",
    "color_ignored": "models/csg_ops.csg",
    "compose_reversed": "models/csg_ops.csg",
    "pov_clearance_wide": "models/csg_ops.csg",
    "pov_shadows_kept": "tests/scenes/cube_on_plate.csg",
}

SIZE, SEGMENTS, RAYS = (160, 120), [64, 128, 256, 512], 400  # as .ci/run's oracle line


def oracle_problems(binary, scene, fault):
    env = dict(os.environ, CSGRT_MUTANT=fault)
    rows, bad = oracle.check_scene(os.path.join(ROOT, scene), [binary], *SIZE, SEGMENTS, RAYS, env=env, first_fault=True)
    return bad


def tool_fails(fault, script, *args):
    """(whether tools/SCRIPT failed with the fault on, a line that says why)."""
    env = dict(os.environ, CSGRT_MUTANT=fault)
    r = subprocess.run(
        [sys.executable, "-m", "tools.oracle." + script.removesuffix(".py"), *args], env=env, capture_output=True, text=True, cwd=ROOT
    )
    lines = [x for x in r.stdout.splitlines() + r.stderr.splitlines() if x.strip()]
    return r.returncode != 0, lines


def accuracy_fails(binary, fault, kinds):
    failed, lines = tool_fails(fault, "accuracy.py", "--csgrt", binary, "--check", "--first-failure", "--kinds", ",".join(kinds))
    return failed, lines[-1] if lines else ""


def pov_fails(binary, scene, fault):
    failed, lines = tool_fails(fault, "pov_check.py", "--csgrt", binary, os.path.join(ROOT, scene))
    return failed, lines[0] if lines else ""


def openscad_checks(fault):
    """The checks by OpenSCAD itself (and by closed forms, for the
    approximation) that must fail with `fault` on: (tool, its arguments)
    from SUITE, MESHES, OFFSETS and APPROXIMATION."""
    out = []
    if fault in SUITE:
        out.append(("suite", ["--only", SUITE[fault]]))
    if fault in MESHES:
        out.append(("openscad_meshes", ["--only", MESHES[fault]]))
    if fault in OFFSETS:
        out.append(("offset_vs_openscad", list(OFFSETS[fault])))
    if fault in APPROXIMATION:
        out.append(("approximation", list(APPROXIMATION[fault])))
    return out


def check_fault(job):
    """(table rows, what escaped) for one fault."""
    binary, fault = job
    rows, escaped = [], []
    scenes, acc = MUTANTS.get(fault, ([], False))
    for scene in scenes:
        bad = oracle_problems(binary, scene, fault)
        rows.append(f"| {fault} | oracle {scene} | {bad[0] if bad else 'NOT CAUGHT'} |")
        if not bad:
            escaped.append(f"{fault} passes the oracle on {scene}")
    if fault in POV:
        failed, first = pov_fails(binary, POV[fault], fault)
        rows.append(f"| {fault} | pov_check.py {POV[fault]} | {first if failed else 'NOT CAUGHT'} |")
        if not failed:
            escaped.append(f"{fault} passes tools/oracle/pov_check.py")
    for tool, args in openscad_checks(fault):
        failed, lines = tool_fails(fault, tool, *args, "--csgrt", binary)
        first = next((x for x in lines if x.lower().startswith("fail") or "MISMATCH" in x or "REFUSED" in x), lines[-1] if lines else "")
        rows.append(f"| {fault} | {tool}.py {' '.join(args)} | {first[:160] if failed else 'NOT CAUGHT'} |")
        if not failed:
            escaped.append(f"{fault} passes tools/oracle/{tool}.py")
    if acc:
        failed, last = accuracy_fails(binary, fault, acc)
        rows.append(f"| {fault} | accuracy.py | {last if failed else 'NOT CAUGHT'} |")
        if not failed:
            escaped.append(f"{fault} passes tools/oracle/accuracy.py")
    return rows, escaped


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csgrt", default=os.path.join(ROOT, "target/mutants/release/csgrt"))
    ap.add_argument("--real", default=os.path.join(ROOT, "target/release/csgrt"), help="the real build it must equal with no fault on")
    ap.add_argument("--only", default=None, help="comma-separated faults")
    ap.add_argument("--report", default=None, help="write the table (Markdown) here")
    a = ap.parse_args()
    binary = os.path.abspath(a.csgrt)
    faults = a.only.split(",") if a.only else list(dict.fromkeys([*MUTANTS, *SUITE, *MESHES, *OFFSETS, *APPROXIMATION]))
    lines = ["| mutant | scene or tool | caught by |", "|---|---|---|"]
    escaped = []
    # The build itself, no fault on, must answer as the real build does to
    # the byte, on everything the oracle and the accuracy tool read of it;
    # the real build passes both (.ci/run's own lines), so a failure below
    # is the fault's, not the build's.
    kinds = sorted({k for f in faults for k in (MUTANTS.get(f, ([], False))[1] or [])})
    failed, said = tool_fails("", "accuracy.py", "--csgrt", binary, "--same-as", a.real, "--check", "--kinds", ",".join(kinds))
    if failed:
        escaped.append(f"the mutant build with no fault answers otherwise than the real one in tools/oracle/accuracy.py: {said[-1] if said else ''}")
    for scene in sorted({s for f in faults for s in MUTANTS.get(f, ([], False))[0]}):
        bad = oracle.same_outputs(os.path.join(ROOT, scene), [binary], [a.real], *SIZE, RAYS, env=dict(os.environ, CSGRT_MUTANT=""))
        if bad:
            escaped.append(f"the mutant build with no fault answers otherwise than the real one on {scene}: {bad[0]}")
    for tool, args in sorted({(t, tuple(x)) for f in faults for t, x in openscad_checks(f)}):
        failed, said = tool_fails("", tool, *args, "--csgrt", binary)
        if failed:
            escaped.append(f"the mutant build with no fault fails tools/oracle/{tool}.py {' '.join(args)}: {said[-1] if said else ''}")
    # The faults checked two (or as many as there are cores) at once, each
    # worker keeping the oracle's side of the scenes it has met.
    with multiprocessing.Pool(os.cpu_count() or 1) as pool:
        for rows, missed in pool.imap(check_fault, [(binary, f) for f in faults]):
            for r in rows:
                lines.append(r)
                print(r, flush=True)
            escaped += missed
    if a.report:
        head = [
            "# Deliberately wrong builds, and what catches each",
            "",
            "Generated by `cargo build --release --features mutants && cp target/release/csgrt target/mutants/release/ &&",
            "  .venv/bin/python -m tools.oracle.mutants --report docs/mutants.md`. Each row: one fault of",
            "src/mutant.rs switched on, a check run on it, and the first reason that check gave for",
            "failing it (every one must fail; the same build with no fault passes them all).",
            "",
        ]
        with open(a.report, "w") as f:
            f.write("\n".join(head + lines) + "\n")
    for e in escaped:
        print(f"FAIL: {e}", file=sys.stderr)
    caught = sum(1 for f in faults if not any(e.startswith(f + " ") for e in escaped))
    print(f"{caught} passed, {len(faults) - caught} failed")
    sys.exit(1 if escaped else 0)


if __name__ == "__main__":
    main()
