// SPDX-License-Identifier: GPL-3.0-or-later
/// @file metrics.hpp
/// @brief Comparing a reconstruction with a reference (ground truth).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// A 2D reference: closed polygons and open polylines over input indices.
struct Reference2 {
  std::vector<std::vector<int>> closed;  ///< closed polygons i0 -> ... -> ik -> i0
  std::vector<std::vector<int>> open;    ///< open polylines i0 -> ... -> ik
  /// True iff the reference is exactly one closed polygon (the reconstruction's target).
  bool single_closed_curve() const noexcept { return closed.size() == 1 && open.empty(); }
  /// Reference edges as (min, max) index pairs, sorted and unique.
  std::vector<std::array<int, 2>> edges() const;
};

/// Reads a `.gt` reference file: `#` comment lines; every other non-blank line is one component,
/// `c i0 i1 ... ik` (closed) or `o i0 ... ik` (open), 0-based indices.
/// @param[in] n_points number of input points; indices must be in [0, n_points)
/// @return Ok, FileNotFound, ParseError ("file:LINE: ..."), EmptyInput (no component)
Status read_reference2(const std::string& path, std::size_t n_points, Reference2& out);

/// Result of compare_polygon2().
struct PolygonComparison {
  bool exact_match = false;            ///< same edge set as a single-closed-curve reference
  std::size_t reference_edges = 0;     ///< edges of the reference
  std::size_t recovered_edges = 0;     ///< reference edges that are polygon edges
  std::size_t polygon_edges = 0;       ///< edges of the polygon
  double edge_recall = 0;              ///< recovered / reference (1 if the reference is empty)
  double edge_precision = 0;           ///< recovered / polygon edges
};

/// Compares a polygon (input indices, boundary order) with a reference. Purely combinatorial.
/// @note O((N + M) log(N + M)).
PolygonComparison compare_polygon2(const std::vector<int>& polygon, const Reference2& reference);

/// Result of compare_rings2(): the edge counts of all rings together, and the rings matched.
struct RingsComparison {
  PolygonComparison
      edges;  ///< over the edges of all rings; exact_match: same edge set as a reference of closed curves only
  std::size_t result_rings = 0;
  std::size_t reference_rings = 0;  ///< the reference's closed curves
  std::size_t same_point_sets = 0;  ///< reference rings whose point set is exactly one result ring's
};

/// Compares a ring set (e.g. a `--topology auto` result; input indices) with a reference of closed
/// curves: the issue-16 measure "the rings hold the same point sets as the ground-truth rings" and
/// the edges recovered. Purely combinatorial. @note O((N + M) log(N + M)).
RingsComparison compare_rings2(const std::vector<std::vector<int>>& rings, const Reference2& reference);

}  // namespace constrict
