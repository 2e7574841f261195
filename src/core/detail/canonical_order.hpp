// SPDX-License-Identifier: GPL-3.0-or-later
// A canonical order of a point set by its coordinates alone: the engines run on the points in
// this order, so the same points in any file order give the same result (STYLE.md; issue 20).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "constrict/points.hpp"

namespace constrict::detail {

// order[k] = the input index of the point that gets engine id k. The order is a Morton (Z) curve
// over the bounding box (neighbouring ids stay close in space, as the engines' arrays like), ties
// broken by the exact lexicographic order of the coordinates: a strict total order on distinct
// points, so it depends on the coordinates only. O(N log N).
// @pre finite coordinates (check_points_deferred). Equal points (operator==, -0.0 == 0.0) come out
// next to each other, in no defined order among them: has_adjacent_duplicate() on the permuted
// points then finds any duplicate in O(N).
std::vector<int> canonical_order(const PointSet& points);

// True when two consecutive points of @p ordered are equal: for points in canonical order, whether
// the set has a duplicate (the caller then gets the message naming it from check_points()).
bool has_adjacent_duplicate(const PointSet& ordered);

// The points in that order.
PointSet permuted(const PointSet& points, const std::vector<int>& order);

// Engine ids back to input ids, in place (order[k] = the input id of engine id k).
inline void to_input_ids(const std::vector<int>& order, std::vector<int>& ids) {
  for (int& v : ids) v = order[static_cast<std::size_t>(v)];
}
template <std::size_t K> void to_input_ids(const std::vector<int>& order, std::vector<std::array<int, K>>& simplices) {
  for (auto& s : simplices)
    for (int& v : s) v = order[static_cast<std::size_t>(v)];
}

}  // namespace constrict::detail
