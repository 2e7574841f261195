// SPDX-License-Identifier: GPL-3.0-or-later
// infer_rings2() in two steps, so that the inference can run on a triangulation that its owner
// goes on changing: the adjacency is taken from it first, then the inference reads only the points
// and the adjacency (reconstruct_rings2() on the engine's triangulation, constrict/detail/share2.hpp).
#pragma once

#include <memory>

#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"

namespace constrict::detail {

struct RingsAdjacency;  // the triangulation's vertex adjacency (infer_rings2.cpp)

/// The adjacency of dt's vertices; keeps dt's triangles and neighbours (moved in: a caller whose
/// triangulation goes on changing copies it, and builds this later, on another core).
std::shared_ptr<const RingsAdjacency> rings_adjacency(Delaunay2&& dt);

/// infer_rings2() on the points and the adjacency of their Delaunay triangulation.
Status infer_rings2(const PointSet& points, const RingsAdjacency& adjacency, const Rings2Options& options,
                    RingsInference& out);

}  // namespace constrict::detail
