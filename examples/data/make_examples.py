#!/usr/bin/env python3
"""Regenerates the bundled example inputs (deterministic; standard library only).
Run from this folder: python3 make_examples.py"""
import math, random

def write(path, pts, header):
    with open(path, "w") as f:
        f.write(f"# {header}\n")
        for p in pts:
            f.write(" ".join(repr(float(c)) for c in p) + "\n")

rng = random.Random(20261123)

# 2D: a five-petal flower curve, non-uniform spacing, shuffled.
ts = sorted(rng.uniform(0, 2 * math.pi) for _ in range(160))
flower = [((1 + 0.3 * math.cos(5 * t)) * math.cos(t), (1 + 0.3 * math.cos(5 * t)) * math.sin(t)) for t in ts]
rng.shuffle(flower)
write("2d/flower.xy", flower, "160 points on r = 1 + 0.3 cos(5t), shuffled")

# 2D: the worked examples of the spec (§5.1, §5.2, §6.2).
write("2d/rectangle_point.xy", [(0, 0), (8, 0), (8, 6), (0, 6), (3, 2)], "spec 5.1: rectangle plus one point")
write("2d/greedy_lock.xy", [(-8, 13), (12, 13), (20, -3), (15, 20), (8, 6), (9, 11), (4, 17)],
      "spec 5.2: greedy constriction locks with P5 inside")
write("2d/nonhamiltonian9.xy", [(12, 2), (0, 0), (-1, 12), (-14, -3), (0, -14), (1, 2), (12, 15), (-20, 4), (8, -19)],
      "spec 6.2: non-Hamiltonian Delaunay triangulation")

# 3D: a candlestick-like surface of revolution (thin neck, concavities), closed by two caps.
def radius(z):  # z in [0, 1]
    return 0.35 + 0.25 * math.cos(2 * math.pi * z) ** 2 * (1 - z) + 0.15 * math.exp(-((z - 0.75) / 0.08) ** 2)
cand = []
for _ in range(900):
    z = rng.uniform(0.0, 1.0)
    a = rng.uniform(0, 2 * math.pi)
    r = radius(z)
    cand.append((r * math.cos(a), r * math.sin(a), 2.0 * z))
for zc in (0.0, 1.0):
    r0 = radius(zc)
    for _ in range(90):
        rr = r0 * math.sqrt(rng.uniform(0.0, 0.95))
        a = rng.uniform(0, 2 * math.pi)
        cand.append((rr * math.cos(a), rr * math.sin(a), 2.0 * zc))
rng.shuffle(cand)
write("3d/candlestick.xyz", cand, "1080 points on a closed surface of revolution, shuffled")

# 3D: ellipsoid with uniform-ish sampling.
ell = []
for _ in range(500):
    while True:
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in v))
        if n > 1e-9:
            break
    ell.append((2.0 * v[0] / n, 1.2 * v[1] / n, 0.8 * v[2] / n))
write("3d/ellipsoid.xyz", ell, "500 points on an ellipsoid with semi-axes 2, 1.2, 0.8")

write("3d/tetra_interior.xyz", [(0, 0, 0), (6, 0, 0), (0, 6, 0), (0, 0, 6), (1, 2, 1)], "spec 5.3: tetrahedron plus one interior point")
