#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Two separate parts in the default single mode (docs/reconstruction-3d.md §4.14): a unit sphere
and, beside it, a capped tube (radius 0.15) along half of its equator at a gap of g spacings. One
genus-0 surface must join them; the best it can do is one neck across the gap, about g/2 from the
true surfaces. Each result (ours, single mode; and the advancing-front peer, which gives the two
surfaces) is sampled on its triangles (centroids, edge midpoints and 8 random points per triangle)
and measured against the exact surfaces: the largest distance, in units of g/2, and our bridge
faces (the report's `bridges`).

Blue noise (bench/topology_sweep3.py's sampler), N = 3 000, 10 000, 30 000; g = 1.5, 2, 3, 4 (in
about the median nearest-neighbour distance); seeds 1 and 2; a random rotation per set.

Usage: bench/apart_parts3.py [BUILD_DIR (build-bench)] [OUT (out/apart_parts3)] [N,N,... (3000,10000,30000)]
Writes OUT/data/*.xyz (kept), OUT/out/* and OUT/table.md. Needs numpy. About 3 minutes."""
import importlib.util
import json
import math
import os
import subprocess
import sys

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("topology_sweep3", os.path.join(_here, "topology_sweep3.py"))
ts = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ts)

RT, ALPHA = 0.15, math.pi  # the tube's radius and the arc it runs along
GAPS = (1.5, 2.0, 3.0, 4.0)
SEEDS = (1, 2)


def geometry(g, n):
    """The tube's ring radius and the gap for g spacings at n points."""
    area = 4 * math.pi + 2 * math.pi * RT * (1 + RT) * ALPHA + 4 * math.pi * RT * RT
    h = 1.2 * math.sqrt(0.66 * area / n)  # about the median nearest-neighbour distance of the blue noise
    gap = g * h
    return 1 + gap + RT, gap, area


def arc_distance(p, rc):
    """Distance from p to the tube's centre line (the arc of radius rc, angles 0..ALPHA, z = 0)."""
    ang = np.arctan2(p[:, 1], p[:, 0]) % (2 * math.pi)
    d_in = np.hypot(np.hypot(p[:, 0], p[:, 1]) - rc, p[:, 2])
    e0, e1 = np.array([rc, 0, 0]), np.array([rc * math.cos(ALPHA), rc * math.sin(ALPHA), 0])
    d_end = np.minimum(np.linalg.norm(p - e0, axis=1), np.linalg.norm(p - e1, axis=1))
    return np.where(ang <= ALPHA, np.minimum(d_in, d_end), d_end)


def truth_distance(p, rc):
    return np.minimum(np.abs(np.linalg.norm(p, axis=1) - 1), np.abs(arc_distance(p, rc) - RT))


def make(g, n, seed):
    rng = np.random.default_rng(seed)
    rc, gap, area = geometry(g, n)
    m = 12 * n
    a_s, a_t, a_c = 4 * math.pi, 4 * math.pi ** 2 * rc * RT * ALPHA / (2 * math.pi), 4 * math.pi * RT * RT
    tot = a_s + a_t + a_c
    sph = ts.sample_sphere(rng, int(m * a_s / tot), np.zeros(3), 1.0)
    tor = ts.sample_torus(rng, int(m * a_t / tot * 2 * math.pi / ALPHA), rc, RT)
    tor = tor[np.arctan2(tor[:, 1], tor[:, 0]) % (2 * math.pi) <= ALPHA]
    caps = np.vstack([ts.sample_sphere(rng, int(m * a_c / tot), c, RT)
                      for c in ([rc, 0, 0], [rc * math.cos(ALPHA), rc * math.sin(ALPHA), 0])])
    in_tube = ((np.arctan2(caps[:, 1], caps[:, 0]) % (2 * math.pi) <= ALPHA)
               & (np.hypot(np.hypot(caps[:, 0], caps[:, 1]) - rc, caps[:, 2]) < RT - 1e-12))
    pts, _ = ts.blue_noise(rng, np.vstack([sph, tor, caps[~in_tube]]), area, n)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return pts, q, rc, gap


def read_off(path):
    toks = open(path).read().split()
    nv, nf = int(toks[1]), int(toks[2])
    v = np.array(toks[4:4 + 3 * nv], float).reshape(nv, 3)
    f = np.array(toks[4 + 3 * nv:], float).reshape(nf, -1)[:, 1:4].astype(int)
    return v, f


def surface_distance(off, q, rc):
    """The largest distance from the surface to the truth (samples on every triangle)."""
    v, f = read_off(off)
    v = v @ q  # back to the generator's frame (the points were written as p @ q.T)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    rng = np.random.default_rng(0)
    samples = [(a + b + c) / 3, (a + b) / 2, (b + c) / 2, (a + c) / 2]
    for _ in range(8):
        r1, r2 = rng.random((len(f), 1)), rng.random((len(f), 1))
        s = np.sqrt(r1)
        samples.append((1 - s) * a + s * (1 - r2) * b + s * r2 * c)
    return float(truth_distance(np.vstack(samples), rc).max())


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build-bench"
    out = sys.argv[2] if len(sys.argv) > 2 else "out/apart_parts3"
    ns = [int(x) for x in sys.argv[3].split(",")] if len(sys.argv) > 3 else [3000, 10000, 30000]
    cli, afsr = os.path.join(build, "cli", "constrict"), os.path.join(build, "bench", "constrict_afsr")
    for x in (cli, afsr):
        if not os.access(x, os.X_OK):
            sys.exit(f"missing {x}: run make bench")
    os.makedirs(os.path.join(out, "data"), exist_ok=True)
    os.makedirs(os.path.join(out, "out"), exist_ok=True)
    rows = []
    for n in ns:
        for g in GAPS:
            for seed in SEEDS:
                name = f"apart_N{n}_g{g:g}_s{seed}"
                path = os.path.join(out, "data", name + ".xyz")
                pts, q, rc, gap = make(g, n, seed)
                if not os.path.exists(path):
                    np.savetxt(path, pts @ q.T, fmt="%.17g")
                ours, peer = os.path.join(out, "out", name + ".off"), os.path.join(out, "out", name + ".afsr.off")
                rep = os.path.join(out, "out", name + ".json")
                subprocess.run([cli, "reconstruct", path, "-o", ours, "-q", "--report", rep], check=True)
                subprocess.run([afsr, path, peer], check=True, capture_output=True)
                r = json.load(open(rep))
                d_ours, d_peer = surface_distance(ours, q, rc) / (gap / 2), surface_distance(peer, q, rc) / (gap / 2)
                rows.append((n, g, seed, d_ours, d_peer, r["bridges"]["faces"], r["valid"]))
                print(f"{name}: ours {d_ours:.2f} peer {d_peer:.2f} (x g/2), bridge faces {r['bridges']['faces']}",
                      flush=True)
    with open(os.path.join(out, "table.md"), "w") as t:
        t.write("| points | gap / h | seed | ours: surface → truth ÷ (g/2) | peer (two surfaces) | bridge faces | valid |\n")
        t.write("|---|---|---|---|---|---|---|\n")
        for n, g, seed, d, p, b, v in rows:
            t.write(f"| {n} | {g:g} | {seed} | {d:.2f} | {p:.2f} | {b} | {v} |\n")
        near = sum(1 for row in rows if row[3] <= 1.3)
        t.write(f"\n{near} of {len(rows)} sets within 1.3 g/2 of the truth (one neck).\n")
    print(open(os.path.join(out, "table.md")).read())


if __name__ == "__main__":
    main()
