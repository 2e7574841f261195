#!/usr/bin/env python3
"""Writes the seed corpora of the engine fuzz targets (fuzz/corpus/{reconstruct2,reconstruct3,surfaces3,compare3,
gamma_graph}/) in the byte layout of fuzz/fuzz_engine.hpp: [options][mode][count][params][points].
Run from the repository root after changing the layout; the files are committed."""
import math
import os
import random
import struct

SMALL, RAW, SCALED, MIXED, LATTICE, COSPH, NEARLINE, RAWF = range(8)


def si(v):  # byte of a small integer in [-4, 4]
    return (v + 4) % 256


def i8(v):
    return v & 0xFF


def points(mode, pts, params=b"", keep_nonfinite=False):
    head = bytes([mode | (0x80 if keep_nonfinite else 0), len(pts)]) + params
    body = b""
    for p in pts:
        if mode in (SMALL, SCALED):
            body += bytes(si(c) for c in p)
        elif mode == RAW:
            body += b"".join(struct.pack("<d", c) for c in p)
        elif mode == RAWF:
            body += b"".join(struct.pack("<f", c) for c in p)
        elif mode == MIXED:
            body += b"".join(bytes([si(c), i8(e)]) for c, e in p)
        else:
            body += bytes(i8(c) for c in p)
    return head + body


def curve(n, dim, scale):
    out = []
    for i in range(n):
        t = 2 * math.pi * i / n
        q = [math.cos(t) * (1 + 0.3 * math.cos(3 * t)) * scale, math.sin(t) * scale]
        if dim == 3:
            q.append(0.5 * math.sin(2 * t) * scale + (scale if i % 2 else -scale) * 0.2)
        out.append(q)
    return out


def sets(dim):
    rnd = random.Random(20)
    sq = [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, 0)] if dim == 2 else \
        [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)] + [(0, 0, 0)]
    line = [tuple(t * (j + 1) // 2 for j in range(dim)) for t in range(-2, 3)]
    dup = sq + sq[:2]
    lattice = bytes([2, 40]) + bytes(c for i in range(27 if dim == 3 else 16)
                                     for c in [i] + [rnd.randrange(256) for _ in range(dim)])
    cosph = bytes([4] * dim + [0]) + bytes(c for i in range(14) for c in [i if i < 13 else 250] + ([] if i < 13 else [5] * dim))
    near = bytes(c for i in range(6) for c in [si(i - 2)] + [rnd.randrange(256) for _ in range(dim)])
    mixed = [[(rnd.randrange(-4, 5) or 1, rnd.choice([-120, -60, 0, 60, 110])) for _ in range(dim)] for _ in range(6)]
    return {
        "small_square": points(SMALL, sq),
        "small_collinear": points(SMALL, line),
        "small_duplicates": points(SMALL, dup),
        "raw_curve_1e-287": points(RAW, curve(20, dim, 1e-287)),
        "raw_curve_1e300": points(RAW, curve(12, dim, 1e300)),
        "raw_nonfinite": points(RAW, [[1.0] * dim, [float("nan")] * dim, [0.0] * dim, [2.0, 1.0, 0.0][:dim]],
                                keep_nonfinite=True),
        "scaled_square_tiny_2e-1098": points(SCALED, sq, bytes([i8(-122)])),
        "mixed_magnitudes": points(MIXED, mixed),
        "lattice_jitter": bytes([LATTICE, 27 if dim == 3 else 16]) + lattice,
        "cospherical": bytes([COSPH, 14]) + cosph,
        "near_line": bytes([NEARLINE, 6]) + near,
        "rawfloat_curve": points(RAWF, curve(16, dim, 3.0)),
        # A grid of a surface of revolution: cocircular rings, cospherical cells, flat tetrahedra
        # (docs/reconstruction-3d.md 4.10); in 2D two evenly sampled concentric circles.
        "raw_grid_revolution": points(RAW, grid_revolution(dim)),
    }


def grid_revolution(dim):
    if dim == 2:
        return [[r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n)] for r, n in ((4, 24), (2, 12))
                for i in range(n)]
    out = []
    for i in range(16):
        for j in range(12):
            u, v = 2 * math.pi * i / 16, 2 * math.pi * j / 12
            out.append([(2 + 0.7 * math.cos(v)) * math.cos(u), (2 + 0.7 * math.cos(v)) * math.sin(u), 0.7 * math.sin(v)])
    return out


def write(target, opts, dim, lead=b""):
    d = os.path.join("fuzz", "corpus", target)
    os.makedirs(d, exist_ok=True)
    for i, (name, body) in enumerate(sorted(sets(dim).items())):
        o = opts[i % len(opts)]
        with open(os.path.join(d, name), "wb") as f:
            f.write(lead(i) if callable(lead) else lead)
            f.write(bytes(o) + body)


# 2D options: preset/fallback/criterion/repair byte, refine budget byte.
write("reconstruct2", [(0, 0), (1, 0), (2, 0), (4, 0), (6, 0), (8, 3), (0x20 | 2, 0), (16, 0x80)], 2)
# 3D options: preset/fallback/criterion/grow byte, sculpt/refine byte.
write("reconstruct3", [(0, 0), (1, 0), (2, 0), (0x20, 0), (4, 0), (8, 6), (0, 2), (0, 0x40)], 3)
# Auto topology: gap / min part / handles / growth byte (fuzz_surfaces3.cpp).
write("surfaces3", [(0,), (1,), (3,), (5,), (0x08,), (0x10,), (0x20,), (2,)], 3)
# γ-graph: dimension byte, then spec kind and values (no options pair: lead holds them).
specs = [b"\x00\x01", b"\x00\x02", b"\x01\x05\x05", b"\x01\x06\x06", b"\x01\x0b\x00", b"\x02\x00\x01\x02\x01",
         b"\x00\x05\x60", b"\x00\x06\x30", b"\x01\x03\x04", b"\x00\x08"]
for dim in (2, 3):
    d = os.path.join("fuzz", "corpus", "gamma_graph")
    os.makedirs(d, exist_ok=True)
    for i, (name, body) in enumerate(sorted(sets(dim).items())):
        if i % 2 != dim - 2 and name not in ("near_line", "cospherical"):
            continue
        with open(os.path.join(d, f"{dim}d_{name}"), "wb") as f:
            f.write(bytes([dim - 2]) + specs[i % len(specs)] + body)
# Mesh comparison: a triangle count byte (1 + b % 24) and three index bytes per triangle (modulo
# the point count), then the points (fuzz_compare3.cpp): a tetrahedron's four faces, a fan.
tetra = bytes([3, 0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3])
fan = bytes([5] + [v for k in range(6) for v in (0, k + 1, k + 2)])
write("compare3", [()], 3, lambda i: tetra if i % 2 == 0 else fan)
