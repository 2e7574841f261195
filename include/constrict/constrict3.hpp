// SPDX-License-Identifier: GPL-3.0-or-later
/// @file constrict3.hpp
/// @brief 3D reconstruction: a closed genus-0 polyhedron through all points by γ-constriction of
/// the Delaunay tetrahedralization (Veltkamp, seed paper §4.2, §4.3, §5; spec gamma-graph.md
/// §3), with a local fallback when the greedy constriction locks, an optional sculpting post-pass
/// and the Refine3 edge-flip post-pass (default). Algorithm, guarantees and measurements:
/// docs/reconstruction-3d.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "constrict/criterion.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

struct Delaunay3;
struct Mesh3Result;
struct Constrict3Options;
namespace detail {
// reconstruct3() with the tetrahedralization already built (src/constrict/detail/share3.hpp).
Status reconstruct3_sharing(const PointSet& points, const Constrict3Options& options, Delaunay3&& dt, Mesh3Result& result,
                            std::vector<int> part_of);
}  // namespace detail

/// What to do when the Delaunay constriction locks (heap empty, points still inside).
enum class Fallback3 {
  Auto,  ///< star-cavity re-tetrahedralization around each stuck point, then continue (default)
  None,  ///< stop at the lock: result.complete = false, stuck_points listed
};

/// Sculpting after every point is on the boundary (paper §4.2, candlestick figure).
enum class Sculpt3 {
  None,     ///< stop as soon as all points are on the boundary (the paper's rule)
  TwoFace,  ///< keep removing removable two-face tetrahedra while their criterion (sum of
            ///< 1 - γ over the two boundary faces) is >= sculpt_threshold
  Bridges,  ///< remove removable two-face tetrahedra whose larger surface face is a bridge:
            ///< longest edge >= bridge_ratio x the local spacing (largest first)
};

/// Criterion of a removable tetrahedron with two boundary faces.
enum class TwoFaceKey {
  Sum,  ///< (1 - γ1) + (1 - γ2), in [0, 4] (paper §4.2, spec §3.4)
  Max,  ///< max(1 - γ1, 1 - γ2), in [0, 2]: same scale as one-face tetrahedra (default, chosen
        ///< by measurement with Refine3::Area, docs/reconstruction-3d.md §4)
};

/// Post-pass after every point is on the surface (docs/reconstruction-3d.md §4): surface edge
/// flips through Delaunay tetrahedra in both directions — remove a body tetrahedron with two
/// surface faces (the paper's two-face rule) or add back a removed one with two faces on the
/// surface (its exact reverse) — whenever the flip lowers the energy of the surface, best first.
/// Every point stays on the surface and the surface stays a closed genus-0 2-manifold.
enum class Refine3 {
  None,          ///< the paper's result, unchanged (spec §5.3 golden behaviour)
  Area,          ///< energy = surface area: fills the deep dents and bridging pits
  Circumradius,  ///< energy = sum of face circumradii: prefers well-shaped small triangles
  Alternate,     ///< Area, then Circumradius, then Area again: each energy leaves the other's
                 ///< local minimum (default, best measured)
};

/// One run of reconstruct3()'s variant selection (Constrict3Options::variants).
struct Constrict3Variant {
  double size_bias = 0;     ///< Constrict3Options::size_bias of this run
  double label_weight = 0;  ///< Constrict3Options::label_weight of this run
};

