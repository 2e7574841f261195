// SPDX-License-Identifier: GPL-3.0-or-later
// Small fixture helpers shared by the unit tests.
#pragma once

#include <array>
#include <vector>

#include "constrict/points.hpp"

namespace constrict::test {

/// A 2D PointSet from coordinate pairs.
inline PointSet make2(const std::vector<std::array<double, 2>>& xy) {
  PointSet p;
  p.dim = 2;
  for (const auto& q : xy) {
    p.coords.push_back(q[0]);
    p.coords.push_back(q[1]);
  }
  return p;
}

/// A 3D PointSet from coordinate triples.
inline PointSet make3(const std::vector<std::array<double, 3>>& xyz) {
  PointSet p;
  p.dim = 3;
  for (const auto& q : xyz) p.coords.insert(p.coords.end(), q.begin(), q.end());
  return p;
}

}  // namespace constrict::test
