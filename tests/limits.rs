//! Every limit and bad value ends in its own whole, placed message.

mod common;
use common::{csgrt, fails, files, scene};

#[test]
fn a_non_finite_number_where_a_finite_one_belongs() {
    assert_eq!(
        fails("sphere(r = inf);\n"),
        "error: `r` of `sphere` must be finite\n --> bad.csg:1:12\n  |\n1 | sphere(r = inf);\n  |            ^^^ expected a finite number\n"
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
        fails("cylinder(h = 2, r = -1);\n"),
        "error: `r` of `cylinder` must not be negative\n --> bad.csg:1:21\n  |\n1 | cylinder(h = 2, r = -1);\n  |                     ^^ expected a number ≥ 0\n"
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
            vec!["--threads", "0"],
            "invalid value '0' for '--threads <N>': 0 is not in 1..=1024",
        ),
        (
            vec!["--size", "40000x10"],
            "`40000x10`: each side may be at most 32768 pixels",
        ),
        (
            vec!["--size", "20000x20000"],
            "`20000x20000`: at most 100000000 pixels in all",
        ),
        (
            vec!["--size", "0x10"],
            "`0x10`: width and height must be at least 1",
        ),
    ] {
        let mut a = vec!["s.csg", "-q"];
        a.extend(args.iter());
        let r = csgrt(dir.path(), &a);
        assert_eq!(r.status, 2, "{args:?}: {}", r.stderr);
        assert!(r.stderr.contains(needle), "{args:?}: {}", r.stderr);
        assert_eq!(files(dir.path()), ["s.csg"], "{args:?}: nothing written");
    }
}

#[test]
fn a_file_over_the_size_limit_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.csg");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(csgrt::cli::MAX_FILE_BYTES + 1).unwrap();
    let r = csgrt(dir.path(), &["huge.csg", "-q"]);
    assert_eq!(r.status, 2);
    assert_eq!(
        r.stderr,
        format!(
            "error: huge.csg: the file has {} bytes; the limit is 64 MiB\n",
            csgrt::cli::MAX_FILE_BYTES + 1
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

#[test]
fn a_million_nested_braces_end_in_an_error_not_a_stack_overflow() {
    let n = 1_000_000;
    let text = "group() {".repeat(n) + &"}".repeat(n);
    let (dir, _) = scene("deep.csg", &text);
    let r = csgrt(dir.path(), &["deep.csg", "-q"]);
    assert_eq!(r.status, 2, "{}", r.stderr);
    let first: Vec<&str> = r.stderr.lines().take(2).collect();
    assert_eq!(first[0], "error: the file nests too deeply to be parsed");
    assert!(first[1].starts_with(" --> deep.csg:1:"), "{}", first[1]);
    // The echoed line is a window, not ten megabytes.
    assert!(r.stderr.len() < 600, "{} bytes of message", r.stderr.len());
    assert_eq!(files(dir.path()), ["deep.csg"]);
}

#[test]
fn an_unwritable_output_is_a_clear_io_error() {
    let (dir, _) = scene("s.csg", "sphere();\n");
    let r = csgrt(
        dir.path(),
        &["s.csg", "--size", "8x6", "-q", "-o", "missing/x.png"],
    );
    assert_eq!(r.status, 1, "{}", r.stderr);
    assert_eq!(r.stderr, "error: missing/x.png: no such folder: missing\n");
    assert_eq!(files(dir.path()), ["s.csg"]);
}
