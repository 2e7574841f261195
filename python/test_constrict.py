# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of the Python module (run by ctest as python.bindings)."""
import json
import math
import unittest

import numpy as np

import constrict


def polygon_is_simple(pts, b):
    """Brute force: no two non-adjacent edges meet (general position inputs only)."""
    n = len(b)

    def orient(a, c, d):
        return np.sign((c[0] - a[0]) * (d[1] - a[1]) - (c[1] - a[1]) * (d[0] - a[0]))

    for i in range(n):
        p, q = pts[b[i]], pts[b[(i + 1) % n]]
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            r, s = pts[b[j]], pts[b[(j + 1) % n]]
            if orient(p, q, r) != orient(p, q, s) and orient(r, s, p) != orient(r, s, q):
                return False
    return True


class Reconstruct2(unittest.TestCase):
    def test_curve_gives_the_curve_order(self):
        t = np.linspace(0, 2 * math.pi, 60, endpoint=False)
        r = 1 + 0.3 * np.cos(5 * t)
        curve = np.column_stack([r * np.cos(t), r * np.sin(t)])
        perm = np.random.default_rng(1).permutation(len(curve))
        res = constrict.reconstruct2(curve[perm])
        self.assertTrue(res.valid)
        self.assertEqual(res.method, "gamma")
        b = perm[res.boundary]  # back to curve order: consecutive parameters
        steps = {(int(b[(i + 1) % 60]) - int(b[i])) % 60 for i in range(60)}
        self.assertEqual(steps, {1})
        self.assertGreater(res.area, 0)
        self.assertAlmostEqual(res.perimeter, sum(np.linalg.norm(curve[(i + 1) % 60] - curve[i]) for i in range(60)))

    def test_random_inputs_are_simple_polygons_through_all_points(self):
        rng = np.random.default_rng(7)
        for seed in range(30):
            pts = rng.random((int(rng.integers(3, 80)), 2))
            for fallback in ("auto", "degree4"):
                res = constrict.reconstruct2(pts, fallback=fallback)
                self.assertTrue(res.valid, seed)
                self.assertEqual(sorted(res.boundary.tolist()), list(range(len(pts))), seed)
                self.assertTrue(polygon_is_simple(pts, res.boundary), seed)
                ok, reason = constrict.validate_polygon(pts, res.boundary)
                self.assertTrue(ok, reason)

    def test_lock_is_reported(self):
        # Spec example B (§5.2): the Delaunay constriction locks with P5 inside.
        pts = [[-8, 13], [12, 13], [20, -3], [15, 20], [8, 6], [9, 11], [4, 17]]
        res = constrict.reconstruct2(pts, refine=False)
        self.assertTrue(res.locked)
        self.assertTrue(res.valid)
        self.assertNotEqual(res.method, "gamma")
        locked = constrict.reconstruct2(pts, fallback="none")
        self.assertFalse(locked.complete)
        self.assertEqual(locked.stuck_points.tolist(), [5])

    def test_bad_input_raises_with_the_status_name(self):
        cases = {
            "Duplicate": [[0, 0], [1, 0], [0, 1], [1, 0]],
            "Collinear": [[0, 0], [1, 1], [2, 2]],
            "TooFewPoints": [[0, 0], [1, 1]],
            "NonFinite": [[0, 0], [1, 0], [float("nan"), 1]],
        }
        for code, pts in cases.items():
            with self.assertRaises(constrict.Error) as ctx:
                constrict.reconstruct2(pts)
            self.assertEqual(ctx.exception.code, code)
        with self.assertRaises(ValueError) as ctx:
            constrict.reconstruct2([[0, 0], [1, 0], [0, 1], [1, 0]])
        self.assertIn("points 1 and 3", str(ctx.exception))
        with self.assertRaises(constrict.Error):
            constrict.reconstruct2(np.zeros((5, 3)))
        with self.assertRaises(constrict.Error):
            constrict.reconstruct2(np.random.random((5, 2)), fallback="sometimes")


class Reconstruct3(unittest.TestCase):
    def test_sphere_with_inside_points_is_a_closed_genus0_surface(self):
        rng = np.random.default_rng(3)
        v = rng.normal(size=(400, 3))
        v /= np.linalg.norm(v, axis=1)[:, None]
        v *= 1 + 0.05 * rng.random((400, 1))  # a shell: some points are not on the hull
        res = constrict.reconstruct3(v)
        self.assertTrue(res.valid)
        self.assertEqual(res.genus, 0)
        tri = res.triangles
        self.assertEqual(tri.shape, (2 * len(v) - 4, 3))
        self.assertEqual(sorted(set(tri.ravel().tolist())), list(range(len(v))))
        ok, reason = constrict.validate_surface(v, tri)
        self.assertTrue(ok, reason)
        # The body: its volume is the enclosed volume (divergence theorem on the surface).
        a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
        enclosed = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
        t = res.tetrahedra
        p0, p1, p2, p3 = (v[t[:, k]] for k in range(4))
        body = np.einsum("ij,ij->i", p1 - p0, np.cross(p2 - p0, p3 - p0)).sum() / 6
        self.assertAlmostEqual(body, enclosed, places=9)
        self.assertAlmostEqual(res.volume, enclosed, places=9)
        self.assertLess(res.volume, 4 / 3 * math.pi * 1.05 ** 3)
        # The library's report: the same writer as the CLI's --report.
        rep = json.loads(res.report())
        self.assertTrue(rep["valid"])
        self.assertEqual(rep["method"], res.method)
        self.assertEqual(rep["faces"], len(tri))
        self.assertEqual(rep["stages"][0]["name"], "hull")

    def test_coplanar_input_raises(self):
        with self.assertRaises(constrict.Error) as ctx:
            constrict.reconstruct3([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 3, 0]])
        self.assertEqual(ctx.exception.code, "Coplanar")


class GammaGraph(unittest.TestCase):
    def test_family_nests_and_matches_the_definition(self):
        pts = np.random.default_rng(5).random((40, 2))
        dt = constrict.gamma_graph(pts)
        gab = constrict.gamma_graph(pts, preset="gabriel")
        hull = constrict.gamma_graph(pts, preset="hull")
        as_set = lambda g: {tuple(e) for e in g["faces"].tolist()}
        self.assertLessEqual(as_set(hull), as_set(dt))
        self.assertLessEqual(as_set(gab), as_set(dt))
        self.assertEqual(len(dt["faces"]), 3 * 40 - 3 - len(hull["faces"]))  # planar triangulation
        # Gabriel by definition: no point inside the circle with diameter ab.
        for a, b in gab["faces"].tolist():
            m, r2 = (pts[a] + pts[b]) / 2, np.sum((pts[a] - pts[b]) ** 2) / 4
            d2 = np.sum((pts - m) ** 2, axis=1)
            d2[[a, b]] = np.inf
            self.assertTrue(np.all(d2 > r2))
        same = constrict.gamma_graph(pts, interval=(-1, 1, 0, 1))
        self.assertEqual(as_set(same), as_set(dt))
        self.assertEqual(as_set(constrict.gamma_graph(pts, gamma=(0, 0))), as_set(gab))
        with self.assertRaises(constrict.Error):
            constrict.gamma_graph(pts, preset="gabriel", gamma=(0, 0))

    def test_3d_faces_are_triangles(self):
        pts = np.random.default_rng(2).random((30, 3))
        g = constrict.gamma_graph(pts)
        self.assertEqual(g["faces"].shape[1], 3)
        self.assertEqual(len(g["faces"]), len(g["delta"]))


if __name__ == "__main__":
    unittest.main()
