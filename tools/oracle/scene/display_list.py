"""The seed's display list (.ray)."""

import re

import numpy as np

from . import meaning
from . import syntax

__all__ = ['read_ray']


# --------------------------------------------------------------------------
# The seed's display list (.ray)
# --------------------------------------------------------------------------


def read_ray(path, text):
    """Slide 32's format: one statement a line; `surface` takes ten numbers
    over as many lines as it needs and applies to the spheres after it."""
    sc = meaning.Scene()
    eye, lookat, up, fov = np.array([0.0, 0, 10]), np.zeros(3), np.array([0.0, 1, 0]), 30.0
    sc.background = np.zeros(3)
    words = []  # (word, line, col)
    for ln, line in enumerate(text.split("\n"), 1):
        line = re.split(r"#|//", line, maxsplit=1)[0]
        for m in re.finditer(r"\S+", line):
            words.append((m.group(), ln, m.start() + 1))
    i, mat, spheres = 0, None, []

    def nums(k):
        nonlocal i
        out = []
        for _ in range(k):
            if i >= len(words):
                raise syntax.ReadError(path, words[-1][1], words[-1][2], "expected a number")
            w, ln, col = words[i]
            try:
                out.append(float(w))
            except ValueError:
                raise syntax.ReadError(path, ln, col, f"expected a number, found {w!r}")
            i += 1
        return np.array(out)

    while i < len(words):
        w, ln, col = words[i]
        i += 1
        if w == "eye":
            eye = nums(3)
        elif w == "lookat":
            lookat = nums(3)
        elif w == "up":
            up = nums(3)
        elif w == "fov":
            fov = float(nums(1)[0])
        elif w == "background":
            sc.background = nums(3)
        elif w == "light":
            c = nums(3)
            kind = words[i][0]
            i += 1
            if kind == "ambient":
                sc.lights.append(("ambient", c, None, False))
            elif kind == "directional":
                d = nums(3)
                sc.lights.append(("directional", c, d / np.linalg.norm(d), True))
            elif kind == "point":
                sc.lights.append(("point", c, nums(3), True))
            else:
                raise syntax.ReadError(path, ln, col, f"unknown light kind {kind!r}")
        elif w == "surface":
            n = nums(10)
            mat = dict(color=n[:3], ka=n[3], kd=n[4], ks=n[5], ns=n[6], kr=n[7], kt=n[8], ior=n[9])
        elif w == "sphere":
            n = nums(4)
            st = syntax.Stmt("sphere", [], [], "", ln, col)
            leaf = meaning.Leaf("sphere", dict(r=float(n[3])), meaning.affine(t=n[:3]), dict(mat or meaning.CORNFIELD), st)
            leaf.id = len(sc.leaves)
            sc.leaves.append(leaf)
            spheres.append(leaf)
        else:
            raise syntax.ReadError(path, ln, col, f"unknown statement {w!r}")
    sc.camera = (eye, lookat, up, fov)
    sc.root = meaning.Reader.union(spheres)
    return sc
