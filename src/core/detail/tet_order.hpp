// SPDX-License-Identifier: GPL-3.0-or-later
// The tetrahedra of a Delaunay tetrahedralization in a spatial order (core/tet_order.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "constrict/delaunay.hpp"

namespace constrict::detail {

// Renumbers the tetrahedra of @p dt by their smallest vertex id, in CGAL's container order among
// those with the same one (a stable counting sort), and their neighbour indices with them; the
// rows of @p also (one per tetrahedron, may be null) move with their tetrahedra. For points in
// canonical order (a Morton curve) the tetrahedra then follow the curve: the 3D engine's passes,
// which read a tetrahedron's neighbours and per-vertex arrays, find them nearby in memory (CGAL's
// container order is the order in which cells were made and reused during the insertion, nearly
// random at 10^6 points). Deterministic, and the same at any thread count. O(T + N).
void order_tets_by_vertex(Delaunay3& dt, std::vector<std::array<int, 4>>* also = nullptr);

// From this many tetrahedra on (about 300 000 surface points) the 3D engine and the auto topology
// work on ordered tetrahedra: 5 % of a 10^6-point run (docs/benchmarks.md, fourteenth session).
// Below, CGAL's order stays: the engine breaks some ties by tetrahedron number (the fill's,
// carve's and handle stage's regions), and the handle stage's rules were measured on that order
// (ordered, the noisy torus of its tests got its handle in 0 of 6 axis orders instead of 4).
// Single mode and auto follow the same rule, so that auto on one part gives single's surface.
inline constexpr std::size_t kOrderTetsFrom = std::size_t{1} << 21;

// Whether a tetrahedralization of @p tets tetrahedra is ordered (the rule above).
inline bool ordered_size(std::size_t tets) { return tets >= kOrderTetsFrom; }

// order_tets_by_vertex when @p dt has kOrderTetsFrom tetrahedra or more; whether it did.
inline bool order_large_tets(Delaunay3& dt, std::vector<std::array<int, 4>>* also = nullptr) {
  if (!ordered_size(dt.tets.size())) return false;
  order_tets_by_vertex(dt, also);
  return true;
}

}  // namespace constrict::detail
