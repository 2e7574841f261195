# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of the Python module (run by ctest as python.bindings)."""
import importlib.util
import json
import math
import os
import pickle
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np

import constrict
import sample_data


def cli():
    """The CLI built with this tree (ctest passes it), else the one inside the package."""
    path = os.environ.get("CONSTRICT_CLI")
    if path:
        return path
    try:
        return constrict.cli_path()
    except FileNotFoundError:
        return None


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
        self.assertIn("merge_duplicates=True", str(ctx.exception))
        self.assertNotIn("--", str(ctx.exception))  # Python has no such flag
        with self.assertRaises(constrict.Error):
            constrict.reconstruct2(np.zeros((5, 3)))
        with self.assertRaises(constrict.Error):
            constrict.reconstruct2(np.random.random((5, 2)), fallback="sometimes")
        # Complex coordinates were cut to their real part with only numpy's warning.
        for pts in (np.random.random((8, 2)) + 1j, (np.random.random((8, 2)) + 1j).tolist()):
            with self.assertRaises(constrict.Error) as ctx:
                constrict.reconstruct2(pts)
            self.assertIn("real numbers", str(ctx.exception))
        with self.assertRaises(constrict.Error):
            constrict.reconstruct3(np.random.random((20, 3)).astype(np.complex64))
        # Counts beyond size_t or of numpy's integer types gave pybind11's cast errors.
        pts = np.random.default_rng(3).random((40, 2))
        a = constrict.reconstruct2(pts, stop_after=np.int64(5), fallback="none")
        b = constrict.reconstruct2(pts, stop_after=5, fallback="none")
        self.assertEqual(a.boundary.tolist(), b.boundary.tolist())
        self.assertTrue(constrict.reconstruct2(pts, stop_after=2**64).complete)
        with self.assertRaises(constrict.Error):
            constrict.reconstruct2(pts, method="voronoi-skeleton", seed_limit=2**64)


class Topology2(unittest.TestCase):
    """reconstruct2(topology="auto"): the rings the data show (docs/topology.md)."""

    @staticmethod
    def annulus(n_outer=120, n_inner=60):
        t = np.linspace(0, 2 * math.pi, n_outer, endpoint=False)
        u = np.linspace(0, 2 * math.pi, n_inner, endpoint=False) + 0.01
        pts = np.r_[np.c_[3 * np.cos(t), 3 * np.sin(t)], np.c_[1.5 * np.cos(u), 1.5 * np.sin(u)]]
        return pts[np.random.default_rng(4).permutation(len(pts))]

    def test_annulus_gives_a_shell_and_a_hole(self):
        pts = self.annulus()
        r = constrict.reconstruct2(pts, topology="auto")
        self.assertIsInstance(r, constrict.Rings)
        self.assertTrue(r.valid)
        self.assertEqual(sorted(g.role for g in r.rings), ["hole", "shell"])
        hole = r.holes[0]
        self.assertEqual(r.rings[hole.parent].role, "shell")
        self.assertEqual(sorted(np.concatenate([g.indices for g in r.rings]).tolist()), list(range(len(pts))))
        self.assertTrue(all(np.linalg.norm(pts[hole.indices], axis=1) < 2))  # the inner circle
        ok, reason = constrict.validate_rings(pts, r)
        self.assertTrue(ok, reason)
        self.assertEqual(pickle.loads(pickle.dumps(r)), r)
        self.assertEqual(len(json.loads(r.report())["rings"]), 2)
        # A hole given the wrong way round is rejected.
        bad = [constrict.Ring(g.role, g.parent, g.indices[::-1] if g.role == "hole" else g.indices) for g in r.rings]
        self.assertFalse(constrict.validate_rings(pts, bad)[0])

    def test_single_mode_stays_one_polygon(self):
        r = constrict.reconstruct2(self.annulus())
        self.assertIsInstance(r, constrict.Polygon)
        self.assertTrue(r.valid)


