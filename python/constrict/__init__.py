# SPDX-License-Identifier: GPL-3.0-or-later
"""Object reconstruction with the gamma-neighborhood graph (Veltkamp).

A simple polygon through all points in 2D (:func:`reconstruct2`), a closed genus-0 surface
through all points in 3D (:func:`reconstruct3`), the graphs of the gamma family
(:func:`gamma_graph`), exact validators, and the library's readers and writers.

Arrays in, arrays out: points are any array-like of shape (N, 2) or (N, 3) (copied as float64),
index arrays are int64 numpy arrays of input row numbers. Results are plain dataclasses
(:class:`Polygon`, :class:`Surface`) that pickle, so they travel between processes (Dask,
multiprocessing). Bad input raises :class:`Error` (a ``ValueError``) with the library's
one-line message and the status name in ``.code``. The C++ work releases the GIL, so threads run
reconstructions in parallel. ``python3 -m constrict`` is the command line. See docs/python.md.
"""
from __future__ import annotations

import collections.abc
import dataclasses
import json
import math
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core

__version__: str = _core.__version__

Error = _core.Error
Error.__module__ = "constrict"  # constrict.Error in messages, and what pickle looks up
Error.__doc__ = (
    "Bad input or a failed read/write: the library's one-line message, the status name "
    "(Duplicate, Collinear, Coplanar, TooFewPoints, NonFinite, InvalidArgument, FileNotFound, "
    "ParseError, WriteFailed, ...) in .code. A subclass of ValueError."
)

__all__ = [
    "Error", "Polygon", "Rings", "Ring", "Surface", "reconstruct", "reconstruct2", "reconstruct3", "gamma_graph",
    "validate_polygon", "validate_rings", "validate_surface", "read_points", "read_points_info", "read_mesh",
    "write_mesh", "write_polygon", "write_body", "cli_path", "__version__",
]

ArrayLike = Any  # anything numpy.asarray takes: arrays, lists of rows, ...
Refine = Union[bool, str]
PathLike = Union[str, bytes, "os.PathLike[str]"]


# ---- results ---------------------------------------------------------------------------------

def _optional(module: str, what: str, package: str):
    """Imports an optional dependency, or says which Debian package / pip name provides it."""
    try:
        return __import__(module, fromlist=["_"])
    except ImportError as e:
        raise ImportError(f"{what} needs the '{module}' module: install {package}") from e


def _result_points(points: ArrayLike, dim: int, used: List[np.ndarray], rows: Optional[int], what: str) -> np.ndarray:
    """The points a result's indices refer to, checked: (N, dim), every used row present, and
    exactly ``rows`` rows when the result knows its point count (a complete one)."""
    try:
        raw = np.asarray(points)
        # (The cast drops a complex number's imaginary part and parses text: as reconstruct2 does,
        # only real numbers.)
        xy = np.asarray(raw, dtype=float) if raw.dtype.kind in "fiuO" else None
    except (TypeError, ValueError) as e:
        raise _invalid(f"{what}: points must be an (N, {dim}) array of numbers ({e})") from None
    if xy is None:
        raise _invalid(f"{what}: points must be real numbers, not {raw.dtype}")
    if xy.ndim != 2 or xy.shape[1] != dim:
        raise _invalid(f"{what}: points must have shape (N, {dim}), got {xy.shape}")
    top = max((int(u.max()) for u in used if len(u)), default=-1)
    if xy.shape[0] <= top or (rows is not None and xy.shape[0] != rows):
        want = rows if rows is not None else f"at least {top + 1}"
        raise _invalid(f"{what}: the result is over {want} points, got {xy.shape[0]}: pass the array it was made from")
    return xy


