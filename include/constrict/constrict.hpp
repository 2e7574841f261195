// SPDX-License-Identifier: GPL-3.0-or-later
/// @file constrict.hpp
/// @brief 2D reconstruction: a simple polygon through all points by γ-constriction of the
/// Delaunay triangulation (Veltkamp, seed paper §4.1, §4.3, §5; spec gamma-graph.md §3), with
/// local fallbacks when the greedy constriction locks. Algorithm and guarantees:
/// docs/reconstruction-2d.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "constrict/criterion.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "constrict/validate.hpp"

namespace constrict {

/// What to do when the Delaunay constriction locks (heap empty, points still inside).
enum class Fallback {
  Auto,     ///< γ0 schedule, then degree-4 augmentation, then repair (always completes)
  Gamma0,   ///< γ0 schedule, then repair if Constrict2Options::repair
  Degree4,  ///< degree-4 augmentation, then repair if Constrict2Options::repair
  None,     ///< stop at the lock: result.complete = false, stuck_points listed
};

/// Post-pass on the complete polygon (docs/reconstruction-2d.md §"Refinement").
enum class Refine2 {
  None,         ///< the polygon of the constriction and its fallbacks, unchanged (the paper's)
  LocalSearch,  ///< 2-opt and Or-opt moves between Delaunay neighbours that shorten the polygon
                ///< and keep it simple (exact tests); measured on the ground truth: 36 -> 37/43
};

/// Fallback by name: "auto", "gamma0", "degree4", "none". @return false for another name
bool fallback_from_name(const std::string& name, Fallback& out) noexcept;
const char* to_string(Fallback fallback) noexcept;

/// Constrict2Options::refine_multi_start applies up to this many points (more: one start).
constexpr std::size_t kRefineMultiStartMaxPoints = 5000;

/// Options of reconstruct2(). Defaults reproduce the paper's algorithm plus the fallbacks.
struct Constrict2Options {
  /// The paper's algorithm (seed paper §4.1) with the lock fallbacks: no refinement post-pass.
  /// `constrict reconstruct --refine none` in 2D.
  static Constrict2Options paper() {
    Constrict2Options o;
    o.refine = Refine2::None;
    return o;
  }
  /// Options by preset name: "default", "paper". @return Ok, or InvalidArgument
  static Status from_preset(const std::string& name, Constrict2Options& out);
  Fallback fallback = Fallback::Auto;  ///< behaviour on lock
  /// Which removable triangle goes next (criterion.hpp); the fallbacks rank with the same key.
  Criterion criterion = Criterion::Gamma;
  /// γ0 values tried in order (each < 0, decreasing); the graph γ([-1,1],[γ0,1]) grows with each.
  std::vector<double> gamma0_schedule = {-0.05, -0.1, -0.2, -0.3, -0.5, -0.75, -1};
  /// Run the final repair after Gamma0/Degree4 (Auto always does). The repair guarantees a
  /// complete polygon.
  bool repair = true;
  /// The γ0 and degree-4 stages insert a stuck point z into a boundary edge ab only when neither
  /// new edge is longer than this many times |ab| (exact): a longer one is a needle from z to an
  /// edge across an empty interior (the γ0 graph holds every Delaunay edge, and a point inside a
  /// noisy band has Delaunay neighbours across the whole figure). Needles are left to the repair
  /// (the complete graph, no limit), so with the repair the ladder still completes; without it
  /// (repair = false) a point only a needle could place stays inside. A value that is not a
  /// positive finite number turns the limit off (the fallbacks before 2026-12-06); a tiny positive
  /// one leaves every insertion to the repair. docs/reconstruction-2d.md §2.
  double fallback_needle_ratio = 4;
  /// Post-pass on the complete polygon. Default LocalSearch (measured better on the shared ground
  /// truth, docs/reconstruction-2d.md); Refine2::None gives the paper's algorithm.
  Refine2 refine = Refine2::LocalSearch;
  /// Work bound of the LocalSearch refinement: at most refine_work_per_point · N array elements
  /// moved (the polygon stays simple when the bound stops it; Polygon2Result::refine_budget_hit).
  std::size_t refine_work_per_point = 64;
  /// The LocalSearch refinement of an input of at most kRefineMultiStartMaxPoints points runs from
  /// 8 evenly spaced starts and keeps the shortest result (docs/reconstruction-2d.md §4c); false:
  /// one start (up to 8 times less refinement work on such inputs; the polygon may differ).
  bool refine_multi_start = true;
  /// The γ0 fallback's graph tests done side by side ahead of its queue (0: each test as its
  /// candidate comes out; at most 1024 are used). A tuning knob only: the polygon is the same for
  /// every value and thread count.
  std::size_t fallback_tests_ahead = 16;
  /// The γ0 fallback rules most candidate pairs out by witnesses among the Delaunay neighbours of
  /// their two ends before queueing them; it reads at most this many neighbours of each end (0:
  /// all). A tuning knob only: a pair not ruled out is tested exactly when it comes out of the
  /// queue, so the polygon is the same for every value. Reading every neighbour of a point of
  /// thousands (an outlier inside a sampled curve) for each pair at it made the stage quadratic.
  std::size_t fallback_witness_reads = 32;
  /// Stop the Delaunay constriction after this many removals (debugging / figures). The result is
  /// then incomplete (no fallback runs) unless all points were already on the boundary.
  std::size_t stop_after = SIZE_MAX;
  /// Validate the final polygon exactly (validate_polygon_in_triangulation() with the Delaunay
  /// triangulation: O(N) when every edge is a Delaunay edge, else the O(N log N) sweep). A complete
  /// polygon that fails is a bug: InternalError. The outcome is in Polygon2Result::check.
  bool validate = true;
};

/// One fallback stage and how many points it placed on the boundary.
struct Constrict2Stage {
  std::string name;        ///< "gamma", "gamma0=-0.1", "degree4", "repair", "star"
  std::size_t placed = 0;  ///< points that joined the boundary in this stage
  /// Fallback stages: candidate insertions queued (the first queue and those offered after each
  /// insertion; a work count, the same on every thread count).
  std::size_t candidates = 0;
};

/// Result of reconstruct2().
struct Polygon2Result {
  std::vector<int> boundary;  ///< CCW polygon as input indices (each point once when complete)
  bool complete = false;      ///< all points on the boundary (always true unless Fallback::None
                              ///< or stop_after stopped the run early)
  bool locked_at_gamma0 = false;  ///< the Delaunay (γ0 = 0) constriction locked
  std::vector<int> stuck_points;  ///< points inside when the Delaunay constriction stopped
  /// The last stage that placed a point: "gamma" (no fallback needed), "gamma0=<v>", "degree4",
  /// "repair" or "star"; "locked" with Fallback::None, "stopped" after stop_after.
  std::string method;
  std::vector<Constrict2Stage> stages;  ///< every stage run, in order
  std::size_t removed_simplices = 0;    ///< triangles removed by the Delaunay constriction
  std::size_t fallback_insertions = 0;  ///< points placed by the fallbacks
  std::vector<std::array<int, 2>> fallback_edges;  ///< non-Delaunay polygon edges (made by a
                                                   ///< fallback or the refinement), (min, max) ids
  std::size_t refine_moves = 0;     ///< 2-opt + Or-opt + deep moves of the refinement
  bool refine_budget_hit = false;   ///< the refinement stopped at its work bound
  double perimeter_before_refine = 0;  ///< perimeter before the refinement (== perimeter if none)
  double area = 0, perimeter = 0;       ///< of the final polygon (double arithmetic)
  bool validated = false;  ///< the polygon was validated (Constrict2Options::validate)
  PolygonCheck check;      ///< the validation outcome (an incomplete polygon misses points)
  /// Complete and validated: a simple counter-clockwise polygon through every point.
  bool valid() const noexcept { return complete && validated && check.reason.empty(); }
  double ms_delaunay = 0, ms_constrict = 0, ms_fallback = 0, ms_refine = 0, ms_validate = 0;
};

/// Event passed to a visitor.
struct Constrict2Event {
  enum class Kind { RemoveTriangle, InsertPoint, Lock, StageBegin };
  Kind kind = Kind::RemoveTriangle;
  std::array<int, 3> triangle{{-1, -1, -1}};  ///< (a, b, y): boundary edge a->b, apex y
  double criterion = 0;                       ///< the key: 1 - γ(ab; y) for Criterion::Gamma
  std::string stage;                          ///< stage name ("refine": StageBegin of the refinement)
};

/// Observer of the constriction (for figures, debugging, tests). Called synchronously, on the
/// thread that runs the constriction; it must not call back into the Constrictor2 it observes.
class Constrict2Visitor {
 public:
  virtual ~Constrict2Visitor() = default;
  virtual void on_event(const Constrict2Event& event) = 0;
  /// False: the RemoveTriangle and InsertPoint events come without their triangle ({-1, -1, -1})
  /// and criterion (0), the same events otherwise. A visitor that only counts them (a progress
  /// display) spares the engine mapping each event's points to input ids: about 5 % of the
  /// constriction's time on 10^6 points. Asked once, when the constrictor is initialised.
  virtual bool wants_triangles() const { return true; }
};

namespace detail {
struct Constrictor2Access;  // the engine's triangulation for the library's own stages (constrict2.cpp)
}  // namespace detail

/// Step-able constrictor. Usage: init(); while (step()) {...}; finish(result).
/// reconstruct2() does exactly this.
class Constrictor2 {
 public:
  Constrictor2();
  ~Constrictor2();
  Constrictor2(const Constrictor2&) = delete;
  Constrictor2& operator=(const Constrictor2&) = delete;