class Topology3(unittest.TestCase):
    """reconstruct3(topology="auto"): parts, inner shells and handles (docs/topology.md)."""

    @staticmethod
    def fibonacci_sphere(n, centre, radius):
        k = np.arange(n) + 0.5
        phi = np.arccos(1 - 2 * k / n)
        theta = math.pi * (1 + 5 ** 0.5) * k
        v = np.c_[np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)]
        return np.asarray(centre) + radius * v

    @staticmethod
    def torus(nu=48, nv=18, R=1.0, r=0.4):
        pts = []
        for i in range(nu):
            for j in range(nv):
                u = 2 * math.pi * (i + 0.5 * (j % 2)) / nu
                v = 2 * math.pi * j / nv
                pts.append([(R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v)])
        return np.array(pts)

    def test_two_spheres_and_a_hollow_one(self):
        two = np.r_[self.fibonacci_sphere(600, (0, 0, 0), 1), self.fibonacci_sphere(600, (2.6, 0, 0), 1)]
        r = constrict.reconstruct3(two, topology="auto")
        self.assertTrue(r.valid)
        self.assertEqual(r.topology, "auto")
        self.assertEqual([s["role"] for s in r.surfaces], ["outer", "outer"])
        self.assertEqual(sorted(np.concatenate([s["points"] for s in r.surfaces]).tolist()), list(range(len(two))))
        self.assertTrue(constrict.validate_surface(two, r.triangles, r.tetrahedra)[0])
        self.assertFalse(constrict.validate_surface(two, r.triangles)[0])  # not one genus-0 surface
        self.assertEqual(pickle.loads(pickle.dumps(r)), r)
        hollow = np.r_[self.fibonacci_sphere(900, (0, 0, 0), 1.5), self.fibonacci_sphere(400, (0, 0, 0), 1)]
        h = constrict.reconstruct3(hollow, topology="auto")
        self.assertTrue(h.valid)
        roles = sorted((s["role"], s["parent"]) for s in h.surfaces)
        self.assertEqual([x[0] for x in roles], ["inner", "outer"])
        self.assertLess(h.volume, 4 / 3 * math.pi * 1.5 ** 3 - 4 / 3 * math.pi * 0.9)  # the cavity is not solid

    def test_torus_has_genus_one_in_auto_and_zero_in_single(self):
        pts = self.torus()
        a = constrict.reconstruct3(pts, topology="auto")
        self.assertTrue(a.valid)
        self.assertEqual(a.genus, 1)
        self.assertEqual(len(a.surfaces), 1)
        s = constrict.reconstruct3(pts)
        self.assertTrue(s.valid)
        self.assertEqual(s.genus, 0)
        self.assertIsNone(s.surfaces)
        with self.assertRaises(constrict.Error):
            constrict.reconstruct3(pts, topology="sometimes")


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
        self.assertTrue(constrict.validate_surface(v, tri.tolist())[0])
        # Float indices are refused, not truncated (2.7 -> 2 passed as the same surface).
        for bad in (tri + 0.7, tri.astype(float)):
            with self.assertRaisesRegex(constrict.Error, "integer indices"):
                constrict.validate_surface(v, bad)
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


