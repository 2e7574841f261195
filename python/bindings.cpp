// SPDX-License-Identifier: GPL-3.0-or-later
// The compiled half of the Python package: constrict._core (pybind11, numpy). Thin: numpy arrays
// in, plain dicts of arrays and numbers out; constrict/__init__.py turns them into the pickleable
// result dataclasses, checks which keyword applies to which dimension and carries the docstrings.
// Bad input raises constrict.Error (a ValueError) with the library's one-line message and its
// status name in .code. Every computation releases the GIL. See docs/python.md.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/criterion.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/report.hpp"
#include "constrict/topology.hpp"
#include "constrict/validate.hpp"
#include "constrict/version.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace py = pybind11;
using namespace constrict;

namespace {

PyObject* g_error = nullptr;  // constrict.Error

// The library's duplicate message ends with the CLI's remedy; Python's is a keyword argument.
constexpr const char* kCliDuplicateRemedy = "use --merge-duplicates to keep the first of each";
constexpr const char* kPythonDuplicateRemedy = "pass merge_duplicates=True to keep the first of each";

std::string python_message(const Status& st) {
  std::string msg = st.message();
  if (st.code() == StatusCode::Coplanar) {  // (the hint for an outline with a constant coordinate)
    static const char* const kCli[][2] = {
        {"--columns 2,3", "columns=(1, 2)"}, {"--columns 1,3", "columns=(0, 2)"}, {"--dim 2", "dim=2"}};
    for (const auto& r : kCli)
      if (const auto at = msg.find(r[0]); at != std::string::npos) msg.replace(at, std::string(r[0]).size(), r[1]);
    return msg;
  }
  // (read_points' advice names the CLI's 1-based --columns: here the keyword, 0-based.)
  if (const auto at = msg.find(kChooseColumnsAdvice); at != std::string::npos)
    msg.replace(at, std::string(kChooseColumnsAdvice).size(),
                "choose the coordinate columns with columns= (0-based field numbers such as (1, 2, 3), or header "
                "names such as (\"x\", \"y\", \"z\")) or name them x, y, z in a header line");
  if (st.code() != StatusCode::Duplicate) return msg;
  const auto at = msg.find(kCliDuplicateRemedy);
  if (at != std::string::npos) msg.replace(at, std::string(kCliDuplicateRemedy).size(), kPythonDuplicateRemedy);
  return msg;
}

// A library string as a Python str: messages and warnings quote file names and file bytes, which
// need not be UTF-8 (a Latin-1 file, a name from os.listdir): those bytes are escaped (\xff)
// instead of a UnicodeDecodeError replacing the library's error.
py::str py_str(const std::string& s) {
  PyObject* o = PyUnicode_DecodeUTF8(s.data(), static_cast<py::ssize_t>(s.size()), "backslashreplace");
  if (o == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

[[noreturn]] void raise(const Status& st) {
  py::object err = py::reinterpret_borrow<py::object>(g_error)(py_str(python_message(st)));
  err.attr("code") = to_string(st.code());
  PyErr_SetObject(g_error, err.ptr());
  throw py::error_already_set();
}
void check(const Status& st) {
  if (!st) raise(st);
}
// Runs f() (returning a Status) without the GIL; raises constrict.Error when it fails.
template <class F>
void run_nogil(F&& f) {
  Status st;
  {
    py::gil_scoped_release nogil;
    st = f();
  }
  check(st);
}

// An object array with a str or bytes entry (numpy would parse it as a number).
bool holds_text(const py::array& a) {
  for (const py::handle x : a.attr("ravel")())
    if (PyUnicode_Check(x.ptr()) || PyBytes_Check(x.ptr()) || PyBool_Check(x.ptr())) return true;
  return false;
}

// (N, dim) float array -> PointSet (copied; any numeric dtype and memory layout is accepted).
PointSet to_points(const py::handle& obj, int dim) {
  // (numpy's conversion reads a masked array's hidden values as points: refused.)
  if (const py::module_ ma = py::module_::import("numpy.ma");
      py::isinstance(obj, ma.attr("MaskedArray")) && ma.attr("is_masked")(obj).cast<bool>())
    raise({StatusCode::InvalidArgument, "points is a masked array with masked entries: drop those rows first "
                                        "(points[~points.mask.any(axis=1)]) or fill them (points.filled(...))"});
  // (The cast keeps a complex number's real part, with only numpy's warning; and it reads text
  // ("0.5"), dates, time spans and booleans as numbers without a word: all refused.)
  if (const py::array raw = py::array::ensure(obj)) {
    const char kind = raw.dtype().kind();
    const bool numbers = kind == 'f' || kind == 'i' || kind == 'u' || (kind == 'O' && !holds_text(raw));
    if (!numbers)
      raise({StatusCode::InvalidArgument, "points must be real numbers, not " + py::str(raw.dtype()).cast<std::string>() +
                                              (kind == 'U' || kind == 'S' ? " (text: convert it with np.asarray(points, dtype=float) first)"
                                               : kind == 'O' ? " (an object array holding text or booleans)"
                                                             : "")});
  }
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) raise({StatusCode::InvalidArgument, "points must be an array of numbers"});
  if (a.ndim() != 2 || a.shape(1) != dim)
    raise({StatusCode::InvalidArgument, "points must have shape (N, " + std::to_string(dim) + "), got " +
                                            (a.ndim() == 2 ? "(" + std::to_string(a.shape(0)) + ", " +
                                                                 std::to_string(a.shape(1)) + ")"
                                                           : std::to_string(a.ndim()) + " dimensions")});
  PointSet p;
  p.dim = dim;
  p.coords.assign(a.data(), a.data() + a.size());
  return p;
}
py::array_t<double> to_array(const PointSet& p) {
  py::array_t<double> out({static_cast<py::ssize_t>(p.size()), static_cast<py::ssize_t>(p.dim)});
  std::copy(p.coords.begin(), p.coords.end(), out.mutable_data());
  return out;
}
// (F, K) index array -> rows of K ints, each in [0, n).
// Index arrays must hold integers: a float array was cast silently (2.7 -> 2), and a float list
// gave pybind11's generic cast error.
void check_integer_dtype(const py::handle& obj, const char* what) {
  const py::array a = py::array::ensure(obj);
  if (!a) raise({StatusCode::InvalidArgument, std::string(what) + " must be an array or a sequence of integer indices"});
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && !(a.size() == 0 && kind == 'f'))  // (an empty list is float64)
    raise({StatusCode::InvalidArgument, std::string(what) + " must hold integer indices, not " +
                                            py::str(a.dtype()).cast<std::string>()});
  // (uint64 above 2^63 - 1 wraps to a negative int64 in the cast: "index -1" for 2^64 - 1.)
  if (kind == 'u' && a.itemsize() == 8 && a.size() > 0) {
    const py::int_ top = a.attr("max")();
    if (top > py::int_(std::numeric_limits<std::int64_t>::max()))
      raise({StatusCode::InvalidArgument,
             std::string(what) + ": index " + py::str(py::object(top)).cast<std::string>() + " out of range"});
  }
}

template <std::size_t K>
std::vector<std::array<int, K>> to_rows(const py::handle& obj, std::size_t n, const char* what) {
  check_integer_dtype(obj, what);
  const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!t || t.ndim() != 2 || t.shape(1) != static_cast<py::ssize_t>(K))
    raise({StatusCode::InvalidArgument, std::string(what) + " must have shape (F, " + std::to_string(K) + ")"});
  std::vector<std::array<int, K>> rows(static_cast<std::size_t>(t.shape(0)));
  const std::int64_t* d = t.data();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t k = 0; k < K; ++k) {
      const std::int64_t v = d[i * K + k];
      if (v < 0 || static_cast<std::uint64_t>(v) >= n)
        raise({StatusCode::InvalidArgument, std::string(what) + ": index " + std::to_string(v) + " out of range (" +
                                                std::to_string(n) + " points)"});
      rows[i][k] = static_cast<int>(v);
    }
  return rows;
}
// A 1-D index array as int64 (integer dtypes only).
std::vector<std::int64_t> to_ids64(const py::handle& obj) {
  check_integer_dtype(obj, "indices");
  const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!t || t.ndim() != 1) raise({StatusCode::InvalidArgument, "indices must be one-dimensional"});
  return std::vector<std::int64_t>(t.data(), t.data() + t.size());
}
bool fits_int(std::int64_t v) { return v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max(); }
// ... as ints: an index beyond them is refused.
std::vector<int> to_ids(const py::handle& obj) {
  std::vector<int> out;
  for (const std::int64_t v : to_ids64(obj)) {
    if (!fits_int(v)) raise({StatusCode::InvalidArgument, "index " + std::to_string(v) + " out of range"});
    out.push_back(static_cast<int>(v));
  }
  return out;
}
// ... for a validator: an index beyond the ints is passed on as -1, which it names out of range
// (validate_polygon([0, 1, 2, 4]) and [0, 1, 2, 2**40] both answer with a verdict; the second raised).
std::vector<int> to_ids_to_judge(const py::handle& obj) {
  std::vector<int> out;
  for (const std::int64_t v : to_ids64(obj)) out.push_back(fits_int(v) ? static_cast<int>(v) : -1);
  return out;
}

