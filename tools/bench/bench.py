#!/usr/bin/env python3
"""csgrt against POV-Ray 3.7, side by side, on the same scenes.

Each scene of the bench set (models/*.csg and the generated bench/*.csg) is
exported by csgrt (--export-pov) and rendered by both renderers at the same
size, one sample per pixel, shadows on, with one thread and with all cores
(csgrt --threads N, POV-Ray +WTN). Runs alternate between the renderers and
the thread counts, and the median of --runs is kept (the speed-up on all cores
also as the median of each round's own ratio); times are wall-clock for the whole process,
parse included, and render only: csgrt's render_seconds (--stats-json)
against POV-Ray's own "Trace Time". The table gives the times, the ratio
csgrt / POV-Ray,
csgrt's primary rays per second, primitive tests per primary ray and per
primitive entered (examples/entered), and BENCHMARKS.md (--out) records it
with the machine it ran on.

POV-Ray comes from Debian: apt-get install -y povray.

With --sweep SCENE it instead measures run time against error: csgrt at
--spp 1, 2, 4, 8, 16, 64 and POV-Ray with adaptive anti-aliasing (+A0.0
+R1..+R4), both against a 256-spp csgrt reference (RMSE over 8-bit channels),
plotted in --plot (matplotlib, tools/requirements-bench.txt), and counts
the silhouette pixels of each at one sample that disagree with the
manifold3d oracle (tools/oracle/oracle/; tools/requirements.txt).

Usage: bench.py [--csgrt BIN] [--size WxH] [--runs N] [--out BENCHMARKS.md] [SCENE...]
       bench.py --sweep SCENE [--size WxH] [--plot docs/time-vs-error.png]
"""

import argparse
import glob
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time


def timed(cmd):
    """(wall-clock seconds, captured stderr)."""
    t = time.perf_counter()
    r = subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    return time.perf_counter() - t, r.stderr


def pov_trace_seconds(stderr):
    for line in stderr.splitlines():
        if "Trace Time:" in line:
            return float(line.split("(")[1].split()[0])
    raise ValueError("POV-Ray printed no trace time")


def csgrt_render_seconds(path):
    with open(path) as f:
        return json.load(f)["render_seconds"]


def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    pov = subprocess.run(["povray", "--version"], capture_output=True, text=True)
    lines = (pov.stdout + pov.stderr).splitlines()
    pov_version = next((x for x in lines if x.startswith("POV-Ray")), "POV-Ray (version unknown)")
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}; {pov_version}"


from tools import ROOT
# Scenes whose text is also given to POV-Ray as its own `text` objects.
POV_TEXT_SCENES = ["bench/text_block.csg"]


def peer_png(peer):
    return "pov_" + "".join(c if c.isalnum() else "_" for c in peer) + ".png"


def rgb(path):
    """An image's 8-bit channels as floats, height x width x 3."""
    import numpy as np
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"), dtype=float)


def differing_pixels(a, b):
    """(pixels differing by more than 8 levels in some channel, pixels)."""
    x, y = rgb(a), rgb(b)
    return int((abs(x - y).max(axis=2) > 8).sum()), x.shape[0] * x.shape[1]


def rmse(a, b):
    import numpy as np

    x, y = rgb(a), rgb(b)
    return float(np.sqrt(np.mean((x - y) ** 2)))


ORACLE_SEGMENTS = 256
# Scenes without a floor, whose silhouettes are mostly edges.
SILHOUETTE_SCENES = ["models/csg_ops.csg", "models/bracket.csg", "bench/nested_tori.csg"]


