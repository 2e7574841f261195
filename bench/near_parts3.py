#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Parts that nearly touch, in 3D auto mode (issues 16 and 17; docs/topology.md, "Parts that nearly
touch"): two boxes whose flat faces face each other across a gap of 1 to 4 sample spacings, as the
parts of a machined assembly or a scanned object's limbs do. Truth: two genus-0 surfaces. The gap
rule (T = 2 local spacings, the distance to the third nearest neighbour) joins the two boxes up to
about 3 nearest-neighbour spacings; what the result is then (one surface, with false handles where
the labels leave cuts in the gap, or two) is what this measures. A result with genus is counted
apart.

Families (numpy generators; seeds fixed, so the sets are the same on every run):
  stack   two boxes 2 x 1 x 0.3 (half sides), one on the other: their 4 x 2 faces face each other
  side    the same boxes side by side: their 2 x 0.6 faces face each other
  plates  two plates 2 x 1 x 0.08, one on the other
Each box is blue noise of N/2 points (N = 3 000 and 8 000); the gap is g times the median
nearest-neighbour distance of the first box (g = 1, 1.5, 2, 2.5, 3, 4), 3 seeds, rotated and
shuffled.

Usage: bench/near_parts3.py [BUILD_DIR (build-bench)] [OUT (out/near_parts3)] [N,N,... (3000,8000)]
Writes OUT/data/*.xyz (kept: a second run with another build reads the same sets), OUT/out/*.json
and OUT/table.md (right sets per family and gap). Needs numpy (python3-numpy). About 5 minutes."""
import importlib.util
import os

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("cad_sweep3", os.path.join(_here, "cad_sweep3.py"))
cad = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cad)
hs, ts = cad.hs, cad.ts

SEEDS = (1, 2, 3)
GAPS = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0)
FAMILIES = {"stack": ((2, 1, 0.3), 2), "side": ((2, 1, 0.3), 0), "plates": ((2, 1, 0.08), 2)}  # half sides, axis


def median_spacing(p, rng):
    """The median nearest-neighbour distance of 500 random points of p (brute force)."""
    idx = rng.choice(len(p), min(500, len(p)), replace=False)
    return float(np.median([np.partition(np.linalg.norm(p - p[i], axis=1), 1)[1] for i in idx]))


def make(fam, n, gap, rng):
    half, axis = FAMILIES[fam]
    a = hs.thin_to(cad.box_minus(rng, 6 * n, *half), n // 2, tolerance=0.04, rounds=10)
    b = hs.thin_to(cad.box_minus(rng, 6 * n, *half), n // 2, tolerance=0.04, rounds=10)
    shift = np.zeros(3)
    shift[axis] = 2 * half[axis] + gap * median_spacing(a, rng)
    pts = np.vstack([a, b + shift])
    pts = (pts @ ts.random_rotation(rng).T) * 3.7 + [1, -2, 5]
    return pts[rng.permutation(len(pts))]


def main():
    cli, out, ns = ts.args("out/near_parts3", [3000, 8000])
    rows, groups = [], []
    for fi, fam in enumerate(FAMILIES):
        for gap in GAPS:
            group = f"{fam}, gap {gap:g}"
            groups.append(group)
            for n in ns:
                for seed in SEEDS:
                    name = f"{fam}_N{n}_g{gap:g}_s{seed}"
                    path = os.path.join(out, "data", name + ".xyz")
                    if not os.path.exists(path):  # (another build on the same sets: the data are kept)
                        rng = np.random.default_rng([fi, n, int(gap * 10), seed])
                        np.savetxt(path, make(fam, n, gap, rng), fmt="%.17g")
                    hs.run_set(cli, out, group, name, path, (2, 0), rows)
    hs.write_table(out, groups, rows)


if __name__ == "__main__":
    main()
