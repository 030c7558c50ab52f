//! Several images in one run: several models (beside each model or into
//! `-O DIR`) and `--animate N` frames of a `.scad` model. Each image must be
//! byte for byte the one a run of that model alone writes.

use crate::common;
use crate::common::csgrt;
use std::path::Path;

const CUBE: &str = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\ncube(2, center = true);\n";
const BALL: &str = "camera(eye = [3, -6, 2], lookat = [0, 0, 0]);\nsphere(1.2);\n";

fn read(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Renders `text` alone as `name` in a fresh folder and returns its PNG.
fn alone(name: &str, text: &str) -> Vec<u8> {
    let (dir, _) = common::scene(name, text);
    let r = csgrt(dir.path(), &[name, "--size", "40x30", "-q", "-o", "x.png"]);
    assert_eq!(r.status, 0, "{}", r.stderr);
    read(dir.path(), "x.png")
}

#[test]
fn several_models_into_a_folder() {
    let (dir, _) = common::scene("cube.csg", CUBE);
    std::fs::create_dir(dir.path().join("more")).unwrap();
    std::fs::write(dir.path().join("more/ball.csg"), BALL).unwrap();
    let r = csgrt(
        dir.path(),
        &[
            "cube.csg",
            "more/ball.csg",
            "-O",
            "thumbs/new",
            "--size",
            "40x30",
            "-q",
        ],
    );
    assert_eq!((r.status, r.stderr.as_str()), (0, ""));
    assert_eq!(
        common::files(&dir.path().join("thumbs/new")),
        ["ball.png", "cube.png"]
    );
    assert_eq!(
        read(dir.path(), "thumbs/new/cube.png"),
        alone("a.csg", CUBE)
    );
    assert_eq!(
        read(dir.path(), "thumbs/new/ball.png"),
        alone("a.csg", BALL)
    );
    // Without -O, each image goes beside its model.
    let r = csgrt(
        dir.path(),
        &["cube.csg", "more/ball.csg", "--size", "40x30", "-q"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    assert_eq!(read(dir.path(), "more/ball.png"), alone("a.csg", BALL));
    assert_eq!(read(dir.path(), "cube.png"), alone("a.csg", CUBE));
}

#[test]
fn a_bad_model_among_several_fails_alone() {
    let (dir, _) = common::scene("cube.csg", CUBE);
    std::fs::write(dir.path().join("bad.csg"), "cube(1;\n").unwrap();
    std::fs::write(dir.path().join("ball.csg"), BALL).unwrap();
    let r = csgrt(
        dir.path(),
        &[
            "cube.csg",
            "bad.csg",
            "ball.csg",
            "missing.csg",
            "-O",
            "out",
            "--size",
            "40x30",
            "-q",
        ],
    );
    assert_eq!(r.status, 2, "{}", r.stderr);
    assert!(r.stderr.contains("bad.csg:1:"), "{}", r.stderr);
    assert!(
        r.stderr.contains("missing.csg: no such file"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("2 of 4 images failed"), "{}", r.stderr);
    assert_eq!(
        common::files(&dir.path().join("out")),
        ["ball.png", "cube.png"]
    );
}

#[test]
fn several_models_refuse_single_file_options_and_clashing_names() {
    let (dir, _) = common::scene("a.csg", CUBE);
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/a.csg"), BALL).unwrap();
    std::fs::write(dir.path().join("b.csg"), BALL).unwrap();
    std::fs::write(dir.path().join("file"), "x").unwrap();
    for (args, says) in [
        (&["a.csg", "b.csg", "-o", "x.png"][..], "use -O DIR"),
        (
            &["a.csg", "b.csg", "--mask", "m.png"],
            "--mask writes one file",
        ),
        (
            &["a.csg", "b.csg", "--stats-json", "s.json"],
            "--stats-json writes one file",
        ),
        (
            &["a.csg", "sub/a.csg", "-O", "out"],
            "would both be written to out/a.png",
        ),
        (&["a.csg", "b.csg", "-O", "file"], "is a file, not a folder"),
        (
            &["a.csg", "-o", "x.png", "-O", "out"],
            "cannot be used with",
        ),
    ] {
        common::refused(dir.path(), args, says, &["a.csg", "b.csg", "file", "sub"]);
    }
}

/// A stand-in for `openscad -o DIR/NAME.csg ... --animate=N ...` that
/// records its arguments and writes frame i as `DIR/NAME0000i.csg`: the
/// CSG `body` prints with `$1` = i/N (six decimals), `$2` = i, `$3` = N
/// (shell builtins only: PATH holds nothing else).
#[cfg(unix)]
fn fake_animating_openscad(body: &str) -> tempfile::TempDir {
    common::fake_openscad(&format!(
        r#"n=1
for a in "$@"; do case "$a" in --animate=*) n="${{a#--animate=}}";; esac; done
echo "$@" >> "${{0%/*}}/calls.txt"
base="${{2%.csg}}"
i=0
while [ $i -lt $n ]; do
  t="$((i / n)).$(printf %06d $(( (i * 1000000 / n) % 1000000 )))"
  frame() {{
{body}
  }}
  frame "$t" "$i" "$n" > "$base$(printf %05d $i).csg"
  i=$((i + 1))
done"#
    ))
}

/// `--animate N` runs OpenSCAD once, as `openscad --animate=N` (which sets
/// `$t` before the program's own assignments; a stand-in here that moves a
/// ball by `$t`), and frame i is the image of OpenSCAD's frame i, named as
/// OpenSCAD names frames.
#[cfg(unix)]
#[test]
fn animate_renders_openscads_frames() {
    let (dir, _) = common::scene("spin.scad", "translate([$t, 0, 0]) sphere(1);\n");
    let bin = fake_animating_openscad(
        r#"printf 'camera(eye = [0, -5, 0], lookat = [0, 0, 0]);\nmultmatrix([[1, 0, 0, %s], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(1);\n' "$1""#,
    );
    let (status, said) = common::csgrt_with_path(
        dir.path(),
        bin.path(),
        &[
            "spin.scad",
            "--animate",
            "4",
            "-D",
            "k=1",
            "--size",
            "40x30",
            "-q",
            "-o",
            "f.png",
        ],
    );
    assert_eq!((status, said.as_str()), (0, ""));
    assert_eq!(
        common::files(dir.path()),
        [
            "f00000.png",
            "f00001.png",
            "f00002.png",
            "f00003.png",
            "spin.scad"
        ]
    );
    // One run of OpenSCAD for all the frames, the user's -D first.
    let calls = std::fs::read_to_string(bin.path().join("calls.txt")).unwrap();
    assert_eq!(calls.lines().count(), 1, "{calls}");
    assert!(calls.contains("--animate=4"), "{calls}");
    assert!(!calls.contains("$t="), "{calls}");
    let k = calls.find("-D k=1").expect("the user's -D");
    assert!(k < calls.find("-D __csgrt_view").unwrap(), "{calls}");
    let mut frames = Vec::new();
    for i in 0..4 {
        let x = format!("{:.6}", i as f64 / 4.0);
        let want = alone(
            "a.csg",
            &format!("camera(eye = [0, -5, 0], lookat = [0, 0, 0]);\nmultmatrix([[1, 0, 0, {x}], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(1);\n"),
        );
        let got = read(dir.path(), &format!("f{i:05}.png"));
        assert_eq!(got, want, "frame {i}");
        frames.push(got);
    }
    assert!(frames.windows(2).all(|w| w[0] != w[1]), "the ball moves");
    // Without -o, the frames go beside the model; -O puts them in a folder.
    let (status, said) = common::csgrt_with_path(
        dir.path(),
        bin.path(),
        &[
            "spin.scad",
            "--animate",
            "2",
            "--size",
            "40x30",
            "-q",
            "-O",
            "frames",
        ],
    );
    assert_eq!((status, said.as_str()), (0, ""));
    assert_eq!(
        common::files(&dir.path().join("frames")),
        ["spin00000.png", "spin00001.png"]
    );
}

/// The frames of an animation share one camera, framing the box of them
/// all: a cube that stands still while a ball moves away stays where it
/// is, pixel for pixel, in every frame (framed anew, it would shrink).
#[cfg(unix)]
#[test]
fn animate_keeps_one_camera_for_all_frames() {
    let (dir, _) = common::scene(
        "slide.scad",
        "cube(10); translate([40*$t, 0, 0]) sphere(3);\n",
    );
    let bin = fake_animating_openscad(
        r#"printf 'cube(size = [10, 10, 10], center = false);\nmultmatrix([[1, 0, 0, %s], [0, 1, 0, -8], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(r = 3);\n' "$((40 * $2 / $3))""#,
    );
    let (status, said) = common::csgrt_with_path(
        dir.path(),
        bin.path(),
        &["slide.scad", "--animate", "4", "--size", "80x60", "-q"],
    );
    assert_eq!((status, said.as_str()), (0, ""));
    let frame = |i: usize| {
        image::open(dir.path().join(format!("slide{i:05}.png")))
            .unwrap()
            .to_rgb8()
    };
    // The cube alone, under the camera the four frames share: the frames'
    // box is the cube's and the balls' (at x = 0 and x = 30).
    let (cube_dir, _) = common::scene(
        "cube.csg",
        "cube(size = [10, 10, 10], center = false);\n\
         multmatrix([[1, 0, 0, 0], [0, 1, 0, -8], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(r = 3);\n\
         multmatrix([[1, 0, 0, 30], [0, 1, 0, -8], [0, 0, 1, 0], [0, 0, 0, 1]]) sphere(r = 3);\n",
    );
    let r = csgrt(
        cube_dir.path(),
        &["cube.csg", "--size", "80x60", "-q", "-o", "c.png"],
    );
    assert_eq!(r.status, 0, "{}", r.stderr);
    let both = image::open(cube_dir.path().join("c.png"))
        .unwrap()
        .to_rgb8();
    // Where the two end balls are not, frames 0 and 3 show the cube as
    // the union of the three does: the same camera.
    let (f0, f3) = (frame(0), frame(3));
    let mut same = 0;
    for (x, y, p) in both.enumerate_pixels() {
        if f0.get_pixel(x, y) == p && f3.get_pixel(x, y) == p {
            same += 1;
        }
    }
    assert!(
        same as f64 > 0.9 * 80.0 * 60.0,
        "{same} of 4800 pixels agree"
    );
}

#[test]
fn animate_needs_a_scad_model_and_one_image_per_frame() {
    let (dir, _) = common::scene("a.csg", CUBE);
    std::fs::write(dir.path().join("a.scad"), "cube(1);\n").unwrap();
    for (args, says) in [
        (&["a.csg", "--animate", "3"][..], "for a `.scad` model only"),
        (
            &["a.scad", "--animate", "3", "--mask", "m.png"],
            "cannot be used with --animate",
        ),
        (
            &["a.scad", "--animate", "3", "-o", "-"],
            "cannot be used with --animate",
        ),
        (&["a.scad", "--animate", "0"], "--animate"),
    ] {
        common::refused(dir.path(), args, says, &["a.csg", "a.scad"]);
    }
}