py::array_t<std::int64_t> ids(const std::vector<int>& v) {
  py::array_t<std::int64_t> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}
template <std::size_t K>
py::array_t<std::int64_t> ids(const std::vector<std::array<int, K>>& v) {
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(K)});
  std::int64_t* d = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t k = 0; k < K; ++k) d[i * K + k] = v[i][k];
  return out;
}
py::array_t<std::int64_t> ids64(const std::vector<std::int64_t>& v) {
  return py::array_t<std::int64_t>(static_cast<py::ssize_t>(v.size()), v.data());
}
// Maps reconstruction ids back to the caller's rows (merge_duplicates); empty: identity.
using RowMap = std::vector<std::size_t>;
template <class Vec>
void remap(Vec& v, const RowMap& m) {
  if (m.empty()) return;
  for (auto& x : v) x = static_cast<typename Vec::value_type>(m[static_cast<std::size_t>(x)]);
}
template <std::size_t K>
void remap(std::vector<std::array<int, K>>& v, const RowMap& m) {
  if (m.empty()) return;
  for (auto& a : v)
    for (int& x : a) x = static_cast<int>(m[static_cast<std::size_t>(x)]);
}
py::array_t<double> doubles(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// The points a reconstruction runs on: as given, or without the later copies of duplicates
// (merge_duplicates=True; `rows` then maps each kept point to its row in the caller's array).
struct Input {
  PointSet points;
  RowMap rows;
  std::vector<std::int64_t> dropped;  // rows of the copies dropped
};
Input prepare(const py::handle& obj, int dim, bool merge) {
  Input in;
  in.points = to_points(obj, dim);
  if (!merge) return in;
  PointSet merged = merge_duplicates(in.points, &in.rows);
  if (merged.size() == in.points.size()) {
    in.rows.clear();
    return in;
  }
  std::vector<char> kept(in.points.size(), 0);
  for (std::size_t r : in.rows) kept[r] = 1;
  for (std::size_t r = 0; r < kept.size(); ++r)
    if (!kept[r]) in.dropped.push_back(static_cast<std::int64_t>(r));
  in.points = std::move(merged);
  return in;
}

bool parse_refine(const std::string& s) {
  if (s == "auto") return true;
  if (s == "none") return false;
  raise({StatusCode::InvalidArgument, "refine must be True/'auto' or False/'none', got '" + s + "'"});
}
// method: a criterion name (criterion.hpp) or "voronoi-skeleton" (the comparison method).
bool parse_method(const std::string& s, Criterion& c) {
  if (s == "voronoi-skeleton") return true;
  if (!criterion_from_name(s, c))
    raise({StatusCode::InvalidArgument,
           "method must be gamma, min-area-change, boissonnat or voronoi-skeleton, got '" + s + "'"});
  return false;
}
std::size_t parse_stop_after(const py::object& v) {
  if (v.is_none()) return SIZE_MAX;
  // (bool is an int in Python; a float or a negative number is refused by name, not by pybind11's
  // generic cast error.)
  // (numpy integers count as integers; one beyond size_t gave pybind11's "Unable to cast".)
  const py::object i = py::module_::import("operator").attr("index");
  py::int_ n;
  bool ok = !py::isinstance<py::bool_>(v) && !py::isinstance(v, py::module_::import("numpy").attr("bool_"));
  if (ok) {
    try {
      n = i(v);
    } catch (const py::error_already_set&) {
      ok = false;
    }
  }
  if (!ok || n < py::int_(0))
    raise({StatusCode::InvalidArgument, "stop_after must be None or an integer >= 0, not " + py::repr(v).cast<std::string>()});
  if (n > py::int_(SIZE_MAX)) return SIZE_MAX;  // (more removals than any run makes: no stop)
  return n.cast<std::size_t>();
}

py::dict skeleton_stats(const VoronoiSkeletonStats& s, std::size_t seed_limit) {
  py::dict d;
  d["seed_limit"] = seed_limit;
  d["simplices"] = s.simplices;
  d["seeds_tried"] = s.seeds_tried;
  d["seeds_pruned"] = s.seeds_pruned;
  d["seeds_complete"] = s.seeds_complete;
  d["best_seed"] = s.best_seed;
  d["tree_length"] = s.tree_length;
  return d;
}

// ---- 2D ------------------------------------------------------------------------------------

// The options exactly as `constrict reconstruct` builds them from the same flags (cmd_reconstruct.cpp).
Constrict2Options options2(const std::string& fallback, bool refine, Criterion criterion, std::size_t stop_after) {
  Constrict2Options o;
  check(Constrict2Options::from_preset(refine ? "default" : "paper", o));
  if (!fallback_from_name(fallback, o.fallback))
    raise({StatusCode::InvalidArgument, "fallback must be auto, gamma0, degree4 or none, got '" + fallback + "'"});
  o.stop_after = stop_after;
  o.criterion = criterion;
  return o;
}

py::dict polygon_dict(Polygon2Result& r, const Constrict2Options& o, const Input& in) {
  remap(r.boundary, in.rows);
  remap(r.stuck_points, in.rows);
  remap(r.fallback_edges, in.rows);
  py::dict d;
  d["boundary"] = ids(r.boundary);
  d["valid"] = r.valid();
  d["complete"] = r.complete;
  d["method"] = r.method;
  d["criterion"] = criterion_name(o.criterion);
  d["locked"] = r.locked_at_gamma0;
  d["stuck_points"] = ids(r.stuck_points);
  d["area"] = r.area;
  d["perimeter"] = r.perimeter;
  d["removed_simplices"] = r.removed_simplices;
  d["fallback_edges"] = ids(r.fallback_edges);
  py::list stages;
  for (const auto& s : r.stages) stages.append(py::make_tuple(s.name, s.placed));
  d["stages"] = stages;
  d["refine_moves"] = r.refine_moves;
  py::dict t;
  t["delaunay"] = r.ms_delaunay;
  t["constrict"] = r.ms_constrict;
  t["fallback"] = r.ms_fallback;
  t["refine"] = r.ms_refine;
  t["validate"] = r.ms_validate;
  d["timings_ms"] = t;
  d["merged_duplicates"] = ids64(in.dropped);
  d["report_json"] = to_json(r, o);
  return d;
}

py::dict reconstruct2_py(const py::handle& points, const std::string& fallback, const std::string& refine,
                         const std::string& method, const py::object& stop_after, std::size_t seed_limit,
                         bool merge) {
  Criterion criterion = Criterion::Gamma;
  const bool skeleton = parse_method(method, criterion);
  const Constrict2Options o = options2(fallback, parse_refine(refine), criterion, parse_stop_after(stop_after));
  const Input in = prepare(points, 2, merge);
  Polygon2Result r;
  py::object stats = py::none();
  if (skeleton) {
    // The comparison method's result in the constriction's result type, as the CLI does it.
    VoronoiSkeletonOptions vo;
    vo.seed_limit = seed_limit;
    VoronoiSkeleton2Result v;
    run_nogil([&] { return voronoi_skeleton2(in.points, vo, v); });
    stats = skeleton_stats(v.stats, seed_limit);
    r = as_reconstruction(std::move(v));
  } else {
    run_nogil([&] { return reconstruct2(in.points, o, r); });
  }
  py::dict d = polygon_dict(r, o, in);
  d["skeleton"] = stats;
  return d;
}

// ---- 3D ------------------------------------------------------------------------------------

Constrict3Options options3(const std::string& fallback, bool refine, bool fast, bool grow, Criterion criterion,
                           std::size_t stop_after, bool self_intersections) {
  if (fallback == "gamma0" || fallback == "degree4")
    raise({StatusCode::InvalidArgument, "fallback '" + fallback + "' is a 2D fallback; 3D has auto (star cavities) or none"});
  Constrict3Options o;
  check(Constrict3Options::from_preset(!refine ? "paper" : fast ? "fast" : "default", o));
  if (!fallback3_from_name(fallback, o.fallback))
    raise({StatusCode::InvalidArgument, "fallback must be auto or none in 3D, got '" + fallback + "'"});
  o.stop_after = stop_after;
  if (!grow) o.grow = false;
  o.criterion = criterion;
  o.validate_self_intersections = self_intersections;
  return o;
}

py::dict surface_dict(Mesh3Result& r, const Constrict3Options& o, const Input& in) {
  remap(r.mesh.triangles, in.rows);
  remap(r.tets, in.rows);
  remap(r.stuck_points, in.rows);
  remap(r.unplaced_points, in.rows);
  py::dict d;
  d["triangles"] = ids(r.mesh.triangles);
  d["tetrahedra"] = ids(r.tets);
  d["valid"] = r.valid();
  d["complete"] = r.complete;
  d["genus"] = r.valid() ? 0 : -1;
  d["method"] = std::string(to_string(r.method));
  d["criterion"] = criterion_name(o.criterion);
  d["volume"] = r.volume;
  d["area"] = r.surface_area;
  d["locked"] = r.locked;
  d["stuck_points"] = ids(r.stuck_points);
  d["unplaced_points"] = ids(r.unplaced_points);
  py::list stages;
  for (const auto& s : r.stages) stages.append(py::make_tuple(std::string(to_string(s.name)), s.placed, s.removed));
  d["stages"] = stages;
  py::dict t;
  t["delaunay"] = r.ms_delaunay;
  t["grow"] = r.ms_grow;
  t["fill"] = r.ms_fill;
  t["constrict"] = r.ms_constrict;
  t["fallback"] = r.ms_fallback;
  t["sculpt"] = r.ms_sculpt;
  t["carve"] = r.ms_carve;
  t["refine"] = r.ms_refine;
  t["validate"] = r.ms_validate;
  t["setup"] = r.ms_setup;
  t["variants"] = r.ms_variants;
  d["timings_ms"] = t;
  d["merged_duplicates"] = ids64(in.dropped);
  d["report_json"] = to_json(r, o);
  return d;
}

py::dict reconstruct3_py(const py::handle& points, const std::string& fallback, const std::string& refine, bool fast,
                         bool grow, const std::string& method, const py::object& stop_after, std::size_t seed_limit,
                         bool merge, bool self_intersections) {
  Criterion criterion = Criterion::Gamma;
  const bool skeleton = parse_method(method, criterion);
  const Constrict3Options o = options3(fallback, parse_refine(refine), fast, grow, criterion,
                                       parse_stop_after(stop_after), self_intersections);
  const Input in = prepare(points, 3, merge);
  Mesh3Result r;
  py::object stats = py::none();
  if (skeleton) {
    VoronoiSkeletonOptions vo;
    vo.seed_limit = seed_limit;
    VoronoiSkeleton3Result v;
    run_nogil([&] { return voronoi_skeleton3(in.points, vo, v); });
    stats = skeleton_stats(v.stats, seed_limit);
    r = as_reconstruction(std::move(v));
  } else {
    run_nogil([&] { return reconstruct3(in.points, o, r); });
  }
  py::dict d = surface_dict(r, o, in);
  d["skeleton"] = stats;
  return d;
}

// topology="auto" in 3D: reconstruct_surfaces3 (topology.hpp); the surface dict plus the surfaces.
py::dict surfaces3_py(const py::handle& points, const std::string& topology, double gap, const std::string& fallback,
                      const std::string& refine, bool fast, bool grow, const std::string& method, bool merge,
                      bool self_intersections) {
  Criterion criterion = Criterion::Gamma;
  if (parse_method(method, criterion))
    raise({StatusCode::InvalidArgument, "topology: needs the constriction (method voronoi-skeleton gives one surface)"});
  Surfaces3Options so;
  if (!topology_from_name(topology, so.topology))
    raise({StatusCode::InvalidArgument, "topology must be 'single' or 'auto', not '" + topology + "'"});
  so.topology_gap = gap;
  so.surface = options3(fallback, parse_refine(refine), fast, grow, criterion, SIZE_MAX, self_intersections);
  const Input in = prepare(points, 3, merge);
  Surfaces3Result r;
  run_nogil([&] { return reconstruct_surfaces3(in.points, so, r); });
  py::list surfaces;
  for (Surface3& x : r.surfaces) {
    remap(x.points, in.rows);
    py::dict d;
    d["role"] = to_string(x.role);
    d["parent"] = x.parent;
    d["genus"] = x.genus;
    d["triangles"] = ids(x.triangles);
    d["points"] = ids(x.points);
    d["gap_spacings"] = x.gap_spacings;
    surfaces.append(d);
  }
  const bool valid = r.valid();
  const int genus = r.genus;
  py::dict d = surface_dict(r.mesh, so.surface, in);
  d["valid"] = valid;
  d["genus"] = valid ? genus : -1;
  d["surfaces"] = surfaces;
  d["topology"] = to_string(r.topology);
  return d;
}

// ---- graphs, validation --------------------------------------------------------------------

GraphSpec parse_spec(const std::string& preset, const py::object& gamma, const py::object& interval) {
  const int given = !preset.empty() + !gamma.is_none() + !interval.is_none();
  if (given > 1) raise({StatusCode::InvalidArgument, "give one of preset, gamma, interval"});
  GraphSpec spec;
  if (!gamma.is_none()) {
    const auto g = gamma.cast<std::vector<double>>();
    if (g.size() != 2) raise({StatusCode::InvalidArgument, "gamma must be (g0, g1)"});
    spec = GraphSpec::fixed(g[0], g[1]);
  } else if (!interval.is_none()) {
    const auto g = interval.cast<std::vector<double>>();
    if (g.size() != 4) raise({StatusCode::InvalidArgument, "interval must be (a0, a1, b0, b1)"});
    spec = GraphSpec::interval(g[0], g[1], g[2], g[3]);
  } else {
    check(GraphSpec::from_preset(preset.empty() ? "delaunay" : preset, spec));
  }
  check(spec.validate());
  return spec;
}

int dim_of(const py::handle& points) {
  const auto a = py::array::ensure(points);
  if (a && a.ndim() == 2 && a.shape(1) != 2 && a.shape(1) != 3)
    raise({StatusCode::InvalidArgument, "points must have shape (N, 2) or (N, 3), got (" + std::to_string(a.shape(0)) +
                                            ", " + std::to_string(a.shape(1)) + ")"});
  return a && a.ndim() == 2 && a.shape(1) == 3 ? 3 : 2;
}

py::dict gamma_graph_py(const py::handle& points, const std::string& preset, const py::object& gamma,
                        const py::object& interval) {
  const PointSet p = to_points(points, dim_of(points));
  const GraphSpec spec = parse_spec(preset, gamma, interval);
  GammaFaces f;
  run_nogil([&] {
    Status st = check_points(p);
    if (st) st = build_gamma_graph(p, spec, f);
    return st;
  });
  py::array_t<std::int64_t> faces({static_cast<py::ssize_t>(f.size()), static_cast<py::ssize_t>(f.dim)});
  auto m = faces.mutable_unchecked<2>();
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < f.dim; ++k) m(static_cast<py::ssize_t>(i), k) = f.vertex(i, k);
  py::dict d;
  d["faces"] = faces;
  d["gamma_a"] = doubles(f.gamma_a);
  d["gamma_b"] = doubles(f.gamma_b);
  d["delta"] = doubles(f.delta);
  d["graph"] = spec.describe();
  return d;
}

