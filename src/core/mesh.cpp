// SPDX-License-Identifier: GPL-3.0-or-later
// Measures of a triangle mesh (mesh.hpp): enclosed volume and area, in double arithmetic. Its
// validation is src/validate/validate3.cpp, its reading and writing src/io/*_mesh.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "constrict/mesh.hpp"

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

double mesh_volume(const PointSet& pts, const TriMesh3& mesh) {
  const auto o = bbox_centre(pts);
  double vol = 0;
  for (const auto& t : mesh.triangles) {
    const double* a = pts[static_cast<std::size_t>(t[0])];
    const double* b = pts[static_cast<std::size_t>(t[1])];
    const double* c = pts[static_cast<std::size_t>(t[2])];
    const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
    const double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
    const double cx = c[0] - o[0], cy = c[1] - o[1], cz = c[2] - o[2];
    vol += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
  }
  return vol / 6.0;
}

double mesh_area(const PointSet& pts, const TriMesh3& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const double* a = pts[static_cast<std::size_t>(t[0])];
    const double* b = pts[static_cast<std::size_t>(t[1])];
    const double* c = pts[static_cast<std::size_t>(t[2])];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    area += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
  }
  return area;
}

}  // namespace constrict
