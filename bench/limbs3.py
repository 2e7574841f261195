#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Limbs that nearly touch, in 3D auto mode (issues 16 and 17; docs/topology.md, "Limbs that nearly
touch"): one genus-0 object whose parts hang close to each other, as a scanned figure's legs, arms
and fingers do. Any bridge across such a gap closes a loop through the object (leg, gap, leg,
body), so in `--topology auto` it would show as a false handle; the truth is one surface of
genus 0.

Families (numpy generators; seeds fixed, so the sets are the same on every run), each the surface
of a union of primitives (points of one primitive inside another dropped):
  legs   a ball with two parallel capsules (legs) hanging below it
  arm    an upright capsule (a torso) with a thinner one (an arm) hanging beside it from a
         shoulder bar
  comb   a box with five box fingers on it
The gap between the facing surfaces is g times the median nearest-neighbour distance (g = 1.5, 2,
3, 4, 6). Two samplings: blue noise ("bn", Poisson-disk thinning, as mesh vertices are) and
uniformly random points ("rand", with the empty patches of a Poisson process), N = 4 000 and
12 000, 2 seeds; rotated, scaled and shuffled.

Usage: bench/limbs3.py [BUILD_DIR (build-bench)] [OUT (out/limbs3)] [N,N,... (4000,12000)]
Writes OUT/data/*.xyz (kept: a second run with another build reads the same sets), OUT/out/*.json
and OUT/table.md (right sets per family, sampling and gap; sets with more genus than the truth
counted apart). Needs numpy (python3-numpy). About 10 minutes."""
import importlib.util
import math
import os

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("handles_sweep3", os.path.join(_here, "handles_sweep3.py"))
hs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(hs)
ts = hs.ts

SEEDS = (1, 2)
GAPS = (1.5, 2.0, 3.0, 4.0, 6.0)
FAMILIES = ("legs", "arm", "comb")
SAMPLINGS = ("bn", "rand")


# ---------- primitives: (signed distance, area, area-uniform sampler) ----------
class Capsule:
    def __init__(self, a, b, r):
        self.a, self.b, self.r = np.asarray(a, float), np.asarray(b, float), float(r)
        self.len = float(np.linalg.norm(self.b - self.a))

    def sdf(self, p):
        ab = self.b - self.a
        t = np.clip((p - self.a) @ ab / (ab @ ab), 0, 1)
        return np.linalg.norm(p - (self.a + t[:, None] * ab), axis=1) - self.r

    def area(self):
        return 2 * math.pi * self.r * self.len + 4 * math.pi * self.r ** 2

    def sample(self, rng, m):
        axis = (self.b - self.a) / self.len
        u = np.cross(axis, [1, 0, 0] if abs(axis[0]) < 0.9 else [0, 1, 0])
        u /= np.linalg.norm(u)
        v = np.cross(axis, u)
        side = rng.random(m) < 2 * math.pi * self.r * self.len / self.area()
        t, ang = rng.random(m), rng.random(m) * 2 * math.pi
        cyl = self.a + t[:, None] * (self.b - self.a) + self.r * (np.cos(ang)[:, None] * u + np.sin(ang)[:, None] * v)
        d = rng.normal(size=(m, 3))
        d /= np.linalg.norm(d, axis=1)[:, None]
        cap = np.where((d @ axis)[:, None] > 0, self.b, self.a) + self.r * d
        return np.where(side[:, None], cyl, cap)


class Box:
    def __init__(self, lo, hi):
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)

    def sdf(self, p):
        c, h = (self.lo + self.hi) / 2, (self.hi - self.lo) / 2
        q = np.abs(p - c) - h
        return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)

    def area(self):
        e = self.hi - self.lo
        return 2 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2])

    def sample(self, rng, m):
        e = self.hi - self.lo
        faces = np.array([e[1] * e[2], e[0] * e[2], e[0] * e[1]] * 2)
        k = rng.choice(6, m, p=faces / faces.sum())
        p = self.lo + rng.random((m, 3)) * e
        ax = k % 3
        p[np.arange(m), ax] = np.where(k < 3, self.lo[ax], self.hi[ax])
        return p


class Ball(Capsule):
    def __init__(self, c, r):
        super().__init__(c, c, r)

    def sdf(self, p):
        return np.linalg.norm(p - self.a, axis=1) - self.r

    def area(self):
        return 4 * math.pi * self.r ** 2

    def sample(self, rng, m):
        d = rng.normal(size=(m, 3))
        return self.a + self.r * d / np.linalg.norm(d, axis=1)[:, None]


def shape(fam, gap):
    """The primitives of a family with a gap (in model units) between its facing surfaces."""
    if fam == "legs":
        r = 0.3
        x = r + gap / 2
        return [Ball((0, 0, 0), 1.0), Capsule((-x, 0, -0.5), (-x, 0, -3.0), r), Capsule((x, 0, -0.5), (x, 0, -3.0), r)]
    if fam == "arm":
        R, r = 0.6, 0.25
        x = R + gap + r
        return [Capsule((0, 0, -1.8), (0, 0, 1.8), R), Capsule((0, 0, 1.5), (x, 0, 1.5), r),
                Capsule((x, 0, 1.5), (x, 0, -1.4), r)]
    a = 0.5  # comb: five fingers a wide, gap apart, on a base
    w = 5 * a + 4 * gap
    prims = [Box((0, 0, 0), (w, 1.0, 0.6))]
    for i in range(5):
        x0 = i * (a + gap)
        prims.append(Box((x0, 0, 0.3), (x0 + a, 1.0, 3.0)))
    return prims


def candidates(rng, prims, m):
    """About m area-uniform points on the surface of the union of prims."""
    total = sum(p.area() for p in prims)
    out = []
    for i, p in enumerate(prims):
        q = p.sample(rng, int(m * p.area() / total) + 1)
        ok = np.ones(len(q), bool)
        for j, o in enumerate(prims):
            if j != i:
                ok &= o.sdf(q) > 1e-9
        out.append(q[ok])
    c = np.concatenate(out)
    return c[rng.permutation(len(c))]


def sample(fam, sampling, n, gap, rng):
    """n points of the family with a gap of `gap` median nearest-neighbour distances."""
    h = 0.05
    for _ in range(2):  # the spacing of a first sample sets the gap of the second
        prims = shape(fam, gap * h)
        if sampling == "bn":
            pts = hs.thin_to(candidates(rng, prims, 8 * n), n, tolerance=0.04, rounds=10)
        else:
            pts = candidates(rng, prims, n)
        idx = rng.choice(len(pts), min(500, len(pts)), replace=False)
        h = float(np.median([np.partition(np.linalg.norm(pts - pts[i], axis=1), 1)[1] for i in idx]))
    pts = (pts @ ts.random_rotation(rng).T) * 2.3 + [0.5, -1, 3]
    return pts[rng.permutation(len(pts))]


def main():
    cli, out, ns = ts.args("out/limbs3", [4000, 12000])
    rows, groups = [], []
    for fi, fam in enumerate(FAMILIES):
        for si, sampling in enumerate(SAMPLINGS):
            for gap in GAPS:
                group = f"{fam} {sampling}, gap {gap:g}"
                groups.append(group)
                for n in ns:
                    for seed in SEEDS:
                        name = f"{fam}_{sampling}_N{n}_g{gap:g}_s{seed}"
                        path = os.path.join(out, "data", name + ".xyz")
                        if not os.path.exists(path):
                            rng = np.random.default_rng([fi, si, n, int(gap * 10), seed])
                            np.savetxt(path, sample(fam, sampling, n, gap, rng), fmt="%.17g")
                        hs.run_set(cli, out, group, name, path, (1, 0), rows)
    hs.write_table(out, groups, rows)


if __name__ == "__main__":
    main()