// (ok, reason); a check that failed before it could name a reason (a non-finite coordinate, an
// index out of range) gives its message.
py::tuple verdict(const Status& st, const std::string& reason) {
  return py::make_tuple(st.is_ok(), py_str(st.is_ok() || !reason.empty() ? reason : st.message()));
}

// ---- files ---------------------------------------------------------------------------------

py::tuple read_points_py(const std::string& path, int dim, bool merge, bool check_input, const std::string& columns) {
  ReadOptions o;
  o.dim = dim;
  if (!columns.empty()) check(parse_columns(columns, o.columns));
  o.merge_duplicates = merge;
  o.check = check_input;
  PointSet p;
  ReadReport rep;
  run_nogil([&] { return read_points(path, o, p, &rep); });
  py::dict info;
  info["points_read"] = rep.points_read;
  info["merged_duplicates"] = rep.merged_duplicates;
  std::vector<std::int64_t> rows(p.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    rows[i] = static_cast<std::int64_t>(rep.original_index.empty() ? i : rep.original_index[i]);
  info["original_index"] = ids64(rows);
  py::list warnings;
  for (const std::string& w : rep.warnings) warnings.append(py_str(w));
  info["warnings"] = warnings;
  const auto n = static_cast<py::ssize_t>(p.size());
  if (!rep.attributes.normals.empty())
    info["normals"] = doubles(rep.attributes.normals).reshape({n, py::ssize_t{3}});
  if (rep.attributes.color_channels > 0)
    info["colors"] = doubles(rep.attributes.colors).reshape({n, static_cast<py::ssize_t>(rep.attributes.color_channels)});
  return py::make_tuple(to_array(p), info);
}

}  // namespace

