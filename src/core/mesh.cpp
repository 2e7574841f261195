// SPDX-License-Identifier: GPL-3.0-or-later
// Measures of a triangle mesh (mesh.hpp): enclosed volume and area, in double arithmetic. Its
// validation is src/validate/validate3.cpp, its reading and writing src/io/*_mesh.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "constrict/mesh.hpp"
#include "constrict/points.hpp"

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

}  // namespace

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
  const auto o = bbox_centre(q);
  double vol = 0;
  for (const auto& t : mesh.triangles) {
    const double* a = q[static_cast<std::size_t>(t[0])];
    const double* b = q[static_cast<std::size_t>(t[1])];
    const double* c = q[static_cast<std::size_t>(t[2])];
    const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
    const double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
    const double cx = c[0] - o[0], cy = c[1] - o[1], cz = c[2] - o[2];
    vol += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
  }
  return std::ldexp(vol / 6.0, 3 * e);
}

double mesh_area(const PointSet& pts, const TriMesh3& mesh) {
  const int e = magnitude_exponent(pts);
  // x · 2^-e is ldexp(x, -e) bit for bit (one correctly rounded scaling) while 2^-e is a normal
  // double; a multiplication costs less than the library call per coordinate.
  const bool mul = e >= -1022 && e <= 1022;
  const double f = std::ldexp(1.0, -e);
  double area = 0;
  for (const auto& t : mesh.triangles) {
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
