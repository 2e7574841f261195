// SPDX-License-Identifier: GPL-3.0-or-later
/// @file topology.hpp
/// @brief 2D reconstruction with the topology the data show (issue 16): a set of rings (shells and
/// holes, nested to any depth) through all points, or the single polygon of reconstruct2() when the
/// data show one curve. Method, threshold and measurements: docs/topology.md.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// What topology a reconstruction may give.
enum class Topology2 {
  Single,  ///< one simple polygon through all points: reconstruct2(), the paper's problem
  Auto,    ///< the rings the data show (infer_rings2()); one ring: the Single polygon
};

/// Topology by name: "single", "auto". @return false for another name
bool topology_from_name(const std::string& name, Topology2& out) noexcept;
const char* to_string(Topology2 topology) noexcept;

/// Role of a ring: a shell bounds the region on its left (counter-clockwise), a hole the region on
/// its right (clockwise); rings alternate shell / hole with the nesting depth.
enum class RingRole { Shell, Hole };
const char* to_string(RingRole role) noexcept;

/// One ring of a ring set.
struct Ring2 {
  RingRole role = RingRole::Shell;
  int parent = -1;           ///< the ring that directly contains this one (index in the set), or -1
  std::vector<int> indices;  ///< input indices in order, closed implicitly; starts at the smallest
  /// The smallest gap between this ring and another, in units of the local spacing (see
  /// infer_rings2()), and that ring; infinity and -1 when there is no other ring. Double
  /// arithmetic, for the report: the decision itself is exact (compare_gap2()).
  double gap_spacings = std::numeric_limits<double>::infinity();
  int nearest_ring = -1;
};

/// The default of Rings2Options::topology_gap: measured on the shared data (docs/topology.md
/// §"Threshold"): the topology sets have gaps of >= 2.4 spacings, the single-curve controls that
/// split into several cycles have gaps <= 1.6.
constexpr double kDefaultTopologyGap = 2.0;

/// Why infer_rings2() gave its answer.
enum class RingsDecision {
  NotDegree2,   ///< some point has NN-crust degree != 2: no clean cycles (noise, area sample, corners)
  OneCycle,     ///< the NN-crust is one cycle: one curve
  GapTooSmall,  ///< several cycles, but two come closer than topology_gap local spacings
  Rings,        ///< several cycles, every two separated by a clear gap: the multi-ring answer
};
const char* to_string(RingsDecision decision) noexcept;

/// What the data show (infer_rings2()).
struct RingsInference {
  RingsDecision decision = RingsDecision::NotDegree2;
  /// The cycles (OneCycle, GapTooSmall, Rings), ordered by their lexicographically smallest point
  /// (so a parent precedes its children), oriented and nested; empty for NotDegree2.
  std::vector<Ring2> rings;
  std::size_t bad_degree_points = 0;  ///< points whose NN-crust degree is not 2
  int first_bad_point = -1;           ///< the smallest such index, or -1
  double gap_threshold = kDefaultTopologyGap;  ///< the threshold used
  /// The smallest gap between two rings in local spacings (double; infinity with < 2 rings).
  double min_gap_spacings = std::numeric_limits<double>::infinity();
  std::size_t shells() const noexcept;
  std::size_t holes() const noexcept;
  bool several() const noexcept { return decision == RingsDecision::Rings; }
};

/// Options of reconstruct_rings2().
struct Rings2Options {
  Topology2 topology = Topology2::Single;  ///< Single: today's polygon exactly
  /// Several rings are accepted only when every two are at least this many local spacings apart
  /// (infer_rings2()). Default measured (kDefaultTopologyGap); larger splits less often.
  double topology_gap = kDefaultTopologyGap;
  /// Single mode: still infer the topology (one extra Delaunay triangulation, O(N log N)), so that
  /// the caller can tell the user when the data show several rings (Rings2Result::inferred).
  bool infer_in_single = true;
  /// Validate the ring set exactly (validate_rings2()); a set that fails is a bug: Internal.
  bool validate = true;
  Constrict2Options polygon;  ///< the options of the single polygon (reconstruct2())
};

/// What validate_rings2() found.
struct RingsCheck {
  bool indices_ok = false;  ///< every entry in [0, N), every parent -1 or another ring's index
  bool all_points = false;  ///< every input point in exactly one ring, once
  bool simple = false;      ///< every ring simple, and no two rings meet (not even touch)
  bool oriented = false;    ///< shells counter-clockwise, holes clockwise
  bool nested = false;      ///< each parent is the innermost ring containing the ring; roles by depth
  std::string reason;       ///< one line; empty when valid
};

