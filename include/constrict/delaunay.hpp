// SPDX-License-Identifier: GPL-3.0-or-later
/// @file delaunay.hpp
/// @brief Delaunay triangulations as plain index arrays (the only module that uses CGAL's
/// triangulation packages; exact predicates, spatial sort, symbolic perturbation in 3D).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// 2D Delaunay triangulation. Triangles are counter-clockwise; neighbors[t][i] is the triangle
/// across the edge opposite triangles[t][i], or -1 on the convex hull. Vertex ids = input indices.
struct Delaunay2 {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 3>> neighbors;
  std::size_t n_vertices = 0;
};

/// 3D Delaunay tetrahedralization. Tetrahedra are positively oriented
/// (orient3(v0,v1,v2,v3) > 0); neighbors[t][i] is the tetrahedron across the face opposite
/// tets[t][i], or -1 on the convex hull.
struct Delaunay3 {
  std::vector<std::array<int, 4>> tets;
  std::vector<std::array<int, 4>> neighbors;
  std::size_t n_vertices = 0;
};

/// Builds the 2D Delaunay triangulation with CGAL (exact predicates, spatial sort). Ties between
/// co-circular points are resolved by CGAL's own rule; use the gamma module to get the
/// degeneracy-complete graph.
/// @pre points.dim == 2, no duplicates, not all collinear (check_points()).
/// @return Ok, or InvalidArgument/Collinear/Duplicate if the precondition is violated.
/// @note O(N log N) expected.
Status build_delaunay2(const PointSet& points, Delaunay2& out);

/// Builds the 3D Delaunay tetrahedralization with CGAL (exact predicates, spatial sort,
/// symbolic perturbation for co-spherical points).
/// @pre points.dim == 3, no duplicates, not all coplanar.
/// @note Expected near-linear for well-spread and surface samples; O(N^2) worst case.
Status build_delaunay3(const PointSet& points, Delaunay3& out);

}  // namespace constrict