@dataclasses.dataclass(repr=False)
class Polygon:
    """Result of :func:`reconstruct2`: a simple counter-clockwise polygon through the points.

    Plain data (numpy arrays, numbers, strings): it pickles, and ``==`` compares every field
    but the wall-clock ones (timings_ms, report_json).
    Indices are rows of the array given to reconstruct2 (also with ``merge_duplicates=True``).
    """

    boundary: np.ndarray  #: int64 (B,): vertex rows in counter-clockwise order, each point once
    valid: bool  #: complete and validated exactly: simple, CCW, every point once
    complete: bool  #: every point on the boundary (false only for fallback="none" / stop_after)
    method: str  #: last stage that placed a point: gamma, gamma0=<v>, degree4, repair, star, locked, stopped, voronoi-skeleton
    criterion: str  #: the constriction's criterion (gamma, min-area-change, boissonnat)
    locked: bool  #: the Delaunay (gamma0 = 0) constriction locked
    stuck_points: np.ndarray  #: int64: points inside when the constriction stopped
    area: float
    perimeter: float
    removed_simplices: int  #: triangles removed by the Delaunay constriction
    fallback_edges: np.ndarray  #: int64 (K, 2): polygon edges that are not Delaunay edges
    stages: List[Tuple[str, int]]  #: (stage name, points placed), in order
    refine_moves: int  #: moves of the local-search refinement
    timings_ms: Dict[str, float]  #: delaunay, constrict, fallback, refine, validate
    merged_duplicates: np.ndarray  #: int64: rows dropped as later copies (merge_duplicates=True)
    report_json: str  #: the library's JSON report, verbatim (see report())
    skeleton: Optional[Dict[str, Any]] = None  #: method="voronoi-skeleton": the search statistics
    #: topology="auto": one dict per closed surface -- "role" ("outer" | "inner": faces into a
    #: cavity), "parent" (index or -1), "genus", "triangles" (int64 rows of ``triangles``),
    #: "points" (int64), "gap_spacings" (to the nearest other surface); None in single mode.
    surfaces: Optional[List[Dict[str, Any]]] = None
    topology: str = "single"  #: "single" or "auto"

    def report(self) -> str:
        """The library's JSON report (the fields of ``constrict reconstruct --report`` that the
        library writes; the CLI adds input/output names and read/write times), a str."""
        return self.report_json

    def report_dict(self) -> Dict[str, Any]:
        """:meth:`report` parsed into a dict."""
        return json.loads(self.report_json)

    def __eq__(self, other: object) -> bool:
        return _same(self, other)

    def __repr__(self) -> str:
        state = "valid" if self.valid else "incomplete" if not self.complete else "invalid"
        return f"<constrict.Polygon {len(self.boundary)} vertices, method={self.method}, {state}>"

    def coordinates(self, points: ArrayLike) -> np.ndarray:
        """(B, 2) coordinates of the boundary, in order (the ring not closed). ``points``: the
        array given to reconstruct2 (checked: its shape and, for a complete result, its rows)."""
        rows = len(self.boundary) + len(self.merged_duplicates) if self.complete else None
        xy = _result_points(points, 2, [self.boundary, self.stuck_points], rows, "Polygon.coordinates()")
        return xy[self.boundary]

    def to_shapely(self, points: ArrayLike):
        """The polygon as a ``shapely.geometry.Polygon`` over ``points`` (the array given to
        reconstruct2). Needs shapely (Debian: python3-shapely)."""
        geometry = _optional("shapely.geometry", "Polygon.to_shapely()", "python3-shapely (pip: shapely)")
        return geometry.Polygon(self.coordinates(points))


@dataclasses.dataclass
class Ring:
    """One ring of :class:`Rings`: a simple polygon over input rows."""

    role: str  #: "shell" (counter-clockwise) or "hole" (clockwise)
    parent: int  #: index of the ring that directly contains it, -1 for none
    indices: np.ndarray  #: int64: input rows in order (closed implicitly)
    gap_spacings: float = math.inf  #: the smallest gap to another ring, in local spacings

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Ring) and self.role == other.role and self.parent == other.parent
                and np.array_equal(self.indices, other.indices))


@dataclasses.dataclass(repr=False)
class Rings:
    """Result of :func:`reconstruct2` with ``topology="auto"``: the rings the data show.

    Every input point is a vertex of exactly one ring; rings are simple and do not touch; shells
    run counter-clockwise, holes clockwise, and each hole lies inside its parent (any depth).
    Plain data: it pickles. docs/topology.md.
    """

    topology: str  #: "auto" or "single"
    rings: List[Ring]
    valid: bool  #: validated exactly (validate_rings)
    decision: str  #: what decided it (see report()["topology"])
    area: float  #: holes subtract
    perimeter: float
    report_json: str

    def report(self) -> str:
        """The library's JSON report (``rings`` and the ``topology`` block), a str."""
        return self.report_json

    def report_dict(self) -> Dict[str, Any]:
        return json.loads(self.report_json)

    @property
    def shells(self) -> List[Ring]:
        return [r for r in self.rings if r.role == "shell"]

    @property
    def holes(self) -> List[Ring]:
        return [r for r in self.rings if r.role == "hole"]

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Rings) and self.topology == other.topology and self.rings == other.rings
                and self.valid == other.valid)

    def __repr__(self) -> str:
        return (f"<constrict.Rings {len(self.shells)} shell(s), {len(self.holes)} hole(s), "
                f"{'valid' if self.valid else 'invalid'}>")

    def to_shapely(self, points: ArrayLike):
        """The rings as a shapely Polygon or MultiPolygon (holes inside their shells). Needs shapely."""
        geometry = _optional("shapely.geometry", "Rings.to_shapely()", "python3-shapely (pip: shapely)")
        # (A valid ring set covers every point once; an incomplete one, fallback="none", may not.)
        rows = sum(len(r.indices) for r in self.rings) if self.valid else None
        xy = _result_points(points, 2, [r.indices for r in self.rings], rows, "Rings.to_shapely()")
        polys = []
        for k, r in enumerate(self.rings):
            if r.role != "shell":
                continue
            holes = [xy[h.indices] for h in self.rings if h.role == "hole" and h.parent == k]
            polys.append(geometry.Polygon(xy[r.indices], holes))
        return polys[0] if len(polys) == 1 else geometry.MultiPolygon(polys)