/// Result of reconstruct_rings2().
struct Rings2Result {
  Topology2 topology = Topology2::Single;  ///< the mode that ran
  /// The rings: Single mode, or Auto when the data show one curve: one shell, the polygon of
  /// reconstruct2() (`polygon.boundary`); Auto with RingsDecision::Rings: inferred.rings.
  std::vector<Ring2> rings;
  bool from_polygon = true;  ///< rings[0] is the reconstruct2() polygon (polygon is filled)
  Polygon2Result polygon;    ///< the reconstruct2() run (empty when Auto found several rings)
  RingsInference inferred;   ///< what the data show (Auto, or Single with infer_in_single)
  bool inferred_run = false;  ///< infer_rings2() ran
  bool validated = false;
  RingsCheck check;
  bool complete() const noexcept { return from_polygon ? polygon.complete : true; }
  /// Complete and validated: every point in exactly one ring, rings simple, disjoint, oriented, nested.
  bool valid() const noexcept { return complete() && validated && check.reason.empty(); }
  /// Area (holes subtract) and total perimeter of the rings, double arithmetic.
  double area = 0, perimeter = 0;
  double ms_infer = 0, ms_validate = 0;  ///< infer_rings2() (with its Delaunay), validate_rings2()
};

/// Infers the rings the points show: the NN-crust of Dey and Kumar ("A simple provable algorithm
/// for curve reconstruction", SODA 1999) on the Delaunay triangulation: each point p joins its
/// nearest Delaunay neighbour q and its nearest Delaunay neighbour r with angle(q, p, r) > 90°
/// (compare_distance2() and diametral_side2(), exact; ties by the lexicographic order of the
/// points). When every point has degree 2 the edges are disjoint cycles. Their nesting follows from
/// the faces of the triangulation they separate (an exact, combinatorial flood fill), their
/// orientation from orient2 at the lexicographically smallest vertex. Several cycles are accepted
/// (RingsDecision::Rings) only when every Delaunay edge between two cycles, pq, is at least
/// @p gap times the local spacing: the root mean square of the four cycle edges at p and q
/// (compare_gap2(), exact). Deterministic; the same rings for the points in any order.
/// @param[in] points 2D points (check_points() passed)
/// @param[in] dt their Delaunay triangulation (build_delaunay2())
/// @param[in] gap the threshold in local spacings (finite, >= 0)
/// @param[out] out the decision and the rings
/// @return Ok; InvalidArgument for a bad @p gap or a triangulation of other points
/// @note O(N log N) (sorting the edge lists), O(N) otherwise.
Status infer_rings2(const PointSet& points, const Delaunay2& dt, double gap, RingsInference& out);

/// Reconstructs the rings through all points (2D): Single: reconstruct2()'s polygon as one shell;
/// Auto: infer_rings2()'s rings when it decides RingsDecision::Rings, else the Single polygon.
/// @param[in] points dim == 2, at least 3 points, no duplicates, not all collinear
/// @param[out] result the rings, the single-mode run and the inference
/// @param[in] visitor observes the reconstruct2() run
/// @return Ok, the check_points() status for bad input, InvalidArgument for a bad topology_gap,
///   Internal if a complete ring set fails validation (a bug)
/// @note Guarantee: with validate, a complete result is a valid ring set (validate_rings2()).
///   Auto costs one Delaunay triangulation and O(N) more than Single, and skips reconstruct2()
///   when it finds several rings.
Status reconstruct_rings2(const PointSet& points, const Rings2Options& options, Rings2Result& result,
                          Constrict2Visitor* visitor = nullptr);

/// Checks a ring set exactly: indices, every point in exactly one ring once, each ring >= 3 points
/// and simple, no two rings meet (closed segments: touching counts), shells counter-clockwise and
/// holes clockwise, each parent the innermost ring that contains the ring (exact point-in-polygon)
/// and the roles alternating with depth (depth 0 a shell).
/// @return Ok, or InvalidArgument with the reason (also in details->reason)
/// @note O(E log E) sweep over all ring edges for the intersections; the nesting test is
///   O(R · E_box), E_box the edges of the rings whose bounding box holds a ring's first vertex.
Status validate_rings2(const PointSet& points, const std::vector<Ring2>& rings, RingsCheck* details = nullptr);

/// Same checks by testing all edge pairs and all ring pairs: O(E^2). Meant for tests.
Status validate_rings2_brute_force(const PointSet& points, const std::vector<Ring2>& rings,
                                   RingsCheck* details = nullptr);

}  // namespace constrict
