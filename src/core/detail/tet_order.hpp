// SPDX-License-Identifier: GPL-3.0-or-later
// The tetrahedra of a Delaunay tetrahedralization in a spatial order (core/tet_order.cpp).
#pragma once

#include <array>
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
// The engine orders the tetrahedra it builds itself (single mode: 10^6 ellipsoid and star 5 %
// faster, igea 5 %); a tetrahedralization shared by the auto topology keeps CGAL's order, whose
// ties the handle stage's tests were measured with (docs/benchmarks.md, fourteenth session).
void order_tets_by_vertex(Delaunay3& dt, std::vector<std::array<int, 4>>* also = nullptr);

}  // namespace constrict::detail
