// SPDX-License-Identifier: GPL-3.0-or-later
// infer_rings2() in two steps, so that the inference can run on a triangulation that its owner
// goes on changing: the adjacency is taken from it first, then the inference reads only the points
// and the adjacency (reconstruct_rings2() on the engine's triangulation, constrict/detail/share2.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"

namespace constrict::detail {

/// A region of triangles with W wall sides (its walls, one inside it counted twice) is never fat
/// (compare_region_fatness2 > 0 at kMinRingFatness) when W <= kThinWallSides, so the open-arc test
/// measures only the others. Its boundary is at most W walls: closed polygons of k_j <= W edges,
/// each enclosing at most P_j² / (4 k_j tan(π/k_j)) (the regular polygon) <= Σ|e|² / (4 tan(π/W))
/// by Cauchy–Schwarz, so 2A / Σ|w|² <= 1 / (2 tan(π/W)): 0.866 for W = 6, below kMinRingFatness
/// (W = 7: 1.04). Test: Topology2Property.RegionsOfFewWallsAreNeverFat.
constexpr unsigned kThinWallSides = 6;
static_assert(kMinRingFatness >= 0.87, "kThinWallSides needs kMinRingFatness > 1 / (2 tan(pi / 6))");

/// The Delaunay neighbours of every vertex (CSR: nbr[start[v] .. start[v + 1])), each edge once per
/// end, in no particular order; and dt's triangles and neighbours (the enclosed regions).
struct RingsAdjacency {
  std::vector<std::size_t> start;
  std::vector<int> nbr;
  std::vector<std::array<int, 3>> triangles, neighbors;
  explicit RingsAdjacency(Delaunay2&& dt);
};

/// The adjacency of dt's vertices; keeps dt's triangles and neighbours (moved in: a caller whose
/// triangulation goes on changing copies it, and builds this later, on another core).
std::shared_ptr<const RingsAdjacency> rings_adjacency(Delaunay2&& dt);

/// infer_rings2() on the points and the adjacency of their Delaunay triangulation.
Status infer_rings2(const PointSet& points, const RingsAdjacency& adjacency, const Rings2Options& options,
                    RingsInference& out);

}  // namespace constrict::detail
