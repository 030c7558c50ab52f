//! Every limit and bad value ends in its own whole, placed message.

use crate::common;
use crate::common::{csgrt, fails, files, scene};

#[test]
fn a_non_finite_number_where_a_finite_one_belongs() {
    // OpenSCAD makes nothing of a sphere of infinite radius, and warns.
    assert_eq!(
        common::lenient("sphere(r = inf);\ncube();\n", "cube();\n"),
        "error: `r` of `sphere` must be finite\n --> bad.csg:1:12\n  |\n1 | sphere(r = inf);\n  |            ^^^ expected a finite number; this `sphere` is left out, as OpenSCAD leaves it out (an error under --strict)\n"
    );
}

#[test]
fn a_rotation_about_a_zero_axis() {
    assert_eq!(
        fails("rotate(a = 30, v = [0, 0, 0]) cube();\n"),
        "error: the axis of a rotation must not be zero\n --> bad.csg:1:20\n  |\n1 | rotate(a = 30, v = [0, 0, 0]) cube();\n  |                    ^^^^^^^^^ expected a non-zero vector\n"
    );
}

#[test]
fn a_negative_radius() {
    assert_eq!(
        common::lenient("cylinder(h = 2, r = -1);\nsphere();\n", "sphere();\n"),
        "error: `r` of `cylinder` must not be negative\n --> bad.csg:1:21\n  |\n1 | cylinder(h = 2, r = -1);\n  |                     ^^ expected a number ≥ 0; this `cylinder` is left out, as OpenSCAD leaves it out (an error under --strict)\n"
    );
}

#[test]
fn a_negative_index_of_refraction() {
    assert_eq!(
        fails("material(ior = -1.5) sphere();\n"),
        "error: `ior` of `material` must not be negative\n --> bad.csg:1:16\n  |\n1 | material(ior = -1.5) sphere();\n  |                ^^^^ expected a number ≥ 0\n"
    );
}

#[test]
fn a_point_light_without_a_position() {
    assert_eq!(
        fails("point_light([1, 1, 1]);\nsphere();\n"),
        "error: `point_light` needs the argument `position`\n --> bad.csg:1:12\n  |\n1 | point_light([1, 1, 1]);\n  |            ^^^^^^^^^^^ expected `position = …`\n"
    );
}

#[test]
fn a_field_of_view_out_of_range() {
    assert_eq!(
        fails("camera(eye = [5, 0, 0], lookat = [0, 0, 0], fov = 180);\nsphere();\n"),
        "error: the camera's field of view is out of range\n --> bad.csg:1:51\n  |\n1 | camera(eye = [5, 0, 0], lookat = [0, 0, 0], fov = 180);\n  |                                                   ^^^ expected degrees strictly between 0 and 180\n"
    );
}

#[test]
fn the_eye_at_the_look_at_point() {
    assert_eq!(
        fails("camera(eye = [1, 2, 3], lookat = [1, 2, 3]);\nsphere();\n"),
        "error: the camera looks at its own eye\n --> bad.csg:1:34\n  |\n1 | camera(eye = [1, 2, 3], lookat = [1, 2, 3]);\n  |                                  ^^^^^^^^^ expected `lookat` to differ from `eye`\n"
    );
}

#[test]
fn a_string_where_a_vector_belongs() {
    assert_eq!(
        fails("translate(\"up\") cube();\n"),
        "error: `v` of `translate` must be a vector of 2 or 3 numbers\n --> bad.csg:1:11\n  |\n1 | translate(\"up\") cube();\n  |           ^^^^ expected a vector of 2 or 3 numbers, found a string\n"
    );
}