@dataclasses.dataclass(repr=False)
class Surface:
    """Result of :func:`reconstruct3`: a closed genus-0 triangulated surface through the points
    and the tetrahedral body it bounds.

    Plain data (numpy arrays, numbers, strings): it pickles, and ``==`` compares every field
    but the wall-clock ones (timings_ms, report_json).
    Indices are rows of the array given to reconstruct3 (also with ``merge_duplicates=True``).
    """

    triangles: np.ndarray  #: int64 (F, 3): vertex rows, oriented outward
    tetrahedra: np.ndarray  #: int64 (T, 4): the body, positively oriented
    valid: bool  #: complete and validated: closed, manifold, outward, genus 0, every point a vertex
    complete: bool  #: every point on the surface
    genus: int  #: 0 when valid, else -1
    method: str  #: gamma, grow, cavity, locked, stopped, voronoi-skeleton, incomplete
    criterion: str  #: the constriction's criterion (gamma, min-area-change, boissonnat)
    volume: float
    area: float
    locked: bool  #: the Delaunay constriction locked
    stuck_points: np.ndarray  #: int64: points inside when it locked
    unplaced_points: np.ndarray  #: int64: points still inside at the end (empty when complete)
    stages: List[Tuple[str, int, int]]  #: (stage name, points placed, tetrahedra removed)
    timings_ms: Dict[str, float]  #: the library's phases
    merged_duplicates: np.ndarray  #: int64: rows dropped as later copies (merge_duplicates=True)
    report_json: str  #: the library's JSON report, verbatim (see report())
    skeleton: Optional[Dict[str, Any]] = None  #: method="voronoi-skeleton": the search statistics
    #: topology="auto": one dict per closed surface -- "role" ("outer" | "inner": faces into a
    #: cavity), "parent" (index or -1), "genus", "triangles" (int64 rows of ``triangles``),
    #: "points" (int64), "gap_spacings" (to the nearest other surface); None in single mode.
    surfaces: Optional[List[Dict[str, Any]]] = None
    topology: str = "single"  #: "single" or "auto"

    def report(self) -> str:
        """The library's JSON report (the fields of ``constrict reconstruct --report`` that the
        library writes; the CLI adds input/output names, validation details and times), a str."""
        return self.report_json

    def report_dict(self) -> Dict[str, Any]:
        """:meth:`report` parsed into a dict."""
        return json.loads(self.report_json)

    def __eq__(self, other: object) -> bool:
        return _same(self, other)

    def __repr__(self) -> str:
        state = "valid" if self.valid else "incomplete" if not self.complete else "invalid"
        return f"<constrict.Surface {len(self.triangles)} triangles, method={self.method}, {state}>"

    def to_meshio(self, points: ArrayLike, body: bool = False):
        """The surface as a ``meshio.Mesh`` (vertices = all points, one "triangle" cell block;
        with ``body=True`` also the "tetra" block). Needs meshio (Debian: python3-meshio)."""
        _check_flags(body=body)
        meshio = _optional("meshio", "Surface.to_meshio()", "python3-meshio (pip: meshio)")
        xyz = self._points(points, "Surface.to_meshio()")
        cells = [("triangle", self.triangles)]
        if body:
            cells.append(("tetra", self.tetrahedra))
        return meshio.Mesh(xyz, cells)

    def _points(self, points: ArrayLike, what: str) -> np.ndarray:
        """``points`` checked against this result (the array given to reconstruct3)."""
        rows = None
        if self.complete and self.topology == "single":
            rows = len(np.unique(self.triangles)) + len(self.merged_duplicates)
        return _result_points(points, 3, [self.triangles, self.tetrahedra, self.unplaced_points], rows, what)

    def to_open3d(self, points: ArrayLike):
        """The surface as an ``open3d.geometry.TriangleMesh``. Needs Open3D (not in Debian 12:
        ``pip install open3d`` where wheels exist)."""
        o3d = _optional("open3d", "Surface.to_open3d()", "open3d (pip: open3d; not packaged in Debian 12)")
        return o3d.geometry.TriangleMesh(
            o3d.utility.Vector3dVector(self._points(points, "Surface.to_open3d()")),
            o3d.utility.Vector3iVector(self.triangles.astype(np.int32)),
        )


