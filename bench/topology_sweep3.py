#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Topology sweep in 3D (issue 16; docs/topology.md, Limits): new blue-noise samples of the shared
topology families (torus, chain of 2-3 tangent rings, 2-3 separate spheres, a hollow ball, two
linked tori) at 600 to 20 000 points, 3 seeds each, run through `constrict reconstruct --topology
auto`; the number of surfaces and the total genus are compared with the truth. The samples follow
../shared/data/topology/README.md (blue noise, random rotation, scale and offset, shuffled) but
are not those files: this measures other sets of the same kinds. Each set also gets the size of its
feature (tube radius, shell thickness, smallest gap) in units of its Poisson-disk radius (the
smallest distance between two samples before scaling), which is where the sparse cases fail.

Usage: bench/topology_sweep3.py [BUILD_DIR (build-bench)] [OUT (out/topology_sweep3)] [N,N,... (all)] [SEED (31337)]
Writes OUT/data/*.xyz, OUT/out/*.json and OUT/table.md. Needs numpy (python3-numpy)."""
import json, math, os, subprocess, sys

import numpy as np

FAMS = ["torus", "chain", "spheres", "hollow", "links"]
NS = [600, 1000, 1500, 3000, 8000, 20000]
REPS = 3
OVERSAMPLE = 12

# ---------- uniform-area samplers ----------
def sample_torus(rng, m, R, r):
    """m uniform-area points on torus (core circle radius R in xy-plane, tube r)."""
    out = []
    got = 0
    while got < m:
        k = int((m - got) * 1.3) + 16
        u = rng.uniform(0, 2 * np.pi, k)
        v = rng.uniform(0, 2 * np.pi, k)
        acc = rng.uniform(0, 1, k) < (R + r * np.cos(v)) / (R + r)
        u, v = u[acc], v[acc]
        p = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], 1)
        out.append(p); got += len(p)
    return np.concatenate(out)[:m]

def sample_sphere(rng, m, c, rad):
    g = rng.normal(size=(m, 3))
    g /= np.linalg.norm(g, axis=1)[:, None]
    return np.asarray(c)[None, :] + rad * g

def dist_to_circle(p, center, normal_axis_rot, R):
    """distance from points p to circle of radius R; circle = rot applied to xy-plane circle, then + center.
    normal_axis_rot: 3x3 rotation mapping local->world."""
    q = (p - center) @ normal_axis_rot  # world->local
    rho = np.hypot(q[:, 0], q[:, 1])
    return np.hypot(rho - R, q[:, 2])

# ---------- Poisson-disk thinning ----------
def poisson_thin(pts, d):
    """greedy thinning in the given (already random) order with a 3D hash grid, min dist d."""
    inv = 1.0 / d
    cells = np.floor(pts * inv).astype(np.int64)
    grid = {}
    keep = []
    d2 = d * d
    offs = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    P = pts.tolist()
    C = cells.tolist()
    for i in range(len(P)):
        cx, cy, cz = C[i]
        px, py, pz = P[i]
        ok = True
        for a, b, c in offs:
            lst = grid.get((cx + a, cy + b, cz + c))
            if lst:
                for j in lst:
                    qx, qy, qz = P[j]
                    if (px - qx) ** 2 + (py - qy) ** 2 + (pz - qz) ** 2 < d2:
                        ok = False; break
                if not ok: break
        if ok:
            keep.append(i)
            grid.setdefault((cx, cy, cz), []).append(i)
    return np.array(keep, dtype=np.int64)

def blue_noise(rng, cand, area, N):
    """cand: uniform-area candidates (shuffled here). Radius from area, corrected up to 3 times."""
    cand = cand[rng.permutation(len(cand))]
    d = math.sqrt(0.66 * area / N)
    best = None
    for it in range(4):
        keep = poisson_thin(cand, d)
        n = len(keep)
        if best is None or abs(n - N) < abs(len(best[0]) - N):
            best = (keep, d)
        if abs(n - N) <= 0.02 * N:
            break
        d *= math.sqrt(n / N)
    keep, d = best
    return cand[keep], d

# ---------- families ----------
def make_surface(fam, rng, N):
    """returns (candidates, area_estimate, labels(per candidate surface id), params, truth)"""
    M = OVERSAMPLE * N
    if fam == "torus":
        R, r = 1.0, float(rng.uniform(0.25, 0.45))
        cand = sample_torus(rng, M, R, r)
        return cand, 4 * np.pi ** 2 * R * r, np.zeros(len(cand), int), dict(R=R, r=r), (1, 1)
    if fam == "chain":
        R, r = 1.0, float(rng.uniform(0.22, 0.3))
        k = int(rng.integers(2, 4))
        A1 = 4 * np.pi ** 2 * R * r
        Mtot = int(M * 1.25)  # extra to compensate trimmed parts
        parts = []
        centers = [np.array([2 * R * i, 0.0, 0.0]) for i in range(k)]
        for i in range(k):
            parts.append(sample_torus(rng, Mtot // k, R, r) + centers[i])
        allc = np.concatenate(parts)
        lab = np.repeat(np.arange(k), Mtot // k)
        keepmask = np.ones(len(allc), bool)
        for i in range(k):
            sel = lab == i
            for j in range(k):
                if j == i: continue
                dj = dist_to_circle(allc[sel], centers[j], np.eye(3), R)
                inside = dj < r
                idx = np.where(sel)[0]
                keepmask[idx[inside]] = False
        area = k * A1 * keepmask.mean()
        return allc[keepmask], area, lab[keepmask], dict(R=R, r=r, k=k), (1, k)
    if fam == "spheres":
        k = int(rng.integers(2, 4))
        radii = rng.uniform(0.6, 1.0, k)
        while True:
            centers = [np.zeros(3)]
            gaps = []
            ok = True
            for i in range(1, k):
                g = float(rng.uniform(0.3, 1.0))
                dvec = rng.normal(size=3); dvec /= np.linalg.norm(dvec)
                c = centers[-1] + dvec * (radii[i - 1] + g + radii[i])
                for j in range(i - 1):
                    if np.linalg.norm(c - centers[j]) - radii[i] - radii[j] < 0.3:
                        ok = False
                centers.append(c); gaps.append(g)
            if ok: break
        areas = 4 * np.pi * radii ** 2
        cnt = rng.multinomial(M, areas / areas.sum())
        cand = np.concatenate([sample_sphere(rng, cnt[i], centers[i], radii[i]) for i in range(k)])
        lab = np.repeat(np.arange(k), cnt)
        min_gap = min(float(np.linalg.norm(centers[i] - centers[j])) - radii[i] - radii[j]
                      for i in range(k) for j in range(i + 1, k))
        return cand, areas.sum(), lab, dict(k=k, radii=[round(float(x), 4) for x in radii],
                                             gaps=[round(x, 4) for x in gaps], min_gap=min_gap), (k, 0)
    if fam == "hollow":
        rin = float(rng.uniform(0.65, 0.75))
        radii = np.array([1.0, rin])
        areas = 4 * np.pi * radii ** 2
        cnt = rng.multinomial(M, areas / areas.sum())
        cand = np.concatenate([sample_sphere(rng, cnt[i], np.zeros(3), radii[i]) for i in range(2)])
        lab = np.repeat(np.arange(2), cnt)
        return cand, areas.sum(), lab, dict(r_out=1.0, r_in=rin), (2, 0)
    if fam == "links":
        R, r = 1.0, float(rng.uniform(0.2, 0.3))
        a = sample_torus(rng, M // 2, R, r)
        b = sample_torus(rng, M - M // 2, R, r)
        Rx = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], float)  # 90 deg about x
        b = b @ Rx.T + np.array([R, 0, 0])
        cand = np.concatenate([a, b])
        lab = np.repeat([0, 1], [len(a), len(b)])
        return cand, 2 * 4 * np.pi ** 2 * R * r, lab, dict(R=R, r=r), (2, 2)
    raise ValueError(fam)

def random_rotation(rng):
    Q, Rm = np.linalg.qr(rng.normal(size=(3, 3)))
    Q = Q * np.sign(np.diag(Rm))[None, :]
    if np.linalg.det(Q) < 0:
        Q[:, 0] = -Q[:, 0]
    return Q


def feature(fam, params):
    if fam in ("torus", "chain"):
        return params["r"], "tube radius"
    if fam == "links":
        return min(params["r"], 1 - 2 * params["r"]), "min(tube radius, gap)"
    if fam == "hollow":
        return 1 - params["r_in"], "shell thickness"
    return params["min_gap"], "smallest gap"


def prepare(build, out):
    """The CLI of the build (exits when it is missing) and the output folders OUT/data, OUT/out."""
    cli = os.path.join(build, "cli", "constrict")
    if not os.access(cli, os.X_OK):
        sys.exit(f"missing {cli}: run make bench (or give the build directory)")
    os.makedirs(os.path.join(out, "data"), exist_ok=True)
    os.makedirs(os.path.join(out, "out"), exist_ok=True)
    return cli


def args(default_out, default_ns):
    """The sweeps' command line: [BUILD_DIR (build-bench)] [OUT (default_out)] [N,N,... (default_ns)];
    returns the CLI (prepare()), OUT and the sizes."""
    build = sys.argv[1] if len(sys.argv) > 1 else "build-bench"
    out = sys.argv[2] if len(sys.argv) > 2 else default_out
    ns = [int(x) for x in sys.argv[3].split(",")] if len(sys.argv) > 3 and sys.argv[3] else list(default_ns)
    return prepare(build, out), out, ns


def main():
    cli, out, ns = args("out/topology_sweep3", NS)
    seed = int(sys.argv[4]) if len(sys.argv) > 4 else 31337
    rows = []
    for fi, fam in enumerate(FAMS):
        for N in ns:
            for rep in range(REPS):
                rng = np.random.default_rng([fi, N, rep, seed])
                cand, area, _, params, truth = make_surface(fam, rng, N)
                pts, d = blue_noise(rng, cand, area, N)
                Q = random_rotation(rng)
                s = float(math.exp(rng.uniform(-2, 2)))
                pts = (pts @ Q.T) * s + rng.uniform(-100, 100, 3)
                pts = pts[rng.permutation(len(pts))]
                name = f"{fam}_N{N}_s{rep}"
                path = os.path.join(out, "data", name + ".xyz")
                with open(path, "w") as f:
                    f.write("".join(f"{float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in pts))
                rep_path = os.path.join(out, "out", name + ".json")
                p = subprocess.run([cli, "reconstruct", path, "-o", os.path.join(out, "out", name + ".off"),
                                    "--topology", "auto", "--report", rep_path, "-q"], capture_output=True, text=True)
                r = json.load(open(rep_path)) if p.returncode == 0 else {}
                got = (r.get("components"), r.get("genus"))
                size, what = feature(fam, params)
                rows.append((fam, N, rep, len(pts), truth, got, (r.get("topology") or {}).get("decision"),
                             size / d, what, p.returncode, p.stderr.strip()))
                ok = p.returncode == 0 and got == truth
                print(f"{name}: {len(pts)} points, truth {truth}, got {got}, {what} {size / d:.2f} radii"
                      f"{'' if ok else '  WRONG'}", flush=True)
    lines = ["| family | " + " | ".join(map(str, ns)) + " | all |", "|---" * (len(ns) + 2) + "|"]
    for fam in FAMS:
        cells, tot = [], [0, 0]
        for N in ns:
            sel = [r for r in rows if r[0] == fam and r[1] == N]
            k = sum(r[9] == 0 and r[4] == r[5] for r in sel)
            cells.append(f"{k}/{len(sel)}")
            tot[0] += k
            tot[1] += len(sel)
        lines.append(f"| {fam} | " + " | ".join(cells) + f" | {tot[0]}/{tot[1]} |")
    right = sum(r[9] == 0 and r[4] == r[5] for r in rows)
    lines += ["", f"{right} of {len(rows)} right (surfaces, total genus).", "",
              "| wrong set | points | truth (surfaces, genus) | result | decision | feature / Poisson radius |",
              "|---|---|---|---|---|---|"]
    for r in rows:
        if not (r[9] == 0 and r[4] == r[5]):
            lines.append(f"| {r[0]}_N{r[1]}_s{r[2]} | {r[3]} | {r[4]} | {r[5]} | {r[6]} | {r[8]} {r[7]:.2f}"
                         + (f" (exit {r[9]}: {r[10]})" if r[9] else "") + " |")
    ok_sizes = {}
    for r in rows:
        if r[9] == 0 and r[4] == r[5]:
            ok_sizes.setdefault(r[0], []).append(r[7])
    lines += ["", "Smallest feature / Poisson radius among the right sets: " +
              ", ".join(f"{f} {min(v):.2f}" for f, v in ok_sizes.items())]
    open(os.path.join(out, "table.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
