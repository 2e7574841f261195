// SPDX-License-Identifier: GPL-3.0-or-later
/// @file compare.hpp
/// @brief Geometric comparison of a reconstruction with a reference (ground truth): Hausdorff and
/// mean distances between two triangle meshes (3D) or two sets of polylines (2D), and the share of
/// reference triangles recovered. Sampling and accuracy: docs/evaluation.md.
#pragma once

#include <cstddef>
#include <vector>

#include "constrict/mesh.hpp"
#include "constrict/metrics.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// Options of compare_meshes3() and compare_curves2(): how densely each side is sampled.
/// Each triangle (segment) is cut into a regular grid of k×k sub-triangles (k pieces) whose edges
/// are at most `spacing` long; every grid node is a sample. spacing = max(relative_spacing ×
/// bbox diagonal of the reference, the spacing that keeps about max_samples samples per side).
struct DistanceOptions {
  /// Wanted sample spacing relative to the reference's bounding-box diagonal (default 1/500:
  /// each one-sided Hausdorff value is then at most 0.12% of the diagonal below the true one).
  double relative_spacing = 2e-3;
  /// Upper bound on the samples per side; the spacing grows when it would be exceeded
  /// (default 1e6: about a second per side on 2 cores).
  std::size_t max_samples = 1000000;
  /// Match the two meshes' vertices by their coordinates rounded to 32-bit floats (where they fit)
  /// instead of exactly: for a mesh read from STL, which stores floats, against one in doubles.
  /// Distances are measured on the coordinates as given either way.
  bool match_single_precision = false;
};

/// Distances between a result mesh A and a reference mesh B (3D), both directions.
/// d(p, X) is the exact Euclidean distance (double) from p to the nearest point of the triangles
/// X (CGAL AABB tree). One-sided values are taken over the samples of the first mesh, so each is
/// a lower bound of the true value and at most `spacing_*` / √3 below it (distance is 1-Lipschitz,
/// every surface point is that close to a sample).
struct MeshDistance {
  double hausdorff = 0;                       ///< max of the two one-sided values
  double hausdorff_result_to_reference = 0;   ///< max over result samples of d(p, reference)
  double hausdorff_reference_to_result = 0;   ///< max over reference samples of d(p, result)
  /// Where the one-sided maxima are reached: the first result / reference triangle (index in its
  /// mesh) holding the farthest sample, -1 for an empty side. Shows where the worst error is.
  long worst_result_element = -1, worst_reference_element = -1;
  double mean_result_to_reference = 0;        ///< area-weighted mean of d(p, reference) over the result
  double mean_reference_to_result = 0;        ///< area-weighted mean of d(p, result) over the reference
  double mean = 0;                            ///< (mean_result_to_reference + mean_reference_to_result) / 2
  double bbox_diagonal = 0;                   ///< of the reference's used vertices
  double relative_hausdorff = 0;              ///< hausdorff / bbox_diagonal
  double relative_mean = 0;                   ///< mean / bbox_diagonal
  double spacing_result = 0, spacing_reference = 0;  ///< sample spacing used on each side
  std::size_t samples_result = 0, samples_reference = 0;  ///< samples taken on each side
  std::size_t reference_triangles = 0;        ///< triangles of the reference
  std::size_t result_triangles = 0;           ///< triangles of the result
  std::size_t recovered_triangles = 0;        ///< reference triangles that are result triangles
  double triangle_recovery = 0;               ///< recovered / reference triangles (0..1)
  double triangle_precision = 0;              ///< result triangles in the reference / result triangles
  std::size_t matched_vertices = 0;           ///< reference vertices (used) with an identical result vertex
  bool identical = false;                     ///< same triangle set (as vertex-position triples)
};

/// Compares a result mesh with a reference mesh.
/// Triangles are matched as unordered triples of vertex positions (exact coordinate equality), so
/// meshes over the same points match whether or not their vertex lists are ordered alike; the
/// orientation is ignored. Distances: see MeshDistance and DistanceOptions. Degenerate
/// (collinear) triangles are sampled at their vertices only and left out of the distance targets;
/// so are triangles smaller or thinner than 2^-200 of the used coordinates' magnitude (their
/// projections underflow): points near them are measured to their neighbours.
/// @param[in] result_points, result the result mesh (dim 3)
/// @param[in] reference_points, reference the reference mesh (dim 3)
/// @param[out] out distances and recovery (finite and non-negative); unchanged on error
/// @return Ok, InvalidArgument (not 3D, index out of range, a mesh without any non-degenerate
///         triangle, or whose every triangle is below 2^-200 of the coordinates: "not at
///         comparable scales", bad options), NonFinite (a non-finite coordinate, or distances
///         beyond the largest double near 1e308)
/// @note O((S + F) log F) for S samples; deterministic (fixed sampling pattern, per-triangle
///       results reduced in a fixed order), parallel with TBB.
Status compare_meshes3(const PointSet& result_points, const TriMesh3& result, const PointSet& reference_points,
                       const TriMesh3& reference, MeshDistance& out, const DistanceOptions& options = {});

/// A 2D polyline: coordinates x0 y0 x1 y1 ...; closed adds the edge from the last to the first point.
struct Polyline2 {
  std::vector<double> xy;
  bool closed = true;
};

/// Distances between result curves and reference curves (2D), both directions; the 2D analogue of
/// MeshDistance (means weighted by length; each one-sided value at most spacing / 2 below the
/// true one).
struct CurveDistance2 {
  double hausdorff = 0;
  double hausdorff_result_to_reference = 0;
  double hausdorff_reference_to_result = 0;
  long worst_result_element = -1, worst_reference_element = -1;  ///< segments holding the maxima
  double mean_result_to_reference = 0;
  double mean_reference_to_result = 0;
  double mean = 0;
  double bbox_diagonal = 0;  ///< of the reference's points
  double relative_hausdorff = 0;
  double relative_mean = 0;
  double spacing_result = 0, spacing_reference = 0;
  std::size_t samples_result = 0, samples_reference = 0;
};

/// Compares 2D curves (e.g. a reconstructed polygon and a .gt reference).
/// @return Ok, or InvalidArgument (no segment on one side, odd coordinate count, bad options)
/// @note O((S + M) log M) for S samples and M segments; deterministic.
Status compare_curves2(const std::vector<Polyline2>& result, const std::vector<Polyline2>& reference,
                       CurveDistance2& out, const DistanceOptions& options = {});

/// The polylines of a reference over @p points (closed components closed, open ones open).
std::vector<Polyline2> reference_polylines2(const PointSet& points, const Reference2& reference);
/// The closed polyline of a polygon given as indices into @p points (@pre dim 2, indices in range).
Polyline2 polygon_polyline2(const PointSet& points, const std::vector<int>& polygon);

}  // namespace constrict