/// Options of reconstruct3(). Defaults: the γ-constriction with TwoFaceKey::Max, a size bias
/// and inside/outside labels in the key (two variants, the smallest-area surface wins), the lock
/// fallback and the Refine3::Alternate post-pass (best GT recovery measured,
/// docs/reconstruction-3d.md §4.2, §4.5). paper() selects the paper's plain behaviour (spec §5.3
/// golden tests).
struct Constrict3Options {
  /// The paper's algorithm (seed paper §4.2, §4.3; spec gamma-graph.md §5.3 golden tests):
  /// TwoFaceKey::Sum, one run with neither size bias nor labels, no growth, no carve, no
  /// post-pass; the lock fallback stays. `constrict reconstruct --refine none` in 3D.
  static Constrict3Options paper() {
    Constrict3Options o;
    o.two_face_key = TwoFaceKey::Sum;
    o.refine = Refine3::None;
    o.variants.clear();
    o.size_bias = 0;
    o.label_weight = 0;
    o.carve_confidence = kCarveOff;
    o.grow = false;
    return o;
  }
  /// One constriction run (size bias and labels) instead of the default two variants, when the
  /// growth does not reach every point (CLI --fast).
  static Constrict3Options fast() {
    Constrict3Options o;
    o.variants = {{1.0, 1.0}};
    return o;
  }
  /// Options by preset name: "default", "paper", "fast".
  /// @return Ok, or InvalidArgument naming the presets
  static Status from_preset(const std::string& name, Constrict3Options& out);
  /// carve_confidence above 1: no carve pass.
  static constexpr double kCarveOff = 2.0;
  Fallback3 fallback = Fallback3::Auto;  ///< behaviour on lock
  Sculpt3 sculpt = Sculpt3::None;        ///< post-pass (measured in docs/reconstruction-3d.md)
  TwoFaceKey two_face_key = TwoFaceKey::Max;  ///< criterion of two-face tetrahedra
  /// Which removable tetrahedron goes next (criterion.hpp); two_face_key applies to Gamma only.
  /// The lock fallback ranks its target faces with the same criterion.
  Criterion criterion = Criterion::Gamma;
  Refine3 refine = Refine3::Alternate;        ///< flip post-pass on complete surfaces
  /// Minimum criterion for the TwoFace post-pass, in [0, 4] (the two_face_key scale). 2 = the average γ of the two faces
  /// is < 0 (the tetrahedron's circumcentre lies outside the current surface, spec §3.5).
  double sculpt_threshold = 2.0;
  /// Sculpt3::Bridges: a surface face is a bridge when its longest edge is at least bridge_ratio
  /// times the largest nearest-neighbour distance of its three vertices.
  double bridge_ratio = 5.0;
  /// Size bias of the constriction key: key += size_bias · ln(max(1, r)) with r the largest
  /// bridge ratio (see bridge_ratio) of the tetrahedron's surface faces. 0 = the γ key alone.
  double size_bias = 0.0;
  /// reconstruct3() with two or more variants runs one constriction per variant (size_bias,
  /// label_weight), sharing the Delaunay tetrahedralization, in parallel, and keeps the complete
  /// surface with the smallest area (docs/reconstruction-3d.md §4.5). Empty or one variant: a
  /// single run with size_bias / label_weight (or the one variant's values). The step-able
  /// Constrictor3 always does a single run. Default chosen by measurement on the shared models.
  std::vector<Constrict3Variant> variants = {{1.0, 0.0}, {1.0, 1.0}};
  /// Weight of the inside/outside labelling of the Delaunay tetrahedra (circumball propagation
  /// from the convex hull, as in the power crust; docs/reconstruction-3d.md §4.6): key += w for a
  /// tetrahedron labelled outside, -w for inside, scaled by the label's confidence. 0 = off.
  double label_weight = 0.0;
  /// Carve pass after the constriction, before the flips (Criterion::Gamma only;
  /// docs/reconstruction-3d.md §4.6): remove the surface-connected regions of Delaunay
  /// tetrahedra labelled outside with at least this confidence, through non-manifold
  /// intermediate states, keeping a region's removals only up to its last valid state (closed
  /// 2-manifold, genus 0, every point on the surface). > 1 = off.
  double carve_confidence = 0.5;
  /// Growth (Criterion::Gamma; docs/reconstruction-3d.md §4.7): before any constriction, grow
  /// the body from the inside along the inside/outside labels, adding Delaunay tetrahedra only by
  /// the mirror images of the removal rules (a triangulated ball with every point on its
  /// surface), then fill the inside regions it left out; points it cannot reach get a star cavity
  /// mirrored to the outside of the body. When every point is reached this is the result (then
  /// the γ pass, the carve, the flips and the variants are not run; Mesh3Result::method "grow");
  /// otherwise (Mesh3Result::grow_unreached > 0) the constriction from the convex hull runs as
  /// without it. Not used when every point is on the convex hull (the hull is the result), with
  /// stop_after, with a sculpting post-pass or another criterion. Default on: the best GT
  /// recovery and distances measured on every shared model.
  bool grow = true;
  /// Handles (the auto topology, topology.hpp; docs/topology.md §"3D"): after the growth and its
  /// fill, a handle stage may close loops through the regions labelled inside that the genus-0
  /// growth had to leave out, and open tunnels through regions labelled outside, keeping every
  /// vertex manifold and every point on the surface; a change is kept only where it lowers the
  /// bridge measure (no face spanning a gap). The result may then have genus > 0. Off: genus 0.
  bool handles = false;
  /// Cavity size limit (tetrahedra) of one fallback attempt.
  std::size_t max_cavity_tets = 2048;
  /// Stop the Delaunay constriction after this many removals (debugging / figures). The result is
  /// then incomplete (no fallback runs) unless all points were already on the boundary.
  std::size_t stop_after = SIZE_MAX;
  /// Validate the surface (validate_mesh3) and the body (positive tetrahedra whose free faces are
  /// exactly the surface triangles); a failure is a bug and throws InternalError.
  bool validate = true;
  /// Include the exact self-intersection test in the validation (O(F log F + K); off by default:
  /// the surface is the boundary of a tetrahedralization, which already excludes it).
  bool validate_self_intersections = false;

