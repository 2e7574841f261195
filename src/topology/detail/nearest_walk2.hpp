// SPDX-License-Identifier: GPL-3.0-or-later
// The nearest-neighbour walk (docs/topology.md, Method 6): a second opinion of infer_rings2() on
// holes nearer to their outline than the gap rule's threshold, and the rule by which its rings
// replace the gap rule's.
#pragma once

#include <cstddef>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/topology.hpp"
#include "topology/detail/infer_rings2.hpp"

namespace constrict::detail {

/// The walk's rings must be at least this share of the gap threshold T apart (at T = 2: one local
/// spacing, the curves farther from each other than their own points).
constexpr double kWalkGapShare = 0.5;

/// Rings traced point by point (after Parakkat and Muthuganapathy's "Crawl through neighbors", SGP
/// 2016): a path starts at the shortest Delaunay edge between nearest neighbours whose ends are both
/// free; each step takes, at the end whose nearest free Delaunay neighbour is nearer, that
/// neighbour; after 4 steps the path closes when one end is among the other's two nearest Delaunay
/// neighbours. All or nothing: true with every point on a closed path (in `rings`, each a cycle of
/// point ids, unoriented); false when a path cannot go on, a point is left over, or the work bound
/// is reached. Deterministic; the same rings for the points in any order.
bool nearest_walk_rings2(const PointSet& points, const RingsAdjacency& adjacency, std::vector<std::vector<int>>& rings);

/// Do the walk's rings (nested: Ring2::parent set) add holes to ours (each point's ring of ours in
/// `ring_of`, `ours` rings)? More rings; each within one of ours; and of those within one of ours,
/// exactly one not inside another of them (the others are its holes, or islands in those): never
/// one of our rings split into rings side by side.
bool walk_adds_holes(const std::vector<Ring2>& walk, const std::vector<int>& ring_of, std::size_t ours);

}  // namespace constrict::detail
