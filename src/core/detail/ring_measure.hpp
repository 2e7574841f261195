// SPDX-License-Identifier: GPL-3.0-or-later
// Shoelace area and length of closed rings of point indices (the 2D results' reported area and
// perimeter), in double arithmetic, far from the origin and at any magnitude.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "constrict/points.hpp"

namespace constrict::detail {

// Adds one ring's area terms and edge lengths to `area` and `length`, on coordinates times 2^-e
// (e = rescale_exponent(max_coordinate_exponent(points)): 0 unless the input lies beyond
// 2^±kRescaleExponent; the caller scales the sums back, ldexp(area, 2e) and ldexp(length, e),
// once for all its rings). Each area term is (a - o) x (b - a) about the ring's first vertex o:
// about the origin a ring far from it cancels (a set moved by 10^15 gave -2.8e14 for 1.5e6), and
// unscaled products at 10^300 overflow (inf - inf: NaN). Clockwise rings subtract.
inline void add_ring_measure(const PointSet& points, const std::vector<int>& ring, int e, double& area,
                             double& length) {
  if (ring.empty()) return;
  const auto s = [e](double x) { return std::ldexp(x, -e); };
  const auto at = [&](std::size_t i) { return points[static_cast<std::size_t>(ring[i])]; };
  const double* o = at(0);
  const double ox = s(o[0]), oy = s(o[1]);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double* a = at(i);
    const double* b = at(i + 1 == ring.size() ? 0 : i + 1);
    const double ax = s(a[0]), ay = s(a[1]), ux = s(b[0]) - ax, uy = s(b[1]) - ay;
    area += 0.5 * ((ax - ox) * uy - (ay - oy) * ux);
    length += std::hypot(ux, uy);
  }
}

}  // namespace constrict::detail
