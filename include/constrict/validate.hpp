// SPDX-License-Identifier: GPL-3.0-or-later
/// @file validate.hpp
/// @brief Exact validation of reconstruction output (2D polygons).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// What validate_polygon() found. All flags are meaningful only up to the first failing check
/// (order: indices, every point once, simple, counter-clockwise).
struct PolygonCheck {
  bool indices_ok = false;    ///< every entry in [0, N)
  bool all_points = false;    ///< every input point appears exactly once
  /// No two non-adjacent edges meet; adjacent edges only at their vertex. (simple and ccw are also
  /// set for a boundary that only misses points, an incomplete result: over its own vertices.)
  bool simple = false;
  bool ccw = false;           ///< counter-clockwise (positive signed area)
  int missing_point = -1;     ///< first point that does not appear (or -1)
  int repeated_point = -1;    ///< first point that appears twice (or -1)
  std::array<int, 2> crossing_edges{{-1, -1}};  ///< positions i, j of edges (b[i], b[i+1]) that meet
  std::string reason;         ///< one line; empty when valid
};

/// Checks that @p boundary is a simple counter-clockwise polygon through every point of @p points
/// exactly once. Exact: only orient2 and coordinate comparisons are used.
/// Touching and collinear overlaps of non-adjacent edges count as intersections; a 180° vertex
/// (the two edges at a vertex collinear and pointing in opposite directions) is allowed, a fold-back
/// (collinear, same direction) is not.
/// @param[in] points the input, dim == 2
/// @param[in] boundary the polygon as input indices, in order
/// @param[out] details optional diagnostics
/// @return Ok, or InvalidArgument with the reason (also in details->reason)
/// @note O(N log N): Shamos–Hoey sweep with an exact comparator.
Status validate_polygon(const PointSet& points, const std::vector<int>& boundary,
                        PolygonCheck* details = nullptr);

/// Same checks as validate_polygon() for a polygon whose edges are (mostly) edges of a known
/// triangulation of all the points, e.g. the Delaunay triangulation the constriction used.
/// When every polygon edge is a triangulation edge the simplicity test is O(N): distinct edges of
/// a triangulation meet only at shared endpoints, so a cycle through every vertex once is simple.
/// Otherwise the O(N log N) sweep of validate_polygon() runs.
/// @param[in] triangles a valid triangulation of all @p points (e.g. Delaunay2::triangles); its
///   validity is the precondition that makes the fast path exact
Status validate_polygon_in_triangulation(const PointSet& points, const std::vector<int>& boundary,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          PolygonCheck* details = nullptr);

/// Reference check by testing all edge pairs: O(N^2). Same semantics as validate_polygon();
/// meant for tests.
Status validate_polygon_brute_force(const PointSet& points, const std::vector<int>& boundary,
                                    PolygonCheck* details = nullptr);

}  // namespace constrict