def silhouette_mismatch(a, scene):
    """{renderer: (mismatched pixels, of which off the oracle's edge, pixels)}
    at one sample per pixel, against the manifold3d oracle's mask, and
    ("csgrt vs POV-Ray", pixels where the two masks differ)."""
    import numpy as np
    from PIL import Image

    from tools.oracle import oracle
    from tools.oracle import scene as reader

    w, h = a.size.split("x")
    with tempfile.TemporaryDirectory() as work:
        mask, img, pov, pimg, dump = (os.path.join(work, f) for f in ("m.png", "c.png", "s.pov", "p.png", "s.json"))
        subprocess.run([a.csgrt, scene, "--size", a.size, "--spp", "1", "--mask", mask,
                        "-o", img, "--export-pov", pov, "--dump-scene", dump, "-q"], check=True)
        subprocess.run(["povray", f"+I{pov}", f"+O{pimg}", f"+W{w}", f"+H{h}", "+FN", "-D", "-A"],
                       check=True, capture_output=True)
        # The oracle's own reading of the file: its camera, background, mesh.
        sc = reader.read(scene)
        bg = np.round(np.clip(np.array(sc.background, dtype=float), 0, 1) * 255)
        not_bg = lambda path: np.any(rgb(path) != bg, axis=2)
        cmask = np.asarray(Image.open(mask).convert("L")) == 255
        if not np.array_equal(not_bg(img), cmask):
            raise SystemExit(f"{scene}: object pixels take the background colour; "
                             "the POV-Ray silhouette rule cannot be used on this scene")
        cw, ch = int(w), int(h)
        caster = oracle.Caster(sc, ORACLE_SEGMENTS)
        rays = oracle.camera_rays(sc.view(cw, ch, oracle.framed_box(dump)), cw, ch)
        omask = np.array([caster.cast(o, v) is not None for o, v in rays]).reshape(ch, cw)
        edge = oracle.mixed(omask)
        out = {}
        pmask = not_bg(pimg)
        for who, m in (("csgrt", cmask), ("POV-Ray", pmask)):
            mism = m != omask
            out[who] = (int(mism.sum()), int((mism & ~edge).sum()), cw * ch)
            print(scene, who, "silhouette", out[who], flush=True)
        out["csgrt vs POV-Ray"] = int((cmask != pmask).sum())
        return out


