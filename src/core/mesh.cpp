// SPDX-License-Identifier: GPL-3.0-or-later
// Measures of a triangle mesh (mesh.hpp): enclosed volume and area, in double arithmetic. Its
// validation is src/validate/validate3.cpp, its reading and writing src/io/*_mesh.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "core/detail/fetch_ahead.hpp"
#include "core/detail/surface_components.hpp"
#include "core/detail/union_find.hpp"
#include "core/detail/volume_filter.hpp"

namespace constrict {
namespace {

std::array<double, 3> bbox_centre(const PointSet& pts) {
  std::array<double, 3> lo{{0, 0, 0}}, hi{{0, 0, 0}};
  if (pts.size() == 0) return lo;
  for (std::size_t k = 0; k < 3; ++k) lo[k] = hi[k] = pts[0][k];
  for (std::size_t i = 1; i < pts.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], pts[i][k]);
      hi[k] = std::max(hi[k], pts[i][k]);
    }
  return {{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])}};
}

double dist2(const double* p, const double* q) {
  return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
}
// Rotates the corners (a, b, c) (orientation kept) so that a lies between the two shortest edges:
// bc is the longest (ties: the first in the order bc, ca, ab).
void rotate_to_shortest(const double*& a, const double*& b, const double*& c) {
  const double bc = dist2(b, c), ca = dist2(c, a), ab = dist2(a, b);
  if (ca > bc && ca >= ab) {
    const double* t = a;  // (b, c, a): ca becomes the edge opposite the first corner
    a = b, b = c, c = t;
  } else if (ab > bc && ab > ca) {
    const double* t = c;  // (c, a, b)
    c = b, b = a, a = t;
  }
}

// The origin of the volume's terms per connected surface: the centre of the box of all points when
// the mesh is one surface through every point (as before), else of each surface's own vertices.
std::vector<std::array<double, 3>> surface_centres(const PointSet& pts, const std::vector<int>& comp) {
  int count = 0;
  bool every = true;
  for (int c : comp) {
    count = std::max(count, c + 1);
    every = every && c >= 0;
  }
  if (count <= 1 && every) return {bbox_centre(pts)};
  std::vector<std::array<double, 3>> lo(static_cast<std::size_t>(count), {{HUGE_VAL, HUGE_VAL, HUGE_VAL}}),
      hi(static_cast<std::size_t>(count), {{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}});
  for (std::size_t v = 0; v < pts.size(); ++v) {
    if (comp[v] < 0) continue;
    const auto c = static_cast<std::size_t>(comp[v]);
    for (std::size_t k = 0; k < 3; ++k) {
      lo[c][k] = std::min(lo[c][k], pts[v][k]);
      hi[c][k] = std::max(hi[c][k], pts[v][k]);
    }
  }
  std::vector<std::array<double, 3>> o(static_cast<std::size_t>(count));
  for (std::size_t c = 0; c < o.size(); ++c)
    for (std::size_t k = 0; k < 3; ++k) o[c][k] = 0.5 * (lo[c][k] + hi[c][k]);
  // (count 1 but not every point: still one entry, at its own box.)
  return o;
}

}  // namespace

std::vector<int> detail::surface_of_vertex(std::size_t n, const TriMesh3& mesh) {
  UnionFind uf(n);
  for (const auto& t : mesh.triangles) {
    uf.join(t[0], t[1]);
    uf.join(t[0], t[2]);
  }
  return number_surfaces(n, mesh, [&](int v) { return uf.find(v); });
}

// Far from 1 (beyond 2^±kRescaleExponent) the products overflow (inf - inf = NaN) or underflow:
// the volume and the area are then evaluated on the coordinates times 2^-e, e the largest
// exponent (magnitudes <= 1, no overflow), and scaled back: +-inf when the result exceeds the
// double range, never NaN. Nearer to 1 the plain formulas run (same bits as before).
namespace {
int magnitude_exponent(const PointSet& pts) {
  const int e = max_coordinate_exponent(pts);
  return e > kRescaleExponent || e < -kRescaleExponent ? e : 0;
}
}  // namespace