class Keywords(unittest.TestCase):
    def test_inapplicable_and_unknown_keywords_raise(self):
        pts2 = sample_data.curve(20, 1)
        pts3 = sample_data.shell(30, 1)
        with self.assertRaisesRegex(TypeError, "3D only"):
            constrict.reconstruct2(pts2, grow=False)
        with self.assertRaisesRegex(TypeError, "grow=False"):
            constrict.reconstruct3(pts3, no_grow=True)
        with self.assertRaisesRegex(TypeError, "write_mesh"):
            constrict.reconstruct3(pts3, ascii=True)
        with self.assertRaisesRegex(TypeError, "unexpected keyword argument 'colour'"):
            constrict.reconstruct3(pts3, colour="red")
        bad = [
            lambda: constrict.reconstruct3(pts3, fallback="degree4"),
            lambda: constrict.reconstruct3(pts3, fast=True, refine=False),
            lambda: constrict.reconstruct2(pts2, seed_limit=3),
            lambda: constrict.reconstruct2(pts2, method="voronoi-skeleton", stop_after=3),
            lambda: constrict.reconstruct2(pts2, method="nearest"),
            lambda: constrict.reconstruct2(pts2, refine="sometimes"),
            # (the third hostile-input sweep: auto ignored stop_after, or stopped one part early;
            # a negative or fractional stop_after gave pybind11's generic cast error)
            lambda: constrict.reconstruct2(pts2, topology="auto", stop_after=3),
            lambda: constrict.reconstruct2(pts2, stop_after=-1),
            lambda: constrict.reconstruct2(pts2, stop_after=2.5),
            lambda: constrict.reconstruct3(pts3, stop_after=True),
            # wrong types: one short line, not pybind11's signature dump
            lambda: constrict.reconstruct2(pts2, topology=None),
            lambda: constrict.reconstruct3(pts3, fallback=None),
            lambda: constrict.reconstruct2(pts2, seed_limit=-1),
            lambda: constrict.reconstruct3(pts3, merge_duplicates="no"),
            lambda: constrict.reconstruct3(pts3, grow="no"),
            lambda: constrict.reconstruct2(pts2, topology="auto", topology_gap="2"),
            # (the fourth sweep: these gave pybind11's signature dump, a slice error, or were
            # taken as true)
            lambda: constrict.reconstruct(pts2, dim="2"),
            lambda: constrict.reconstruct(pts2, dim=4),
            lambda: constrict.reconstruct(pts3, merge_duplicates=1),
            lambda: constrict.gamma_graph(pts2, preset=None),
            lambda: constrict.gamma_graph(pts2, gamma=(0, "a")),
            lambda: constrict.gamma_graph(pts2, interval=(0, 1)),
            lambda: constrict.reconstruct2(pts2, topology_gap=3),  # (returned Rings)
            lambda: constrict.reconstruct3(pts3, topology_gap=3),
        ]
        for i, f in enumerate(bad):
            with self.assertRaises(constrict.Error, msg=i) as ctx:
                f()
            self.assertEqual(ctx.exception.code, "InvalidArgument", i)

    def test_help_explains_every_argument(self):
        import inspect
        for f in (constrict.reconstruct2, constrict.reconstruct3):
            for name in inspect.signature(f).parameters:
                if name != "unknown":
                    self.assertIn(f"    {name}:", f.__doc__, (f.__name__, name))

    def test_stop_after_and_criteria(self):
        pts = sample_data.curve(60, 2)
        stopped = constrict.reconstruct2(pts, stop_after=3)
        self.assertFalse(stopped.complete)
        self.assertEqual(stopped.method, "stopped")
        self.assertEqual(stopped.removed_simplices, 3)
        for m in ("min-area-change", "boissonnat", "voronoi-skeleton"):
            r = constrict.reconstruct2(pts, method=m)
            self.assertTrue(r.valid, m)
            self.assertEqual(sorted(r.boundary.tolist()), list(range(60)), m)
        self.assertIsNotNone(constrict.reconstruct2(pts, method="voronoi-skeleton").skeleton)
        s = constrict.reconstruct3(sample_data.shell(60, 3), grow=False, validate_self_intersections=True)
        self.assertTrue(s.valid)
        self.assertNotEqual(s.method, "grow")


class MergeDuplicates(unittest.TestCase):
    def test_ids_stay_rows_of_the_input(self):
        pts = sample_data.curve(30, 4)
        dup = np.vstack([pts[:5], pts[2:3], pts[5:], pts[7:9]])  # rows 5, 31, 32 are later copies
        r = constrict.reconstruct2(dup, merge_duplicates=True)
        self.assertTrue(r.valid)
        self.assertEqual(r.merged_duplicates.tolist(), [5, 31, 32])
        self.assertEqual(sorted(r.boundary.tolist()), sorted(set(range(len(dup))) - {5, 31, 32}))
        ok, reason = constrict.validate_polygon(np.delete(dup, [5, 31, 32], axis=0),
                                                np.searchsorted(np.setdiff1d(np.arange(len(dup)), [5, 31, 32]),
                                                                r.boundary))
        self.assertTrue(ok, reason)
        s3 = sample_data.shell(40, 5)
        s = constrict.reconstruct3(np.vstack([s3, s3[:3]]), merge_duplicates=True)
        self.assertTrue(s.valid)
        self.assertEqual(s.merged_duplicates.tolist(), [40, 41, 42])
        self.assertEqual(s.triangles.max(), 39)


class Pickle(unittest.TestCase):
    def test_results_round_trip(self):
        p = constrict.reconstruct2(sample_data.curve(40, 6))
        s = constrict.reconstruct3(sample_data.shell(50, 6))
        for r in (p, s):
            back = pickle.loads(pickle.dumps(r))
            self.assertEqual(back, r)
            self.assertEqual(back.report(), r.report())
            self.assertEqual(back.timings_ms, r.timings_ms)
        err = None
        try:
            constrict.reconstruct2([[0, 0], [1, 1]])
        except constrict.Error as e:
            err = pickle.loads(pickle.dumps(e))
        self.assertIsInstance(err, constrict.Error)
        self.assertEqual(err.code, "TooFewPoints")


