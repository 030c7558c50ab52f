"""Which shadow decisions two builds disagree on, and which build is right.

Usage: explain_shadows.py SCENE.json OLD.txt NEW.txt

SCENE.json is `csgrt SCENE --dump-scene SCENE.json` (the resolved tree: each
torus's f64 matrix and minor radius); OLD.txt and NEW.txt are
`examples/samples.rs` run by each build. For every sample whose shadow
decision differs, both builds' shadow rays are settled exactly: mpmath at 300
bits on the dumped matrices, taken as exact, finds whether the ray starts
inside a torus or enters one at t > 0. Only for scenes whose tree is a union
of tori (bench/nested_tori.csg); a primary hit that moves is reported as such.
"""
import json
import re
import sys

import mpmath as mp

from tools.oracle.accuracy import torus_crossings


def parse(path):
    """(x, y, sample) -> (primitive, t, [per light: '-' or (blocked, ray)])."""
    out = {}
    for line in open(path):
        words = line.split(None, 5)
        x, y, s, prim, t = words[:5]
        flags = re.findall(r"(-|[01] \[[^\]]*\])", words[5] if len(words) > 5 else "")
        out[(int(x), int(y), int(s))] = (
            int(prim),
            float(t),
            [f if f == "-" else (int(f[0]), [float(v) for v in f[3:-1].split()]) for f in flags],
        )
    return out


def exact_occluded(leaves, ray):
    """(blocked, torus, why) for the ray o + t d, exactly: it starts inside a
    torus (an odd number of crossings behind it) or crosses one at t > 0."""
    o = mp.matrix([mp.mpf(v) for v in ray[:3]])
    d = mp.matrix([mp.mpf(v) for v in ray[3:]])
    for leaf in leaves:
        m = leaf["matrix"]
        inv = mp.matrix([[mp.mpf(m[i][j]) for j in range(3)] for i in range(3)]) ** -1
        t = mp.matrix([mp.mpf(m[i][3]) for i in range(3)])
        ts = torus_crossings(inv * (o - t), inv * d, mp.mpf(1), mp.mpf(leaf["minor"]))
        if sum(1 for x in ts if x < 0) % 2 == 1:
            return True, leaf["id"], "origin inside"
        ahead = [x for x in ts if x > 0]
        if ahead:
            return True, leaf["id"], "enters at t=%s" % mp.nstr(ahead[0], 5)
    return False, None, ""


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    mp.mp.prec = 300
    scene = json.load(open(sys.argv[1]))
    leaves = scene["root"]["children"]
    if any(c.get("primitive") != "torus" for c in leaves):
        sys.exit("explain_shadows.py: only a union of tori is handled")
    old, new = parse(sys.argv[2]), parse(sys.argv[3])
    diff = 0
    for k in sorted(old):
        po, to, fo = old[k]
        pn, tn, fn = new[k]
        if po != pn or abs(to - tn) > 1e-9 * abs(to):
            print(k, "PRIMARY differs", old[k][:2], new[k][:2])
            diff += 1
            continue
        for li, (a, b) in enumerate(zip(fo, fn)):
            if a == "-" or b == "-":
                if a != b:
                    print(k, "light", li, "facing differs")
                    diff += 1
                continue
            if a[0] != b[0]:
                diff += 1
                print(k, "light", li, "old occluded=%d new occluded=%d; exact: old ray %s, new ray %s"
                      % (a[0], b[0], exact_occluded(leaves, a[1]), exact_occluded(leaves, b[1])))
    print("samples", len(old), "decisions differing", diff)


if __name__ == "__main__":
    main()
