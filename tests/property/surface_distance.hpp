// SPDX-License-Identifier: GPL-3.0-or-later
// The largest distance from a reconstructed surface to a known true surface, over a barycentric
// grid of every triangle (the property tests of shapes with a distance function).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "constrict/mesh.hpp"

namespace constrict::test {

/// corner(v): the coordinates of vertex v (any frame the distance is measured in);
/// distance(q): the (signed or unsigned) distance of q to the true surface.
template <class Corner, class Distance>
double max_distance_over_surface(const TriMesh3& m, Corner corner, Distance distance, int grid = 4) {
  double worst = 0;
  for (const auto& t : m.triangles) {
    const std::array<double, 3> p0 = corner(t[0]), p1 = corner(t[1]), p2 = corner(t[2]);
    for (int i = 0; i <= grid; ++i)
      for (int j = 0; i + j <= grid; ++j) {
        const double a = double(i) / grid, b = double(j) / grid, c = 1 - a - b;
        const std::array<double, 3> q{a * p0[0] + b * p1[0] + c * p2[0], a * p0[1] + b * p1[1] + c * p2[1],
                                      a * p0[2] + b * p1[2] + c * p2[2]};
        worst = std::max(worst, std::fabs(distance(q)));
      }
  }
  return worst;
}

}  // namespace constrict::test