class Files(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def test_read_points(self):
        pts = sample_data.shell(30, 7)
        sample_data.save(self.path("a.xyz"), pts)
        self.assertTrue(np.array_equal(constrict.read_points(self.path("a.xyz")), pts))
        self.assertTrue(np.array_equal(constrict.read_points(self.path("a.xyz"), dim=2), pts[:, :2]))
        self.assertTrue(np.array_equal(constrict.read_points(self.path("a.xyz"), columns=(0, 2)), pts[:, [0, 2]]))
        # Any field by number or by header name (an id column first, two extra fields after).
        with open(self.path("t.csv"), "w") as f:
            f.write("id,x,y,z,intensity\n")
            for i, q in enumerate(pts):
                f.write(f"{i},{q[0]!r},{q[1]!r},{q[2]!r},7\n")
        self.assertTrue(np.array_equal(constrict.read_points(self.path("t.csv")), pts))  # by the header
        self.assertTrue(np.array_equal(constrict.read_points(self.path("t.csv"), columns=(1, 2, 3)), pts))
        self.assertTrue(np.array_equal(constrict.read_points(self.path("t.csv"), columns=("z", "x")), pts[:, [2, 0]]))
        sample_data.save(self.path("d.xyz"), np.vstack([pts, pts[4:5]]))
        with self.assertRaises(constrict.Error) as ctx:
            constrict.read_points(self.path("d.xyz"))
        self.assertEqual(ctx.exception.code, "Duplicate")
        self.assertIn("merge_duplicates=True", str(ctx.exception))
        merged, info = constrict.read_points_info(self.path("d.xyz"), merge_duplicates=True)
        self.assertTrue(np.array_equal(merged, pts))
        self.assertEqual(info["merged_duplicates"], 1)
        self.assertEqual(info["points_read"], 31)
        with self.assertRaises(constrict.Error) as ctx:
            constrict.read_points(self.path("missing.xyz"))
        self.assertEqual(ctx.exception.code, "FileNotFound")
        with open(self.path("bad.xy"), "w") as f:
            f.write("0 0\n1 x\n")
        with self.assertRaises(constrict.Error) as ctx:
            constrict.read_points(self.path("bad.xy"))
        self.assertEqual(ctx.exception.code, "ParseError")
        self.assertIn("bad.xy:2", str(ctx.exception))
        with open(self.path("flat.xyz"), "w") as f:  # an outline written with a constant x
            f.write("1 0 0\n1 2 0\n1 2 1\n1 0 1\n")
        with self.assertRaises(constrict.Error) as ctx:
            constrict.read_points(self.path("flat.xyz"))
        self.assertEqual(ctx.exception.code, "Coplanar")
        self.assertIn("columns=(1, 2)", str(ctx.exception))  # Python's keyword, not the CLI's flag
        with open(self.path("wide.txt"), "w") as f:  # more fields than x, y, z: the keyword's advice
            f.write("0 0 0 1\n1 4 0 1\n2 4 4 1\n")
        with self.assertRaises(constrict.Error) as ctx:
            constrict.read_points(self.path("wide.txt"))
        self.assertEqual(ctx.exception.code, "ParseError")
        self.assertIn("columns= (0-based", str(ctx.exception))
        self.assertNotIn("--columns", str(ctx.exception))
        for kw in ({"dim": "3"}, {"dim": 1}, {"merge_duplicates": 1}, {"check": "no"}):
            with self.assertRaises(constrict.Error, msg=kw) as ctx:
                constrict.read_points_info(self.path("t.csv"), **kw)
            self.assertEqual(ctx.exception.code, "InvalidArgument", kw)
        self.assertEqual(constrict.read_points(self.path("t.csv"), dim=np.int64(3)).shape, pts.shape)

    def test_writers_round_trip(self):
        pts3 = sample_data.shell(40, 8)
        s = constrict.reconstruct3(pts3)
        for ext in ("off", "ply", "obj"):
            constrict.write_mesh(self.path("s." + ext), pts3, s.triangles)
            v, t = constrict.read_mesh(self.path("s." + ext))
            self.assertTrue(np.array_equal(v, pts3), ext)
            self.assertTrue(np.array_equal(t, s.triangles), ext)
        constrict.write_body(self.path("b.vtk"), pts3, s.tetrahedra)
        with open(self.path("b.vtk")) as f:
            self.assertIn("UNSTRUCTURED_GRID", f.read())
        pts = sample_data.curve(30, 8)
        p = constrict.reconstruct2(pts)
        constrict.write_polygon(self.path("p.idx"), pts, p.boundary)
        self.assertEqual(np.loadtxt(self.path("p.idx"), dtype=int).tolist(), p.boundary.tolist())
        with self.assertRaises(constrict.Error) as ctx:
            constrict.write_polygon(self.path("p.docx"), pts, p.boundary)
        self.assertIn(ctx.exception.code, ("InvalidArgument", "WriteFailed"))


@unittest.skipIf(cli() is None, "built without the CLI")
class SameAsTheCli(unittest.TestCase):
    """Every keyword against the CLI flag it stands for: the output files are byte-identical."""

    CASES2 = [({}, []), ({"refine": False}, ["--refine", "none"]),
              ({"fallback": "none"}, ["--fallback", "none"]),
              ({"fallback": "degree4", "method": "boissonnat"}, ["--fallback", "degree4", "--method", "boissonnat"]),
              ({"method": "min-area-change"}, ["--method", "min-area-change"]),
              ({"method": "voronoi-skeleton", "seed_limit": 5}, ["--method", "voronoi-skeleton", "--seed-limit", "5"]),
              ({"stop_after": 7}, ["--stop-after", "7"])]
    CASES3 = [({}, []), ({"grow": False}, ["--no-grow"]), ({"grow": False, "fast": True}, ["--no-grow", "--fast"]),
              ({"refine": False}, ["--refine", "none"]), ({"fallback": "none", "grow": False}, ["--fallback", "none", "--no-grow"]),
              ({"method": "min-area-change"}, ["--method", "min-area-change"]),
              ({"stop_after": 20, "grow": False}, ["--stop-after", "20", "--no-grow"])]

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def run_cli(self, argv, exe=None):
        cmd = [exe] if exe else [cli()]
        return subprocess.run(cmd + argv, capture_output=True, text=True)

    def check_cases(self, pts, cases, out_ext, write):
        inp = os.path.join(self.dir, "in.txt")
        sample_data.save(inp, pts)
        for i, (kw, flags) in enumerate(cases):
            out = os.path.join(self.dir, f"cli{i}.{out_ext}")
            done = self.run_cli(["reconstruct", inp, "-o", out, "-q"] + flags)
            self.assertIn(done.returncode, (0, 13), (flags, done.stderr))  # 13: Incomplete
            r = constrict.reconstruct(inp, **kw)
            self.assertEqual(r.complete, done.returncode == 0, flags)
            mine = os.path.join(self.dir, f"py{i}.{out_ext}")
            write(mine, pts, r)
            with open(out, "rb") as a, open(mine, "rb") as b:
                self.assertEqual(a.read(), b.read(), flags)

    def test_2d_keywords(self):
        pts = np.vstack([sample_data.curve(70, 9), [[0.1, 0.05], [-0.2, 0.1], [0.05, -0.3]]])
        self.check_cases(pts, self.CASES2, "idx", lambda p, x, r: constrict.write_polygon(p, x, r.boundary))

    def test_3d_keywords(self):
        pts = np.vstack([sample_data.shell(120, 9), [[0, 0, 0], [0.2, 0.1, 0], [0, -0.3, 0.2]]])
        self.check_cases(pts, self.CASES3, "off", lambda p, x, r: constrict.write_mesh(p, x, r.triangles))

    def test_python_m_constrict_is_the_cli(self):
        inp = os.path.join(self.dir, "in.xyz")
        sample_data.save(inp, sample_data.shell(80, 10))
        outs = []
        for who in ("cli", "module"):
            out = os.path.join(self.dir, who + ".ply")
            argv = ["reconstruct", inp, "-o", out, "-q", "--fast"]
            if who == "cli":
                done = self.run_cli(argv)
            else:
                done = subprocess.run([sys.executable, "-m", "constrict"] + argv, capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out, "rb") as f:
                outs.append(f.read())
        self.assertEqual(outs[0], outs[1])
        bad = subprocess.run([sys.executable, "-m", "constrict", "reconstruct", os.path.join(self.dir, "none.xy"),
                              "-o", "x.idx"], capture_output=True, text=True)
        ref = self.run_cli(["reconstruct", os.path.join(self.dir, "none.xy"), "-o", "x.idx"])
        self.assertEqual((bad.returncode, bad.stderr), (ref.returncode, ref.stderr))
        self.assertNotEqual(bad.returncode, 0)


class Conversions(unittest.TestCase):
    @unittest.skipIf(importlib.util.find_spec("shapely") is None, "python3-shapely is not installed")
    def test_shapely(self):
        pts = sample_data.curve(50, 11)
        p = constrict.reconstruct2(pts)
        g = p.to_shapely(pts)
        self.assertTrue(g.is_valid)
        self.assertAlmostEqual(g.area, p.area)
        self.assertAlmostEqual(g.length, p.perimeter)

    @unittest.skipIf(importlib.util.find_spec("meshio") is None, "python3-meshio is not installed")
    def test_meshio(self):
        pts = sample_data.shell(40, 11)
        s = constrict.reconstruct3(pts)
        m = s.to_meshio(pts, body=True)
        self.assertTrue(np.array_equal(m.cells_dict["triangle"], s.triangles))
        self.assertTrue(np.array_equal(m.cells_dict["tetra"], s.tetrahedra))

    def test_missing_module_says_what_to_install(self):
        if importlib.util.find_spec("open3d") is not None:
            self.skipTest("open3d is installed")
        pts = sample_data.shell(30, 12)
        with self.assertRaisesRegex(ImportError, "open3d"):
            constrict.reconstruct3(pts).to_open3d(pts)


class Threads(unittest.TestCase):
    def test_the_gil_is_released_during_a_reconstruction(self):
        pts = sample_data.shell(12000, 13)
        ticks = []
        stop = threading.Event()

        def ticker():
            while not stop.is_set():
                ticks.append(time.perf_counter())
                time.sleep(0.001)

        t = threading.Thread(target=ticker)
        t.start()
        time.sleep(0.01)
        t0 = time.perf_counter()
        constrict.reconstruct3(pts, fast=True)
        t1 = time.perf_counter()
        stop.set()
        t.join()
        # Holding the GIL would freeze the ticker for the whole call (sys.getswitchinterval()
        # lets it in only between Python bytecodes of this thread).
        margin = 0.2 * (t1 - t0)
        inside = [x for x in ticks if t0 + margin < x < t1 - margin]
        self.assertGreater(t1 - t0, 0.05, "too fast to tell")
        self.assertGreater(len(inside), 5, (t1 - t0, len(ticks)))

    def test_threads_give_the_sequential_results(self):
        from concurrent.futures import ThreadPoolExecutor
        inputs = [sample_data.curve(50 + 5 * k, k) for k in range(4)] + [sample_data.shell(60, k) for k in range(2)]
        seq = [constrict.reconstruct(x) for x in inputs]
        with ThreadPoolExecutor(max_workers=3) as pool:
            par = list(pool.map(constrict.reconstruct, inputs))
        self.assertEqual(par, seq)


class Hostile(unittest.TestCase):
    """Found by a sweep of hostile arguments (2026-12-07): each was a silently wrong result or an
    error that was not constrict.Error."""

    def assertInvalid(self, pattern, f, *args, **kw):
        with self.assertRaisesRegex(constrict.Error, pattern) as ctx:
            f(*args, **kw)
        self.assertEqual(ctx.exception.code, "InvalidArgument")

    def test_arrays_reconstruct_refuses(self):
        pts = sample_data.curve(30, 3)
        # complex (the cast kept the real part), fewer columns than dim, ragged rows, (N, 4)
        self.assertInvalid("real numbers", constrict.reconstruct, pts + 1j)
        masked = np.ma.masked_array(pts, mask=np.zeros_like(pts, dtype=bool))
        masked.mask[3, 0] = True  # (the hidden value was read as a coordinate)
        self.assertInvalid("masked", constrict.reconstruct, masked)
        self.assertInvalid("masked", constrict.reconstruct2, masked)
        self.assertEqual(constrict.reconstruct2(np.ma.masked_array(pts)), constrict.reconstruct2(pts))
        self.assertInvalid("dim=3: the array has 2 columns", constrict.reconstruct, pts, dim=3)
        self.assertInvalid(r"\(N, 2\) or \(N, 3\)", constrict.reconstruct, [[0, 0], [1, 0, 0], [0, 1]])
        self.assertInvalid(r"\(N, 2\) or \(N, 3\), got \(10, 4\)", constrict.reconstruct, np.zeros((10, 4)))
        self.assertInvalid(r"\(N, 2\) or \(N, 3\)", constrict.gamma_graph, np.zeros((10, 4)))
        self.assertInvalid("seed_limit", constrict.reconstruct2, pts, topology="auto", seed_limit=2)
        self.assertInvalid("topology_gap must be a number", constrict.reconstruct2, pts, topology="auto",
                           topology_gap=10**400)
        self.assertInvalid("gamma must be 2 numbers", constrict.gamma_graph, pts, gamma=(0, 10**400))

    def test_second_sweep(self):
        """The second sweep (2026-12-07, 1 770 calls): text, dates and booleans were read as
        coordinates, refine= raised TypeError, a uint64 index 2**64 - 1 was named -1."""
        pts = sample_data.curve(30, 3)
        for bad in (pts.astype(str), pts.astype("S32"), pts.astype(str).astype(object), pts > 0.5,
                    pts.astype("datetime64[s]") if False else np.zeros(pts.shape, "datetime64[s]"),
                    np.zeros(pts.shape, "timedelta64[s]"), [["0", "0"], ["1", "0"], ["1", "1"], ["0", "1"]]):
            self.assertInvalid("real numbers", constrict.reconstruct2, bad)
            self.assertInvalid("real numbers", constrict.validate_polygon, bad, np.arange(len(bad)))
        self.assertEqual(constrict.reconstruct2(pts.astype(object)), constrict.reconstruct2(pts))  # numbers
        poly = constrict.reconstruct2(pts)
        self.assertInvalid("real numbers", poly.coordinates, pts + 1j)  # (the imaginary part was dropped)
        self.assertEqual(constrict.reconstruct2(pts, refine=np.bool_(False)), constrict.reconstruct2(pts, refine=False))
        for bad in (1, None, 0.0):
            self.assertInvalid("refine must be", constrict.reconstruct2, pts, refine=bad)
        big = np.array([0, 1, 2, 2**64 - 1], np.uint64)
        self.assertInvalid("18446744073709551615 out of range", constrict.validate_polygon, pts, big)
        for far in (len(pts), 2**40, -2**40):  # a verdict either way (2**40 raised)
            ok, why = constrict.validate_polygon(pts, list(range(len(pts) - 1)) + [far])
            self.assertFalse(ok)
            self.assertIn("out of range", why)
        self.assertInvalid("columns must be a sequence", constrict.read_points, "x.xy", columns=5)
        for bad in (None, 5, "shell"):
            self.assertInvalid("rings must be", constrict.validate_rings, pts, bad)
        self.assertInvalid("not -1$", constrict.reconstruct2, pts, topology="auto", topology_gap=-1)  # (-1.000000)
        with self.assertRaises(constrict.Error) as ctx:
            constrict.gamma_graph(pts, gamma=(10**400, 0))
        self.assertLess(len(str(ctx.exception)), 120)  # (the 400 digits were echoed whole)

    def test_validators_name_a_non_finite_point(self):
        q = np.array([[0, 0], [1, 0], [np.nan, 1]])
        ok, why = constrict.validate_rings(q, [dict(role="shell", parent=-1, indices=[0, 1, 2])])
        self.assertFalse(ok)  # (it was valid: every predicate at the NaN point was false)
        self.assertIn("non-finite", why)
        ok, why = constrict.validate_polygon(q, [0, 1, 2])
        self.assertFalse(ok)
        self.assertIn("non-finite", why)  # (the reason was empty)
        for bad in ({"role": "shell", "parent": None, "indices": [0, 1, 2]}, {"role": 1, "parent": -1, "indices": [0]},
                    {"role": "shell", "indices": [0, 1, 2]}, {"role": "shell", "parent": 2**40, "indices": [0]}):
            self.assertInvalid("ring 0", constrict.validate_rings, q, [bad])
        for parent in (np.array([-1]), np.bool_(False), True, -1.0):  # (TypeError, or taken for 0/-1)
            self.assertInvalid("parent must be", constrict.validate_rings, q, [dict(role="shell", parent=parent,
                                                                                     indices=[0, 1, 2])])
        ok, _ = constrict.validate_rings(np.array([[0, 0], [1, 0], [0, 1]]), [("shell", -1, [0, 1, 2])])
        self.assertTrue(ok)
        ok, _ = constrict.validate_rings(np.array([[0, 0], [1, 0], [0, 1]]), [("shell", np.int64(-1), [0, 1, 2])])
        self.assertTrue(ok)

    def test_file_names(self):
        pts = sample_data.curve(20, 4)
        poly = constrict.reconstruct2(pts)
        with tempfile.TemporaryDirectory() as d:
            # An embedded NUL cut the name there: PLY bytes went into "m.off".
            self.assertInvalid("null byte", constrict.write_polygon, os.path.join(d, "a.csv\0.idx"), pts, poly.boundary)
            self.assertFalse(os.path.exists(os.path.join(d, "a.csv")))
            # Names that are not UTF-8 (bytes, or os.listdir's surrogate escapes) and their errors.
            raw = os.path.join(os.fsencode(d), b"p\xff.xy")
            np.savetxt(raw.decode("utf-8", "surrogateescape"), pts)
            listed = [n for n in os.listdir(d) if n.startswith("p")][0]
            self.assertEqual(constrict.read_points(raw).shape, pts.shape)
            self.assertEqual(constrict.read_points(os.path.join(d, listed)).shape, pts.shape)
            with self.assertRaisesRegex(constrict.Error, r"missing\\xff") as ctx:
                constrict.read_points(os.path.join(os.fsencode(d), b"missing\xff.xy"))
            self.assertEqual(ctx.exception.code, "FileNotFound")
            # A file's bytes that are not UTF-8 in a parse error.
            bad = os.path.join(d, "latin.xy")
            with open(bad, "wb") as f:
                f.write(b"0 0\n1 \xff\n")
            with self.assertRaisesRegex(constrict.Error, r"latin.xy:2: .*\\xff") as ctx:
                constrict.read_points(bad)
            self.assertEqual(ctx.exception.code, "ParseError")
            # "-" is a file name here, not standard input.
            np.savetxt(os.path.join(d, "-"), pts[:5])
            cwd = os.getcwd()
            try:
                os.chdir(d)
                self.assertEqual(constrict.read_points("-").shape, (5, 2))
            finally:
                os.chdir(cwd)
            # Fewer than 3 vertices made "POLYGON (())"; ascii for a format that has no choice.
            self.assertInvalid("at least 3 vertices", constrict.write_polygon, os.path.join(d, "e.wkt"), pts, [0, 1])
            s = constrict.reconstruct3(sample_data.shell(30, 5))
            self.assertInvalid("True or False", constrict.write_mesh, os.path.join(d, "m.ply"),
                               sample_data.shell(30, 5), s.triangles, ascii="no")
            self.assertInvalid(".ply", constrict.write_mesh, os.path.join(d, "m.off"), sample_data.shell(30, 5),
                               s.triangles, ascii=True)
            # columns: Python's 0-based numbers, header names that are names.
            np.savetxt(os.path.join(d, "c.xyz"), np.c_[np.arange(20), pts])
            self.assertInvalid("not a header name", constrict.read_points, os.path.join(d, "c.xyz"), columns=("1", "2"))
            self.assertInvalid("given twice", constrict.read_points, os.path.join(d, "c.xyz"), columns=(1, 1))
            self.assertTrue(np.array_equal(constrict.read_points(os.path.join(d, "c.xyz"), columns=(1, 2)), pts))

    def test_what_worked_before_still_works(self):
        # Extra columns with dim: the first dim of them (as read_points(dim=...) takes a file's).
        xyz = sample_data.shell(40, 8)
        s = constrict.reconstruct(np.c_[xyz, np.arange(40.0)], dim=3)
        self.assertEqual(s, constrict.reconstruct3(xyz))
        # An incomplete ring set (fallback="none") draws over the array it was made from.
        rng = np.random.default_rng(6)
        pts = np.vstack([rng.random((40, 2)), rng.random((40, 2)) + [5, 0]])
        rr = constrict.reconstruct2(pts, topology="auto", fallback="none")
        if importlib.util.find_spec("shapely") is not None:
            rr.to_shapely(pts)
        self.assertInvalid("at least", rr.to_shapely, pts[:10])

    def test_result_helpers_check_their_points(self):
        pts = sample_data.curve(30, 6)
        poly = constrict.reconstruct2(pts)
        self.assertTrue(np.array_equal(poly.coordinates(pts), pts[poly.boundary]))
        self.assertInvalid("over 30 points, got 60", poly.coordinates, np.random.default_rng(5).random((60, 2)))
        self.assertInvalid(r"shape \(N, 2\)", poly.coordinates, np.c_[pts, pts[:, :1]])
        shell = sample_data.shell(40, 6)
        s = constrict.reconstruct3(shell)
        self.assertInvalid("over 40 points, got 10", s._points, shell[:10], "to_meshio")
        self.assertEqual(s._points(shell, "to_meshio").shape, (40, 3))


if __name__ == "__main__":
    unittest.main()