def sweep(a):
    w, h = a.size.split("x")
    rows = []
    with tempfile.TemporaryDirectory() as work:
        ref = os.path.join(work, "ref.png")
        pov = os.path.join(work, "scene.pov")
        subprocess.run([a.csgrt, a.sweep, "--size", a.size, "--spp", "256", "-o", ref, "-q",
                        "--export-pov", pov], check=True)
        for spp in (1, 2, 4, 8, 16, 64):
            out = os.path.join(work, f"c{spp}.png")
            t = statistics.median(
                timed([a.csgrt, a.sweep, "--size", a.size, "--spp", str(spp), "-o", out, "-q"])[0]
                for _ in range(a.runs)
            )
            rows.append(("csgrt", f"--spp {spp}", t, rmse(out, ref)))
            print(rows[-1], flush=True)
        # csgrt's default: adaptive anti-aliasing (1 sample; corners where
        # neighbours differ by more than 0.3; 16 where corners differ).
        out = os.path.join(work, "cadaptive.png")
        t = statistics.median(
            timed([a.csgrt, a.sweep, "--size", a.size, "-o", out, "-q"])[0] for _ in range(a.runs)
        )
        rows.append(("csgrt adaptive", "default", t, rmse(out, ref)))
        print(rows[-1], flush=True)
        for depth in (None, 1, 2, 3, 4):
            out = os.path.join(work, f"p{depth}.png")
            aa = ["-A"] if depth is None else ["+A0.0", f"+R{depth}"]
            t = statistics.median(
                timed(["povray", f"+I{pov}", f"+O{out}", f"+W{w}", f"+H{h}", "+FN", "-D", *aa])[0]
                for _ in range(a.runs)
            )
            rows.append(("POV-Ray", " ".join(aa), t, rmse(out, ref)))
            print(rows[-1], flush=True)
    silhouettes = {sc: silhouette_mismatch(a, sc) for sc in [a.sweep, *SILHOUETTE_SCENES]}
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=100)
    for who, marker in (("csgrt", "o"), ("csgrt adaptive", "D"), ("POV-Ray", "s")):
        pts = [(t, e, lab) for r, lab, t, e in rows if r == who]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=who)
        for t, e, lab in pts:
            ax.annotate(lab, (t, e), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall-clock seconds (whole process, all cores)")
    ax.set_ylabel("RMSE against csgrt at 256 spp (8-bit levels)")
    ax.set_title(f"{os.path.basename(a.sweep)}, {a.size}: run time against error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.plot)
    table = os.path.splitext(a.plot)[0] + ".md"
    with open(table, "w") as f:
        f.write(f"# Run time against error: {a.sweep}, {a.size}\n\n")
        f.write(f"Generated by `tools/bench/bench.py --sweep {a.sweep} --size {a.size} --plot {a.plot}` on "
                f"{machine()}; median of {a.runs} runs, wall-clock, all cores. RMSE in 8-bit levels "
                "against csgrt at 256 spp.\n\n| renderer | setting | seconds | RMSE |\n|---|---|---|---|\n")
        for who, lab, t, e in rows:
            f.write(f"| {who} | `{lab}` | {t:.3f} | {e:.3f} |\n")
        f.write(
            "\nSilhouettes at one sample per pixel against the manifold3d oracle (the mesh at "
            f"n = {ORACLE_SEGMENTS} segments ray-cast through the same pixel centres): pixels whose "
            "hit/miss differs from the oracle's, and how many of them lie off the oracle's "
            "silhouette edge (a 3x3 neighbourhood holding both). csgrt's mask is its `--mask`; "
            "POV-Ray's is every pixel whose colour is not the background's, a rule checked on "
            "csgrt's own image, where it must reproduce `--mask`.\n\n"
            "| scene | pixels | csgrt: mismatched | off the edge | POV-Ray: mismatched | off the edge "
            "| csgrt and POV-Ray differ |\n|---|---|---|---|---|---|---|\n"
        )
        for sc, r in silhouettes.items():
            (cm, co, total), (pm, po, _) = r["csgrt"], r["POV-Ray"]
            f.write(f"| `{sc}` | {total} | {cm} | {co} | {pm} | {po} | {r['csgrt vs POV-Ray']} |\n")
    print(f"wrote {a.plot} and {table}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--csgrt", default="target/release/csgrt")
    ap.add_argument("--entered", default="target/release/examples/entered",
                    help="built by cargo build --release --examples")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--out", default=None)
    ap.add_argument("--sweep", default=None, help="a scene: measure run time against error")
    ap.add_argument("--plot", default="docs/time-vs-error.png")
    a = ap.parse_args()
    if a.sweep:
        return sweep(a)
    scenes = a.scenes or sorted(glob.glob("models/*.csg")) + sorted(glob.glob("bench/*.csg"))
    w, h = a.size.split("x")
    cores = os.cpu_count() or 1
    rows, skipped = [], []
    with tempfile.TemporaryDirectory() as work:
        for scene in scenes:
            name = os.path.splitext(os.path.basename(scene))[0]
            pov = os.path.join(work, name + ".pov")
            stats = os.path.join(work, name + ".json")
            img = os.path.join(work, name + ".png")
            subprocess.run(
                [a.csgrt, scene, "--size", a.size, "--spp", "1", "-o", img, "--export-pov", pov,
                 "--stats-json", stats, "-q", "--threads", "1"],
                check=True,
            )
            with open(stats) as f:
                s = json.load(f)
            with open(pov) as f:
                if "#error" in f.read():
                    # A twisted extrusion: POV-Ray has no such solid.
                    print(f"{name}: skipped, no POV-Ray equivalent (a twisted linear_extrude)", flush=True)
                    skipped.append(name)
                    continue
            entered = json.loads(subprocess.run(
                [a.entered, scene, a.size, "4"], check=True, capture_output=True, text=True).stdout)
            # POV-Ray's peers: the export, and for text its own `text`.
            peers = [(name, pov)]
            if os.path.normpath(scene) in POV_TEXT_SCENES:
                text_pov = os.path.join(work, name + "_text.pov")
                subprocess.run([sys.executable, "-m", "tools.bench.pov_text", scene, pov, text_pov], cwd=ROOT,
                               check=True)
                peers.append((f"{name} (POV-Ray `text`)", text_pov))
            # One run of each of (csgrt, each POV-Ray peer) x (1 thread, all)
            # in turn, so that a slow spell of the machine falls on all.
            times = {peer: {t: ([], [], [], []) for t in (1, cores)} for peer, _ in peers}
            for _ in range(a.runs):
                for threads in (1, cores):
                    wall, _ = timed([a.csgrt, scene, "--size", a.size, "--spp", "1", "-o", img, "-q",
                                     "--threads", str(threads), "--stats-json", stats])
                    render = csgrt_render_seconds(stats)
                    for peer, peer_pov in peers:
                        cw, pw, cr, pr = times[peer][threads]
                        cw.append(wall)
                        cr.append(render)
                        out = os.path.join(work, peer_png(peer))
                        pwall, err = timed(["povray", f"+I{peer_pov}", f"+O{out}", f"+W{w}", f"+H{h}",
                                            "+FN", "-D", "-A", f"+WT{threads}"])
                        pw.append(pwall)
                        pr.append(pov_trace_seconds(err))
            for peer, _ in peers:
                row = {"scene": peer, "stats": s, "entered": entered}
                for threads in (1, cores):
                    row[threads] = tuple(statistics.median(x) for x in times[peer][threads])
                # Each round's 1-thread and all-core renders ran a moment apart: the
                # median of their ratios is the paired estimate of the speed-up
                # (see the note under the table).
                row["paired"] = statistics.median(
                    one / many for one, many in zip(times[peer][1][2], times[peer][cores][2]))
                if peer != name:
                    row["same_shapes"] = differing_pixels(os.path.join(work, peer_png(name)),
                                                          os.path.join(work, peer_png(peer)))
                rows.append(row)
                c1, p1, r1, t1 = row[1]
                print(f"{peer}: process {c1:.3f} s vs {p1:.3f} s ({c1 / p1:.2f}); "
                      f"render {r1:.3f} s vs trace {t1:.3f} s ({r1 / t1:.2f})", flush=True)
    lines = [
        "# Benchmarks: csgrt against POV-Ray 3.7",
        "",
        f"Generated by `tools/bench/bench.py --out BENCHMARKS.md` on {machine()}.",
        f"{a.size}, one sample per pixel, shadows on; median of {a.runs} alternating runs, wall-clock",
        "for the whole process (parse included; POV-Ray needs about 0.7 s to start), and render",
        "only: csgrt's `render_seconds` against POV-Ray's reported trace time. Ratios are csgrt's",
        "time over POV-Ray's: below 1 csgrt is faster. The last two columns come from",
        "`examples/entered` (every 4th pixel centre): the primitive tests of the first-hit query",
        "of a primary ray against the primitives that ray enters at t > 0 (found by brute force),",
        "and the share of rays whose tests are at most 3× the primitives they enter (or 3 for a",
        "ray that enters none).",
        "",
        f"The speed-up on {cores} threads is given twice: from the median render times, and as the",
        "median over rounds of each round's own ratio (its 1-thread and all-core renders ran a",
        "moment apart). On a machine shared with other work (a virtual machine, say) the run",
        "that uses every core loses time whenever anything else runs, and the machine's speed",
        "drifts from minute to minute; pairing cancels the drift.",
        "",
        "| scene | 1 thread: csgrt process | POV-Ray process | ratio | csgrt render | POV-Ray trace | ratio "
        f"| {cores} threads: csgrt render | POV-Ray trace | ratio | csgrt speed-up (medians) "
        "| (paired rounds) | primary rays/s (1 thread) "
        "| primitive tests per primary ray (shadows included) | first-hit tests per primitive entered "
        "| rays within 3× |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        c1, p1, r1, t1 = r[1]
        _, _, rn, tn = r[cores]
        s = r["stats"]
        lines.append(
            f"| {r['scene']} | {c1:.3f} s | {p1:.3f} s | {c1 / p1:.2f} | {r1:.3f} s | {t1:.3f} s | "
            f"{r1 / t1:.2f} | {rn:.3f} s | {tn:.3f} s | {rn / tn:.2f} | {r1 / rn:.2f}× | "
            f"{r['paired']:.2f}× | "
            f"{s['primary_rays'] / r1:,.0f} | {s['primitive_tests'] / s['primary_rays']:.2f} | "
            f"{r['entered']['tests_per_entered']:.2f} | {100 * r['entered']['rays_within_3x']:.1f} % |"
        )
    for r in rows:
        if "same_shapes" in r:
            n, total = r["same_shapes"]
            lines += ["", f"{r['scene']}: the same glyphs as POV-Ray's own `text` objects, one a glyph, "
                      "placed by OpenSCAD's layout as the oracle computes it (`tools/bench/pov_text.py`), "
                      "instead of the export's prisms; POV-Ray's two pictures differ by more than 8 "
                      f"levels in {n} of {total:,} pixels."]
    if skipped:
        lines += ["", "Not compared (no POV-Ray equivalent: a twisted or unevenly scaled `linear_extrude`): "
                  + ", ".join(skipped) + "."]
    text = "\n".join(lines) + "\n"
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    sys.exit(main())
