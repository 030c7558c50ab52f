#!/usr/bin/env python3
"""Where csgrt's time goes, scene by scene: instruction counts from callgrind.

Each scene is rendered once under valgrind's callgrind (one thread, one sample
a pixel, --size, default 320x240), and its instructions are split two ways:

- by phase, from inclusive counts: start-up and output (everything outside
  `render::render`: reading, resolving, building hierarchies, writing the
  image), first hits of primary rays (`render::render` less the shader), and
  shading (`Shader::shade`: Phong, and the shadow, reflected and refracted
  rays it casts);
- by kind of work, from each function's own count (inlined code counted in the
  function it is inlined into): the CSG walk (the unions' walks, span lists,
  their merging, the scratch), the solids' own tests (each kind's spans:
  `geometry::`, `plane::`, polynomial roots), shading arithmetic (`shade`,
  `pow`, …) and the rest (camera, pixels, start-up).

The counts do not drift with the machine's load, unlike times. Needs valgrind
(`apt-get install -y valgrind`); the renderer is target/release/csgrt unless
--csgrt names another. Debian's valgrind (3.19) does not decode every AVX
instruction of the default build, which is compiled for this machine's
processor (.cargo/config.toml): count a portable build instead,
`RUSTFLAGS="-C target-cpu=x86-64" cargo build --release --target-dir
target/portable` and `--csgrt target/portable/release/csgrt`.

Usage: profile.py [--csgrt BIN] [--size WxH] [--out FILE.md] [SCENE...]
"""

import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

WALK = re.compile(
    r"csgrt::csg::(Csg::(union_first|push_spans|push_spans_within|push_prim_spans|"
    r"first_boundary_for|first_boundary|occluded|spans_with|prim_spans|leaf_first)|"
    r"Scratch::merge|spans::)|geometry::bvh::|LocalKey<T>::with|csgrt::csg::query|with_scratch"
)
SHADING = re.compile(r"render::shade::|__ieee754_pow|__pow|__exp|__ieee754_exp|__sqrt")


def run(binary, scene, size):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", binary, scene,
               "--size", size, "--spp", "1", "--threads", "1", "-q", "-o", os.path.join(tmp, "x.png")]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise SystemExit(f"{scene}: callgrind run failed:\n{r.stderr[-2000:]}")
        incl, _, _ = annotate(out, inclusive=True)
        _, rows, total = annotate(out, inclusive=False)
    return incl, rows, total


def annotate(path, inclusive):
    """The listing's {function: count} (a function's largest entry: with
    --inclusive, its own symbol's), its [(source file, function, count)]
    lines (inlined code keeps the file it comes from), and the total."""
    args = ["callgrind_annotate", "--threshold=100"]
    if inclusive:
        args.append("--inclusive=yes")
    r = subprocess.run(args + [path], capture_output=True, text=True, check=True)
    counts, rows = {}, []
    total = None
    for line in r.stdout.splitlines():
        m = re.match(r"^\s*([\d,]+) \([^)]*\)\s+(\S+?):(.*)$", line)
        if not m:
            t = re.match(r"^\s*([\d,]+) \([^)]*\)\s+PROGRAM TOTALS", line)
            if t:
                total = int(t.group(1).replace(",", ""))
            continue
        n = int(m.group(1).replace(",", ""))
        src, fn = m.group(2), re.sub(r"\s*\[[^\]]*\]\s*$", "", m.group(3))
        if src in ("=>", "*", "<"):
            continue
        counts[fn] = max(counts.get(fn, 0), n)
        rows.append((src, fn, n))
    return counts, rows, total


def find(counts, pattern):
    return max((n for f, n in counts.items() if re.search(pattern, f)), default=0)


# What a solid's source file is called in the table.
KIND = {"plane/mod.rs": "region crossings", "poly.rs": "polynomial roots",
        "cone.rs": "cylinders and cones", "lathe.rs": "lathes", "prism.rs": "prisms",
        "torus.rs": "tori", "sphere.rs": "spheres", "cuboid.rs": "boxes",
        "mesh.rs": "meshes", "convex.rs": "hulls", "twist.rs": "twisted prisms",
        "round_offset.rs": "offsets", "offset_prism.rs": "offset prisms", "robust.rs": "robust tests",
        "halfspace.rs": "half-spaces", "rounded.rs": "rounded solids", "shape.rs": "dispatch",
        "solid.rs": "dispatch", "transform.rs": "transforms", "pencil.rs": "line families"}


