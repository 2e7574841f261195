#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Handles in 3D beyond the shared families (issue 16; docs/topology.md, Limits "Uneven sampling of
handles"): shapes of genus 2 and 3 sampled evenly and very unevenly, run through `constrict
reconstruct --topology auto`; the number of surfaces and the total genus are compared with the
truth, and a result with more genus than the truth (an invented handle) is counted apart.

Families (numpy generators; seeds fixed, so the sets are the same on every run):
  tori2, tori3   2 or 3 tori side by side (ring radius 1, tube 0.25 or 0.4; neighbouring tubes
                 overlap), the union's surface: blue noise (Poisson-disk thinning)
  tori2u, tori3u the same, uniformly random with a smooth density change of up to 4x
  eight          a tube around a figure eight (g(x, y)^2 + z^2 = c, g = x(x-1)^2(x-2) + y^2,
                 c = 0.02 or 0.035): blue noise
  eightn         the same tube from random points of a box pulled onto it by Newton steps: dense
                 on the top and bottom of the tube, up to 8x sparser on its sides (as
                 tests/property/test_surfaces3_property.cpp eight_by_projection, another generator)

Usage: bench/handles_sweep3.py [BUILD_DIR (build-bench)] [OUT (out/handles_sweep3)] [N,N,... (3000,10000,30000)]
Writes OUT/data/*.xyz (kept: a second run with another build reads the same sets), OUT/out/*.json
and OUT/table.md. Needs numpy (python3-numpy). About 15 minutes, most of it making blue noise."""
import importlib.util
import json
import math
import os
import subprocess

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("topology_sweep3", os.path.join(_here, "topology_sweep3.py"))
ts = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ts)

SEEDS = (1, 2)


def thin_to(cand, n, tolerance=0.03, rounds=8):
    """Poisson-disk thinning of shuffled candidates to about n points."""
    d = 0.05
    keep = None
    for _ in range(rounds):
        keep = ts.poisson_thin(cand, d)
        if abs(len(keep) - n) <= tolerance * n:
            break
        d *= math.sqrt(len(keep) / n)
    return cand[keep]


def tori_union(rng, k, r, m):
    """m candidates, uniform by area, on the surface of the union of k tori along x."""
    R = 1.0
    centres = [np.array([2.0 * R * i, 0, 0]) for i in range(k)]

    def d2c(p, c):
        q = p - c
        return np.hypot(np.hypot(q[:, 0], q[:, 1]) - R, q[:, 2])

    out = []
    for i, c in enumerate(centres):
        p = ts.sample_torus(rng, m // k, R, r) + c
        ok = np.ones(len(p), bool)
        for j, c2 in enumerate(centres):
            if j != i:
                ok &= d2c(p, c2) > r
        out.append(p[ok])
    return np.concatenate(out)


def eight_newton(rng, m, c):
    """Random points of a box pulled onto the figure-eight tube by Newton steps."""
    def g(x, y):
        return x * (x - 1) ** 2 * (x - 2) + y * y

    def gx(x):
        return (x - 1) ** 2 * (2 * x - 2) + 2 * x * (x - 1) * (x - 2)

    lo, hi = np.array([-0.5, -1, -0.6]), np.array([2.5, 1, 0.6])
    pts = []
    got = 0
    while got < m:
        p = lo + (hi - lo) * rng.random((m * 4, 3))
        for _ in range(30):
            gg = g(p[:, 0], p[:, 1])
            f = gg * gg + p[:, 2] ** 2 - c
            gr = np.stack([2 * gg * gx(p[:, 0]), 2 * gg * 2 * p[:, 1], 2 * p[:, 2]], 1)
            p = p - (f / ((gr * gr).sum(1) + 1e-300))[:, None] * gr
        gg = g(p[:, 0], p[:, 1])
        ok = np.abs(gg * gg + p[:, 2] ** 2 - c) < 1e-12
        pts.append(p[ok])
        got += int(ok.sum())
    return np.concatenate(pts)[:m]


def make(fam, param, n, rng):
    """Points and the true (surfaces, genus)."""
    if fam in ("tori2", "tori3"):
        k = int(fam[-1])
        cand = tori_union(rng, k, param, 10 * n)
        return thin_to(cand[rng.permutation(len(cand))], n), (1, k)
    if fam in ("tori2u", "tori3u"):
        k = int(fam[4])
        cand = tori_union(rng, k, param, 12 * n)
        ph = rng.uniform(0, 6.3, 3)
        w = 0.25 + 0.75 * (0.5 + 0.5 * np.sin(1.7 * cand[:, 0] + ph[0]) * np.cos(2.3 * cand[:, 1] + ph[1] + cand[:, 2]))
        cand = cand[rng.uniform(0, 1, len(cand)) < w]
        return cand[rng.permutation(len(cand))[:n]], (1, k)
    if fam == "eight":
        cand = eight_newton(rng, 8 * n, param)
        return thin_to(cand[rng.permutation(len(cand))], n), (1, 2)
    if fam == "eightn":
        return eight_newton(rng, n, param), (1, 2)
    raise ValueError(fam)


FAMS = [("tori2", (0.25, 0.4)), ("tori3", (0.25, 0.4)), ("tori2u", (0.25, 0.4)), ("tori3u", (0.25, 0.4)),
        ("eight", (0.02, 0.035)), ("eightn", (0.02, 0.035))]


def run_set(cli, out, fam, name, path, truth, rows):
    """`constrict reconstruct PATH --topology auto`: appends (fam, name, truth, got, exit) to rows."""
    npts = sum(1 for _ in open(path))
    rep = os.path.join(out, "out", name + ".json")
    p = subprocess.run([cli, "reconstruct", path, "-o", os.path.join(out, "out", name + ".off"),
                        "--topology", "auto", "--report", rep, "-q"], capture_output=True, text=True)
    r = json.load(open(rep)) if p.returncode == 0 else {}
    got = (r.get("components"), r.get("genus"))
    rows.append((fam, name, truth, got, p.returncode))
    ok = p.returncode == 0 and got == truth
    print(f"{name}: {npts} points, truth {truth}, got {got}{'' if ok else '  WRONG'}", flush=True)


def write_table(out, fams, rows):
    """OUT/table.md: per family the sets, the right ones and those with more genus than the truth."""
    lines = ["| family | sets | right | more genus than the truth |", "|---|---|---|---|"]
    for fam in fams:
        sel = [r for r in rows if r[0] == fam]
        right = sum(r[4] == 0 and r[2] == r[3] for r in sel)
        over = sum(r[4] == 0 and (r[3][1] or 0) > r[2][1] for r in sel)
        lines.append(f"| {fam} | {len(sel)} | {right} | {over} |")
    right = sum(r[4] == 0 and r[2] == r[3] for r in rows)
    over = sum(r[4] == 0 and (r[3][1] or 0) > r[2][1] for r in rows)
    lines += ["", f"{right} of {len(rows)} right (surfaces, total genus); {over} with more genus than the truth.", "",
              "| wrong set | truth | result |", "|---|---|---|"]
    lines += [f"| {r[1]} | {r[2]} | {r[3]}{'' if r[4] == 0 else f' (exit {r[4]})'} |" for r in rows
              if not (r[4] == 0 and r[2] == r[3])]
    open(os.path.join(out, "table.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    cli, out, ns = ts.args("out/handles_sweep3", [3000, 10000, 30000])
    rows = []
    for fi, (fam, params) in enumerate(FAMS):
        for param in params:
            for n in ns:
                for seed in SEEDS:
                    name = f"{fam}_{param}_N{n}_s{seed}"
                    path = os.path.join(out, "data", name + ".xyz")
                    truth = (1, 3 if fam.startswith("tori3") else 2)
                    if not os.path.exists(path):  # (another build on the same sets: the data are kept)
                        rng = np.random.default_rng([fi, int(param * 1000), n, seed])
                        pts, truth = make(fam, param, n, rng)
                        np.savetxt(path, pts @ ts.random_rotation(rng).T, fmt="%.17g")
                    run_set(cli, out, fam, name, path, truth, rows)
    write_table(out, [fam for fam, _ in FAMS], rows)


if __name__ == "__main__":
    main()