def _same(a: object, b: object) -> bool:
    """Field-by-field equality with numpy arrays compared by value."""
    if type(a) is not type(b):
        return NotImplemented
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, np.ndarray):
            if not np.array_equal(x, y):
                return False
        elif f.name == "timings_ms" or f.name == "report_json":
            continue  # wall-clock times differ between equal runs
        elif f.name == "surfaces" and x is not None and y is not None:
            if len(x) != len(y) or any(set(s) != set(t) or any(
                    not np.array_equal(s[k], t[k]) if isinstance(s[k], np.ndarray) else s[k] != t[k] for k in s)
                    for s, t in zip(x, y)):
                return False
        elif x != y:
            return False
    return True


# ---- keyword checking --------------------------------------------------------------------------

# CLI flags that are not reconstruction options, and what to do in Python instead.
_NOT_OPTIONS = {
    "dim": "pass an (N, 2) or (N, 3) array (read_points(path, dim=...) forces the dimension of a file)",
    "output": "write the result with write_polygon()/write_mesh()",
    "o": "write the result with write_polygon()/write_mesh()",
    "body": "write the body with write_body(path, points, surface.tetrahedra)",
    "ascii": "pass ascii=True to write_mesh()",
    "report": "the report is result.report() (str) / result.report_dict()",
    "render": "the CLI draws pictures: python3 -m constrict reconstruct IN -o OUT --render PIC",
    "quiet": "the Python functions print nothing",
    "no_grow": "use grow=False",
}
_ONLY_3D = ("fast", "grow", "validate_self_intersections")


def _reject(func: str, extra: Dict[str, Any]) -> None:
    """TypeError for keywords reconstruct2/3 do not take, naming the right place for each."""
    if not extra:
        return
    name = sorted(extra)[0]
    if name in _NOT_OPTIONS:
        hint = _NOT_OPTIONS[name]
    elif func == "reconstruct2" and name in _ONLY_3D:
        hint = f"'{name}' applies to 3D only (reconstruct3)"
    else:
        hint = "see help(constrict." + func + ")"
    raise TypeError(f"{func}() got an unexpected keyword argument '{name}': {hint}")


def _refine_name(refine: Refine) -> str:
    if isinstance(refine, (bool, np.bool_)):
        return "auto" if refine else "none"
    if isinstance(refine, str):
        return refine
    raise _invalid(f"refine must be True, False or a name ('auto', 'none'), not {refine!r}")


def _skeleton_options(method: str, seed_limit: int, **constriction: Any) -> None:
    """seed_limit belongs to the Voronoi skeleton; the constriction's options do not."""
    if method == "voronoi-skeleton":
        given = sorted(k for k, (value, default) in constriction.items() if value != default)
        if given:
            raise _invalid(f"{', '.join(given)}: not an option of method='voronoi-skeleton'")
    elif seed_limit:
        raise _invalid("seed_limit applies to method='voronoi-skeleton' only")


def _invalid(message: str):
    err = Error(message)
    err.code = "InvalidArgument"
    return err


def _check_types(**options: Any) -> None:
    """Refuses a keyword of the wrong type with one short line (pybind11's own TypeError printed
    the whole internal signature and the point array): strings, flags, counts and numbers."""
    for name, value in options.items():
        if name in ("fallback", "method", "topology"):
            ok, want = isinstance(value, str), "a string"
        elif name in ("merge_duplicates", "grow", "fast", "validate_self_intersections"):
            ok, want = isinstance(value, (bool, np.bool_)), "True or False"
        elif name == "seed_limit":
            ok = (isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))
                  and 0 <= value < 2**64)
            want = "an integer from 0 to 2**64 - 1"
        elif name == "topology_gap":
            ok = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
            ok = ok and _as_float(value) is not None
            want = "a number"
        else:
            continue
        if not ok:
            raise _invalid(f"{name} must be {want}, not {_shown(value)}")


def _check_dim(dim: Any) -> None:
    """dim: None (from the data), 2 or 3, as the CLI's --dim."""
    if dim is not None and (isinstance(dim, (bool, np.bool_)) or not isinstance(dim, (int, np.integer))
                            or dim not in (2, 3)):
        raise _invalid(f"dim must be None, 2 or 3, not {dim!r}")


def _check_flags(**flags: Any) -> None:
    for name, value in flags.items():
        if not isinstance(value, (bool, np.bool_)):
            raise _invalid(f"{name} must be True or False, not {value!r}")


def _shown(value: Any) -> str:
    """repr(value) for a message, cut to 60 characters (an int of 400 digits was echoed whole)."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _as_float(value: Any) -> Optional[float]:
    """float(value), or None where Python cannot (an int beyond the doubles: OverflowError)."""
    try:
        return float(value)
    except (OverflowError, TypeError, ValueError):
        return None


def _numbers(name: str, value: Any, count: int) -> Optional[list]:
    """A gamma graph's threshold pair or interval: None or `count` real numbers."""
    if value is None:
        return None
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != count or not all(
            isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))
            and _as_float(v) is not None for v in value):
        raise _invalid(f"{name} must be {count} numbers, not {_shown(value)}")
    return [float(v) for v in value]


