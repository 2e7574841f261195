#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Parts of one object that nearly touch, sampled unevenly (issue 17): a genus-0 object whose parts
face each other across a gap of g local spacings, reconstructed by ours (default single mode: no
bridge across the gap is wanted) and by the advancing-front peer, both measured against the exact
surface. The other near-parts families (near_parts3.py, apart_parts3.py) are uniform blue noise;
real scans and decimated meshes are not: their spacing varies over the surface, comes in scan rows
or carries noise, and the gap is then a few spacings on one side and fewer on the other.

Shapes (smooth unions of exact distance primitives; all genus 0, one surface):
  figure   torso, neck, head and legs; two arms hanging beside the torso at the gap
  ears     a rounded-box head with flat cheeks and a neck; two flat ear plates (0.16 thick) hanging
           beside the cheeks at the gap
  hook     a tube (radius 0.15) up, over, down and curling back so that its tip faces the stem
  fingers  palm, wrist and four parallel fingers (radius 0.1), neighbours at the gap
Sampling modes (N points; seeded numpy generators, so the sets are the same on every run):
  curv     variable-radius blue noise, spacing ~ curvedness^-1/2 (density factor up to 5)
  field    the same with a smooth random spacing field (6 cosine waves; density factor 5)
  rows     scan rows: parallel planes in a random direction, along-row step = row distance / 3
  curv_n, field_n, rows_n   the same plus Gaussian noise along the normal, sigma 0.15 local spacing
The gap is g local spacings at the gap (mean over the two facing sides), g = 1.5, 2, 3, 4; the table
also gives g_nn, the gap over the measured median nearest-neighbour distance of the facing samples.
Each set is rotated at random and shuffled.

Measured: the symmetric Hausdorff distance to the truth in % of its bounding-box diagonal, for ours
and the peer, and their ratio (result -> truth on a grid of points on every triangle against a dense
truth sample; truth -> result from 8 N truth points to the nearest triangles); our report's bridge
faces; cross-gap faces (a face with vertices on both parts of a facing pair and a point farther than
0.3 gap from the truth), ours and the peer's; whether the peer is closed (no boundary or
non-manifold edge); where each result's worst point is (out: the surface leaves the truth; miss:
the truth is far from the surface; pN: the part; gap: within 2 gaps of the facing part).
Found to date (N = 5 000 and 20 000, seeds 1 and 2): the worst case is the ears with field_n sampling
at g = 1.5, ours 2.3-3.3x the peer on three of its four sets, a fold of our surface into the thin ear
plate. With rows sampling (rows and rows_n) the peer is open on every set and ours is closer (median
ratio about 0.5).

Usage: bench/uneven_parts3.py [BUILD_DIR (build-bench)] [OUT (out/uneven_parts3)] [--n 5000]
         [--seeds 1,2] [--shapes figure,ears,hook,fingers] [--modes field,field_n,curv,rows]
         [--gaps 1.5,2,3,4] [--table]   (--table: only rebuild OUT/table.md from OUT/rows.jsonl)
