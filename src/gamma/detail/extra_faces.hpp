// SPDX-License-Identifier: GPL-3.0-or-later
// Non-Delaunay members of the γ-graphs with a negative threshold (spec §1.2, §2.2, §4.3;
// docs/gamma-lens-graphs.md). Private to the library.
#pragma once

#include <cstddef>

#include "constrict/gamma_graph.hpp"

namespace constrict::detail {

/// Every face that is NOT in @p delaunay_faces, is not blocked and has min(γ_a, γ_b) >= @p m,
/// i.e. whose lens L(m) = C+(m) ∪ C-(m) ∪ D contains no point (spec §1.2; 2D: the lune
/// β-skeleton with β = 1 + m). Appended to @p out with exact side values (the minima over all
/// points, bit-identical to side_values_scan()), Δ = filtration_value(), flags 0, sorted by ids.
/// @param[in] points the input, check_points() Ok, dim 2 or 3
/// @param[in] m threshold, -1 <= m < 0 (m = -1: every non-blocked face, refused when there are
///            more than 2e7 k-subsets)
/// @param[in] delaunay_faces the faces of γ([-1,1],[0,1]) (delaunay_gamma2/3), ascending ids
/// @param[in,out] out faces are appended; out.dim must equal points.dim
/// @param[out] candidates_tested optional: number of faces that went to the exact lens test
/// @return Ok; InvalidArgument (m out of range, dim mismatch); Unsupported when the output would
///         exceed 2e7 faces or the 3D candidate budget is exhausted (message says which).
/// @note 2D: near O(N log N) for well-spread samples when m is close to 0 (1e5 points, m = -0.05:
///       ~2-3 s); output-sensitive best-first k-d tree walk with exact shadow pruning.
///       3D: exact, vertex "ice-cream cone" pruning; practical only for a few thousand
///       well-spread points (boundary and surface points are not pruned, see docs/gamma-lens-graphs.md §6).
Status lens_faces(const PointSet& points, double m, const GammaFaces& delaunay_faces,
                  GammaFaces& out, std::size_t* candidates_tested);

}  // namespace constrict::detail