  /// Do these options plan the growth (grow, the γ criterion, no stop_after, no sculpting)? It
  /// then runs unless every point is on the convex hull. The report's `grow.enabled`.
  bool growth_planned() const noexcept {
    return grow && criterion == Criterion::Gamma && stop_after == SIZE_MAX && sculpt == Sculpt3::None;
  }
};

/// The stages of the 3D engine, in pipeline order (docs/architecture.md).
enum class Stage3 {
  Hull,        ///< the start: the convex hull (the points on it)
  Grow,        ///< growth from the inside (docs/reconstruction-3d.md §4.7)
  Fill,        ///< fill pass after the growth
  Handles,     ///< handle stage after the fill (Constrict3Options::handles)
  Gamma,       ///< the γ-constriction from the convex hull (seed paper §4.2)
  Cavity,      ///< star cavities after a lock (seed paper §4.3)
  Carve,       ///< carve pass (docs/reconstruction-3d.md §4.6)
  Sculpt,      ///< sculpting post-pass (Sculpt3)
  Refine,      ///< Refine3 edge flips
  Candidates,  ///< the variant runs (Constrict3Options::variants)
};
/// "hull", "grow", "fill", "handles", "gamma", "cavity", "carve", "sculpt", "refine", "candidates".
const char* to_string(Stage3 stage) noexcept;

/// How a 3D result was reached (Mesh3Result::method).
enum class Method3 {
  Gamma,            ///< "gamma": the constriction from the hull, no fallback needed
  Grow,             ///< "grow": the growth from the inside reached every point
  Cavity,           ///< "cavity": the lock fallback placed points
  Locked,           ///< "locked": Fallback3::None, or the fallback exhausted (incomplete)
  Stopped,          ///< "stopped": stop_after (incomplete)
  VoronoiSkeleton,  ///< "voronoi-skeleton": the comparison method (voronoi_skeleton.hpp)
  Incomplete,       ///< "incomplete": a comparison method that did not reach every point
};
const char* to_string(Method3 method) noexcept;

/// Fallback3 by name: "auto", "none". @return false for another name
bool fallback3_from_name(const std::string& name, Fallback3& out) noexcept;
const char* to_string(Fallback3 fallback) noexcept;