double mesh_volume(const PointSet& pts, const TriMesh3& mesh) {
  return detail::mesh_volume_of_surfaces(pts, mesh, detail::surface_of_vertex(pts.size(), mesh));
}

double detail::mesh_volume_of_surfaces(const PointSet& pts, const TriMesh3& mesh, const std::vector<int>& comp,
                                       VolumeEstimate* estimate) {
  const int e = magnitude_exponent(pts);
  PointSet scaled;
  const PointSet* use = &pts;
  if (e != 0) {
    scaled.dim = pts.dim;
    scaled.coords.reserve(pts.coords.size());
    for (double c : pts.coords) scaled.coords.push_back(std::ldexp(c, -e));
    use = &scaled;
  }
  const PointSet& q = *use;
  // Each connected surface about the centre of its own box: the terms of a surface far from the
  // common centre cancel (two spheres of radius 1 at 1e9 from each other: the volume came out
  // wrong in its first digit). One surface through every point keeps the common box's centre.
  const std::vector<std::array<double, 3>> origin = surface_centres(q, comp);
  const bool one = origin.size() == 1;
  double vol = 0;
  // (The filter's terms read the coordinates as given, in the triangle's own order.)
  VolumeFilterSum filter(mesh.triangles.empty() ? nullptr : pts[static_cast<std::size_t>(mesh.triangles[0][0])]);
  const std::size_t nf = mesh.triangles.size();
  for (std::size_t f = 0; f < nf; ++f) {
    // (The faces name their points in input order, at random for a shuffled file.)
    detail::fetch_ahead(mesh.triangles, f, nf, [&](int v) {
      __builtin_prefetch(q[static_cast<std::size_t>(v)]);
      if (!one) __builtin_prefetch(&comp[static_cast<std::size_t>(v)]);
    });
    const auto& t = mesh.triangles[f];
    if (estimate)
      filter.add(pts[static_cast<std::size_t>(t[0])], pts[static_cast<std::size_t>(t[1])], pts[static_cast<std::size_t>(t[2])]);
    const double* a = q[static_cast<std::size_t>(t[0])];
    const double* b = q[static_cast<std::size_t>(t[1])];
    const double* c = q[static_cast<std::size_t>(t[2])];
    const auto& o = origin[one ? 0 : static_cast<std::size_t>(comp[static_cast<std::size_t>(t[0])])];
    // (a - o) . ((b - a) x (c - a)), which is det(a - o, b - o, c - o), with a the corner between
    // the two shortest edges: their cross product is small for a small or thin triangle, where
    // long vectors cancel in their products (a body with faces 10^9 long, 10^9 from o: its volume
    // came out 1 700 times too large, or negative).
    rotate_to_shortest(a, b, c);
    const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    vol += ax * (uy * vz - uz * vy) + ay * (uz * vx - ux * vz) + az * (ux * vy - uy * vx);
  }
  if (estimate) *estimate = filter.estimate(mesh.triangles.size());
  return std::ldexp(vol / 6.0, 3 * e);
}

double mesh_area(const PointSet& pts, const TriMesh3& mesh) {
  const int e = magnitude_exponent(pts);
  // x · 2^-e is ldexp(x, -e) bit for bit (one correctly rounded scaling) while 2^-e is a normal
  // double; a multiplication costs less than the library call per coordinate.
  const bool mul = e >= -1022 && e <= 1022;
  const double f = std::ldexp(1.0, -e);
  double area = 0;
  const std::size_t nf = mesh.triangles.size();
  for (std::size_t i = 0; i < nf; ++i) {
    detail::fetch_ahead(mesh.triangles, i, nf, [&](int v) { __builtin_prefetch(pts[static_cast<std::size_t>(v)]); });
    const auto& t = mesh.triangles[i];
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) {
        const double x = pts[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])][d];
        p[k][d] = mul ? x * f : std::ldexp(x, -e);
      }
    const double ux = p[1][0] - p[0][0], uy = p[1][1] - p[0][1], uz = p[1][2] - p[0][2];
    const double vx = p[2][0] - p[0][0], vy = p[2][1] - p[0][1], vz = p[2][2] - p[0][2];
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    area += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
  }
  return std::ldexp(area, 2 * e);
}

}  // namespace constrict