def _path(path: Any) -> bytes:
    """A file name for the library: str, bytes or os.PathLike, as open() takes them (a name
    that is not UTF-8, e.g. from os.listdir, is passed as its bytes). "-" is the file of that
    name (the CLI's standard input is not the Python API's)."""
    try:
        name = os.fsencode(os.fspath(path))
    except TypeError:
        raise _invalid(f"a file name must be str, bytes or os.PathLike, not {type(path).__name__}") from None
    except UnicodeEncodeError:  # (a lone surrogate that no file system name escapes)
        raise _invalid(f"file name that cannot be encoded: {path!r}") from None
    if b"\0" in name:
        raise _invalid(f"file name with an embedded null byte: {path!r}")  # (a C string would end there)
    return b"./-" if name == b"-" else name


def _gap_needs_auto(topology: str, topology_gap: Any) -> None:
    if topology == "single" and topology_gap != 2.0:
        raise _invalid("topology_gap applies to topology='auto' (the single mode has no parts to separate)")


def _with_skeleton(d: Dict[str, Any]) -> Dict[str, Any]:
    """The CLI's report fields of the Voronoi skeleton, added to the library's report."""
    if d["skeleton"] is not None:
        rep = json.loads(d["report_json"])
        rep["method_requested"] = "voronoi-skeleton"
        rep["criterion"] = None
        rep["voronoi_skeleton"] = d["skeleton"]
        d["report_json"] = json.dumps(rep, sort_keys=True, separators=(",", ":"))
    return d


# ---- reconstruction ----------------------------------------------------------------------------

def reconstruct2(
    points: ArrayLike,
    fallback: str = "auto",
    refine: Refine = True,
    *,
    method: str = "gamma",
    stop_after: Optional[int] = None,
    seed_limit: int = 0,
    merge_duplicates: bool = False,
    topology: str = "single",
    topology_gap: float = 2.0,
    **unknown: Any,
) -> Union[Polygon, "Rings"]:
    """Simple polygon through every point of an (N, 2) array (or, with ``topology="auto"``,
    the rings the data show).

    The gamma-constriction of the Delaunay triangulation, local fallbacks after a lock, a
    length-decreasing refinement; validated exactly. The keywords are the options of
    ``constrict reconstruct`` (same names, ``-`` spelled ``_``) and give the same polygon:

    Args:
        points: (N, 2) array-like of numbers; N >= 3, not all collinear, no duplicates (unless
            merge_duplicates).
        fallback: on a lock: "auto" (gamma0 schedule, degree-4, repair; always completes),
            "gamma0", "degree4", or "none" (stop: complete=False, stuck_points listed).
            CLI --fallback.
        refine: True / "auto": the local-search post-pass (2-opt, Or-opt); False / "none": the
            paper's algorithm (Constrict2Options::paper()). CLI --refine.
        method: the constriction's criterion: "gamma" (default), "min-area-change",
            "boissonnat"; or "voronoi-skeleton" (the comparison method). CLI --method.
        stop_after: stop the constriction after this many removals (the result is then
            incomplete); None: run to the end. CLI --stop-after.
        seed_limit: method="voronoi-skeleton" only: try at most this many seeds (0 = all).
            CLI --seed-limit.
        merge_duplicates: drop later copies of identical points instead of raising; indices in
            the result stay rows of ``points``, the dropped rows are in
            ``result.merged_duplicates``. CLI --merge-duplicates.
        topology: "single" (default): one polygon, a :class:`Polygon`. "auto": the rings the
            data show (holes, several parts, nesting), a :class:`Rings`. CLI --topology.
        topology_gap: parts at least this many local spacings apart become separate rings, and
            holes traced by the nearest-neighbour walk at least half of it (topology="auto";
            docs/topology.md, Method 6). CLI --topology-gap.

    Returns:
        :class:`Polygon`.

    Raises:
        Error: bad input (Duplicate names the rows, Collinear, TooFewPoints, NonFinite) or an
            unknown option value (InvalidArgument).
        TypeError: a keyword reconstruct2 does not take (e.g. grow, which is 3D only).
    """
    _reject("reconstruct2", unknown)
    _check_types(fallback=fallback, method=method, topology=topology, topology_gap=topology_gap,
                 seed_limit=seed_limit, merge_duplicates=merge_duplicates)
    ref = _refine_name(refine)
    _gap_needs_auto(topology, topology_gap)
    if topology != "single":
        if merge_duplicates:
            err = Error("topology: merge the duplicates first (merge_duplicates gives one polygon)")
            err.code = "InvalidArgument"
            raise err
        if seed_limit:
            raise _invalid("seed_limit applies to method='voronoi-skeleton' (one polygon), not to topology='auto'")
        d = _core.rings2(points, topology, float(topology_gap), fallback, ref, method, stop_after)
        d["rings"] = [Ring(**r) for r in d["rings"]]
        return Rings(**d)
    _skeleton_options(method, seed_limit, fallback=(fallback, "auto"), refine=(ref, "auto"),
                      stop_after=(stop_after, None))
    d = _core.reconstruct2(points, fallback, ref, method, stop_after, seed_limit, merge_duplicates)
    return Polygon(**_with_skeleton(d))