/// One stage and how many points it placed on the boundary.
struct Constrict3Stage {
  Stage3 name = Stage3::Hull;
  std::size_t placed = 0;    ///< points that joined the boundary in this stage
  std::size_t removed = 0;   ///< tetrahedra removed in this stage
};

/// One variant run of reconstruct3() (Constrict3Options::variants) and its outcome.
struct Constrict3Candidate {
  double size_bias = 0;
  double label_weight = 0;
  double surface_area = 0;
  bool complete = false;
  double ms = 0;  ///< constriction + fallback + post-passes of this candidate
};

/// One topology change the handle stage kept (Constrict3Options::handles; docs/topology.md §3D):
/// what it did and what decided it.
struct Handle3Change {
  enum class Kind { CloseLoop, OpenTunnel, SealCavity };
  Kind kind = Kind::CloseLoop;
  std::size_t tetrahedra = 0;          ///< tetrahedra added or removed
  /// Its change of the surfaces' face count F = 2N - 4c + 4g: +4 per loop closed or tunnel
  /// opened, -4 per surface sealed off (a region may close several loops at once).
  long long delta_faces = 0;
  int bridges_before = 0;              ///< bridge faces (kBridgeRatio) around it before ...
  int bridges_after = 0;               ///< ... and after (kept: fewer)
  double worst_ratio_before = 0, worst_ratio_after = 0;  ///< largest face ratio around it
  bool separates_parts = false;        ///< kept because it separates two parts of the gap rule
  /// A sealed cavity (an inner shell closer than the gap rule's threshold): the void it encloses,
  /// its tetrahedra, the points on it and its widest tetrahedron's bridge ratio (kept: large and wide).
  std::size_t cavity_tetrahedra = 0, cavity_points = 0;
  double cavity_width = 0;
  /// Kept by a rule that asks for a long loop (the thin-tube and noisy-tube rules, a pinch,
  /// several loops, or long faces left on an even sample): the shortest loop it closes, in
  /// nearest-neighbour spacings, measured up to that rule's minimum (16, 48 or 100: the minimum
  /// means that much or more); 0 for the other rules.
  double loop_spacings = 0;
  /// Its region became valid only through a move of several tetrahedra at a pinched point.
  bool pinched = false;
};
/// "close-loop", "open-tunnel", "seal-cavity".
const char* to_string(Handle3Change::Kind kind) noexcept;

