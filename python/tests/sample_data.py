# SPDX-License-Identifier: GPL-3.0-or-later
"""Small generated inputs shared by the tests (fixed seeds): curves in 2D, shells in 3D."""
import math
import os

import numpy as np


def curve(n, seed, lobes=5):
    """n points of a star-shaped closed curve, shuffled."""
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    r = 1 + 0.3 * np.cos(lobes * t)
    pts = np.column_stack([r * np.cos(t), r * np.sin(t)])
    return pts[np.random.default_rng(seed).permutation(n)]


def shell(n, seed):
    """n points near the unit sphere (a shell: some not on the hull)."""
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    return v * (1 + 0.05 * rng.random((n, 1)))


def save(path, pts):
    np.savetxt(path, pts, fmt="%.17g")


def write_folder(root):
    """points.xy, scan.xyz, slices/*.xy and scans/*.xyz under root; returns the list of the
    folder files (slices, then scans)."""
    os.makedirs(os.path.join(root, "slices"), exist_ok=True)
    os.makedirs(os.path.join(root, "scans"), exist_ok=True)
    save(os.path.join(root, "points.xy"), curve(80, 1))
    save(os.path.join(root, "scan.xyz"), shell(200, 2))
    files = []
    for k in range(4):
        files.append(os.path.join(root, "slices", f"s{k}.xy"))
        save(files[-1], curve(40 + 10 * k, 10 + k, lobes=3 + k))
    for k in range(2):
        files.append(os.path.join(root, "scans", f"shell{k}.xyz"))
        save(files[-1], shell(80 + 40 * k, 20 + k))
    return files