// --topology: the rings of reconstruct_rings2 (topology.hpp) as plain Python data.
py::dict rings2_py(const py::handle& points, const std::string& topology, double gap, const std::string& fallback,
                   const std::string& refine, const std::string& method, const py::object& stop_after) {
  Criterion criterion = Criterion::Gamma;
  if (parse_method(method, criterion))
    raise({StatusCode::InvalidArgument, "topology: needs the constriction (method voronoi-skeleton gives one polygon)"});
  Rings2Options o;
  if (!topology_from_name(topology, o.topology))
    raise({StatusCode::InvalidArgument, "topology must be 'single' or 'auto', not '" + topology + "'"});
  o.topology_gap = gap;
  o.polygon = options2(fallback, parse_refine(refine), criterion, parse_stop_after(stop_after));
  const PointSet p = to_points(points, 2);
  Rings2Result r;
  run_nogil([&] { return reconstruct_rings2(p, o, r); });
  py::list rings;
  for (const Ring2& g : r.rings) {
    py::dict d;
    d["role"] = to_string(g.role);
    d["parent"] = g.parent;
    d["indices"] = ids(g.indices);
    d["gap_spacings"] = g.gap_spacings;
    rings.append(d);
  }
  py::dict d;
  d["topology"] = to_string(r.topology);
  d["rings"] = rings;
  d["valid"] = r.valid();
  d["decision"] = to_string(r.inferred.decision);
  d["area"] = r.area;
  d["perimeter"] = r.perimeter;
  d["report_json"] = to_json(r, o);
  return d;
}

