// SPDX-License-Identifier: GPL-3.0-or-later
// Python bindings (pybind11, numpy): reconstruction in 2D and 3D, the γ-graph family, the
// validators. Arrays in, arrays out; bad input raises constrict.Error (a ValueError) with the
// library's one-line message and its status name in .code. See docs/python.md.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/report.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/validate.hpp"
#include "constrict/version.hpp"

namespace py = pybind11;
using namespace constrict;

namespace {

PyObject* g_error = nullptr;  // constrict.Error

[[noreturn]] void raise(const Status& st) {
  py::object err = py::reinterpret_borrow<py::object>(g_error)(st.message());
  err.attr("code") = to_string(st.code());
  PyErr_SetObject(g_error, err.ptr());
  throw py::error_already_set();
}
void check(const Status& st) {
  if (!st) raise(st);
}

// (N, dim) float array -> PointSet (copied; any numeric dtype and memory layout is accepted).
PointSet to_points(const py::handle& obj, int dim) {
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

py::array_t<std::int64_t> ids(const std::vector<int>& v) {
  py::array_t<std::int64_t> out(static_cast<py::ssize_t>(v.size()));
  auto m = out.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) m(static_cast<py::ssize_t>(i)) = v[i];
  return out;
}
template <std::size_t K>
py::array_t<std::int64_t> ids(const std::vector<std::array<int, K>>& v) {
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(K)});
  auto m = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t k = 0; k < K; ++k) m(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = v[i][k];
  return out;
}
py::array_t<double> doubles(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

Fallback parse_fallback(const std::string& s) {
  if (s == "auto") return Fallback::Auto;
  if (s == "gamma0") return Fallback::Gamma0;
  if (s == "degree4") return Fallback::Degree4;
  if (s == "none") return Fallback::None;
  raise({StatusCode::InvalidArgument, "fallback must be auto, gamma0, degree4 or none, got '" + s + "'"});
}

py::tuple verdict(const Status& st, const std::string& reason) { return py::make_tuple(st.is_ok(), reason); }

struct Polygon {
  Polygon2Result r;
  Constrict2Options o;  // what it was made with (the report)
};
struct Surface {
  Mesh3Result r;  // validated by reconstruct3 (closed, manifold, oriented, genus 0) when complete
  Constrict3Options o;
};

Polygon reconstruct2_py(const py::handle& points, const std::string& fallback, bool refine) {
  const PointSet p = to_points(points, 2);
  Constrict2Options o;
  o.fallback = parse_fallback(fallback);
  o.refine = refine ? Refine2::LocalSearch : Refine2::None;
  Polygon out;
  out.o = o;
  {
    py::gil_scoped_release nogil;
    const Status st = reconstruct2(p, o, out.r);
    if (!st) {
      py::gil_scoped_acquire gil;
      raise(st);
    }
  }
  return out;
}

Surface reconstruct3_py(const py::handle& points, bool grow) {
  const PointSet p = to_points(points, 3);
  Constrict3Options o;
  o.grow = grow;
  Surface out;
  out.o = o;
  {
    py::gil_scoped_release nogil;
    const Status st = reconstruct3(p, o, out.r);
    if (!st) {
      py::gil_scoped_acquire gil;
      raise(st);
    }
  }
  return out;
}

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

py::dict gamma_graph_py(const py::handle& points, const std::string& preset, const py::object& gamma,
                        const py::object& interval) {
  const auto a = py::array::ensure(points);
  const int dim = a && a.ndim() == 2 && a.shape(1) == 3 ? 3 : 2;
  const PointSet p = to_points(points, dim);
  const GraphSpec spec = parse_spec(preset, gamma, interval);
  GammaFaces f;
  {
    py::gil_scoped_release nogil;
    Status st = check_points(p);
    if (st) st = build_gamma_graph(p, spec, f);
    if (!st) {
      py::gil_scoped_acquire gil;
      raise(st);
    }
  }
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

}  // namespace

PYBIND11_MODULE(constrict, m) {
  m.doc() = "Object reconstruction with the gamma-neighborhood graph (Veltkamp): a simple polygon "
            "through all points in 2D, a closed genus-0 surface through all points in 3D.";
  m.attr("__version__") = CONSTRICT_VERSION_STRING;
  static py::exception<std::runtime_error> error(m, "Error", PyExc_ValueError);
  g_error = error.ptr();

  py::class_<Polygon>(m, "Polygon", "Result of reconstruct2().")
      .def_property_readonly("boundary", [](const Polygon& p) { return ids(p.r.boundary); },
                             "vertex indices in counter-clockwise order, each point once")
      .def_property_readonly("valid", [](const Polygon& p) { return p.r.validated && p.r.check.reason.empty() && p.r.complete; })
      .def_property_readonly("complete", [](const Polygon& p) { return p.r.complete; })
      .def_property_readonly("method", [](const Polygon& p) { return p.r.method; },
                             "gamma, gamma0=<v>, degree4, repair, star (last stage that placed a point)")
      .def_property_readonly("locked", [](const Polygon& p) { return p.r.locked_at_gamma0; })
      .def_property_readonly("stuck_points", [](const Polygon& p) { return ids(p.r.stuck_points); })
      .def_property_readonly("area", [](const Polygon& p) { return p.r.area; })
      .def_property_readonly("perimeter", [](const Polygon& p) { return p.r.perimeter; })
      .def_property_readonly("removed_simplices", [](const Polygon& p) { return p.r.removed_simplices; })
      .def_property_readonly("timings_ms", [](const Polygon& p) {
        py::dict d;
        d["delaunay"] = p.r.ms_delaunay;
        d["constrict"] = p.r.ms_constrict;
        d["fallback"] = p.r.ms_fallback;
        d["refine"] = p.r.ms_refine;
        d["validate"] = p.r.ms_validate;
        return d;
      })
      .def("report", [](const Polygon& p) { return to_json(p.r, p.o); },
           "the library's JSON report (the same fields as `constrict reconstruct --report`), a str")
      .def("__repr__", [](const Polygon& p) {
        return "<constrict.Polygon " + std::to_string(p.r.boundary.size()) + " vertices, method=" + p.r.method +
               (p.r.complete ? ", valid" : ", incomplete") + ">";
      });

  py::class_<Surface>(m, "Surface", "Result of reconstruct3().")
      .def_property_readonly("triangles", [](const Surface& s) { return ids(s.r.mesh.triangles); },
                             "(F, 3) vertex indices, oriented outward")
      .def_property_readonly("tetrahedra", [](const Surface& s) { return ids(s.r.tets); },
                             "(T, 4) the body bounded by the surface, positively oriented")
      .def_property_readonly("valid", [](const Surface& s) { return s.r.valid(); })
      .def_property_readonly("complete", [](const Surface& s) { return s.r.complete; })
      .def_property_readonly("genus", [](const Surface& s) { return s.r.complete ? 0 : -1; },
                             "0: the library validated a closed genus-0 surface through every point")
      .def_property_readonly("method", [](const Surface& s) { return std::string(to_string(s.r.method)); })
      .def_property_readonly("volume", [](const Surface& s) { return s.r.volume; })
      .def_property_readonly("area", [](const Surface& s) { return s.r.surface_area; })
      .def_property_readonly("unplaced_points", [](const Surface& s) { return ids(s.r.unplaced_points); })
      .def("report", [](const Surface& s) { return to_json(s.r, s.o); },
           "the library's JSON report (the same fields as `constrict reconstruct --report`), a str")
      .def("__repr__", [](const Surface& s) {
        return "<constrict.Surface " + std::to_string(s.r.mesh.triangles.size()) + " triangles, method=" +
               std::string(to_string(s.r.method)) + (s.r.complete ? ", valid" : ", incomplete") + ">";
      });

  m.def("reconstruct2", &reconstruct2_py, py::arg("points"), py::arg("fallback") = "auto",
        py::arg("refine") = true,
        "Simple polygon through every point of an (N, 2) array (the gamma-constriction of the "
        "Delaunay triangulation, local fallbacks after a lock, length-decreasing refinement; "
        "validated exactly). fallback: auto | gamma0 | degree4 | none. refine=False gives the "
        "paper's algorithm. Raises constrict.Error on bad input (duplicates named by index, "
        "collinear, too few, NaN/Inf).");
  m.def("reconstruct3", &reconstruct3_py, py::arg("points"), py::arg("grow") = true,
        "Closed genus-0 triangulated surface through every point of an (N, 3) array, and the "
        "tetrahedral body it bounds; validated (closed, manifold, oriented, genus 0). grow=False "
        "runs the constriction from the convex hull instead of the growth from the inside.");
  m.def("gamma_graph", &gamma_graph_py, py::arg("points"), py::arg("preset") = "", py::arg("gamma") = py::none(),
        py::arg("interval") = py::none(),
        "A graph of the gamma family on an (N, 2) or (N, 3) array: preset (hull, delaunay "
        "[default], gabriel, beta-circle=B, beta-lune=B, complete, void), gamma=(g0, g1) or "
        "interval=(a0, a1, b0, b1). Returns a dict: faces (edges in 2D, triangles in 3D, sorted "
        "ids), gamma_a, gamma_b, delta, graph.");
  m.def(
      "validate_polygon",
      [](const py::handle& points, const py::handle& boundary) {
        const PointSet p = to_points(points, 2);
        const auto b = boundary.cast<std::vector<int>>();
        PolygonCheck c;
        return verdict(validate_polygon(p, b, &c), c.reason);
      },
      py::arg("points"), py::arg("boundary"),
      "(ok, reason): is boundary a simple counter-clockwise polygon through every point exactly "
      "once? Exact predicates.");
  m.def(
      "validate_surface",
      [](const py::handle& points, const py::handle& triangles) {
        const PointSet p = to_points(points, 3);
        const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(triangles);
        if (!t || t.ndim() != 2 || t.shape(1) != 3) raise({StatusCode::InvalidArgument, "triangles must have shape (F, 3)"});
        TriMesh3 mesh;
        for (py::ssize_t i = 0; i < t.shape(0); ++i)
          mesh.triangles.push_back({{static_cast<int>(t.at(i, 0)), static_cast<int>(t.at(i, 1)), static_cast<int>(t.at(i, 2))}});
        MeshCheck c;
        return verdict(validate_mesh3(p, mesh, &c), c.reason);
      },
      py::arg("points"), py::arg("triangles"),
      "(ok, reason): is the mesh closed, manifold, outward oriented, connected, genus 0 and "
      "through every point?");
}
