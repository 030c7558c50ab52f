"""The rays compared: the camera's through every pixel centre, random rays
from all around, and csgrt's answers for them (--trace-rays)."""

import json
import math
import os
import subprocess

import numpy as np
from PIL import Image

from tools.oracle import scene as reader

__all__ = ['camera_rays', 'framed_box', 'random_rays', 'render_csgrt', 'trace_csgrt']


# --------------------------------------------------------------------------
# csgrt's side
# --------------------------------------------------------------------------


def camera_rays(view, w, h):
    eye, lookat, up, fov = (np.asarray(x, dtype=float) if i < 3 else x for i, x in enumerate(view))
    look = lookat - eye
    du = np.cross(look, up)
    du /= np.linalg.norm(du)
    dv = np.cross(look, du)
    dv /= np.linalg.norm(dv)
    fl = w / (2 * math.tan(math.radians(fov) / 2))
    vp = look / np.linalg.norm(look) * fl - 0.5 * (w * du + h * dv)
    out = []
    for j in range(h):
        for i in range(w):
            d = (i + 0.5) * du + (j + 0.5) * dv + vp
            out.append((eye, d / np.linalg.norm(d)))
    return out


def random_rays(sc, count, seed):
    """Rays from a sphere around the bounded solids towards random points
    of their box."""
    rng = np.random.default_rng(seed)
    lo, hi = reader.bounded_box(sc, reader.UNIT)
    c, r = (lo + hi) / 2, max(np.linalg.norm(hi - lo) / 2, 1e-9)
    out = []
    for _ in range(count):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        target = c + rng.uniform(-0.5, 0.5, size=3) * (hi - lo)
        o = c + 2 * r * u
        d = target - o
        out.append((o, d / np.linalg.norm(d)))
    return out


def render_csgrt(cmd, scene, work, w, h, env=None):
    """csgrt's mask, image, and the box its default camera framed (its
    `--dump-scene`'s `framed`: None when the file gives a camera)."""
    mask, image = os.path.join(work, "mask.png"), os.path.join(work, "image.png")
    dump = os.path.join(work, "scene.json")
    subprocess.run(
        [*cmd, scene, "--size", f"{w}x{h}", "--spp", "1", "--mask", mask, "-o", image, "--dump-scene", dump, "-q"],
        check=True,
        env=env,
    )
    m = np.asarray(Image.open(mask).convert("L")) == 255
    img = np.asarray(Image.open(image).convert("RGB")).astype(int)
    return m, img, framed_box(dump)


def framed_box(dump):
    """(min, max) of the box a `--dump-scene` file says the default camera
    framed, or None."""
    with open(dump) as f:
        framed = json.load(f).get("framed")
    if framed is None:
        return None
    return np.array(framed["min"], dtype=float), np.array(framed["max"], dtype=float)


def trace_csgrt(cmd, scene, work, rays, env=None):
    """csgrt's answers for rays: None for a miss, else (t, normal)."""
    ray_file = os.path.join(work, "rays.txt")
    with open(ray_file, "w") as f:
        for o, v in rays:
            f.write(" ".join(repr(float(x)) for x in (*o, *v)) + "\n")
    out = subprocess.run(
        [*cmd, scene, "--trace-rays", ray_file], check=True, capture_output=True, text=True, env=env
    ).stdout.splitlines()
    if len(out) != len(rays):
        raise RuntimeError(f"csgrt answered {len(out)} of {len(rays)} rays")
    traced = []
    for line in out:
        if line == "miss":
            traced.append(None)
        else:
            t, nx, ny, nz = map(float, line.split())
            traced.append((t, np.array([nx, ny, nz])))
    return traced