def kind(area, name):
    """The work of source file `name` of src/`area`: "walk", "shading",
    ("leaf", kind of solid) or None."""
    if area == "csg" or name in ("bvh.rs", "aabb.rs"):
        return "walk"
    if area == "render":
        return "shading" if name == "shade.rs" else None
    if area == "geometry" and name == "mod.rs":
        # The ray itself (`Ray::new`, `Ray::at`), not a solid's work.
        return None
    key = "plane/mod.rs" if (area == "plane" and name == "mod.rs") else name
    return ("leaf", KIND.get(key, key.removesuffix(".rs")))


def kind_of(src, fn):
    """The work of a listing line: by its source file, or for library code
    inlined into a function, by the function's module (or its name)."""
    m = re.search(r"src/(geometry|plane|csg|render)/(.*)$", src)
    if m and (k := kind(*m.groups())) is not None:
        return k
    if WALK.search(fn):
        return "walk"
    if m := re.search(r"csgrt::(geometry|plane)::(\w+)", fn):
        area, module = m.groups()
        # A type of plane/mod.rs (`plane::Region`), or a module's file.
        return kind(area, "mod.rs" if area == "plane" and module[0].isupper() else module + ".rs")
    if SHADING.search(fn) or re.search(r"libm|e_pow|e_exp", src):
        return "shading"
    return None


def summary(scene, incl, rows, total):
    render = find(incl, r"^csgrt::render::render$")
    shade = find(incl, r"csgrt::render::shade::Shader::shade$")
    groups = {"walk": 0, "leaves": 0, "shading": 0}
    leaf_kinds = {}
    for src, fn, n in rows:
        # Only the rendering's work: not reading or resolving the scene.
        if re.search(r"resolve|::new$|Bvh::(build|split|collapse)|syntax|pest", fn):
            continue
        k = kind_of(src, fn)
        if k == "walk":
            groups["walk"] += n
        elif k == "shading":
            groups["shading"] += n
        elif isinstance(k, tuple):
            groups["leaves"] += n
            leaf_kinds[k[1]] = leaf_kinds.get(k[1], 0) + n
    pct = lambda n: 100.0 * n / total
    top = sorted(leaf_kinds.items(), key=lambda kv: -kv[1])[:3]
    return {
        "scene": os.path.splitext(os.path.basename(scene))[0],
        "total": total / 1e6,
        "startup": pct(total - render),
        "primary": pct(render - shade),
        "shade": pct(shade),
        "walk": pct(groups["walk"]),
        "leaves": pct(groups["leaves"]),
        "top": ", ".join(f"{k} {pct(v):.0f} %" for k, v in top if pct(v) >= 1),
        "shading": pct(groups["shading"]),
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csgrt", default="target/release/csgrt")
    p.add_argument("--size", default="320x240")
    p.add_argument("--out")
    p.add_argument("scenes", nargs="*")
    a = p.parse_args()
    scenes = a.scenes or sorted(glob.glob("models/*.csg")) + sorted(glob.glob("bench/*.csg"))
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as ex:
        rows = list(ex.map(lambda s: summary(s, *run(a.csgrt, s, a.size)), scenes))
    head = (
        f"Instructions (callgrind, {a.size}, one thread, one sample a pixel, the whole process) "
        "and their shares. By phase: start-up and output; primary rays' first hits; shading "
        "(with the shadow, reflected and refracted rays it casts). By work (each function's own "
        "instructions): the CSG walk and span lists; the solids' own tests (the largest kinds); "
        "shading arithmetic.\n\n"
        "| scene | M instructions | start-up, output | primary first hits | shading, secondary rays "
        "| CSG walk | solids' tests | largest solids | shading arithmetic |\n"
        "|---|---|---|---|---|---|---|---|---|\n"
    )
    body = "".join(
        f"| {r['scene']} | {r['total']:.1f} | {r['startup']:.0f} % | {r['primary']:.0f} % | "
        f"{r['shade']:.0f} % | {r['walk']:.0f} % | {r['leaves']:.0f} % | {r['top']} | "
        f"{r['shading']:.0f} % |\n"
        for r in rows
    )
    text = head + body
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