/// Result of reconstruct3().
struct Mesh3Result {
  TriMesh3 mesh;                          ///< outward triangles over input ids
  std::vector<std::array<int, 4>> tets;   ///< the body (positively oriented); includes the
                                          ///< non-Delaunay tetrahedra made by the fallback
  bool complete = false;                  ///< every point on the surface
  bool locked = false;                    ///< the Delaunay constriction locked
  std::vector<int> stuck_points;          ///< points inside when it locked (ascending)
  std::vector<int> unplaced_points;       ///< points still inside at the end (empty if complete)
  Method3 method = Method3::Gamma;        ///< how it was reached
  bool validated = false;                 ///< checked by the library (Constrict3Options::validate)
  /// Complete (every point on the surface) and validated: a closed genus-0 2-manifold through
  /// every point, the boundary of the body.
  bool valid() const noexcept { return complete && validated; }
  std::vector<Constrict3Stage> stages;    ///< every stage run, in order
  std::size_t removed_one_face = 0;       ///< tetrahedra removed by the one-face rule
  std::size_t removed_two_face = 0;       ///< ... by the two-face rule (sculpting included)
  std::size_t removed_sculpt = 0;         ///< two-face removals of the sculpting post-pass
  std::size_t carved = 0;                 ///< tetrahedra removed by the carve pass (kept)
  std::size_t carve_undone = 0;           ///< carve removals undone (no valid end state)
  bool carve_capped =
      false;  ///< the carve, fill or handle pass stopped at its work bound (points along curves in space)
  std::size_t grown = 0;                  ///< tetrahedra of the growth (0: growth off or failed)
  std::size_t grown_outside = 0;          ///< of those, labelled outside (to reach missed points)
  std::size_t grown_crawled = 0;          ///< ... of those, joined along two faces into a thin part
                                          ///< the labels miss (docs/reconstruction-3d.md §4.11)
  /// The growth reached every point but took at least 1/kThinWallShare of its tetrahedra against
  /// their labels by the one-face rule (grown_outside - grown_crawled): a wall about a spacing
  /// thick, whose inside the labels cannot see, where the surface zigzags between its two sides.
  /// So the variant constrictions from the hull ran as well (docs/reconstruction-3d.md §4.7,
  /// "Thin walls"); default variants only (not with --fast), and only for a genus-0 growth of
  /// one surface (the handle stage's loops and cavities stay).
  static constexpr std::size_t kThinWallShare = 32;
  bool grow_checked = false;
  bool grow_replaced = false;             ///< ... and the smallest of their surfaces, smaller than the growth's, won
  std::size_t filled = 0;                 ///< tetrahedra added by the fill pass after the growth
  std::size_t handle_added = 0;           ///< tetrahedra the handle stage added (closing loops)
  std::size_t handle_removed = 0;         ///< ... and removed (opening tunnels)
  std::vector<Handle3Change> handle_changes;  ///< what the handle stage kept, in order
  int genus = 0;                          ///< total genus of the surface (> 0 only with handles)
  int surfaces = 1;                       ///< its components (> 1 only with handles: inner shells)
  std::size_t grow_cavities = 0;          ///< points the growth placed by a mirrored star cavity
  /// Points inside pockets labelled inside that the growth's front closed around, brought in by the
  /// fill during the growth (docs/reconstruction-3d.md §4.13), and the tetrahedra it added.
  std::size_t grow_pocket_points = 0, grow_pocket_filled = 0;
  std::size_t grow_unreached = 0;         ///< growth tried and failed: points it left (then the constriction ran)
  std::size_t cavities = 0;               ///< successful fallback re-tetrahedralizations
  std::size_t cavity_attempts = 0;        ///< fallback attempts (successful or not)
  bool cavity_capped = false;  ///< the star cavities (growth or lock fallback) stopped at their work bound (thin rods)
  std::size_t refine_added = 0;           ///< tetrahedra added back by the Refine3 post-pass
  std::size_t refine_removed = 0;         ///< tetrahedra removed by the Refine3 post-pass
  bool refine_capped = false;             ///< a Refine3 pass stopped at its work bound (points along curves in space)
  std::size_t non_delaunay_tets = 0;      ///< body tetrahedra made by the fallback
  /// Bridge measure (docs/reconstruction-3d.md §4.8): surface triangles whose longest edge is at
  /// least kBridgeRatio times the larger nearest-neighbour distance of its end points — sheets
  /// spanning a gap between parts that nearly touch show up here.
  static constexpr double kBridgeRatio = 4.0;
  std::size_t bridge_faces = 0;
  double bridge_area = 0;        ///< their total area (at the input's scale)
  double max_bridge_ratio = 0;   ///< the largest such ratio over all surface triangles
  std::size_t delaunay_tets = 0;          ///< tetrahedra of the Delaunay tetrahedralization
  double volume = 0, surface_area = 0;    ///< of the final surface (double arithmetic)
  double size_bias = 0;                   ///< size bias of the run that produced this result
  double label_weight = 0;                ///< label weight of the run that produced this result
  std::vector<Constrict3Candidate> candidates;  ///< every candidate run (empty: single run)
  double ms_delaunay = 0, ms_constrict = 0, ms_fallback = 0, ms_sculpt = 0, ms_carve = 0, ms_refine = 0, ms_validate = 0;
  double ms_grow = 0, ms_fill = 0;  ///< growth and its fill pass (§4.7)
  /// Variant selection: time of the labels / spacing set-up plus the parallel runs (wall clock);
  /// 0 for a single run. ms_constrict ... ms_refine are those of the winning run.
  double ms_setup = 0, ms_variants = 0;
};