  /// Checks the points, builds the Delaunay triangulation, starts from the convex hull.
  /// @param[in] points 2D points (kept by reference: must outlive the constrictor)
  /// @return check_points() failures (TooFewPoints, Collinear, Duplicate, ...) or Ok
  /// @note O(N log N).
  Status init(const PointSet& points, const Constrict2Options& options,
              Constrict2Visitor* visitor = nullptr);
  /// Removes one triangle of the Delaunay constriction (spec §3.5).
  /// @return false when this stage is over: all points on the boundary, locked, or stop_after.
  /// @note O(log N) amortised.
  bool step();
  /// Current boundary, CCW, starting at its smallest index.
  std::vector<int> boundary() const;
  /// Points not (yet) on the boundary, ascending.
  std::vector<int> inside_points() const;
  /// Runs the fallbacks per the options, validates and fills @p result.
  /// @return Ok (see result.complete), or Internal if init() was not successful.
  Status finish(Polygon2Result& result);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  struct Canonical;  // the canonical point order the engine runs in (constrict2.cpp)
  std::unique_ptr<Canonical> canon_;
  friend struct detail::Constrictor2Access;
};

/// Reconstructs a simple polygon through all points (2D).
/// @param[in] points dim == 2, at least 3 points, no duplicates, not all collinear
/// @param[in] options fallbacks and limits
/// @param[out] result the polygon and diagnostics
/// @return Ok, or the check_points() status for bad input. With Fallback::None a lock is not an
///   error: Ok is returned with result.complete == false and result.stuck_points filled.
/// @note Guarantee: with Fallback::Auto (or repair enabled) result.boundary is a simple CCW polygon
///   through every point (validated exactly). Complexity O(N log N) expected for the Delaunay
///   stage; fallbacks are local to the stuck region (docs/reconstruction-2d.md).
Status reconstruct2(const PointSet& points, const Constrict2Options& options,
                    Polygon2Result& result, Constrict2Visitor* visitor = nullptr);

/// What refine_polygon2() did.
struct Refine2Stats {
  std::size_t moves_2opt = 0;   ///< accepted 2-opt moves
  std::size_t moves_oropt = 0;  ///< accepted Or-opt moves (segments of 1-8 points)
  std::size_t moves_deep = 0;   ///< accepted Lin–Kernighan (k-opt, k <= 6) and double-bridge moves
  std::size_t rejected = 0;     ///< shortening moves rejected because the polygon would not be simple
  bool budget_hit = false;      ///< stopped by the work bound (the polygon is still valid)
  double length_before = 0, length_after = 0;  ///< perimeters (double arithmetic)
  /// polygon edges the simplicity tests compared with a new edge; the search stops, between two
  /// vertices' visits, once they pass 256 · N + 2^22 (budget_hit)
  std::size_t simplicity_tests = 0;
};

/// Shortens a simple polygon through all points by local moves (the Refine2::LocalSearch post-pass
/// of reconstruct2(), usable on any valid polygon): 2-opt moves and Or-opt moves of segments of 1–8
/// points, then Lin–Kernighan (k <= 6) and double-bridge moves (docs/reconstruction-2d.md §4c),
/// built from near Delaunay neighbours. A move is applied only if it shortens the polygon and the
/// result is simple (exact orient2 tests against the nearby edges), so the polygon is valid after
/// every move.
/// Deterministic; the result is counter-clockwise and starts at its smallest index.
/// @param[in] points 2D, at least 3 points, not all collinear
/// @param[in,out] polygon a simple polygon through every point, either orientation
/// @param[out] stats optional move counts and perimeters
/// @param[in] work_per_point bound on the reversal work: work_per_point · N array elements
/// @return Ok; InvalidArgument if @p polygon is not valid (it is then unchanged); the
///   check_points() status for bad points
/// @note O(N log N) for the Delaunay triangulation, O(N) per sweep over the vertices, plus the
///   bounded reversal work. docs/reconstruction-2d.md §"Refinement".
Status refine_polygon2(const PointSet& points, std::vector<int>& polygon, Refine2Stats* stats = nullptr,
                       std::size_t work_per_point = 64);

}  // namespace constrict