def reconstruct3(
    points: ArrayLike,
    grow: bool = True,
    *,
    fallback: str = "auto",
    refine: Refine = True,
    fast: bool = False,
    method: str = "gamma",
    stop_after: Optional[int] = None,
    seed_limit: int = 0,
    merge_duplicates: bool = False,
    validate_self_intersections: bool = False,
    topology: str = "single",
    topology_gap: float = 2.0,
    **unknown: Any,
) -> Surface:
    """Closed genus-0 triangulated surface through every point of an (N, 3) array, and the
    tetrahedral body it bounds; validated (closed, manifold, oriented, genus 0).

    The keywords are the options of ``constrict reconstruct`` (same names, ``-`` spelled ``_``)
    and give the same surface:

    Args:
        points: (N, 3) array-like of numbers; N >= 4, not all coplanar, no duplicates (unless
            merge_duplicates).
        grow: True: grow the body from the inside first (docs/reconstruction-3d.md §4.7);
            False: constrict from the convex hull only. CLI --no-grow is grow=False.
        fallback: on a lock: "auto" (star cavities) or "none" (stop: complete=False).
            CLI --fallback ("gamma0"/"degree4" are 2D only and raise).
        refine: True / "auto": carve and edge-flip post-passes (the default preset); False /
            "none": the paper's algorithm (Constrict3Options::paper(): no growth, no labels, no
            post-pass). CLI --refine.
        fast: one constriction run instead of two variants when the growth does not reach every
            point (Constrict3Options::fast()). CLI --fast. Has no effect with refine=False.
        method: the constriction's criterion: "gamma" (default), "min-area-change",
            "boissonnat"; or "voronoi-skeleton" (the comparison method). CLI --method.
        stop_after: stop the constriction after this many removals (the result is then
            incomplete); None: run to the end. CLI --stop-after.
        seed_limit: method="voronoi-skeleton" only: try at most this many seeds (0 = all).
            CLI --seed-limit.
        merge_duplicates: drop later copies of identical points instead of raising; indices in
            the result stay rows of ``points``, the dropped rows are in
            ``result.merged_duplicates``. CLI --merge-duplicates.
        validate_self_intersections: add the exact self-intersection test to the library's
            validation (O(F log F + K); off by default, the surface bounds a
            tetrahedralization).
        topology: "single" (default): one closed genus-0 surface. "auto": the surfaces the data
            show -- separate parts, inner shells (cavities) and handles (any genus); the result's
            ``surfaces`` lists them and ``genus`` is the total. CLI --topology. docs/topology.md.
        topology_gap: parts at least this many local spacings apart get separate surfaces
            (topology="auto"). CLI --topology-gap.

    Returns:
        :class:`Surface`.

    Raises:
        Error: bad input (Duplicate names the rows, Coplanar, TooFewPoints, NonFinite) or an
            unknown option value (InvalidArgument).
        TypeError: a keyword reconstruct3 does not take.
    """
    _reject("reconstruct3", unknown)
    _check_types(fallback=fallback, method=method, topology=topology, topology_gap=topology_gap,
                 seed_limit=seed_limit, merge_duplicates=merge_duplicates, grow=grow, fast=fast,
                 validate_self_intersections=validate_self_intersections)
    ref = _refine_name(refine)
    _skeleton_options(method, seed_limit, fallback=(fallback, "auto"), refine=(ref, "auto"),
                      stop_after=(stop_after, None), grow=(grow, True), fast=(fast, False))
    if fast and ref == "none":
        raise _invalid("fast=True does not apply with refine=False (the paper's algorithm is one run)")
    _gap_needs_auto(topology, topology_gap)
    if topology != "single":
        if stop_after is not None:
            raise _invalid("topology: needs the constriction run to the end (no stop_after=)")
        d = _core.surfaces3(points, topology, float(topology_gap), fallback, ref, fast, grow, method, merge_duplicates,
                            validate_self_intersections)
        d["skeleton"] = None
        return Surface(**d)
    d = _core.reconstruct3(points, fallback, ref, fast, grow, method, stop_after, seed_limit,
                           merge_duplicates, validate_self_intersections)
    return Surface(**_with_skeleton(d))


