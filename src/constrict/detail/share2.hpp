// SPDX-License-Identifier: GPL-3.0-or-later
// Sharing the 2D engine's Delaunay triangulation (the auto topology, src/topology/
// reconstruct_rings2.cpp, infers the rings on it instead of building a second one).
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"

namespace constrict::detail {

/// What the engine's triangulation is given to: its points (the input relabelled, and possibly
/// scaled by an exact power of two), the triangulation of those points, and to_input[v] = the
/// input index of engine point v. Called once, after init() and before the constriction; the
/// references are valid only during the call (the engine goes on, and frees the triangulation's
/// neighbours before its refinement).
using Triangulation2Hook = std::function<void(const PointSet& points, const Delaunay2& dt, const std::vector<int>& to_input)>;

/// What a cancelled run returns (Incomplete, "cancelled ..."): no result.
inline Status cancelled_status() {
  return {StatusCode::Incomplete, "cancelled: the caller no longer needs the polygon"};
}

/// reconstruct2(), with the hook called on the engine's triangulation once it is built (not
/// called when init() fails). The result is reconstruct2()'s, bit for bit.
/// @param[in] cancel optional: when another thread sets it, the run stops at its next check (in
///   the constriction every 4096 removals, in the fallback every 256 candidates, in the
///   refinement every vertex it visits) and returns cancelled_status() with no result. A run that
///   is not cancelled is not changed by it.
Status reconstruct2_sharing(const PointSet& points, const Constrict2Options& options, Polygon2Result& result,
                            Constrict2Visitor* visitor, const Triangulation2Hook& hook,
                            const std::atomic<bool>* cancel = nullptr);

}  // namespace constrict::detail
