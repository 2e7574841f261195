// SPDX-License-Identifier: GPL-3.0-or-later
/// @file topology.hpp
/// @brief 2D reconstruction with the topology the data show (issue 16): a set of rings (shells and
/// holes, nested to any depth) through all points, or the single polygon of reconstruct2() when the
/// data show one curve. Method, threshold and measurements: docs/topology.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
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

/// The default of Rings2Options::topology_gap, measured on the shared data (docs/topology.md
/// §"Threshold"): the 43 ground-truth single-curve sets split at <= 1.27 local spacings, the 20
/// topology sets' rings are >= 2.57 apart (sd_vase's inner loop 9.8).
constexpr double kDefaultTopologyGap = 2.0;
/// A part whose polygon has 2|A|/Σ|e|² at most kMinRingFatness (compare_ring_fatness2: a sliver
/// along an arc), or an edge longer than kMaxRingEdge times its median edge (an arc closed by a
/// chord across its opening), is a piece of a longer curve, not a ring: it joins the part across
/// its smallest gap (docs/topology.md, "Open arcs").
constexpr double kMinRingFatness = 1.0;
constexpr double kMaxRingEdge = 50.0;
/// A part of at most kTinyRingPoints points has no region fat by that measure (a regular n-gon
/// has 2|A|/Σ|e|² = cot(π/n)/2: 0.5 for a square, 0.87 for a hexagon, 1.87 for 12 points, but its
/// interior is cut by its own short diagonals), so it was always joined to its nearest part,
/// however far: a speck of a CT slice's contours 10 spacings off became a bridge. Such a part
/// always gets its polygon (the kMinRingFatness rule); and any part, of any size, whose every
/// link to another part is at least kTinyRingGap local spacings long is a ring when its polygon
/// has more than kTinyRingFatness times the regular n-gon's value (up to kTinyRingPoints points;
/// kMinRingFatness from there) (docs/topology.md, "Tiny rings", "Archipelagos"). The gap is far
/// above kDefaultTopologyGap: in a random sample along a curve, a run of a few points with gaps
/// of 8 spacings on both sides has a probability of about e^-16 per point.
constexpr std::size_t kTinyRingPoints = 12;
constexpr double kTinyRingGap = 8.0;
constexpr double kTinyRingFatness = 0.5;
/// Two parts whose rings meet are joined and made again, at most this many times per inference
/// (docs/topology.md, "Archipelagos"); then the rings are refused (RingsDecision::Crossing).
constexpr std::size_t kMaxCrossingJoins = 64;
/// The CLI's single mode infers the topology (for its note) up to this many points.
constexpr std::size_t kNoteMaxPoints = 20000;
/// ... and stops it past this much work per input point (Rings2Options::infer_work_limit): the
/// 178 shared 2D and topology sets need at most 3.85 (s2d_Snail_e0.5; most 1-2).
constexpr std::size_t kNoteWorkPerPoint = 8;

/// The inference's default work bound (Rings2Options::infer_work_limit): islands of a few points
/// among larger ones join a growing part one per round, each round O(N) and the part's polygon
/// made again; 1 500 random-angle islands (37 712 points) took 1 161 N and 56 s for one curve.
/// Archipelagos of hostile-input sweeps that end in rings needed at most 116 N (docs/topology.md,
/// "Many islands"); bench/islands2_sweep.py's at most 23 N.
constexpr std::size_t kInferWorkPerPoint = 256;
constexpr std::size_t kInferWorkBase = std::size_t{1} << 22;