def reconstruct(source: Union[ArrayLike, "PathLike"], *, dim: Optional[int] = None,
                merge_duplicates: bool = False, **options: Any) -> Union[Polygon, Surface]:
    """:func:`reconstruct2` or :func:`reconstruct3` by dimension, on an array or a point file
    (read with :func:`read_points`, ``dim`` and ``merge_duplicates`` as there): the Python form
    of ``constrict reconstruct IN``. One function of one argument, handy for ``map`` over files
    (threads, processes, Dask). ``options`` are the keywords of reconstruct2/3."""
    _check_dim(dim)
    _check_flags(merge_duplicates=merge_duplicates)
    if isinstance(source, (str, bytes, os.PathLike)):
        points = read_points(source, dim=dim, merge_duplicates=merge_duplicates)
    else:
        try:  # (not cast here: reconstruct2/3 refuse complex numbers and masked entries)
            points = np.asanyarray(source)
        except (TypeError, ValueError) as e:  # (ragged rows)
            raise _invalid(f"points must be an (N, 2) or (N, 3) array of numbers ({e})") from None
        if dim is not None and points.ndim == 2 and points.shape[1] != dim:
            if points.shape[1] < dim:
                raise _invalid(f"dim={dim}: the array has {points.shape[1]} columns")
            points = points[:, :dim]  # (the first dim columns, as read_points(dim=...) takes a file's)
        if points.ndim != 2 or points.shape[1] not in (2, 3):
            raise _invalid(f"points must have shape (N, 2) or (N, 3), got {points.shape}")
        options["merge_duplicates"] = merge_duplicates
    if points.ndim == 2 and points.shape[1] == 3:
        return reconstruct3(points, **options)
    return reconstruct2(points, **options)


def gamma_graph(points: ArrayLike, preset: str = "", gamma: Optional[Sequence[float]] = None,
                interval: Optional[Sequence[float]] = None) -> Dict[str, Any]:
    """A graph of the gamma family on an (N, 2) or (N, 3) array.

    Give at most one of: ``preset`` (hull, delaunay [default], gabriel, beta-circle=B,
    beta-lune=B, complete, void), ``gamma=(g0, g1)`` or ``interval=(a0, a1, b0, b1)``.

    Returns:
        dict: ``faces`` (int64; edges in 2D, triangles in 3D, sorted ids), ``gamma_a``,
        ``gamma_b``, ``delta`` (float arrays, one per face) and ``graph`` (its name).
    """
    if not isinstance(preset, str):
        raise _invalid(f"preset must be a string (a graph's name), not {preset!r}")
    return _core.gamma_graph(points, preset, _numbers("gamma", gamma, 2), _numbers("interval", interval, 4))


def validate_polygon(points: ArrayLike, boundary: ArrayLike) -> Tuple[bool, str]:
    """(ok, reason): is ``boundary`` a simple counter-clockwise polygon through every point
    exactly once? Exact predicates."""
    return _core.validate_polygon(points, boundary)


def validate_rings(points: ArrayLike, rings: Any) -> Tuple[bool, str]:
    """(ok, reason): is ``rings`` (a :class:`Rings`, or a list of :class:`Ring` / dicts with role,
    parent, indices) a valid ring set: every point once, rings simple and disjoint, shells CCW,
    holes CW, each parent the innermost containing ring? Exact predicates."""
    rings = rings.rings if isinstance(rings, Rings) else rings
    if isinstance(rings, (str, bytes, dict)) or not isinstance(rings, collections.abc.Iterable):
        raise _invalid(f"rings must be a Rings result or a list of Ring / dicts (role, parent, indices), not {rings!r:.80}")
    return _core.validate_rings(points, rings)


def validate_surface(points: ArrayLike, triangles: ArrayLike,
                     tetrahedra: Optional[ArrayLike] = None) -> Tuple[bool, str]:
    """(ok, reason): is the mesh closed, manifold, outward oriented, connected, genus 0 and
    through every point? With ``tetrahedra`` (a topology="auto" result's body): any number of
    surfaces and any genus, and the triangles must be exactly the body's free faces, oriented out
    of it (validate_surfaces3)."""
    return _core.validate_surface(points, triangles, tetrahedra)


# ---- files -------------------------------------------------------------------------------------

