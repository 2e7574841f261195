// SPDX-License-Identifier: GPL-3.0-or-later
/// @file voronoi_skeleton.hpp
/// @brief Shortest Voronoi skeleton growth (O'Rourke, Booth & Washington 1987, as described in
/// the seed paper §2.7 and §6): a comparison method, not γ-constriction. From a seed Delaunay
/// simplex, adjacent Delaunay simplices are added one at a time, always the one whose dual Voronoi
/// edge is shortest among those that bring a point not yet in the body; every Delaunay simplex
/// is tried as a seed (or a deterministic subset, seed_limit) and the body whose Voronoi tree
/// (the dual tree of its simplices) is shortest wins. Every choice the description leaves open is
/// documented in docs/comparison-methods.md.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "constrict/validate.hpp"

namespace constrict {

/// Options of voronoi_skeleton2() / voronoi_skeleton3().
struct VoronoiSkeletonOptions {
  /// At most this many seeds (0 = every Delaunay simplex, the paper's method). Seeds are taken at
  /// an even stride through the simplices sorted by their sorted vertex ids (deterministic).
  std::size_t seed_limit = 0;
  /// Abandon a seed as soon as its tree length plus a lower bound for the points still outside
  /// (the sum of that many smallest dual edges) is no better than the best complete tree so far.
  /// Never changes the result (tests check it), only the time.
  bool prune = true;
  /// Validate the result exactly (validate_polygon_in_triangulation() / validate_mesh3()).
  bool validate = true;
};

/// Statistics shared by both dimensions.
struct VoronoiSkeletonStats {
  std::size_t simplices = 0;       ///< Delaunay triangles / tetrahedra (= possible seeds)
  std::size_t seeds_tried = 0;     ///< seeds grown (seed_limit)
  std::size_t seeds_pruned = 0;    ///< seeds abandoned by the bound
  std::size_t seeds_complete = 0;  ///< seeds whose growth reached every point
  /// The winning seed: a simplex id of the search's own triangulation, built from the points in
  /// canonical order (an index for diagnostics, not one of a caller's build_delaunay2/3 output).
  int best_seed = -1;
  double tree_length = 0;          ///< length of the winning Voronoi tree (double arithmetic)
  double ms_delaunay = 0, ms_grow = 0, ms_validate = 0;
};

/// Result of voronoi_skeleton2().
struct VoronoiSkeleton2Result {
  std::vector<int> boundary;                  ///< CCW polygon through the points reached
  std::vector<std::array<int, 3>> triangles;  ///< the body: Delaunay triangles (CCW), growth order
  bool complete = false;                      ///< every point on the boundary
  std::vector<int> unplaced_points;           ///< points the best growth did not reach (ascending)
  bool validated = false;                     ///< the polygon was validated
  /// Validation outcome. An incomplete polygon is checked over the points it reaches (simple,
  /// counter-clockwise), so check.reason is empty iff that polygon is simple.
  PolygonCheck check;
  double area = 0, perimeter = 0;             ///< of the polygon (double arithmetic)
  VoronoiSkeletonStats stats;
};

/// Result of voronoi_skeleton3().
struct VoronoiSkeleton3Result {
  TriMesh3 mesh;                              ///< outward surface of the body
  std::vector<std::array<int, 4>> tets;       ///< the body: Delaunay tetrahedra, growth order
  bool complete = false;                      ///< every point on the surface
  std::vector<int> unplaced_points;           ///< points the best growth did not reach (ascending)
  bool validated = false;                     ///< the surface was validated (validate_mesh3)
  MeshCheck check;                            ///< validation outcome (all points required iff complete)
  double volume = 0, surface_area = 0;        ///< of the surface (double arithmetic)
  VoronoiSkeletonStats stats;
};

/// Shortest Voronoi skeleton polygon (2D).
/// @param[in] points dim == 2, at least 3 points, no duplicates, not all collinear
/// @param[out] result best body found; result.complete == false when no tried seed reaches every
///   point (then the body reaching most points, shortest tree among those, is returned)
/// @return Ok, or the check_points() status for bad input
/// @note Guarantee: result.boundary is always a simple CCW polygon through the points it reaches
///   (a union of Delaunay triangles that is a disk with no interior vertex). O(S N log N) for S
///   seeds (S = 2N - h - 2 without a limit).
Status voronoi_skeleton2(const PointSet& points, const VoronoiSkeletonOptions& options,
                         VoronoiSkeleton2Result& result);

/// Shortest Voronoi skeleton polyhedron (3D).
/// @param[in] points dim == 3, at least 4 points, no duplicates, not all coplanar
/// @param[out] result best body found (see voronoi_skeleton2())
/// @return Ok, or the check_points() status for bad input
/// @note Guarantee: result.mesh is always a closed genus-0 2-manifold (the boundary of a union of
///   Delaunay tetrahedra that is a ball with no interior vertex). O(S T log T) for S seeds.
Status voronoi_skeleton3(const PointSet& points, const VoronoiSkeletonOptions& options,
                         VoronoiSkeleton3Result& result);

/// The skeleton's result in the constriction's result type (method "voronoi-skeleton", or
/// "incomplete"), so that callers write and report both through one path (CLI, Python).
Polygon2Result as_reconstruction(VoronoiSkeleton2Result&& skeleton);
Mesh3Result as_reconstruction(VoronoiSkeleton3Result&& skeleton);

}  // namespace constrict