/// Options of reconstruct_rings2() and infer_rings2().
struct Rings2Options {
  Topology2 topology = Topology2::Single;  ///< Single: today's polygon exactly
  /// Parts of the data at least this many local spacings apart become separate rings
  /// (infer_rings2()). Default measured (kDefaultTopologyGap); larger splits less often.
  double topology_gap = kDefaultTopologyGap;
  /// Single mode: still infer the topology (one extra Delaunay triangulation, O(N log N): about
  /// 0.2 s at 10^5 points), so that the caller can tell the user when the data show several rings
  /// (Rings2Result::inferred). Off by default (single mode costs what it did); the CLI turns it on
  /// up to kNoteMaxPoints points.
  bool infer_in_single = false;
  /// The inference's part polygons are refined from several starts, as polygon.refine_multi_start
  /// says (the rings of Auto are those polygons). false: from one start whatever it says. The
  /// CLI's single-mode note sets false: on area-like data of 10^4 points its 8-start refinements
  /// of every small part took 10-15 times the single polygon's time; the notes of the 177 shared
  /// 2D and topology sets are the same either way (docs/topology.md, "The note of single mode").
  bool infer_multi_start = true;
  /// A bound on the inference's work: N per round of joins plus the points of the part polygons
  /// it makes. Past it the inference stops with RingsDecision::Capped (Auto then makes the single
  /// polygon). 0: kInferWorkPerPoint · N + kInferWorkBase, which no measured set of rings needs
  /// (docs/topology.md, "Many islands"); SIZE_MAX: no bound. The CLI sets kNoteWorkPerPoint · N
  /// for the single mode's note: 2 000 separate small rings took a note of 64 s beside a polygon of
  /// 70 ms (a part polygon made again for every thin part joined to it).
  std::size_t infer_work_limit = 0;
  /// Tell an open arc without its polygon (RingsInference::open_parts): a part next to no bounded
  /// region that is fat against its walls or bounded by other parts too. false: make every part's
  /// polygon and test that (slower on large noisy input; the same decisions on every set
  /// measured, docs/topology.md "Open arcs"; the tests compare the two).
  bool open_arc_test = true;
  /// Ask the nearest-neighbour walk (docs/topology.md, Method 6) for holes the gap rule cannot
  /// see: curves nearer to each other than topology_gap spacings but farther apart than their own
  /// spacing. Its rings are taken only when they are complete, valid, and add holes (or islands in
  /// holes) inside the rings found, never a split of one ring into rings side by side. false: the
  /// gap rule alone (as before the fifteenth 2026-12-05 session).
  bool walk_holes = true;
  /// Up to this many points the open-arc regions are made again after every round of joins
  /// (O(N) each); above it only where a join closed a loop that is not a small thin region
  /// (docs/topology.md, Method 3c). For tests; the default is measured.
  std::size_t open_arc_rebuild_max = std::size_t{1} << 14;
  /// Validate the ring set exactly (validate_rings2()); a set that fails is a bug: Internal.
  bool validate = true;
  Constrict2Options polygon;  ///< the options of the single polygon (reconstruct2()), also used
                              ///< for the parts of the data that are not one clean cycle
};

/// Why infer_rings2() gave its answer.
enum class RingsDecision {
  OneCurve,   ///< the points form one part (no gap of topology_gap spacings splits them)
  SmallPart,  ///< a part's polygon could not be made (parts of < 3 points or on a line are joined to
              ///< their nearest part since 2026-12-03, like open arcs)
  Crossing,   ///< the rings of the parts would meet (validate_rings2() failed): not accepted
  Rings,      ///< several parts, each a ring, disjoint: the multi-ring answer
  Capped,     ///< stopped at Rings2Options::infer_work_limit (Auto then makes the single polygon)
};
const char* to_string(RingsDecision decision) noexcept;

/// What validate_rings2() found.
struct RingsCheck {
  bool indices_ok = false;  ///< every entry in [0, N), every parent -1 or another ring's index
  bool all_points = false;  ///< every input point in exactly one ring, once
  bool simple = false;      ///< every ring simple, and no two rings meet (not even touch)
  bool oriented = false;    ///< shells counter-clockwise, holes clockwise
  bool nested = false;      ///< each parent is the innermost ring containing the ring; roles by depth
  std::string reason;       ///< one line; empty when valid
  /// When two edges meet: their rings (the same ring when it is not simple); -1 otherwise.
  int met_a = -1, met_b = -1;
};

