// SPDX-License-Identifier: GPL-3.0-or-later
// Small fixture helpers shared by the 2D unit tests.
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

}  // namespace constrict::test
