#!/usr/bin/env python3
"""Writes the adversarial models of issue 26 into a folder, for the time-limit and
translation measurements in docs/performance.md:

    python3 tools/adversarial_models.py OUT

- grid12100.json, grid600.json, grid360000.json: 110 x 110, 25 x 24 and 600 x 600 (42 MB) grids
  of bilinear patches (heights ((7i + 3j) mod 5) / 10);
- weights.json: one biquadratic patch whose weights span 1e-300..1e300;
- exponent.json: one bilinear patch with a coordinate "1e5000";
- sphere_shifted_100.json, sphere_shifted_1e6.json, torus_shifted_1e6.json: the exact sphere
  (radius 2) and torus (3, 1) of target/golden-models (run `cargo run --example golden_shapes
  -- target/golden-models` first) translated by (t, t, t), exactly.
"""
import json
import os
import sys
from fractions import Fraction


def grid(nx, ny):
    z = lambda a, b: ((a * 7 + b * 3) % 5) / 10
    patches = []
    for i in range(nx):
        for j in range(ny):
            corners = [(i, j), (i, j + 1), (i + 1, j), (i + 1, j + 1)]
            patches.append({"kind": "bezier", "degree": [1, 1],
                            "points": [[a, b, z(a, b)] for a, b in corners]})
    return {"patches": patches}


def shifted(path, t):
    m = json.load(open(path))
    for p in m["patches"]:
        p["points"] = [[str(Fraction(c) + t) for c in q] for q in p["points"]]
    return m


def main():
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit("usage: adversarial_models.py OUT (a directory, made if missing)\n" + __doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    models = {
        "grid12100.json": grid(110, 110),
        "grid600.json": grid(25, 24),
        "grid360000.json": grid(600, 600),
        "weights.json": {"patches": [{
            "kind": "bezier", "degree": [2, 2],
            "points": [[i, j, (i * j) % 3] for i in range(3) for j in range(3)],
            "weights": ["1e-300", "1", "1e300", "1", "1e150", "1", "1e300", "1", "1e-300"]}]},
        "exponent.json": {"patches": [{
            "kind": "bezier", "degree": [1, 1],
            "points": [[0, 0, 0], [0, 1, 0], [1, 0, "1e5000"], [1, 1, 0]]}]},
    }
    shapes = "target/golden-models"
    for name, t in [("sphere", 100), ("sphere", 10**6), ("torus", 10**6)]:
        src = os.path.join(shapes, name + ".json")
        if os.path.exists(src):
            label = "100" if t == 100 else "1e6"
            models[f"{name}_shifted_{label}.json"] = shifted(src, t)
    for name, m in models.items():
        path = os.path.join(out, name)
        if os.path.exists(path):
            print(f"{path}: exists, kept")
            continue
        with open(path, "w") as f:
            json.dump(m, f)
        print(path)


if __name__ == "__main__":
    main()