// Rings from Python: a sequence of (role, parent, indices) or of dicts with those keys.
std::vector<Ring2> to_rings(const py::handle& obj) {
  std::vector<Ring2> out;
  const auto bad = [](std::size_t k, const std::string& what) {
    raise({StatusCode::InvalidArgument, "ring " + std::to_string(k) + ": " + what});
  };
  std::size_t k = 0;
  for (const py::handle& item : obj) {
    Ring2 g;
    py::object role, parent, indices;
    if (py::isinstance<py::dict>(item)) {
      const py::dict d = py::reinterpret_borrow<py::dict>(item);
      for (const char* key : {"role", "parent", "indices"})
        if (!d.contains(key)) bad(k, std::string("no '") + key + "' (a ring is a dict with role, parent and indices)");
      role = d["role"];
      parent = d["parent"];
      indices = d["indices"];
    } else if (py::hasattr(item, "role") && py::hasattr(item, "parent") && py::hasattr(item, "indices")) {
      role = item.attr("role");
      parent = item.attr("parent");
      indices = item.attr("indices");
    } else if (py::isinstance<py::sequence>(item) && !py::isinstance<py::str>(item) && py::len(item) == 3) {
      const py::sequence t = py::reinterpret_borrow<py::sequence>(item);
      role = t[0];
      parent = t[1];
      indices = t[2];
    } else {
      bad(k, "expected a Ring, a dict with role, parent and indices, or a (role, parent, indices) triple");
    }
    py::ssize_t len = 0;
    const char* utf8 = py::isinstance<py::str>(role) ? PyUnicode_AsUTF8AndSize(role.ptr(), &len) : nullptr;
    if (utf8 == nullptr) {
      PyErr_Clear();  // (a lone surrogate)
      bad(k, "role must be 'shell' or 'hole', not " + py::repr(role).cast<std::string>());
    }
    const std::string r(utf8, static_cast<std::size_t>(len));
    if (r != "shell" && r != "hole") bad(k, "role must be 'shell' or 'hole', not '" + r + "'");
    g.role = r == "shell" ? RingRole::Shell : RingRole::Hole;
    // (an integer from -1 up; not a bool, not a float)
    // (numpy's bool has __index__ too: a dtype kind 'b' is a bool)
    const bool boolean = py::isinstance<py::bool_>(parent) ||
                         (py::hasattr(parent, "dtype") && py::str(parent.attr("dtype").attr("kind")).cast<std::string>() == "b");
    const bool integer = (py::isinstance<py::int_>(parent) || py::hasattr(parent, "__index__")) && !boolean &&
                         !py::isinstance<py::float_>(parent);
    long long v = -2;
    if (integer) {
      const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(parent.ptr()));
      if (!i) {
        PyErr_Clear();  // (an array of one element has __index__ and refuses it)
      } else {
        int overflow = 0;
        v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
        if (overflow != 0) v = -2;
      }
    }
    if (!integer || v < -1 || v > std::numeric_limits<int>::max())
      bad(k, "parent must be -1 or a ring's index, not " + py::repr(parent).cast<std::string>());
    g.parent = static_cast<int>(v);
    g.indices = to_ids(indices);
    out.push_back(std::move(g));
    ++k;
  }
  return out;
}

