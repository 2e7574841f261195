#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Surfaces of revolution sampled on a grid of their parameters (docs/reconstruction-3d.md §4.10):
the usual way to make a test torus, and a degenerate input (rings cocircular and coplanar, grid
squares cocircular, neighbouring rings on one sphere).

  torus  R/r = 2, 3, 4 and 5 (r = 1, and r = 0.5 at R = 2.5), grids 40 x 16, 60 x 20, 80 x 24,
         100 x 32, 64 x 32 and 120 x 48, axis-aligned and randomly rotated: 48 sets, truth one
         surface of genus 1 (`--topology auto`);
  vase   the profile rho(t) = sin t (1 + 0.35 sin(4.5 cos t)), z = 1.5 cos t turned around the z
         axis, grids 40 x 20, 60 x 30, 80 x 40 and 160 x 80 with both poles, axis-aligned and
         rotated: 8 sets in single mode, truth one genus-0 surface of the vase's area.

Usage: bench/grid_revolution3.py [BUILD_DIR (build-bench)] [OUT (out/grid_revolution3)]
Writes OUT/data/*.xyz, OUT/out/*.json and OUT/table.md (the wrong tori; each vase's area over the
true area and its bridge faces). Needs numpy. About 1 minute."""
import importlib.util
import json
import math
import os
import subprocess

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("cad_sweep3", os.path.join(_here, "cad_sweep3.py"))
cad = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cad)
hs, ts = cad.hs, cad.ts

TORI = [(R, r, nu, nv) for R, r in ((2, 1), (3, 1), (4, 1), (2.5, 0.5))
        for nu, nv in ((40, 16), (60, 20), (80, 24), (100, 32), (64, 32), (120, 48))]
VASES = [(40, 20), (60, 30), (80, 40), (160, 80)]


def vase_rho(t):
    return np.sin(t) * (1 + 0.35 * np.sin(4.5 * np.cos(t)))


def vase_area():
    t = np.linspace(0, math.pi, 400001)
    rho, z = vase_rho(t), 1.5 * np.cos(t)
    return float(np.sum(math.pi * (rho[1:] + rho[:-1]) * np.hypot(np.diff(rho), np.diff(z))))


def finish(p, rotate, rng):
    if rotate:
        p = p @ ts.random_rotation(rng).T
    return p[rng.permutation(len(p))]


def torus(R, r, nu, nv, rotate, rng):
    u, v = np.meshgrid(np.arange(nu) * 2 * math.pi / nu, np.arange(nv) * 2 * math.pi / nv)
    u, v = u.ravel(), v.ravel()
    return finish(np.c_[(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], rotate, rng)


def vase(nu, nv, rotate, rng):
    u, t = np.meshgrid(np.arange(nu) * 2 * math.pi / nu, np.arange(1, nv) * math.pi / nv)
    u, t = u.ravel(), t.ravel()
    p = np.c_[vase_rho(t) * np.cos(u), vase_rho(t) * np.sin(u), 1.5 * np.cos(t)]
    return finish(np.vstack([p, [[0, 0, 1.5], [0, 0, -1.5]]]), rotate, rng)


def save(out, name, pts):
    path = os.path.join(out, "data", name + ".xyz")
    if not os.path.exists(path):
        np.savetxt(path, pts, fmt="%.17g")
    return path


def main():
    cli, out, _ = ts.args("out/grid_revolution3", [0])
    rows = []
    for i, (R, r, nu, nv) in enumerate(TORI):
        for rot in (0, 1):
            name = f"torus_{R:g}_{r:g}_{nu}x{nv}_{'rot' if rot else 'axes'}"
            path = save(out, name, torus(R, r, nu, nv, rot, np.random.default_rng([i, rot])))
            hs.run_set(cli, out, "torus", name, path, (1, 1), rows)
    truth = vase_area()
    vases = []
    for i, (nu, nv) in enumerate(VASES):
        for rot in (0, 1):
            name = f"vase_{nu}x{nv}_{'rot' if rot else 'axes'}"
            path = save(out, name, vase(nu, nv, rot, np.random.default_rng([100 + i, rot])))
            rep = os.path.join(out, "out", name + ".json")
            p = subprocess.run([cli, "reconstruct", path, "-o", os.path.join(out, "out", name + ".off"), "--report", rep,
                                "-q"], capture_output=True, text=True)
            r = json.load(open(rep)) if p.returncode == 0 else {}
            area = r.get("surface_area", float("nan")) / truth
            vases.append((name, area, r.get("bridges", {}).get("faces"), r.get("bridges", {}).get("area", float("nan")) / truth))
            print(f"{name}: area / truth {area:.4f}, bridge faces {vases[-1][2]}", flush=True)
    hs.write_table(out, ["torus"], rows)
    with open(os.path.join(out, "table.md"), "a") as f:
        f.write("\n| vase (single mode) | area / true area | bridge faces | their area / true area |\n|---|---|---|---|\n")
        for name, area, faces, barea in vases:
            f.write(f"| {name} | {area:.4f} | {faces} | {barea:.4f} |\n")
    print("table: " + os.path.join(out, "table.md"))


if __name__ == "__main__":
    main()