#[test]
fn too_many_samples_threads_or_depth_and_too_big_an_image() {
    let (dir, _) = scene("s.csg", "sphere();\n");
    for (args, needle) in [
        (
            vec!["--spp", "70000"],
            "invalid value '70000' for '--spp <N>': 70000 is not in 1..=65536",
        ),
        (
            vec!["--spp", "0"],
            "invalid value '0' for '--spp <N>': 0 is not in 1..=65536",
        ),
        (
            vec!["--max-depth", "65"],
            "invalid value '65' for '--max-depth <N>': 65 is not in 0..=64",
        ),
        (
            vec!["--threads", "1025"],
            "invalid value '1025' for '--threads <N>': 1025 is not in 0..=1024",
        ),
        (
            vec!["--size", "40000x10"],
            "invalid value '40000x10' for '--size <WxH>': `40000x10`: each side may be at most 32768 pixels",
        ),
        (
            vec!["--size", "20000x20000"],
            "invalid value '20000x20000' for '--size <WxH>': `20000x20000`: at most 100000000 pixels in all",
        ),
        (
            vec!["--size", "0x10"],
            "invalid value '0x10' for '--size <WxH>': `0x10`: width and height must be at least 1",
        ),
    ] {
        let mut a = vec!["s.csg", "-q"];
        a.extend(args.iter());
        let r = csgrt(dir.path(), &a);
        assert_eq!(r.status, 2, "{args:?}: {}", r.stderr);
        assert_eq!(
            r.stderr,
            format!("error: {needle}\n\nFor more information, try '--help'.\n"),
            "{args:?}"
        );
        assert_eq!(files(dir.path()), ["s.csg"], "{args:?}: nothing written");
    }
}

#[test]
fn a_file_over_the_size_limit_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.csg");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(csgrt::source::MAX_FILE_BYTES + 1).unwrap();
    let r = csgrt(dir.path(), &["huge.csg", "-q"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        format!(
            "error: huge.csg: the file has {} bytes; the limit is 256 MiB\n",
            csgrt::source::MAX_FILE_BYTES + 1
        )
    );
    assert_eq!(files(dir.path()), ["huge.csg"]);
}