/// Event passed to a visitor.
struct Constrict3Event {
  enum class Kind { RemoveTet, Lock, Cavity, StageBegin };
  Kind kind = Kind::RemoveTet;
  std::array<int, 4> tet{{-1, -1, -1, -1}};  ///< removed tetrahedron (RemoveTet)
  int boundary_faces = 0;                    ///< 1 or 2 (RemoveTet)
  double criterion = 0;                      ///< the key (Gamma: 1 - γ per two_face_key)
  int point = -1;                            ///< Cavity: the stuck point it is built around
  std::size_t cavity_size = 0;               ///< Cavity: tetrahedra replaced
  Stage3 stage = Stage3::Gamma;              ///< the stage it belongs to / begins
};

/// Observer of the constriction (figures, debugging, tests). Called synchronously.
class Constrict3Visitor {
 public:
  virtual ~Constrict3Visitor() = default;
  virtual void on_event(const Constrict3Event& event) = 0;
};

/// Step-able constrictor. Usage: init(); while (step()) {...}; finish(result).
/// reconstruct3() does exactly this.
class Constrictor3 {
 public:
  Constrictor3();
  ~Constrictor3();
  Constrictor3(const Constrictor3&) = delete;
  Constrictor3& operator=(const Constrictor3&) = delete;

  /// Checks the points, builds the Delaunay tetrahedralization with γ-values, starts from the
  /// convex hull.
  /// @param[in] points 3D points (kept by reference: must outlive the constrictor)
  /// @return check_points() failures (TooFewPoints, Coplanar, Duplicate, ...) or Ok
  Status init(const PointSet& points, const Constrict3Options& options,
              Constrict3Visitor* visitor = nullptr);
  /// Removes one tetrahedron of the Delaunay constriction (spec §3.5).
  /// @return false when this stage is over: all points on the boundary, locked, or stop_after.
  /// @note O(log T) amortised.
  bool step();
  /// Current surface (outward triangles).
  TriMesh3 surface() const;
  /// Points not (yet) on the surface, ascending.
  std::vector<int> inside_points() const;
  /// Runs the fallback and the sculpting post-pass per the options, validates, fills @p result.
  /// @return Ok (see result.complete), or Internal if init() was not successful.
  Status finish(Mesh3Result& result);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  static Status finish_impl(Impl& s, Mesh3Result& r, bool validate, bool growth_only = false);
  static void validate_result(Impl& s, Mesh3Result& r);
  Status run_candidates(const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                        Constrict3Visitor* visitor);
  static Status run(Constrictor3& c, const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                    Constrict3Visitor* visitor);
  friend Status reconstruct3(const PointSet&, const Constrict3Options&, Mesh3Result&, Constrict3Visitor*);
  friend Status detail::reconstruct3_sharing(const PointSet&, const Constrict3Options&, Delaunay3&&, Mesh3Result&,
                                             std::vector<int>);
};

/// Reconstructs a closed genus-0 polyhedron through all points (3D).
/// @param[in] points dim == 3, at least 4 points, no duplicates, not all coplanar
/// @param[in] options fallback, sculpting, validation
/// @param[out] result surface, body and diagnostics
/// @return Ok, or the check_points() status for bad input. A lock is not an error: with
///   Fallback3::None (or if the fallback is exhausted) Ok is returned with result.complete ==
///   false and result.unplaced_points filled.
/// @note Guarantee: result.mesh is always a closed, oriented, vertex-manifold genus-0 surface
///   (the boundary of result.tets), checked exactly when options.validate. Completeness is
///   measured, not proved (docs/reconstruction-3d.md). Complexity O(T log T) for T Delaunay
///   tetrahedra plus the local fallback work.
Status reconstruct3(const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                    Constrict3Visitor* visitor = nullptr);

}  // namespace constrict