PYBIND11_MODULE(_core, m) {
  m.doc() = "The compiled part of constrict (pybind11); use the package `constrict`, not this module.";
  m.attr("__version__") = CONSTRICT_VERSION_STRING;
  static py::exception<std::runtime_error> error(m, "Error", PyExc_ValueError);
  g_error = error.ptr();

  m.def("reconstruct2", &reconstruct2_py, py::arg("points"), py::arg("fallback"), py::arg("refine"),
        py::arg("method"), py::arg("stop_after"), py::arg("seed_limit"), py::arg("merge_duplicates"));
  m.def("reconstruct3", &reconstruct3_py, py::arg("points"), py::arg("fallback"), py::arg("refine"),
        py::arg("fast"), py::arg("grow"), py::arg("method"), py::arg("stop_after"), py::arg("seed_limit"),
        py::arg("merge_duplicates"), py::arg("validate_self_intersections"));
  m.def("gamma_graph", &gamma_graph_py, py::arg("points"), py::arg("preset") = "", py::arg("gamma") = py::none(),
        py::arg("interval") = py::none());
  m.def(
      "validate_polygon",
      [](const py::handle& points, const py::handle& boundary) {
        const PointSet p = to_points(points, 2);
        const std::vector<int> b = to_ids_to_judge(boundary);
        PolygonCheck c;
        Status st;
        {
          py::gil_scoped_release nogil;
          st = validate_polygon(p, b, &c);
        }
        return verdict(st, c.reason);
      },
      py::arg("points"), py::arg("boundary"));
  m.def("surfaces3", &surfaces3_py, py::arg("points"), py::arg("topology"), py::arg("topology_gap"), py::arg("fallback"),
        py::arg("refine"), py::arg("fast"), py::arg("grow"), py::arg("method"), py::arg("merge"),
        py::arg("self_intersections"));
  m.def("rings2", &rings2_py, py::arg("points"), py::arg("topology"), py::arg("topology_gap"), py::arg("fallback"),
        py::arg("refine"), py::arg("method"), py::arg("stop_after"));
  m.def(
      "validate_rings",
      [](const py::handle& points, const py::handle& rings) {
        const PointSet p = to_points(points, 2);
        const std::vector<Ring2> g = to_rings(rings);
        RingsCheck c;
        Status st;
        {
          py::gil_scoped_release nogil;
          st = validate_rings2(p, g, &c);
        }
        return verdict(st, c.reason);
      },
      py::arg("points"), py::arg("rings"));
  m.def(
      "validate_surface",
      [](const py::handle& points, const py::handle& triangles, const py::object& tetrahedra) {
        const PointSet p = to_points(points, 3);
        TriMesh3 mesh;
        mesh.triangles = to_rows<3>(triangles, p.size(), "triangles");
        MeshCheck c;
        Status st;
        if (!tetrahedra.is_none()) {  // any topology, checked against the body (validate_surfaces3)
          const std::vector<std::array<int, 4>> body = to_rows<4>(tetrahedra, p.size(), "tetrahedra");
          py::gil_scoped_release nogil;
          st = validate_surfaces3(p, mesh, body);
          c.reason = st.message();
        } else {
          py::gil_scoped_release nogil;
          st = validate_mesh3(p, mesh, &c);
        }
        return verdict(st, c.reason);
      },
      py::arg("points"), py::arg("triangles"), py::arg("tetrahedra") = py::none());
  m.def("check_points", [](const py::handle& points) {
    const PointSet p = to_points(points, dim_of(points));
    run_nogil([&] { return check_points(p); });
  });
  m.def("merge_duplicates", [](const py::handle& points) {
    const PointSet p = to_points(points, dim_of(points));
    std::vector<std::size_t> kept;
    const PointSet merged = merge_duplicates(p, &kept);
    std::vector<std::int64_t> rows(kept.begin(), kept.end());
    return py::make_tuple(to_array(merged), ids64(rows));
  });
  m.def("read_points", &read_points_py, py::arg("path"), py::arg("dim"), py::arg("merge_duplicates"), py::arg("check"),
        py::arg("columns") = "");
  m.def("read_mesh", [](const std::string& path) {
    PointSet p;
    TriMesh3 mesh;
    run_nogil([&] { return read_mesh(path, p, mesh); });
    return py::make_tuple(to_array(p), ids(mesh.triangles));
  });
  m.def(
      "write_mesh",
      [](const std::string& path, const py::handle& points, const py::handle& triangles, bool ascii) {
        const PointSet p = to_points(points, 3);
        TriMesh3 mesh;
        mesh.triangles = to_rows<3>(triangles, p.size(), "triangles");
        MeshWriteOptions o;
        o.ply_ascii = ascii;
        run_nogil([&] { return write_mesh(path, p, mesh, o); });
      },
      py::arg("path"), py::arg("points"), py::arg("triangles"), py::arg("ascii"));
  m.def(
      "write_body",
      [](const std::string& path, const py::handle& points, const py::handle& tetrahedra) {
        const PointSet p = to_points(points, 3);
        const auto tets = to_rows<4>(tetrahedra, p.size(), "tetrahedra");
        run_nogil([&] { return write_body_vtk(path, p, tets); });
      },
      py::arg("path"), py::arg("points"), py::arg("tetrahedra"));
  m.def(
      "write_polygon",
      [](const std::string& path, const py::handle& points, const py::handle& boundary) {
        const PointSet p = to_points(points, 2);
        const std::vector<int> b = to_ids(boundary);
        run_nogil([&] { return write_polygon2(path, p, b); });
      },
      py::arg("path"), py::arg("points"), py::arg("boundary"));
}
