#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""2D topology on archipelagos (issue 16; docs/topology.md, "Archipelagos"): 25 small islands on a
5 x 5 grid, each an m-gon of 3-16 points (regular; jittered angles; or sorted uniform angles),
stretched up to 1.6:1 and rotated, 0.05 noise; GAP mean edges between islands; alone and inside a
lake ring. Each set is run through `constrict reconstruct --topology auto` and its rings' point
sets are compared with the islands'.

Usage: bench/islands2_sweep.py [BUILD_DIR (build-bench)] [OUT (out/islands2)] [SEEDS (2)]
Needs numpy (python3-numpy). About a minute."""
import math, os, subprocess, sys

import numpy as np
def island(rng, m, kind):
    r = 0.5 / math.sin(math.pi / m)
    if kind == "regular": a = 2 * math.pi * np.arange(m) / m
    elif kind == "jitter": a = 2 * math.pi * (np.arange(m) + rng.uniform(-0.35, 0.35, m)) / m
    else: a = np.sort(rng.random(m)) * 2 * math.pi
    a = a + rng.random() * 2 * math.pi
    e = rng.uniform(1.0, 1.6) if kind != "regular" else 1.0  # ellipse stretch
    P = np.c_[r * e * np.cos(a), r / e * np.sin(a)] + rng.normal(scale=0.05, size=(m, 2))
    th = rng.random() * 2 * math.pi
    R = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    return P @ R.T

def make(rng, kind, gap, mmin, mmax, nx, lake):
    pts, rings = [], []
    isl = [island(rng, int(rng.integers(mmin, mmax + 1)), kind) for _ in range(nx * nx)]
    rad = max(np.max(np.linalg.norm(P, axis=1)) for P in isl)
    D = 2 * rad + gap
    for k, P in enumerate(isl):
        i, j = divmod(k, nx)
        c = np.array([i * D, j * D])
        rings.append(list(range(len(pts), len(pts) + len(P)))); pts.extend(P + c)
    if lake:
        cx = (nx - 1) * D / 2; R = cx * math.sqrt(2) + rad + gap + 2
        n = int(2 * math.pi * R)
        t = 2 * math.pi * (np.arange(n) + rng.uniform(-0.2, 0.2, n)) / n
        rings.append(list(range(len(pts), len(pts) + n)))
        pts.extend(np.c_[cx + R * np.cos(t), cx + R * np.sin(t)])
    pts = np.array(pts)
    perm = rng.permutation(len(pts)); inv = np.empty_like(perm); inv[perm] = np.arange(len(pts))
    return pts[perm], [sorted(int(inv[i]) for i in r) for r in rings]

def main():
  build = sys.argv[1] if len(sys.argv) > 1 else "build-bench"
  out = sys.argv[2] if len(sys.argv) > 2 else "out/islands2"
  seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 2
  cli = os.path.join(build, "cli", "constrict")
  os.makedirs(out, exist_ok=True)
  res = {}
  for kind in ("regular", "jitter", "random"):
    for gap in (3, 4, 6, 8, 12):
      for (mmin, mmax) in ((3, 6), (5, 10), (8, 16)):
        for lake in (0, 1):
          for seed in range(1, seeds + 1):
            rng = np.random.default_rng(seed * 1000 + gap * 10 + mmin + 100000 * lake + {"regular": 0, "jitter": 1, "random": 2}[kind] * 7777)
            P, R = make(rng, kind, gap, mmin, mmax, 5, lake)
            name = f"{kind}_g{gap}_m{mmin}-{mmax}_l{lake}_s{seed}"
            base = os.path.join(out, name)
            np.savetxt(base + ".xy", P, fmt="%.17g")
            r = subprocess.run([cli, "reconstruct", base + ".xy", "--topology", "auto", "-o", base + ".rings", "-q"], capture_output=True, text=True)
            ok = False; ng = -1
            if r.returncode == 0:
              got = sorted(tuple(sorted(map(int, l.split()[1:]))) for l in open(base + ".rings") if l.startswith("c "))
              ng = len(got); ok = got == sorted(tuple(x) for x in R)
            key = (kind, gap, f"{mmin}-{mmax}")
            res.setdefault(key, [0, 0]); res[key][0] += ok; res[key][1] += 1
            print(name, "ok" if ok else f"WRONG truth {len(R)} got {ng} rc {r.returncode}", flush=True)
  tot = [0, 0]
  for k, v in sorted(res.items()):
    print(k, f"{v[0]}/{v[1]}"); tot[0] += v[0]; tot[1] += v[1]
  print("total", tot)


if __name__ == "__main__":
  main()
