#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""2D topology on contours from a grid (issue 16; docs/topology.md, "Tiny rings"): random fields of
six Gaussian blobs (a quarter of them subtracted) on [-1.6, 1.6]^2, sampled on a grid with a random
offset and thresholded at half their maximum by marching squares. The points are the contour's
crossings of the grid edges (as a CT slice's contours give them), shuffled; the truth is the
contours themselves. Each set is run through `constrict reconstruct --topology auto` and its rings'
point sets are compared with the contours'. For a wrong set the smallest gap between two true
rings is given in their median edge lengths: under the gap rule's 2 they merge by design.

Usage: bench/contours2_sweep.py [BUILD_DIR (build-bench)] [OUT (out/contours2)] [STEPS (0.05,0.03,0.02,0.08,0.1,0.12)] [SEEDS (40)]
Needs numpy (python3-numpy). About a minute."""
import os, subprocess, sys

import numpy as np


def blob_field(rng, n=6):
    c = rng.uniform(-1, 1, (n, 2)); s = rng.uniform(0.15, 0.45, n); w = rng.choice([1, 1, 1, -0.7], n)
    return lambda X, Y: sum(wi * np.exp(-((X - ci[0]) ** 2 + (Y - ci[1]) ** 2) / (2 * si * si)) for ci, si, wi in zip(c, s, w))


def marching_squares(V, xs, ys):
    """Contour points (one per crossed grid edge, linear) and the contour rings (point indices)."""
    pid, pts, adj = {}, [], {}

    def crossing(i, j, k):  # k = 0: edge (i,j)-(i+1,j); k = 1: edge (i,j)-(i,j+1)
        if (i, j, k) not in pid:
            a = V[i, j]; b = V[i + 1, j] if k == 0 else V[i, j + 1]; t = a / (a - b)
            pid[(i, j, k)] = len(pts)
            pts.append((xs[i] + t * (xs[i + 1] - xs[i]), ys[j]) if k == 0 else (xs[i], ys[j] + t * (ys[j + 1] - ys[j])))
        return pid[(i, j, k)]

    def link(a, b):
        adj.setdefault(a, []).append(b); adj.setdefault(b, []).append(a)

    for i in range(V.shape[0] - 1):
        for j in range(V.shape[1] - 1):
            s = [V[i, j] > 0, V[i + 1, j] > 0, V[i + 1, j + 1] > 0, V[i, j + 1] > 0]
            e = []  # crossed sides: bottom 0, right 1, top 2, left 3
            if s[0] != s[1]: e.append((0, crossing(i, j, 0)))
            if s[1] != s[2]: e.append((1, crossing(i + 1, j, 1)))
            if s[3] != s[2]: e.append((2, crossing(i, j + 1, 0)))
            if s[0] != s[3]: e.append((3, crossing(i, j, 1)))
            if len(e) == 2:
                link(e[0][1], e[1][1])
            elif len(e) == 4:  # a saddle: the cell centre's sign decides
                d = dict(e)
                if ((V[i, j] + V[i + 1, j] + V[i + 1, j + 1] + V[i, j + 1]) / 4 > 0) == s[0]:
                    link(d[0], d[1]); link(d[2], d[3])
                else:
                    link(d[0], d[3]); link(d[1], d[2])
    seen, rings = set(), []
    for s0 in adj:
        if s0 in seen: continue
        ring, prev, cur = [s0], None, s0
        seen.add(s0)
        while True:
            nxt = [x for x in adj[cur] if x != prev]
            if not nxt or nxt[0] == s0 or nxt[0] in seen: break
            prev, cur = cur, nxt[0]
            ring.append(cur); seen.add(cur)
        rings.append(ring)
    return np.array(pts), [r for r in rings if len(r) >= 3]


def make(seed, step):
    rng = np.random.default_rng(seed)
    f = blob_field(rng)
    xs = np.arange(-1.6, 1.6, step) + rng.uniform(0, step); ys = np.arange(-1.6, 1.6, step) + rng.uniform(0, step)
    X, Y = np.meshgrid(xs, ys, indexing="ij"); F = f(X, Y)
    P, R = marching_squares(F - 0.5 * F.max(), xs, ys)
    used = sorted({i for r in R for i in r}); remap = {o: k for k, o in enumerate(used)}
    P = P[used]; R = [[remap[i] for i in r] for r in R]
    perm = rng.permutation(len(P)); inv = np.argsort(perm)
    return P[perm], [[int(inv[i]) for i in r] for r in R]


def smallest_gap(P, R):
    """The smallest distance between two true rings (point to edge), in their median edge lengths."""
    best = np.inf
    for i in range(len(R)):
        for j in range(i + 1, len(R)):
            A, B = P[R[i]], P[R[j]]
            e = np.concatenate([np.linalg.norm(np.roll(A, -1, 0) - A, axis=1), np.linalg.norm(np.roll(B, -1, 0) - B, axis=1)])
            for X, Y in ((A, B), (B, A)):
                a, b = Y, np.roll(Y, -1, 0); ab = b - a
                t = np.clip(np.einsum("pkd,kd->pk", X[:, None, :] - a[None], ab) / np.maximum((ab * ab).sum(1), 1e-300), 0, 1)
                d = np.linalg.norm(X[:, None, :] - (a[None] + t[..., None] * ab[None]), axis=2).min()
                best = min(best, d / np.median(e))
    return best


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build-bench"
    out = sys.argv[2] if len(sys.argv) > 2 else "out/contours2"
    steps = [float(x) for x in sys.argv[3].split(",")] if len(sys.argv) > 3 and sys.argv[3] else [0.05, 0.03, 0.02, 0.08, 0.1, 0.12]
    seeds = int(sys.argv[4]) if len(sys.argv) > 4 else 40
    cli = os.path.join(build, "cli", "constrict")
    os.makedirs(out, exist_ok=True)
    right = total = 0
    for step in steps:
        ok = 0
        for seed in range(1, seeds + 1):
            P, R = make(seed, step)
            base = os.path.join(out, f"c_{step}_{seed}")
            np.savetxt(base + ".xy", P, fmt="%.17g")
            run = subprocess.run([cli, "reconstruct", base + ".xy", "--topology", "auto", "-o", base + ".rings", "-q"],
                                 capture_output=True, text=True)
            got = []
            if run.returncode == 0:
                got = sorted(tuple(sorted(map(int, l.split()[1:]))) for l in open(base + ".rings") if l.startswith("c "))
            truth = sorted(tuple(sorted(r)) for r in R)
            if got == truth:
                ok += 1
            else:
                print(f"step {step} seed {seed}: truth {len(truth)} rings {[len(r) for r in truth]}, got {len(got)} "
                      f"{[len(r) for r in got]}; smallest true gap {smallest_gap(P, R):.2f} spacings"
                      + (f"; exit {run.returncode}: {run.stderr.strip()}" if run.returncode else ""), flush=True)
        print(f"step {step}: {ok} of {seeds} right", flush=True)
        right += ok; total += seeds
    print(f"{right} of {total} right")


if __name__ == "__main__":
    main()
