"""csgrt's Python side, run from the repository's root as modules:

    .venv/bin/python -m tools.oracle.oracle --check models/*.csg

tools.oracle: the checks that read a model independently of csgrt's code
(the reader tools.oracle.scene, the oracle's meshes, exact crossings, POV-Ray's
reading, the mutants, image fingerprints); tools.bench: benchmarks and
profiles; tools.dev: a developer's aids (galleries, surveys, OpenSCAD's
view, explaining shadow decisions).
"""

import os

# The repository's root, which holds tools/.
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