def read_points_info(path: PathLike, dim: Optional[int] = None, columns: Optional[Sequence[int]] = None,
                     merge_duplicates: bool = False, check: bool = True) -> Tuple[np.ndarray, Dict[str, Any]]:
    """:func:`read_points` plus what the reader saw: a dict with ``points_read``,
    ``merged_duplicates`` (count), ``original_index`` (int64: the file row of each point),
    ``warnings`` and, from PLY files, ``normals`` (N, 3) and ``colors`` (N, 3 or 4) in [0, 1]."""
    path = _path(path)
    _check_dim(dim)
    _check_flags(merge_duplicates=merge_duplicates, check=check)
    if columns is None:
        return _core.read_points(path, 0 if dim is None else dim, merge_duplicates, check)
    if isinstance(columns, (str, bytes)):
        raise _invalid(f"columns must be a sequence of 2 or 3 field numbers or header names, not {columns!r}")
    if not isinstance(columns, collections.abc.Iterable):
        raise _invalid(f"columns must be a sequence of 2 or 3 field numbers or header names, not {columns!r}")
    cols = list(columns)
    if len(cols) not in (2, 3) or dim not in (None, len(cols)):
        raise _invalid(f"columns must name 2 or 3 columns (and match dim), got {cols}")
    if all(isinstance(c, (str, int, np.integer)) for c in cols) and len(set(cols)) != len(cols):
        raise _invalid(f"columns: a column is given twice, {cols}")
    if all(isinstance(c, str) for c in cols):  # header names, as the CLI's --columns x,y,z
        for c in cols:
            if not c.strip() or "," in c or c.strip().isdigit():
                raise _invalid(f"columns: {c!r} is not a header name (field numbers are ints, counted from 0)")
        spec = ",".join(c.strip() for c in cols)
    elif all(isinstance(c, (int, np.integer)) and not isinstance(c, bool) for c in cols):
        if min(cols) < 0:
            raise _invalid(f"columns are 0-based field numbers (or header names), got {cols}")
        spec = ",".join(str(int(c) + 1) for c in cols)  # the library counts from 1
    else:
        raise _invalid(f"columns must be all field numbers or all header names, got {cols}")
    return _core.read_points(path, 0, merge_duplicates, check, spec)


def read_points(path: PathLike, dim: Optional[int] = None, columns: Optional[Sequence[int]] = None,
                merge_duplicates: bool = False) -> np.ndarray:
    """Reads a point file with the library's reader (the CLI's): text columns (.xyz .xy .csv
    .txt: whitespace, comma, semicolon or tab separated; ``#`` comments; one optional header),
    PLY (ascii/binary), OFF, OBJ vertices. docs/input-formats.md has every rule and message.

    Args:
        path: the file.
        dim: None: from the data (2 or 3 columns); 2 or 3: forced (dim=2 drops z). CLI --dim.
        columns: the fields holding x, y[, z]: 0-based numbers, e.g. (1, 2, 3) after an id
            column, or header names, e.g. ("x", "y", "z"). CLI --columns (1-based there).
        merge_duplicates: keep the first of identical points instead of raising Duplicate
            (read_points_info() says which file rows were kept). CLI --merge-duplicates.

    Returns:
        float64 array (N, dim). The points are checked as the CLI checks them (duplicates, too
        few, collinear/coplanar).

    Raises:
        Error: FileNotFound, ParseError ("file:LINE: ..."), NonFinite, EmptyInput, Duplicate,
            TooFewPoints, Collinear, Coplanar.
    """
    return read_points_info(path, dim, columns, merge_duplicates)[0]


def read_mesh(path: PathLike) -> Tuple[np.ndarray, np.ndarray]:
    """(points (V, 3), triangles (F, 3) int64) of an .off, .ply, .obj or .stl mesh (polygons are
    split into fans). No geometric check."""
    return _core.read_mesh(_path(path))


def write_mesh(path: PathLike, points: ArrayLike, triangles: ArrayLike, ascii: bool = False) -> None:
    """Writes a triangle mesh; the format follows the extension: .off, .ply (binary unless
    ``ascii``, CLI --ascii), .obj, .stl. Vertices are all points in order, so the triangles'
    ids are row numbers. The bytes are the CLI's for the same surface."""
    _check_flags(ascii=ascii)
    name = _path(path)
    if ascii and not name.lower().endswith(b".ply"):
        raise _invalid("ascii applies to .ply output (OFF and OBJ are text anyway, STL is binary)")
    _core.write_mesh(name, points, triangles, bool(ascii))


def write_polygon(path: PathLike, points: ArrayLike, boundary: ArrayLike) -> None:
    """Writes a 2D polygon given as rows in boundary order; the format follows the extension:
    .idx (one row number per line), .csv (x,y), .geojson/.json, .wkt, .svg (points and polygon;
    the CLI's SVG also draws the Delaunay edges)."""
    _core.write_polygon(_path(path), points, boundary)


def write_body(path: PathLike, points: ArrayLike, tetrahedra: ArrayLike) -> None:
    """Writes a tetrahedral body (Surface.tetrahedra) as VTK legacy .vtk (CLI --body)."""
    _core.write_body(_path(path), points, tetrahedra)


def cli_path() -> str:
    """Path of the ``constrict`` executable shipped inside the package (what
    ``python3 -m constrict`` runs). Raises FileNotFoundError when the package was built without
    the CLI."""
    exe = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "constrict")
    if not os.access(exe, os.X_OK):
        raise FileNotFoundError(f"{exe}: this constrict package was built without its command line "
                                "(CONSTRICT_BUILD_CLI=OFF)")
    return exe