#[test]
fn a_closed_pipe_on_trace_rays_output_ends_quietly() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let (dir, _) = scene("s.csg", "sphere();\n");
    let rays: String = (0..200_000)
        .map(|i| format!("0 0 -5 0.{} 0 1\n", i % 7))
        .collect();
    let mut child = Command::new(env!("CARGO_BIN_EXE_csgrt"))
        .current_dir(dir.path())
        .args(["s.csg", "--trace-rays", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(rays.as_bytes()).unwrap();
    drop(stdin);
    // Read one line, then close the pipe, as `| head -1` does.
    let mut out = child.stdout.take().unwrap();
    let mut first = [0u8; 8];
    std::io::Read::read_exact(&mut out, &mut first).unwrap();
    drop(out);
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
}

/// A one-line file too deep for the parser: status 2, the message, its
/// place on line 1, a short echo of the line, and nothing written.
fn assert_too_deep_to_parse(name: &str, text: &str) {
    let (dir, _) = scene(name, text);
    let r = csgrt(dir.path(), &[name, "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    let first: Vec<&str> = r.stderr.lines().take(2).collect();
    assert_eq!(first[0], "error: the file nests too deeply to be parsed");
    assert!(
        first[1].starts_with(&format!(" --> {name}:1:")),
        "{}",
        first[1]
    );
    // The echoed line is a window, not megabytes.
    assert!(r.stderr.len() < 600, "{} bytes of message", r.stderr.len());
    assert_eq!(files(dir.path()), [name]);
}

#[test]
fn a_million_nested_braces_end_in_an_error_not_a_stack_overflow() {
    let n = 1_000_000;
    assert_too_deep_to_parse("deep.csg", &("group() {".repeat(n) + &"}".repeat(n)));
}

/// An output in a folder that is not there is the user's to fix: said
/// before the render (exit 2), and no other output is written either.
#[test]
fn an_output_in_a_missing_folder_is_refused_before_anything_is_written() {
    let (dir, _) = scene("s.csg", "sphere();\n");
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "8x6", "-q", "-o", "missing/x.png"],
    );
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert_eq!(r.stderr, "error: missing/x.png: no such folder: missing\n");
    assert_eq!(files(dir.path()), ["s.csg"]);
    for (args, bad) in [
        (
            &["--stats-json", "nodir/s.json", "-o", "t.png"][..],
            "nodir/s.json",
        ),
        (&["-o", "t.png", "--mask", "nodir/m.png"][..], "nodir/m.png"),
        (
            &["-o", "t.png", "--dump-scene", "nodir/d.json"][..],
            "nodir/d.json",
        ),
        (
            &["-o", "t.png", "--export-pov", "nodir/p.pov"][..],
            "nodir/p.pov",
        ),
    ] {
        let r = csgrt(
            dir.path(),
            &[&["s.csg", "--size", "8x6", "-q"][..], args].concat(),
        );
        assert_eq!(r.status, 2, "{args:?}: {}", r.stderr);
        assert_eq!(r.stderr, format!("error: {bad}: no such folder: nodir\n"));
        assert_eq!(files(dir.path()), ["s.csg"], "{args:?}: nothing written");
    }
}

/// `--threads 0` is all the cores, as in most tools: the same image.
#[test]
fn threads_zero_means_every_core() {
    let (dir, _) = scene("s.csg", "sphere();\n");
    for (n, out) in [("0", "a.png"), ("1", "b.png")] {
        let r = csgrt(
            dir.path(),
            &["s.csg", "--size", "40x30", "-q", "--threads", n, "-o", out],
        );
        assert_eq!(r.status, 0, "{}", r.stderr);
    }
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    assert_eq!(read("a.png"), read("b.png"));
}

#[test]
fn a_million_statements_chained_without_braces_end_in_an_error() {
    // The parser reads them (on the CLI's stack); the limit stops them.
    let name = "chain.csg";
    let (dir, _) = scene(name, &("union() ".repeat(1_000_000) + "cube();\n"));
    let r = csgrt(dir.path(), &[name, "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    let col = 8 * csgrt::syntax::MAX_NESTING + 1;
    assert!(
        r.stderr.starts_with(&format!(
            "error: nesting deeper than 4096 levels\n --> {name}:1:{col}\n"
        )),
        "{}",
        r.stderr
    );
    assert!(r.stderr.len() < 600, "{} bytes of message", r.stderr.len());
    assert_eq!(files(dir.path()), [name]);
}

#[test]
fn statements_nest_at_most_4096_deep_with_or_without_braces() {
    assert_eq!(csgrt::syntax::MAX_NESTING, 4096);
    let chained = "translate([1, 0, 0])\n".repeat(4100) + "cube();\n";
    assert_eq!(
        fails(&chained),
        "error: nesting deeper than 4096 levels\n    --> bad.csg:4097:1\n     |\n4097 | translate([1, 0, 0])\n     | ^^^^^^^^^ the limit is reached here\n"
    );
    let braced = "group() {\n".repeat(4100) + &"}\n".repeat(4100);
    assert_eq!(
        fails(&braced),
        "error: nesting deeper than 4096 levels\n    --> bad.csg:4097:1\n     |\n4097 | group() {\n     | ^^^^^ the limit is reached here\n"
    );
    // 4096 levels are fine: read, framed and rendered (a people's model
    // nests 269 deep), with and without braces, and as a chain of
    // differences each level of which the rays walk, alone and as one of
    // a union's eight children (whose hierarchy looks down into it).
    let chain = "difference() {\n".repeat(4093)
        + "cube(10, center = true);\n"
        + &(0..4093)
            .map(|i| {
                format!(
                    "translate([{}, {}, 5]) sphere(0.3);\n}}\n",
                    i % 20 - 10,
                    i / 20 % 20 - 10
                )
            })
            .collect::<String>();
    let wide = "union() {\n".to_string()
        + &chain
        + &(1..8)
            .map(|i| {
                format!(
                    "translate([{}, 0, 0]) rotate([0, 40, 30]) cube([1, 1, 30]);\n",
                    12 * i
                )
            })
            .collect::<String>()
        + "}\n";
    for text in [
        wide,
        "translate([0.001, 0, 0])\n".repeat(4095) + "cube();\n",
        "group() {\n".repeat(4095) + "cube();\n" + &"}\n".repeat(4095),
        "difference() {\n".repeat(4094)
            + "cube(10, center = true);\n"
            + &(0..4094)
                .map(|i| {
                    format!(
                        "translate([{}, {}, 5]) sphere(0.3);\n}}\n",
                        i % 20 - 10,
                        i / 20 % 20 - 10
                    )
                })
                .collect::<String>(),
    ] {
        let (dir, _) = scene("ok.csg", &text);
        let r = csgrt(dir.path(), &["ok.csg", "--size", "8x6", "-q"]);
        assert_eq!(r.status, 0, "{}", r.stderr);
    }
}

#[test]
fn vectors_nest_at_most_4096_deep() {
    let text = "sphere(r =\n".to_string() + &"[\n".repeat(4100) + &"]\n".repeat(4100) + ");\n";
    assert_eq!(
        fails(&text),
        "error: nesting deeper than 4096 levels\n    --> bad.csg:4098:1\n     |\n4098 | [\n     | ^ the limit is reached here\n"
    );
}

#[test]
fn a_stray_closing_brace_at_the_start() {
    assert_eq!(
        fails("}\nsphere();\n"),
        "error: expected a statement or the end of the file, found `}`\n --> bad.csg:1:1\n  |\n1 | }\n  | ^\n"
    );
}

#[test]
fn a_flattened_solid_is_left_out_with_a_warning() {
    let (dir, _) = scene(
        "flat.csg",
        "multmatrix([[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube();\nsphere();\n",
    );
    let r = csgrt(dir.path(), &["flat.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(
        r.stderr,
        "warning: this `cube` is flattened by a singular transform\n --> flat.csg:1:70\n  |\n1 | multmatrix([[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube();\n  |                                                                      ^^^^ it has no volume and is left out, as in OpenSCAD\n"
    );
    assert_eq!(files(dir.path()), ["flat.csg", "flat.png"]);
}

/// Runs `s.csg` into `out` and returns (status, stderr), checking that the
/// folder still holds only what it held.
fn output_fails(out: &str, setup: impl Fn(&std::path::Path)) -> (i32, String) {
    let (status, stderr, _) = output_fails_in(out, setup);
    (status, stderr)
}

/// As [`output_fails`], keeping the folder for a look afterwards.
fn output_fails_in(
    out: &str,
    setup: impl Fn(&std::path::Path),
) -> (i32, String, tempfile::TempDir) {
    let (dir, _) = scene("s.csg", "sphere();\n");
    setup(dir.path());
    let before = files(dir.path());
    let r = csgrt(dir.path(), &["s.csg", "--size", "8x6", "-q", "-o", out]);
    assert_eq!(files(dir.path()), before, "{out}: nothing written");
    (r.status, r.stderr, dir)
}

#[test]
fn outputs_that_cannot_be_written_are_refused_before_the_render() {
    let none = |_: &std::path::Path| {};
    assert_eq!(
        output_fails("s.csg/x.png", none),
        (2, "error: s.csg/x.png: s.csg is not a folder\n".to_string())
    );
    assert_eq!(
        output_fails("sub", |d| std::fs::create_dir(d.join("sub")).unwrap()),
        (2, "error: sub: it is a folder\n".to_string())
    );
}

#[cfg(unix)]
#[test]
fn a_device_or_a_link_to_one_is_never_replaced() {
    let (status, stderr, dir) = output_fails_in("null.png", |d| {
        std::os::unix::fs::symlink("/dev/null", d.join("null.png")).unwrap()
    });
    assert_eq!(status, 2);
    assert_eq!(
        stderr,
        "error: null.png: it exists and is not a regular file; outputs replace regular files only\n"
    );
    // A rename over the link would replace the link (never /dev/null), so
    // what must survive is the link itself, still pointing at the device.
    let link = dir.path().join("null.png");
    let kind = std::fs::symlink_metadata(&link).unwrap().file_type();
    assert!(kind.is_symlink(), "the link was replaced by {kind:?}");
    assert_eq!(
        std::fs::read_link(&link).unwrap(),
        std::path::Path::new("/dev/null")
    );
}

#[cfg(unix)]
#[test]
fn a_folder_that_refuses_new_files_is_a_clear_io_error() {
    use std::os::unix::fs::PermissionsExt;
    // A read-only folder refuses an ordinary user; root may write anywhere
    // on a disk, so for root the folder is /proc, which takes no files.
    let probe = tempfile::tempdir().unwrap();
    let ro = probe.path().join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let is_root = std::fs::write(ro.join("probe"), b"").is_ok();
    if is_root {
        let (status, stderr) = output_fails("/proc/csgrt-test.png", |_| {});
        assert_eq!(status, 1);
        assert_eq!(
            stderr,
            "error: /proc/csgrt-test.png: cannot create a file in /proc: it takes no new files\n"
        );
    } else {
        let (status, stderr) = output_fails("ro/x.png", |d| {
            std::fs::create_dir(d.join("ro")).unwrap();
            std::fs::set_permissions(d.join("ro"), std::fs::Permissions::from_mode(0o555)).unwrap();
        });
        assert_eq!(status, 1);
        assert_eq!(
            stderr,
            "error: ro/x.png: cannot create a file in ro: permission denied\n"
        );
    }
}

#[test]
fn sizes_and_positions_beyond_1e15_are_out_of_range() {
    assert_eq!(
        fails("translate([1e300, 0, 0]) translate([1e300, 0, 0]) cube();\n"),
        "error: this `cube` is out of range\n --> bad.csg:1:51\n  |\n1 | translate([1e300, 0, 0]) translate([1e300, 0, 0]) cube();\n  |                                                   ^^^^ expected sizes and positions within ±1e15\n"
    );
    assert_eq!(
        fails("sphere(r = 2e15);\n"),
        "error: this `sphere` is out of range\n --> bad.csg:1:1\n  |\n1 | sphere(r = 2e15);\n  | ^^^^^^ expected sizes and positions within ±1e15\n"
    );
    // Found by the fuzzer: a display-list sphere whose radius cubed overflows.
    let (dir, _) = scene("big.ray", "sphere 2 -3 1 1e103\n");
    let r = csgrt(dir.path(), &["big.ray", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert_eq!(
        r.stderr,
        "error: this sphere is out of range\n --> big.ray:1:1\n  |\n1 | sphere 2 -3 1 1e103\n  | ^^^^^^^^^^^^^^^^^^^ expected a centre within ±1e15 and a radius from 1e-15 to 1e15\n"
    );
    assert_eq!(files(dir.path()), ["big.ray"]);
    // Just inside the range renders.
    let (dir, _) = scene("ok.csg", "translate([1e14, 0, 0]) sphere(r = 1e14);\n");
    let r = csgrt(dir.path(), &["ok.csg", "--size", "8x6", "-q"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
}

#[test]
fn a_mesh_point_beyond_the_coordinate_limit_is_refused_at_its_statement() {
    // 2^60 is the limit of the mesh hierarchy's f32 arithmetic.
    let err = common::fails(
        "polyhedron(points = [[0, 0, 0], [2e18, 0, 0], [0, 1, 0], [0, 0, 1]], faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);\n",
    );
    assert_eq!(
        err,
        "error: a point of the mesh, [2000000000000000000, 0, 0], lies too far out\n --> bad.csg:1:1\n  |\n1 | polyhedron(points = [[0, 0, 0], [2e18, 0, 0], [0, 1, 0], [0, 0, 1]], faces = [[0, 1, 2], [0, 3, 1], …\n  | ^^^^^^^^^^ expected coordinates within ±1.152921504606847e18\n"
    );
}
