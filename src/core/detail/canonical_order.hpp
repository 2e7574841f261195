// SPDX-License-Identifier: GPL-3.0-or-later
// A canonical order of a point set by its coordinates alone: the engines run on the points in
// this order, so the same points in any file order give the same result (STYLE.md; issue 20).
#pragma once

#include <vector>

#include "constrict/points.hpp"

namespace constrict::detail {

// order[k] = the input index of the point that gets engine id k. The order is a Morton (Z) curve
// over the bounding box (neighbouring ids stay close in space, as the engines' arrays like), ties
// broken by the exact lexicographic order of the coordinates: a strict total order on distinct
// points, so it depends on the coordinates only. O(N log N).
// @pre no two points equal (check_points)
std::vector<int> canonical_order(const PointSet& points);

// The points in that order.
PointSet permuted(const PointSet& points, const std::vector<int>& order);

}  // namespace constrict::detail
