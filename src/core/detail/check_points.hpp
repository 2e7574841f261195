// SPDX-License-Identifier: GPL-3.0-or-later
// The input check of check_points() without its duplicate search, for the engines whose Delaunay
// stage detects coincident points anyway (a triangulation has fewer vertices than points).
#pragma once
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict::detail {

/// check_points() minus the O(N log N) duplicate search: the same statuses in the same precedence,
/// except that a set whose only defect is a duplicate passes. The caller must then detect
/// duplicates itself (build_delaunay2/3 return StatusCode::Duplicate) and call check_points() for
/// the message that names them by index.
Status check_points_deferred(const PointSet& points);

/// NonFinite naming the first point with a NaN or infinite coordinate ("<who>: point I has a
/// non-finite coordinate (nan)"), else Ok: the first check of every public function that takes
/// points, before any predicate sees them (CGAL asserts on infinities). O(N).
Status check_finite(const PointSet& points, const char* who);

}  // namespace constrict::detail