Writes OUT/data/*.xyz and *.meta.json (kept: a second run with another build reads the same sets),
OUT/out/* (ours .off and report .json, the peer's .afsr.off), OUT/rows.jsonl and OUT/table.md
(sorted by ratio, worst first). Uses BUILD_DIR/cli/constrict and BUILD_DIR/bench/constrict_afsr.
Needs numpy. About 15 minutes for the default 128 sets (about 8 once the sets exist)."""
import importlib.util
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("topology_sweep3", os.path.join(_here, "topology_sweep3.py"))
ts = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ts)

SHAPES = ("figure", "ears", "hook", "fingers")
MODES = ("curv", "field", "rows", "curv_n", "field_n", "rows_n")  # (the indices seed the sets)
DEFAULTS = dict(n="5000", seeds="1,2", shapes=",".join(SHAPES), modes="field,field_n,curv,rows", gaps="1.5,2,3,4")
SMAX = math.sqrt(5.0)  # spacing factor sparse / dense: density factor 5
NOISE = 0.15  # normal noise of the _n modes, in local spacings
TIMEOUT = 120  # seconds per reconstruction


# ---------------- distance primitives (exact) ----------------
def d_capsule(p, a, b, r):
    a, b = np.asarray(a, float), np.asarray(b, float)
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0, 1)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1) - r


def d_sphere(p, c, r):
    return np.linalg.norm(p - np.asarray(c, float), axis=1) - r


def d_rbox(p, c, half, rr):
    q = np.abs(p - np.asarray(c, float)) - (np.asarray(half, float) - rr)
    return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0) - rr


def d_arc(p, c, u, v, R, a0, a1, r):
    """Tube of radius r around the arc c + R (cos t u + sin t v), t in [a0, a1] (a0 < a1)."""
    c, u, v = (np.asarray(x, float) for x in (c, u, v))
    n = np.cross(u, v)
    q = p - c
    x, y, z = q @ u, q @ v, q @ n
    rel = (np.arctan2(y, x) - 0.5 * (a0 + a1) + math.pi) % (2 * math.pi) - math.pi  # from the arc's middle
    inside = np.abs(rel) <= 0.5 * (a1 - a0)
    d_in = np.hypot(np.hypot(x, y) - R, z)
    e0 = c + R * (math.cos(a0) * u + math.sin(a0) * v)
    e1 = c + R * (math.cos(a1) * u + math.sin(a1) * v)
    d_end = np.minimum(np.linalg.norm(p - e0, axis=1), np.linalg.norm(p - e1, axis=1))
    return np.where(inside, d_in, d_end) - r


def smin(a, b, k):
    if k <= 0:
        return np.minimum(a, b)
    h = np.maximum(k - np.abs(a - b), 0) / k
    return np.minimum(a, b) - h * h * k * 0.25


def prim_distance(pr, p):
    kind, prm, _ = pr
    return {"capsule": d_capsule, "sphere": d_sphere, "rbox": d_rbox, "arc": d_arc}[kind](p, *prm)


# ---------------- area-uniform samples of the primitives' surfaces ----------------
def _unit(rng, m):
    g = rng.normal(size=(m, 3))
    return g / np.linalg.norm(g, axis=1)[:, None]


def _perp(d):
    a = np.array([1.0, 0, 0]) if abs(d[0]) < 0.9 else np.array([0, 1.0, 0])
    e1 = np.cross(d, a)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


def area_of(kind, prm):
    if kind == "capsule":
        a, b, r = prm
        return 2 * math.pi * r * np.linalg.norm(np.subtract(b, a)) + 4 * math.pi * r * r
    if kind == "sphere":
        return 4 * math.pi * prm[1] ** 2
    if kind == "rbox":
        c, half, rr = prm
        e = np.asarray(half, float) - rr
        return 8 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2]) + 2 * math.pi * rr * 2 * e.sum() + 4 * math.pi * rr * rr
    c, u, v, R, a0, a1, r = prm  # arc
    return 2 * math.pi * r * R * (a1 - a0)


def sample_prim(rng, kind, prm, rho):
    """About rho * area points uniform on the primitive's own surface."""
    m = max(1, rng.poisson(rho * area_of(kind, prm)))
    if kind == "sphere":
        return np.asarray(prm[0]) + prm[1] * _unit(rng, m)
    if kind == "capsule":
        a, b, r = (np.asarray(prm[0], float), np.asarray(prm[1], float), prm[2])
        L = np.linalg.norm(b - a)
        d = (b - a) / L
        e1, e2 = _perp(d)
        mc = rng.binomial(m, 2 * math.pi * r * L / area_of(kind, prm))
        t = rng.uniform(0, L, mc)
        th = rng.uniform(0, 2 * math.pi, mc)
        cyl = a + t[:, None] * d + r * (np.cos(th)[:, None] * e1 + np.sin(th)[:, None] * e2)
        s = _unit(rng, m - mc)
        caps = np.where(((s @ d) < 0)[:, None], a + r * s, b + r * s)
        return np.vstack([cyl, caps])
    if kind == "rbox":
        c, half, rr = np.asarray(prm[0], float), np.asarray(prm[1], float), prm[2]
        e = half - rr
        A = area_of(kind, prm)
        fa = 8 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2]) / A
        ea = 2 * math.pi * rr * 2 * e.sum() / A
        cnt = rng.multinomial(m, [fa, ea, 1 - fa - ea])
        fw = np.array([e[1] * e[2], e[0] * e[2], e[0] * e[1]])  # flat faces
        ax = rng.choice(3, cnt[0], p=fw / fw.sum())
        faces = rng.uniform(-1, 1, (cnt[0], 3)) * e
        faces[np.arange(cnt[0]), ax] = rng.choice([-1.0, 1.0], cnt[0]) * (e[ax] + rr)
        ax = rng.choice(3, cnt[1], p=e / e.sum())  # edges: quarter cylinders along axis i
        edges = np.zeros((cnt[1], 3))
        th = rng.uniform(0, math.pi / 2, cnt[1])
        for i in range(3):
            sel = ax == i
            j, k = [x for x in range(3) if x != i]
            ns = sel.sum()
            edges[sel, i] = rng.uniform(-e[i], e[i], ns)
            sj, sk = rng.choice([-1.0, 1.0], ns), rng.choice([-1.0, 1.0], ns)
            edges[sel, j] = sj * (e[j] + rr * np.cos(th[sel]))
            edges[sel, k] = sk * (e[k] + rr * np.sin(th[sel]))
        s = _unit(rng, cnt[2])  # corners
        return c + np.vstack([faces, edges, np.sign(s) * e + rr * s])
    c, u, v, R, a0, a1, r = prm  # arc
    c, u, v = (np.asarray(x, float) for x in (c, u, v))
    n = np.cross(u, v)
    got, out = 0, []
    while got < m:
        k = int((m - got) * 1.4) + 16
        t = rng.uniform(a0, a1, k)
        w = rng.uniform(0, 2 * math.pi, k)
        acc = rng.uniform(0, 1, k) < (R + r * np.cos(w)) / (R + r)
        t, w = t[acc], w[acc]
        radial = np.cos(t)[:, None] * u + np.sin(t)[:, None] * v
        out.append(c + (R + r * np.cos(w))[:, None] * radial + (r * np.sin(w))[:, None] * n)
        got += len(out[-1])
    return np.vstack(out)[:m]


# ---------------- shapes ----------------
class Shape:
    """The shape `name` built for a gap width `gap`: F (signed distance, smooth unions at the joints),
    parts (distance to each part), pairs (the parts facing each other across the gap), prims
    ((kind, params, part) for the candidate samples) and kblend (the largest smooth-min radius)."""

    def __init__(self, name, gap):
        getattr(self, "_" + name)(gap)

    def _figure(self, gap):
        ra, rt, k = 0.12, 0.45, 0.08
        xa = rt + gap + ra
        P = [("capsule", ((0, 0, -0.3), (0, 0, 0.55), rt), 0),  # torso
             ("capsule", ((0, 0, 0.8), (0, 0, 1.1), 0.13), 0),  # neck
             ("sphere", ((0, 0, 1.3), 0.3), 0),  # head
             ("capsule", ((0.25, 0, -0.6), (0.5, 0, -1.6), 0.16), 0),  # legs
             ("capsule", ((-0.25, 0, -0.6), (-0.5, 0, -1.6), 0.16), 0),
             ("capsule", ((0.25, 0, 0.75), (xa, 0, 0.75), ra), 3),  # shoulders
             ("capsule", ((-0.25, 0, 0.75), (-xa, 0, 0.75), ra), 4),
             ("capsule", ((xa, 0, 0.75), (xa, 0, -0.5), ra), 1),  # hanging arms
             ("capsule", ((-xa, 0, 0.75), (-xa, 0, -0.5), ra), 2)]
        self.prims, self.kblend, self.pairs, self.nparts = P, k, [(0, 1), (0, 2)], 5

        def F(p):
            d = [prim_distance(pr, p) for pr in P]
            T = d[0]
            for i in (1, 2, 3, 4):
                T = smin(T, d[i], k)
            T = smin(smin(T, d[5], k), d[6], k)
            return np.minimum(T, np.minimum(d[7], d[8]))
        self.F = F

    def _ears(self, gap):
        te, k = 0.08, 0.06
        xe = 0.55 + gap + te
        P = [("rbox", ((0, 0, 0), (0.55, 0.7, 0.75), 0.3), 0),  # head
             ("capsule", ((0, 0, -0.6), (0, 0, -1.3), 0.3), 0),  # neck
             ("capsule", ((0.35, 0, 0.55), (xe, 0, 0.3), 0.06), 3),  # ear stalks
             ("capsule", ((-0.35, 0, 0.55), (-xe, 0, 0.3), 0.06), 4),
             ("rbox", ((xe, 0, -0.05), (te, 0.32, 0.4), 0.07), 1),  # ear plates
             ("rbox", ((-xe, 0, -0.05), (te, 0.32, 0.4), 0.07), 2)]
        self.prims, self.kblend, self.pairs, self.nparts = P, k, [(0, 1), (0, 2)], 5

        def F(p):
            d = [prim_distance(pr, p) for pr in P]
            A = smin(smin(smin(d[0], d[1], k), d[2], k), d[3], k)
            return np.minimum(A, np.minimum(smin(d[2], d[4], k), smin(d[3], d[5], k)))
        self.F = F

    def _hook(self, gap):
        r = 0.15
        P = [("capsule", ((0, 0, -1.2), (0, 0, 0.6), r), 0),  # stem
             ("arc", ((0.55, 0, 0.6), (1, 0, 0), (0, 0, 1), 0.55, 0.0, math.pi, r), 2),  # over the top
             ("capsule", ((1.1, 0, 0.6), (1.1, 0, -0.35), r), 2),  # down
             ("arc", ((0.75, 0, -0.35), (1, 0, 0), (0, 0, 1), 0.35, -math.pi / 2, 0.0, r), 1),  # curl
             ("capsule", ((0.75, 0, -0.7), (2 * r + gap, 0, -0.7), r), 1)]  # tip, facing the stem
        self.prims, self.kblend, self.pairs, self.nparts = P, 0.0, [(0, 1)], 3

        def F(p):
            return np.min(np.stack([prim_distance(pr, p) for pr in P]), axis=0)
        self.F = F

    def _fingers(self, gap):
        rf, k = 0.1, 0.06
        pitch = 2 * rf + gap
        hx = max(0.5, 1.5 * pitch + rf + 0.06)
        P = [("rbox", ((0, 0, 0), (hx, 0.14, 0.45), 0.12), 0),  # palm
             ("capsule", ((0, 0, 0.3), (0, 0, 1.0), 0.25), 0)]  # wrist
        for i, length in enumerate((0.8, 0.95, 0.9, 0.7)):
            x = (i - 1.5) * pitch
            P.append(("capsule", ((x, 0, -0.3), (x, 0, -0.3 - length), rf), 1 + i))
        self.prims, self.kblend, self.pairs, self.nparts = P, k, [(1, 2), (2, 3), (3, 4)], 5

        def F(p):
            d = [prim_distance(pr, p) for pr in P]
            Pm = smin(d[0], d[1], k)
            return np.min(np.stack([smin(Pm, d[2 + i], k) for i in range(4)]), axis=0)
        self.F = F

    def parts(self, p):
        D = np.full((len(p), self.nparts), np.inf)
        for pr in self.prims:
            D[:, pr[2]] = np.minimum(D[:, pr[2]], prim_distance(pr, p))
        return D

    def grad(self, p, eps=1e-5):
        g = np.empty_like(p)
        for i in range(3):
            e = np.zeros(3)
            e[i] = eps
            g[:, i] = (self.F(p + e) - self.F(p - e)) / (2 * eps)
        return g

    def project(self, p, iters=6):
        p = p.copy()
        for _ in range(iters):
            f = self.F(p)
            mv = np.abs(f) > 1e-10
            if not mv.any():
                break
            g = self.grad(p[mv])
            p[mv] -= (f[mv] / np.maximum((g * g).sum(1), 1e-12))[:, None] * g
        return p

    def candidates(self, rng, rho):
        """Area-uniform points on F = 0 at about rho per unit area; returns the points and the area."""
        c = np.vstack([sample_prim(rng, kind, prm, rho) for kind, prm, _ in self.prims])
        c = self.project(c[self.F(c) > -(0.3 * self.kblend + 1e-9)])
        c = c[np.abs(self.F(c)) < 1e-7]
        return c, len(c) / rho

    def curvedness(self, p, h=1e-3):
        """sqrt((k1^2 + k2^2) / 2) from the numerical Hessian of F."""
        f0 = self.F(p)
        H = np.empty((len(p), 3, 3))
        E = np.eye(3) * h
        fp = [self.F(p + E[i]) for i in range(3)]
        fm = [self.F(p - E[i]) for i in range(3)]
        for i in range(3):
            H[:, i, i] = (fp[i] - 2 * f0 + fm[i]) / (h * h)
            for j in range(i + 1, 3):
                H[:, i, j] = H[:, j, i] = (self.F(p + E[i] + E[j]) - self.F(p + E[i] - E[j])
                                           - self.F(p - E[i] + E[j]) + self.F(p - E[i] - E[j])) / (4 * h * h)
        g = np.stack([(fp[i] - fm[i]) / (2 * h) for i in range(3)], 1)
        gn = np.linalg.norm(g, axis=1)
        n = g / gn[:, None]
        Pm = np.eye(3)[None] - n[:, :, None] * n[:, None, :]
        ev = np.linalg.eigvalsh(Pm @ H @ Pm / gn[:, None, None])
        ev = np.sort(np.abs(ev), axis=1)[:, 1:]  # drop the normal direction's ~0
        return np.sqrt((ev ** 2).sum(1) / 2)


def unit_normals(sh, p):
    n = sh.grad(p)
    return n / np.linalg.norm(n, axis=1)[:, None]


# ---------------- spacing fields ----------------
def make_field(mode, sh, rng):
    """The relative spacing s(points) in [1, SMAX] of a curv or field mode."""
    probe, _ = sh.candidates(np.random.default_rng(7), 3000 / 10)
    if mode.startswith("field"):
        k = 6
        dirs = rng.normal(size=(k, 3))
        dirs /= np.linalg.norm(dirs, axis=1)[:, None]
        w = dirs * (2 * math.pi / rng.uniform(0.8, 1.6, k))[:, None]
        ph = rng.uniform(0, 2 * math.pi, k)

        def raw(p):
            return np.cos(p @ w.T + ph).sum(1)
        r = raw(probe)  # normalised by its range over a fixed candidate set
        lo, hi = np.percentile(r, 2), np.percentile(r, 98)
        return lambda p: SMAX ** np.clip((raw(p) - lo) / (hi - lo), 0, 1)
    cref = np.percentile(sh.curvedness(probe), 90)
    return lambda p: np.clip(np.sqrt(cref / np.maximum(sh.curvedness(p), 1e-9)), 1, SMAX)


def gap_sides(sh, p, gap, tol=1.3, cosmax=0.8):
    """Per side of each facing pair: the points of that side whose normal faces the partner within tol gaps."""
    D = sh.parts(p)
    lab = D.argmin(1)
    n = unit_normals(sh, p)
    out = []
    for a, b in sh.pairs:
        for side, other in ((a, b), (b, a)):
            m = (lab == side) & (D[:, other] < tol * gap + 1e-4)
            idx = np.nonzero(m)[0]
            if len(idx):
                g = np.empty((len(idx), 3))
                for i in range(3):
                    e = np.zeros(3)
                    e[i] = 1e-5
                    g[:, i] = (sh.parts(p[idx] + e)[:, other] - sh.parts(p[idx] - e)[:, other]) / 2e-5
                g /= np.maximum(np.linalg.norm(g, axis=1), 1e-12)[:, None]
                m[idx] = (n[idx] * g).sum(1) < -cosmax
            out.append(m)
    return out


def side_mean(vals, sides):
    v = [float(np.median(vals[m])) for m in sides if m.sum() >= 3]
    return float(np.mean(v)) if v else float("nan")


# ---------------- samplers ----------------
def poisson_thin_var(pts, rad):
    """Greedy in the given order: reject p if |p - q| < (r_p + r_q) / 2 for a kept q."""
    cells = np.floor(pts / float(rad.max())).astype(np.int64)
    grid = {}
    keep = []
    offs = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    P, C, R = pts.tolist(), cells.tolist(), rad.tolist()
    for i in range(len(P)):
        cx, cy, cz = C[i]
        px, py, pz = P[i]
        ok = True
        for a, b, c in offs:
            for j in grid.get((cx + a, cy + b, cz + c), ()):
                qx, qy, qz = P[j]
                rr = 0.5 * (R[i] + R[j])
                if (px - qx) ** 2 + (py - qy) ** 2 + (pz - qz) ** 2 < rr * rr:
                    ok = False
                    break
            if not ok:
                break
        if ok:
            keep.append(i)
            grid.setdefault((cx, cy, cz), []).append(i)
    return np.array(keep, np.int64)


def thin_to(rng, cand, s, N, rho):
    """Variable-density blue noise of about N points from candidates at rho per area (thinned first to
    density ~ 1/s^2); returns the points, their s and the radius factor d0 (radius d0 s)."""
    keep = rng.uniform(size=len(cand)) < 1.0 / s ** 2
    cand, s = cand[keep], s[keep]
    o = rng.permutation(len(cand))
    cand, s = cand[o], s[o]
    d0 = math.sqrt(0.66 * len(cand) / rho / N)
    best = None
    for _ in range(4):
        k = poisson_thin_var(cand, d0 * s)
        if best is None or abs(len(k) - N) < abs(len(best[0]) - N):
            best = (k, d0)
        if abs(len(k) - N) <= (0.02 if N < 10000 else 0.05) * N:
            break
        d0 *= math.sqrt(len(k) / N)
    k, d0 = best
    return cand[k], s[k], d0


def rows_sample(rng, sh, cand, N, area, udir):
    """Scan rows: the planes udir.x = (i + off) dr; candidates moved along the surface onto the nearest
    plane, then thinned along the rows with step ds = dr / 3. Returns the points, dr and ds."""
    ratio = 3.0
    dr = math.sqrt(ratio * area / N)  # area per point ds dr
    off = rng.uniform(0, 1)
    best = None
    for _ in range(4):
        ds = dr / ratio
        target = (np.round(cand @ udir / dr - off) + off) * dr
        p = cand.copy()
        ok = np.ones(len(p), bool)
        for _ in range(4):
            n = unit_normals(sh, p)
            ut = udir[None, :] - (n @ udir)[:, None] * n
            ut2 = (ut * ut).sum(1)
            step = (target - p @ udir) / np.maximum(ut2, 1e-12)
            ok &= (ut2 > 0.05) & (np.abs(step) < dr)
            p = sh.project(p + np.where(ok, step, 0)[:, None] * ut, 3)
        ok &= (np.abs(p @ udir - target) < 0.02 * dr) & (np.abs(sh.F(p)) < 1e-7)
        pc = p[ok]
        pc = pc[rng.permutation(len(pc))]
        k = ts.poisson_thin(pc, ds)
        if best is None or abs(len(k) - N) < abs(len(best[0]) - N):
            best = (pc[k], dr, ds)
        if abs(len(k) - N) <= (0.02 if N < 10000 else 0.05) * N:
            break
        dr *= math.sqrt(len(k) / N)
    return best


# ---------------- grid nearest neighbours ----------------
_B, _OFF = np.int64(1 << 20), np.int64(1 << 19)
_OFFS = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)], np.int64)


def _keys(c):
    c = c.astype(np.int64) + _OFF
    return (c[:, 0] * _B + c[:, 1]) * _B + c[:, 2]


def _grid(tree, cell):
    tk = _keys(np.floor(tree / cell).astype(np.int64))
    order = np.argsort(tk, kind="stable")
    uk, st, ct = np.unique(tk[order], return_index=True, return_counts=True)
    return order, tree[order], uk, st, ct


def _cell_pairs(grid, qc, o):
    """(query row, sorted tree index) of every tree point in the cell qc + o of each query."""
    _, _, uk, st, ct = grid
    k = _keys(qc + o)
    pos = np.minimum(np.searchsorted(uk, k), len(uk) - 1)
    qi = np.nonzero(uk[pos] == k)[0]
    s, c = st[pos[qi]], ct[pos[qi]]
    seg = np.cumsum(c) - c
    return np.repeat(qi, c), np.repeat(s, c) + (np.arange(int(c.sum())) - np.repeat(seg, c)), qi, c, seg


def nn(tree, q, cell, chunk=20000):
    """The nearest point of tree to each row of q: (distance, index); a grid of cell, then 4x the cell
    for the queries without a point in the 27 cells around."""
    grid = _grid(tree, cell)
    order, ts_ = grid[0], grid[1]
    dist = np.full(len(q), np.inf)
    idx = np.full(len(q), -1, np.int64)
    for s0 in range(0, len(q), chunk):
        qq = q[s0:s0 + chunk]
        qc = np.floor(qq / cell).astype(np.int64)
        bd = np.full(len(qq), np.inf)
        bi = np.full(len(qq), -1, np.int64)
        for o in _OFFS:
            rep, ti, qi, c, seg = _cell_pairs(grid, qc, o)
            if len(qi) == 0:
                continue
            d2 = ((qq[rep] - ts_[ti]) ** 2).sum(1)
            segmin = np.minimum.reduceat(d2, seg)
            ismin = np.nonzero(d2 == np.repeat(segmin, c))[0]
            _, fi = np.unique(rep[ismin], return_index=True)
            pick = ismin[fi]  # one per segment, segments in qi order
            better = segmin < bd[qi]
            bd[qi[better]] = segmin[better]
            bi[qi[better]] = ti[pick[better]]
        dist[s0:s0 + chunk] = np.sqrt(bd)
        idx[s0:s0 + chunk] = np.where(bi >= 0, order[np.maximum(bi, 0)], -1)
    bad = ~(dist <= cell)
    if bad.any():
        dist[bad], idx[bad] = nn(tree, q[bad], cell * 4, chunk)
    return dist, idx


def nn_self(p, cell, chunk=20000):
    """The distance from each point of p to its nearest other point of p within the 27 cells around."""
    grid = _grid(p, cell)
    order, ts_ = grid[0], grid[1]
    dist = np.full(len(p), np.inf)
    qc = np.floor(p / cell).astype(np.int64)
    for s0 in range(0, len(p), chunk):
        qq, qcc = p[s0:s0 + chunk], qc[s0:s0 + chunk]
        pairs = [_cell_pairs(grid, qcc, o)[:2] for o in _OFFS]
        qs, tsx = np.concatenate([x[0] for x in pairs]), np.concatenate([x[1] for x in pairs])
        d2 = ((qq[qs] - ts_[tsx]) ** 2).sum(1)
        d2[order[tsx] == s0 + qs] = np.inf
        np.minimum.at(dist, s0 + qs, np.sqrt(d2))
    return dist


# ---------------- one set ----------------
def generate(shape, mode, N, g, seed):
    """The set (shape, its points in the generator's frame, the rotation Q, info); written as p @ Q.T."""
    rng = np.random.default_rng([SHAPES.index(shape), MODES.index(mode), N, int(g * 10), seed])
    rows = mode.startswith("rows")
    gap = 0.1
    for it in range(3):  # the gap: g local spacings at the gap, fixed on cheap candidate sets
        sh = Shape(shape, gap)
        c, area = sh.candidates(np.random.default_rng([seed, 5, it]), 40000 / 12)
        if rows:
            h_gap = 0.877 * math.sqrt(area / N)  # equivalent isotropic spacing 1.2 sqrt(0.66 area / N)
        else:
            s = make_field(mode, sh, np.random.default_rng([seed, 99]))(c)
            d0 = math.sqrt(0.66 * area * np.mean(1 / s ** 2) / N)
            h_gap = 1.08 * d0 * side_mean(s, gap_sides(sh, c, gap))
        gap = g * h_gap
    sh = Shape(shape, gap)
    info = dict(shape=shape, mode=mode, N=N, g=g, seed=seed, gap=gap)
    if rows:
        cand, area = sh.candidates(rng, 14 * N / area)
        udir = rng.normal(size=3)
        udir /= np.linalg.norm(udir)
        pts, dr, ds = rows_sample(rng, sh, cand, N, area, udir)
        h_loc = np.full(len(pts), 0.877 * math.sqrt(area / len(pts)))
        info.update(dr=dr, ds=ds, udir=udir.tolist(), g_dr=gap / dr)
    else:
        field = make_field(mode, sh, np.random.default_rng([seed, 99]))
        c0, area = sh.candidates(np.random.default_rng([seed, 6]), 20000 / 12)
        rho = 12 * N / (area * float(np.mean(1 / field(c0) ** 2)))  # about 10 candidates per dense disk
        cand, area = sh.candidates(rng, rho)
        pts, s_pts, d0 = thin_to(rng, cand, field(cand), N, rho)
        h_loc = 1.08 * d0 * s_pts
        info.update(d0=d0)
    if mode.endswith("_n"):
        pts = pts + (NOISE * h_loc * rng.normal(size=len(pts)))[:, None] * unit_normals(sh, pts)
    dd = nn_self(pts, 2 * math.sqrt(area / len(pts)))
    info["nn_gap"] = side_mean(dd, gap_sides(sh, pts, gap))  # median NN distance of the facing samples
    info["nn_all"] = float(np.median(dd))
    info["g_nn"] = gap / info["nn_gap"]
    info["area"] = area
    info["n"] = len(pts)
    Q = ts.random_rotation(rng)
    return sh, pts[rng.permutation(len(pts))], Q, info


# ---------------- measurement ----------------
def read_off(path):
    toks = open(path).read().split()
    nv, nf = int(toks[1]), int(toks[2])
    v = np.array(toks[4:4 + 3 * nv], float).reshape(nv, 3)
    f = np.array(toks[4 + 3 * nv:4 + 3 * nv + 4 * nf], float).reshape(nf, 4)[:, 1:4].astype(np.int64)
    return v, f


def edge_stats(f):
    """Boundary edges (one face), non-manifold edges (more than two) and the number of edges."""
    e = np.vstack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    e.sort(1)
    u, c = np.unique(e, axis=0, return_counts=True)
    return int((c == 1).sum()), int((c > 2).sum()), len(u)


def sample_tris(v, f, step):
    """A barycentric grid on every triangle (spacing <= step) and the centroids: points, face ids."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    L = np.max(np.stack([np.linalg.norm(a - b, axis=1), np.linalg.norm(b - c, axis=1),
                         np.linalg.norm(c - a, axis=1)]), axis=0)
    K = np.clip(np.ceil(L / step).astype(int), 2, 300)
    K += K % 2  # even: the edge midpoints are in
    pts, fid = [], []
    for k in np.unique(K):
        sel = np.nonzero(K == k)[0]
        ij = np.array([(i, j) for i in range(k + 1) for j in range(k + 1 - i)], float) / k
        w = np.c_[1 - ij.sum(1), ij]
        P = (w[None, :, 0:1] * a[sel][:, None] + w[None, :, 1:2] * b[sel][:, None]
             + w[None, :, 2:3] * c[sel][:, None])
        pts.append(P.reshape(-1, 3))
        fid.append(np.repeat(sel, len(w)))
    pts.append((a + b + c) / 3)
    fid.append(np.arange(len(f)))
    return np.vstack(pts), np.concatenate(fid)


def point_tri(p, a, b, c):
    """The exact distance from each point p to its triangle (a, b, c), row by row (Ericson's closest point)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    bp = p - b
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    cp = p - c
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    den = va + vb + vc
    den = np.where(np.abs(den) < 1e-300, 1e-300, den)
    res = a + ab * (vb / den)[:, None] + ac * (vc / den)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):  # edges, then vertices
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        res = np.where(m[:, None], a + (d1 / (d1 - d3))[:, None] * ab, res)
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        res = np.where(m[:, None], a + (d2 / (d2 - d6))[:, None] * ac, res)
        m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
        res = np.where(m[:, None], b + ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None] * (c - b), res)
    res = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, res)
    res = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, res)
    res = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, res)
    out = np.linalg.norm(p - res, axis=1)
    corner = np.minimum(np.minimum(np.linalg.norm(p - a, axis=1), np.linalg.norm(p - b, axis=1)),
                        np.linalg.norm(p - c, axis=1))
    return np.where(np.isfinite(out), out, corner)


class Truth:
    """A dense sample of the exact surface (16 N points, at most 320 000) with normals and part labels."""

    def __init__(self, sh, N, info):
        rng = np.random.default_rng(12345)
        c, area = sh.candidates(rng, min(320000, 16 * N) / info["area"])
        self.p, self.n, self.sh = c, unit_normals(sh, c), sh
        self.delta = math.sqrt(area / len(c))
        D = sh.parts(c)
        self.lab = D.argmin(1)
        self.near_other = np.zeros(len(c), bool)  # within 2 gaps of the partner of a facing pair
        for a, b in sh.pairs:
            self.near_other |= (((self.lab == a) & (D[:, b] < 2 * info["gap"]))
                                | ((self.lab == b) & (D[:, a] < 2 * info["gap"])))
        self.diag = float(np.linalg.norm(c.max(0) - c.min(0)))
        self.sub = np.sort(rng.choice(len(c), min(len(c), 8 * N), replace=False))


def measure(off, truth, Q, info, h):
    v, f = read_off(off)
    v = v @ Q  # back to the generator's frame
    nb, nm, ne = edge_stats(f)
    res = dict(faces=len(f), boundary_edges=nb, nonmanifold_edges=nm, euler=len(np.unique(f)) - ne + len(f))
    # result -> truth: normal distance to the nearest truth point, plus the lateral part beyond its spacing
    sp, fid = sample_tris(v, f, h / 2)
    d, i = nn(truth.p, sp, 2 * truth.delta)
    w = sp - truth.p[i]
    dn = np.abs((w * truth.n[i]).sum(1))
    lat = np.sqrt(np.maximum((w * w).sum(1) - dn * dn, 0))
    r2t = np.sqrt(dn * dn + np.maximum(lat - truth.delta, 0) ** 2)
    j = int(np.argmax(r2t))
    res["r2t"] = float(r2t[j])
    res["r2t_at"] = dict(part=int(truth.lab[i[j]]), gap=bool(truth.near_other[i[j]]),
                         p=[round(x, 3) for x in sp[j].tolist()])
    # cross-gap faces: vertices on both parts of a facing pair, and a point off by more than 0.3 gap
    fmax = np.zeros(len(f))
    np.maximum.at(fmax, fid, r2t)
    vl = truth.lab[nn(truth.p, v, 2 * truth.delta)[1]]
    cross = np.zeros(len(f), bool)
    for a, b in truth.sh.pairs:
        cross |= (vl[f] == a).any(1) & (vl[f] == b).any(1)
    res["cross_faces"] = int((cross & (fmax > 0.3 * info["gap"])).sum())
    # truth -> result: to the triangle of the nearest surface sample
    tp = truth.p[truth.sub]
    d2, i2 = nn(sp, tp, h / 2)
    t2r = np.minimum(d2, point_tri(tp, v[f[fid[i2], 0]], v[f[fid[i2], 1]], v[f[fid[i2], 2]]))
    jj = int(np.argmax(t2r))
    j = int(truth.sub[jj])
    res["t2r"] = float(t2r[jj])
    res["t2r_at"] = dict(part=int(truth.lab[j]), gap=bool(truth.near_other[j]),
                         p=[round(x, 3) for x in truth.p[j].tolist()])
    res["haus"] = max(res["r2t"], res["t2r"])
    res["haus_pct"] = 100 * res["haus"] / truth.diag
    return res


def run(cmd):
    """Run cmd (at most TIMEOUT seconds): (exit code or "timeout", seconds)."""
    t = time.time()
    try:
        rc = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT).returncode
    except subprocess.TimeoutExpired:
        rc = "timeout"
    return rc, time.time() - t


def run_one(cli, afsr, out, shape, mode, N, g, seed):
    name = f"{shape}_{mode}_N{N}_g{g:g}_s{seed}"
    path = os.path.join(out, "data", name + ".xyz")
    t0 = time.time()
    if os.path.exists(path) and os.path.exists(path + ".meta.json"):  # (another build on the same sets)
        meta = json.load(open(path + ".meta.json"))
        info, Q = meta["info"], np.array(meta["Q"])
        sh = Shape(shape, info["gap"])
    else:
        sh, pts, Q, info = generate(shape, mode, N, g, seed)
        with open(path, "w") as f:
            f.write("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in (pts @ Q.T).tolist()))
        with open(path + ".meta.json", "w") as f:
            json.dump(dict(Q=Q.tolist(), info=info), f)
    row = dict(name=name, shape=shape, mode=mode, N=N, g=g, seed=seed, info=info, path=path, t_gen=time.time() - t0)
    ours, peer = os.path.join(out, "out", name + ".off"), os.path.join(out, "out", name + ".afsr.off")
    rep = os.path.join(out, "out", name + ".json")
    for x in (ours, peer, rep):
        if os.path.exists(x):
            os.remove(x)
    row["rc_ours"], row["t_ours"] = run([cli, "reconstruct", path, "-o", ours, "-q", "--report", rep])
    row["rc_peer"], row["t_peer"] = run([afsr, path, peer])
    truth = Truth(sh, N, info)
    row["h"] = h = 1.2 * math.sqrt(0.66 * info["area"] / N)
    if row["rc_ours"] == 0 and os.path.exists(rep):
        r = json.load(open(rep))
        row.update(bridges=r.get("bridges"), valid=r.get("valid"), genus=r.get("genus"), closed=r.get("closed"))
        row["ours"] = measure(ours, truth, Q, info, h)
    if row["rc_peer"] == 0 and os.path.exists(peer):
        row["peer"] = measure(peer, truth, Q, info, h)
    row["t_all"] = time.time() - t0
    return row


# ---------------- table ----------------
def hausdorff(r):
    """Ours and the peer's Hausdorff distance in % of the diagonal and their ratio (nan where a run failed)."""
    ho, hp = ((r.get(k) or {}).get("haus_pct", float("nan")) for k in ("ours", "peer"))
    return ho, hp, ho / hp if hp > 0 else float("nan")


def worst(m):
    if not m:
        return "-"
    a, k = (m["r2t_at"], "out") if m["r2t"] >= m["t2r"] else (m["t2r_at"], "miss")
    return f"{k} p{a['part']}{' gap' if a['gap'] else ''}"


def table(out):
    if not os.path.exists(os.path.join(out, "rows.jsonl")):
        sys.exit(f"no {os.path.join(out, 'rows.jsonl')}: run the sets first")
    rows = [json.loads(x) for x in open(os.path.join(out, "rows.jsonl"))]
    rr = []
    for r in rows:
        ho, hp, ratio = hausdorff(r)
        rr.append((ratio, r, ho, hp))
    rr.sort(key=lambda x: -x[0] if x[0] == x[0] else 1e9)
    lines = ["| set | N | g | g_nn | sampling | ours H % | peer H % | ratio | our bridges (report) "
             "| ours cross-gap faces | peer cross-gap faces | peer closed? | ours worst at | peer worst at |",
             "|---" * 14 + "|"]
    for ratio, r, ho, hp in rr:
        o, pe = r.get("ours") or {}, r.get("peer") or {}
        closed = "-" if not pe else ("yes" if pe["boundary_edges"] == 0 and pe["nonmanifold_edges"] == 0
                                     else f"no ({pe['boundary_edges']} bd, {pe['nonmanifold_edges']} nm)")
        lines.append(f"| {r['shape']}_s{r['seed']} | {r['N']} | {r['g']:g} | {r['info']['g_nn']:.2f} | {r['mode']} | "
                     f"{ho:.3f} | {hp:.3f} | {ratio:.2f} | {(r.get('bridges') or {}).get('faces', '-')} | "
                     f"{o.get('cross_faces', '-')} | {pe.get('cross_faces', '-')} | {closed} | {worst(o)} | "
                     f"{worst(pe)} |")
    ratios = [x[0] for x in rr if x[0] == x[0]]
    med = f"{float(np.median(ratios)):.2f}" if ratios else "-"
    worse = sum(1 for x in ratios if x > 1.25)
    crossing = sum(1 for r in rows if (r.get("ours") or {}).get("cross_faces", 0) > 0)
    open_peer = sum(1 for r in rows
                    if r.get("peer") and (r["peer"]["boundary_edges"] or r["peer"]["nonmanifold_edges"]))
    failed = sum(1 for r in rows if not (r.get("ours") and r.get("peer")))
    lines += ["", f"{len(rows)} sets. Median ratio (ours / peer) {med}; sets worse than 1.25x the peer: {worse}; "
              f"with our cross-gap faces: {crossing}; with the peer open: {open_peer}"
              + (f"; with a failed run: {failed}" if failed else "") + "."]
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    pos, opts, table_only = [], dict(DEFAULTS), False
    a = sys.argv[1:]
    i = 0
    while i < len(a):
        if a[i] == "--table":
            table_only = True
        elif a[i].startswith("--") and a[i][2:] in opts and i + 1 < len(a):
            opts[a[i][2:]] = a[i + 1]
            i += 1
        elif a[i].startswith("--") or len(pos) == 2:
            sys.exit(__doc__[__doc__.index("Usage:"):__doc__.index("Writes")])
        else:
            pos.append(a[i])
        i += 1
    build = pos[0] if pos else "build-bench"
    out = pos[1] if len(pos) > 1 else "out/uneven_parts3"
    if not table_only:
        cli, afsr = os.path.join(build, "cli", "constrict"), os.path.join(build, "bench", "constrict_afsr")
        for x in (cli, afsr):
            if not os.access(x, os.X_OK):
                sys.exit(f"missing {x}: run make bench")
        for x in opts["shapes"].split(","):
            if x not in SHAPES:
                sys.exit(f"unknown shape {x}: {', '.join(SHAPES)}")
        for x in opts["modes"].split(","):
            if x not in MODES:
                sys.exit(f"unknown mode {x}: {', '.join(MODES)}")
        os.makedirs(os.path.join(out, "data"), exist_ok=True)
        os.makedirs(os.path.join(out, "out"), exist_ok=True)
        rows_path = os.path.join(out, "rows.jsonl")
        open(rows_path, "w").close()
        for N in [int(x) for x in opts["n"].split(",")]:
            for seed in [int(x) for x in opts["seeds"].split(",")]:
                for mode in opts["modes"].split(","):
                    for shape in opts["shapes"].split(","):
                        for g in [float(x) for x in opts["gaps"].split(",")]:
                            row = run_one(cli, afsr, out, shape, mode, N, g, seed)
                            with open(rows_path, "a") as f:
                                f.write(json.dumps(row) + "\n")
                            ho, hp, ratio = hausdorff(row)
                            print(f"{row['name']}: ours {ho:.3f}% peer {hp:.3f}% ratio {ratio:.2f} "
                                  f"bridges {(row.get('bridges') or {}).get('faces')} cross "
                                  f"{(row.get('ours') or {}).get('cross_faces')}/"
                                  f"{(row.get('peer') or {}).get('cross_faces')} g_nn {row['info']['g_nn']:.2f} "
                                  f"t {row['t_gen']:.0f}+{row['t_ours']:.1f}+{row['t_peer']:.1f}/{row['t_all']:.0f}s",
                                  flush=True)
    table(out)
    print(open(os.path.join(out, "table.md")).read())


if __name__ == "__main__":
    main()