/// What the data show (infer_rings2()).
struct RingsInference {
  RingsDecision decision = RingsDecision::OneCurve;
  /// The rings (Rings, Crossing), ordered by their lexicographically smallest point (a parent
  /// precedes its children), oriented and nested; empty otherwise.
  std::vector<Ring2> rings;
  std::size_t parts = 0;              ///< parts found (1 for OneCurve)
  std::size_t parts_polygon = 0;      ///< parts not one clean NN-crust cycle: reconstruct2() ran on them
  std::size_t bad_degree_points = 0;  ///< points whose NN-crust degree is not 2 (noise, corners)
  /// Parts whose polygon was too thin to be a ring (kMinRingFatness: a sliver along an arc, or an
  /// arc closed by a chord), each joined to the part across its smallest gap.
  std::size_t thin_parts_joined = 0;
  /// Of those, the parts found thin without a polygon: fewer than 3 points, on one line, or next
  /// to no bounded region that is fat or bounded by other parts too (an open arc;
  /// compare_region_fatness2 on the regions their walls enclose). Counted over all rounds.
  std::size_t open_parts = 0;
  /// Joins taken back: a thin part joined an accepted ring and the two made a thin part (two
  /// rings across a gap, not one curve), so the thin part is a ring of its own (docs/topology.md,
  /// "Archipelagos"). Counted over all rounds.
  std::size_t joins_undone = 0;
  /// Pairs of parts whose rings met (crossed or touched), joined into one part and made again
  /// (at most kMaxCrossingJoins; past it the decision is Crossing). Counted over all rounds.
  std::size_t crossings_joined = 0;
  /// Rings that the nearest-neighbour walk added (holes, and islands in them, inside the rings of
  /// the gap rule; Rings2Options::walk_holes); 0 when its rings were not taken.
  std::size_t rings_from_walk = 0;
  double gap_threshold = kDefaultTopologyGap;  ///< the threshold used
  /// The largest threshold at which the points would still split into several parts (double; the
  /// bottleneck of the single-linkage tree of the mutual-crust pieces; 0 for one piece). The data
  /// split iff topology_gap <= split_gap_spacings (up to rounding of the report value).
  double split_gap_spacings = 0;
  /// The smallest gap between two parts in local spacings (double; infinity with one part).
  double min_gap_spacings = std::numeric_limits<double>::infinity();
  RingsCheck check;  ///< validate_rings2() of the rings (Rings, Crossing)
  std::size_t shells() const noexcept;
  std::size_t holes() const noexcept;
  bool several() const noexcept { return decision == RingsDecision::Rings; }
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

/// Infers the rings the points show (docs/topology.md §"Method"). (1) The NN-crust of Dey and
/// Kumar ("A simple provable algorithm for curve reconstruction", SODA 1999) on the Delaunay
/// triangulation: each point p chooses its nearest Delaunay neighbour q and its nearest Delaunay
/// neighbour r with angle(q, p, r) > 90° (compare_distance2(), diametral_side2(); ties by the
/// lexicographic order of the points). (2) Parts: the connected components of the graph of the
/// mutual crust edges (chosen by both ends) and of the Delaunay edges pq shorter than topology_gap
/// times the local spacing, the root mean square of the crust edges at p and q (compare_gap2()).
/// So two parts are everywhere at least topology_gap local spacings apart. (3) A part that is one
/// crust cycle is a ring as it is; any other part gets reconstruct2()'s polygon of its points.
/// (4) Nesting by exact point-in-polygon tests, roles by depth parity, orientation fixed (orient2).
/// (5) validate_rings2(). Deterministic; the same rings for the points in any order.
/// @param[in] points 2D points (check_points() passed)
/// @param[in] dt their Delaunay triangulation (build_delaunay2())
/// @param[in] options topology_gap and the polygon options for the parts
/// @param[out] out the decision and the rings
/// @return Ok; InvalidArgument for a bad topology_gap or a triangulation of other points
/// @note O(N log N) plus reconstruct2() on the parts that are not clean cycles; the nesting test
///   is O(R · E_box) (validate_rings2()).
Status infer_rings2(const PointSet& points, const Delaunay2& dt, const Rings2Options& options, RingsInference& out);

/// Reconstructs the rings through all points (2D): Single: reconstruct2()'s polygon as one shell;
/// Auto: infer_rings2()'s rings when it decides RingsDecision::Rings, else the Single polygon.
/// @param[in] points dim == 2, at least 3 points, no duplicates, not all collinear
/// @param[out] result the rings, the single-mode run and the inference
/// @param[in] visitor observes the reconstruct2() run (in Auto, when the inference finds several
///   rings, that run is stopped where it is then: the visitor sees a prefix of its events, of a
///   length that depends on timing; the result does not)
/// @return Ok, the check_points() status for bad input, InvalidArgument for a bad topology_gap,
///   Internal if a complete ring set fails validation (a bug)
/// @note Guarantee: with validate, a complete result is a valid ring set (validate_rings2()).
///   Auto costs one Delaunay triangulation and O(N log N) more than Single, run on a second
///   thread beside reconstruct2() (whose polygon is dropped, and its run stopped, when the
///   inference finds several rings).
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

// ---- 3D: surfaces (issue 16) --------------------------------------------------------------------

/// What topology a 3D reconstruction may give.
enum class Topology3 {
  Single,  ///< one closed genus-0 surface through all points: reconstruct3(), the paper's problem
  Auto,    ///< the surfaces the data show: separate parts, inner shells and handles
};
/// Topology3 by name: "single", "auto". @return false for another name
bool topology_from_name(const std::string& name, Topology3& out) noexcept;
const char* to_string(Topology3 topology) noexcept;

/// Role of a surface: an outer one bounds a solid part (the body is inside it), an inner one a
/// cavity of a part (the body is outside it; its normals point into the cavity).
enum class SurfaceRole { Outer, Inner };
const char* to_string(SurfaceRole role) noexcept;

/// One closed surface of a surface set.
struct Surface3 {
  SurfaceRole role = SurfaceRole::Outer;
  /// The surface that directly encloses this one (index in the set), or -1: an inner surface's
  /// parent is the outer surface of its part; an outer surface inside a cavity has that cavity's
  /// inner surface as parent.
  int parent = -1;
  int genus = 0;
  std::vector<int> triangles;  ///< indices into the result's mesh.triangles
  std::vector<int> points;     ///< its vertices (input ids, ascending)
  /// The smallest gap to another surface's points in local spacings (double, for the report; the
  /// decision is exact, compare_gap3()); infinity and -1 with one surface.
  double gap_spacings = std::numeric_limits<double>::infinity();
  int nearest_surface = -1;
};

/// The default of Surfaces3Options::topology_gap (docs/topology.md §"3D"): the same rule as in
/// 2D, measured on the shared 3D data.
constexpr double kDefaultTopologyGap3 = 2.0;

/// The default of Surfaces3Options::min_part_points: the 10 shared 3D topology sets have parts of
/// 400+ points; the shared scans have outlier clusters of 2-4 points 2+ spacings from the rest.
constexpr std::size_t kMinPartPoints3 = 10;

/// The CLI's 3D single mode also runs the auto topology (for its note) up to this many points:
/// about 0.1 s there.
constexpr std::size_t kNoteMaxPoints3 = 5000;
/// ... and only when the Delaunay tetrahedralization has at most this many tetrahedra (surface and
/// volume samples: about 6.5 per point; points along curves in 3D: quadratic, 6 M for 5 000 points
/// on two skew lines, where the note doubled a 9 s run).
constexpr std::size_t kNoteMaxTets3 = 40 * kNoteMaxPoints3;

/// Options of reconstruct_surfaces3().
struct Surfaces3Options {
  Topology3 topology = Topology3::Single;  ///< Single: reconstruct3() exactly
  /// Parts of the data at least this many local spacings apart get separate surfaces: Delaunay
  /// edges pq with |pq| >= topology_gap · rms(local spacings of p and q: the distance to the third
  /// nearest Delaunay neighbour) do not join
  /// (compare_gap3()). Larger splits less often.
  double topology_gap = kDefaultTopologyGap3;
  /// A part with fewer points (or flat) is a cluster of outliers, not an object of its own: it
  /// joins the part across its shortest Delaunay edge. >= 4 (a closed surface needs 4 points).
  std::size_t min_part_points = kMinPartPoints3;
  /// Auto: let each part's surface have handles (Constrict3Options::handles).
  bool handles = true;
  bool validate = true;        ///< validate_surfaces3(); a failure is a bug: Internal
  Constrict3Options surface;   ///< the options of each part's reconstruct3()
};

/// Why reconstruct_surfaces3() gave its surfaces.
enum class SurfacesDecision {
  OnePart,      ///< the points form one part (no gap of topology_gap spacings splits them)
  SmallPart,    ///< a part's reconstruct3() gave no complete surface: one part used instead
  NotDelaunay,  ///< a part's surface is not made of Delaunay faces of all points: one part used
  Parts,        ///< several parts, each with its own surfaces, assembled into one body
};
const char* to_string(SurfacesDecision decision) noexcept;

/// Result of reconstruct_surfaces3().
struct Surfaces3Result {
  Topology3 topology = Topology3::Single;
  SurfacesDecision decision = SurfacesDecision::OnePart;
  /// All surfaces in one mesh (outward from the body: an inner surface faces into its cavity) and
  /// the body, its volume and area. With several parts the engine fields (stages, timings, counts)
  /// are sums over the parts and method is the first part's.
  Mesh3Result mesh;
  std::vector<Surface3> surfaces;  ///< ordered by their lexicographically smallest point
  std::size_t parts = 1;           ///< point parts found by the gap rule
  std::vector<std::size_t> part_sizes;  ///< their point counts (Auto), in part order
  /// Parts that could not have a surface of their own (fewer than 4 points, or flat: outliers),
  /// joined to the part across their shortest Delaunay edge.
  std::size_t small_parts_merged = 0;
  /// Parts kept apart at a gap narrower than topology_gap (but at least 3/4 of it) because no
  /// tetrahedra labelled inside join them: two parts that nearly touch (docs/topology.md).
  std::size_t parts_split_by_labels = 0;
  /// Small parts joined to a neighbour as patches of its surface (docs/topology.md, "Decimated
  /// meshes"): at a gap below 1.6 topology_gap, tetrahedra labelled inside between them, no void.
  std::size_t patches_joined = 0;
  /// Tetrahedra toggled to repair the parts' common body where their own surfaces were not
  /// Delaunay faces of all points (noisy nested parts; docs/topology.md §"3D", step 3).
  std::size_t repaired_tetrahedra = 0;
  /// That repair stopped at its work bound (points along curves in space, with thousands of
  /// tetrahedra at every point); the decision is then NotDelaunay (one part).
  bool repair_capped = false;
  double gap_threshold = kDefaultTopologyGap3;
  /// The smallest gap between two parts in local spacings (double; infinity with one part).
  double min_gap_spacings = std::numeric_limits<double>::infinity();
  int genus = 0;       ///< total genus
  bool validated = false;
  std::string check;   ///< validate_surfaces3()'s reason; empty when valid
  bool valid() const noexcept { return mesh.complete && validated && check.empty(); }
  double ms_infer = 0, ms_assemble = 0, ms_validate = 0;
};

/// Reconstructs closed surfaces through all points (3D). Single: reconstruct3(). Auto (docs/topology.md
/// §"3D"): (1) parts: components of the Delaunay edges shorter than topology_gap local spacings
/// (exact); between 3/4 of that and topology_gap the engine's labels decide (parts that nearly
/// touch stay apart unless tetrahedra labelled inside join them; a part at most a quarter of a
/// neighbour's size, closer than 1.6 topology_gap, with tetrahedra labelled inside and outside
/// between them, is a patch of that neighbour's surface and joins it); (2) each part's surface by reconstruct3() on its points, with handles when the labels
/// show them (Constrict3Options::handles); (3) with several parts, the body: the Delaunay
/// tetrahedra of all points inside an odd number of the surfaces (when a surface is not made of
/// Delaunay faces of all points: edge flips, then for parts that are not apart that body repaired
/// point by point, kept when it has the parts' topology; else NotDelaunay and one part); roles and
/// parents from the nesting;
/// (4) validate_surfaces3(). Deterministic; the same surfaces for the points in any order.
/// @return Ok, the check_points() status for bad input, InvalidArgument for a bad topology_gap,
///   what reconstruct3() returns, Internal if a complete result fails validation (a bug)
Status reconstruct_surfaces3(const PointSet& points, const Surfaces3Options& options, Surfaces3Result& result);

/// Checks surfaces and body exactly: the mesh closed, edge- and vertex-manifold, oriented, through
/// every point (each point on one surface), any number of components and genus
/// (MeshCheckOptions::any_topology); every body tetrahedron positive (orient3) and the free faces of
/// the body exactly the mesh triangles, oriented out of the body. @return Ok or InvalidArgument
/// with the reason; @param[out] details optional: the mesh check's details (validate_mesh3())
Status validate_surfaces3(const PointSet& points, const TriMesh3& mesh, const std::vector<std::array<int, 4>>& body,
                          bool self_intersections = false, MeshCheck* details = nullptr);

/// The body part of validate_surfaces3() alone: every tetrahedron positive (orient3), a face shared
/// by two tetrahedra seen from opposite sides (no overlap there), and the faces of exactly one
/// tetrahedron exactly the mesh triangles, oriented out of the body. O(T) plus a radix sort.
/// @return Ok or InvalidArgument naming the first bad face
Status validate_body3(const PointSet& points, const TriMesh3& mesh, const std::vector<std::array<int, 4>>& body);

}  // namespace constrict
