#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Machined parts in 3D (issue 16; docs/topology.md, "Sharp edges"): solids with flat faces, sharp
edges and through holes, like the rocker arm and other CAD models, sampled with blue noise and run
through `constrict reconstruct --topology auto`; the number of surfaces and the total genus are
compared with the truth, and a result with more genus than the truth (an invented handle) is counted
apart. Genus-0 solids of the same kind are the controls.

Families (numpy generators; seeds fixed, so the sets are the same on every run):
  block      a box 4 x 2 x 0.6 (genus 0)
  plate1     the box with one round hole through it (genus 1)
  plate3     a box 6 x 2 x 0.5 with three round holes (genus 3)
  thinwall   a box 3 x 2 x 1 whose hole leaves a wall 0.15 thick on one side (genus 1; at 2 000
             points the wall is 1.3 spacings thick, at 20 000 about 4)
  frame      a box 3 x 3 x 0.6 with a square hole 1.6 x 1.6 (genus 1, all edges sharp)
  can        a closed cylinder (genus 0)
  mug1, mug2 the cylinder with one or two torus handles (genus 1, 2): concave creases where they meet
  gridblock, gridplate1  the box and the plate with one hole, their faces sampled on a square grid
             (every square four cocircular points) instead of blue noise

Usage: bench/cad_sweep3.py [BUILD_DIR (build-bench)] [OUT (out/cad_sweep3)] [N,N,... (2000,6000,20000)]
Writes OUT/data/*.xyz (kept: a second run with another build reads the same sets), OUT/out/*.json
and OUT/table.md. Needs numpy (python3-numpy). About 3 minutes."""
import importlib.util
import math
import os

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("handles_sweep3", os.path.join(_here, "handles_sweep3.py"))
hs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(hs)
ts = hs.ts  # bench/topology_sweep3.py

SEEDS = (1, 2)


def box_minus(rng, m, a, b, c, round_holes=(), square_holes=()):
    """m candidates, uniform by area, on the surface of the box [-a,a]x[-b,b]x[-c,c] minus holes
    through it along z: round (x, y, r) and square (x, y, half side)."""
    areas = [4 * a * b, 4 * a * b, 4 * a * c, 4 * a * c, 4 * b * c, 4 * b * c]
    areas += [2 * math.pi * r * 2 * c for _, _, r in round_holes]
    areas += [4 * 2 * s * 2 * c for _, _, s in square_holes]
    k = rng.multinomial(m, np.array(areas) / sum(areas))
    u = lambda n, lo, hi: rng.uniform(lo, hi, n)
    faces = [np.c_[u(k[0], -a, a), u(k[0], -b, b), np.full(k[0], c)],
             np.c_[u(k[1], -a, a), u(k[1], -b, b), np.full(k[1], -c)],
             np.c_[u(k[2], -a, a), np.full(k[2], b), u(k[2], -c, c)],
             np.c_[u(k[3], -a, a), np.full(k[3], -b), u(k[3], -c, c)],
             np.c_[np.full(k[4], a), u(k[4], -b, b), u(k[4], -c, c)],
             np.c_[np.full(k[5], -a), u(k[5], -b, b), u(k[5], -c, c)]]
    p = np.vstack(faces)
    inside = np.zeros(len(p), bool)
    for x, y, r in round_holes:
        inside |= (p[:, 0] - x) ** 2 + (p[:, 1] - y) ** 2 < r * r
    for x, y, s in square_holes:
        inside |= (np.abs(p[:, 0] - x) < s) & (np.abs(p[:, 1] - y) < s)
    out = [p[~inside]]
    j = 6
    for x, y, r in round_holes:
        t = u(k[j], 0, 2 * math.pi)
        out.append(np.c_[x + r * np.cos(t), y + r * np.sin(t), u(k[j], -c, c)])
        j += 1
    for x, y, s in square_holes:
        n = k[j]
        side = rng.integers(0, 4, n)
        w = u(n, -s, s)
        q = np.c_[np.where(side == 0, s, np.where(side == 1, -s, w)),
                  np.where(side == 2, s, np.where(side == 3, -s, w)), u(n, -c, c)]
        out.append(q + [x, y, 0])
        j += 1
    return np.vstack(out)


def can_with_handles(rng, m, R, H, handles):
    """m candidates on the union of a closed cylinder (radius R, height H, axis z from 0) and
    tori (z, ring radius, tube radius) standing on its side, in the planes through the axis."""
    side, cap = 2 * math.pi * R * H, math.pi * R * R
    areas = [side, cap, cap] + [4 * math.pi ** 2 * Rt * rt for _, Rt, rt in handles]
    k = rng.multinomial(m, np.array(areas) / sum(areas))
    t = rng.uniform(0, 2 * math.pi, k[0])
    parts = [np.c_[R * np.cos(t), R * np.sin(t), rng.uniform(0, H, k[0])]]
    for s, z in ((1, H), (2, 0.0)):
        rr = R * np.sqrt(rng.random(k[s]))
        t = rng.uniform(0, 2 * math.pi, k[s])
        parts.append(np.c_[rr * np.cos(t), rr * np.sin(t), np.full(k[s], z)])
    can = np.vstack(parts)
    frames = []
    tor = []
    for h, (z, Rt, rt) in enumerate(handles):
        ang = 2 * math.pi * h / len(handles)
        ca, sa = math.cos(ang), math.sin(ang)
        frames.append((np.array([R * ca, R * sa, z]), ca, sa, Rt, rt))
        q = ts.sample_torus(rng, k[3 + h], Rt, rt)[:, [0, 2, 1]]  # the torus in the x-z plane
        tor.append(np.c_[q[:, 0] * ca - q[:, 1] * sa + R * ca, q[:, 0] * sa + q[:, 1] * ca + R * sa, q[:, 2] + z])

    def in_tori(p):
        res = np.zeros(len(p), bool)
        for c, ca, sa, Rt, rt in frames:
            q = p - c
            lx, ly, lz = q[:, 0] * ca + q[:, 1] * sa, -q[:, 0] * sa + q[:, 1] * ca, q[:, 2]
            res |= np.hypot(np.hypot(lx, lz) - Rt, ly) < rt
        return res

    tor = np.vstack(tor) if tor else np.zeros((0, 3))
    in_can = (np.hypot(tor[:, 0], tor[:, 1]) < R) & (tor[:, 2] > 0) & (tor[:, 2] < H)
    return np.vstack([can[~in_tori(can)], tor[~in_can]])


def grid_plate(a, b, c, n, hole=0.0):
    """The box [-a,a]x[-b,b]x[-c,c] (minus a round hole of radius `hole` along z) with its faces
    sampled on a square grid of about n points (the hole's wall in rings): every grid square four
    cocircular points, coplanar up to rounding once rotated."""
    area = 8 * (a * b + a * c + b * c) + (2 * math.pi * hole * 2 * c - 2 * math.pi * hole * hole if hole else 0)
    h = math.sqrt(area / n)

    def steps(lo, hi):
        k = max(1, int(round((hi - lo) / h)))
        return [lo + (hi - lo) * i / k for i in range(k + 1)]

    xs, ys, zs = steps(-a, a), steps(-b, b), steps(-c, c)
    pts = {(x, y, z) for x in xs for y in ys for z in (-c, c)}
    pts |= {(x, y, z) for x in xs for z in zs for y in (-b, b)}
    pts |= {(x, y, z) for y in ys for z in zs for x in (-a, a)}
    p = np.array(sorted(pts))
    if hole:
        p = p[np.hypot(p[:, 0], p[:, 1]) > hole + 1e-9]
        k = int(round(2 * math.pi * hole / h))
        t = 2 * math.pi * np.arange(k) / k
        p = np.vstack([p] + [np.c_[hole * np.cos(t), hole * np.sin(t), np.full(k, z)] for z in zs])
    return p


SHAPES = {
    "block": (lambda rng, m: box_minus(rng, m, 2, 1, 0.3), 0),
    "plate1": (lambda rng, m: box_minus(rng, m, 2, 1, 0.3, [(0, 0, 0.4)]), 1),
    "plate3": (lambda rng, m: box_minus(rng, m, 3, 1, 0.25, [(-2, 0, 0.4), (0, 0, 0.5), (2, 0, 0.4)]), 3),
    "thinwall": (lambda rng, m: box_minus(rng, m, 1.5, 1, 0.5, [(0.5, 0, 0.85)]), 1),
    "frame": (lambda rng, m: box_minus(rng, m, 1.5, 1.5, 0.3, (), [(0, 0, 0.8)]), 1),
    "can": (lambda rng, m: can_with_handles(rng, m, 1, 2, []), 0),
    "mug1": (lambda rng, m: can_with_handles(rng, m, 1, 2, [(1.0, 0.55, 0.12)]), 1),
    "mug2": (lambda rng, m: can_with_handles(rng, m, 1, 2.5, [(0.7, 0.45, 0.1), (1.8, 0.45, 0.1)]), 2),
}
# Faces sampled on a grid instead of blue noise (n points, no thinning).
GRID_SHAPES = {
    "gridblock": (lambda n: grid_plate(2, 1, 0.3, n), 0),
    "gridplate1": (lambda n: grid_plate(2, 1, 0.3, n, 0.4), 1),
}


def main():
    cli, out, ns = ts.args("out/cad_sweep3", [2000, 6000, 20000])
    rows = []
    for si, (fam, (gen, genus)) in enumerate(list(SHAPES.items()) + list(GRID_SHAPES.items())):
        for n in ns:
            for seed in SEEDS:
                name = f"{fam}_N{n}_s{seed}"
                path = os.path.join(out, "data", name + ".xyz")
                if not os.path.exists(path):  # (another build on the same sets: the data are kept)
                    rng = np.random.default_rng([si, n, seed])
                    if fam in GRID_SHAPES:
                        pts = gen(n)
                    else:
                        pts = hs.thin_to(gen(rng, 12 * n), n, tolerance=0.04, rounds=10)
                    pts = (pts @ ts.random_rotation(rng).T) * 3.7 + [1, -2, 5]
                    np.savetxt(path, pts[rng.permutation(len(pts))], fmt="%.17g")
                hs.run_set(cli, out, fam, name, path, (1, genus), rows)
    hs.write_table(out, list(SHAPES) + list(GRID_SHAPES), rows)


if __name__ == "__main__":
    main()
