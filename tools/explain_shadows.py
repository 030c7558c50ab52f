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

mp.mp.prec = 300
if len(sys.argv) != 4:
    sys.exit(__doc__)
scene = json.load(open(sys.argv[1]))
if any(c.get("primitive") != "torus" for c in scene["root"]["children"]):
    sys.exit("explain_shadows.py: only a union of tori is handled")
def parse(path):
    out = {}
    for line in open(path):
        x, y, s, prim, t = line.split()[:5]
        tail = line.split(None, 5)[5] if len(line.split()) > 5 else ''
        flags = re.findall(r'(-|[01] \[[^\]]*\])', tail)
        out[(int(x), int(y), int(s))] = (int(prim), float(t), [f if f == '-' else (int(f[0]), [float(v) for v in f[3:-1].split()]) for f in flags])
    return out
old, new = parse(sys.argv[2]), parse(sys.argv[3])
leaves = scene['root']['children']
def exact_occluded(ray):
    o = [mp.mpf(v) for v in ray[:3]]; d = [mp.mpf(v) for v in ray[3:]]
    for leaf in leaves:
        M = mp.matrix([[mp.mpf(leaf['matrix'][i][j]) for j in range(3)] for i in range(3)])
        T = mp.matrix([mp.mpf(leaf['matrix'][i][3]) for i in range(3)])
        Mi = M ** -1
        lo = Mi * (mp.matrix(o) - T); ld = Mi * mp.matrix(d)
        r = mp.mpf(leaf['minor'])
        a = sum(ld[i]**2 for i in range(3)); b = 2*sum(lo[i]*ld[i] for i in range(3)); c = sum(lo[i]**2 for i in range(3)) + 1 - r*r
        axy = ld[0]**2 + ld[1]**2; bxy = 2*(lo[0]*ld[0] + lo[1]*ld[1]); cxy = lo[0]**2 + lo[1]**2
        coef = [a*a, 2*a*b, b*b + 2*a*c - 4*axy, 2*b*c - 4*bxy, c*c - 4*cxy]
        if coef[-1] < 0:
            return True, leaf['id'], 'origin inside'
        roots = mp.polyroots(coef, maxsteps=500, extraprec=600)
        pos = [mp.re(x) for x in roots if abs(mp.im(x)) < mp.mpf(10)**-60 and mp.re(x) > 0]
        if pos:
            return True, leaf['id'], 'enters at t=%s' % mp.nstr(min(pos), 5)
    return False, None, ''
diff = 0
for k in sorted(old):
    po, to, fo = old[k]; pn, tn, fn = new[k]
    if po != pn or abs(to - tn) > 1e-9 * abs(to):
        print(k, 'PRIMARY differs', old[k][:2], new[k][:2]); diff += 1; continue
    for li, (a, b) in enumerate(zip(fo, fn)):
        if a == '-' or b == '-':
            if a != b: print(k, 'light', li, 'facing differs'); diff += 1
            continue
        if a[0] != b[0]:
            diff += 1
            eo = exact_occluded(a[1]); en = exact_occluded(b[1])
            print(k, 'light', li, 'old occluded=%d new occluded=%d; exact: old ray %s, new ray %s' % (a[0], b[0], eo, en))
print('samples', len(old), 'decisions differing', diff)
