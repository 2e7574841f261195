// SPDX-License-Identifier: GPL-3.0-or-later
// reconstruct_rings2(): the ladder of topology.hpp -- infer the rings; several with clear gaps
// (Auto) -> the rings; otherwise -> the single polygon of reconstruct2() as one shell. Then the
// exact validation of whatever ring set came out.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include <tbb/task_group.h>

#include "constrict/delaunay.hpp"
#include "constrict/detail/share2.hpp"
#include "core/detail/ring_measure.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"
#include "core/detail/check_points.hpp"
#include "topology/detail/infer_rings2.hpp"

namespace constrict {
namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// infer_rings2() on the engine's points (engine ids), its rings then in input ids: the same rings
// as on the input (every decision is exact and breaks ties by the points' lexicographic order, and
// the engine's points are the input's times an exact power of two), each from its smallest input
// index again; a check that failed is redone on the input, so that it names input indices.
Status infer_shared(const PointSet& input, const PointSet& points, const detail::RingsAdjacency& adj,
                    const std::vector<int>& to_input, const Rings2Options& o, Rings2Result& r) {
  const auto t = Clock::now();
  if (Status s = detail::infer_rings2(points, adj, o, r.inferred); !s) return s;
  for (Ring2& ring : r.inferred.rings) {
    for (int& v : ring.indices) v = to_input[static_cast<std::size_t>(v)];
    std::rotate(ring.indices.begin(), std::min_element(ring.indices.begin(), ring.indices.end()), ring.indices.end());
  }
  if (!r.inferred.rings.empty() && !r.inferred.check.reason.empty()) (void)validate_rings2(input, r.inferred.rings, &r.inferred.check);
  r.inferred_run = true;
  r.ms_infer += ms_since(t);
  return Status::ok();
}

// Shoelace area (holes run clockwise: they subtract) and perimeter (detail::add_ring_measure).
void measure(const PointSet& pts, Rings2Result& r) {
  r.area = r.perimeter = 0;
  const int e = rescale_exponent(max_coordinate_exponent(pts));
  for (const Ring2& ring : r.rings) detail::add_ring_measure(pts, ring.indices, e, r.area, r.perimeter);
  r.area = std::ldexp(r.area, 2 * e);
  r.perimeter = std::ldexp(r.perimeter, e);
}

}  // namespace

bool topology_from_name(const std::string& name, Topology2& out) noexcept {
  if (name == "single") out = Topology2::Single;
  else if (name == "auto") out = Topology2::Auto;
  else return false;
  return true;
}

const char* to_string(Topology2 t) noexcept { return t == Topology2::Single ? "single" : "auto"; }
const char* to_string(RingRole r) noexcept { return r == RingRole::Shell ? "shell" : "hole"; }

Status reconstruct_rings2(const PointSet& points, const Rings2Options& o, Rings2Result& r, Constrict2Visitor* visitor) {
  r = Rings2Result{};
  r.topology = o.topology;
  if (!(o.topology_gap >= 0) || !std::isfinite(o.topology_gap))
    return {StatusCode::InvalidArgument, "topology gap must be a finite number >= 0, not " + number_text(o.topology_gap)};
  if (o.topology == Topology2::Auto && o.polygon.stop_after != SIZE_MAX)
    return {StatusCode::InvalidArgument,
            "stop_after stops the one constriction of the single topology; the auto topology reconstructs every part to the end (drop one of them)"};
  // Duplicates: the engine's triangulation finds them (and check_points() names them then).
  if (Status s = detail::check_points_deferred(points); !s) return s;
  // The inference runs on the engine's own triangulation (one triangulation, not two): its
  // adjacency is taken when the triangulation is built, and the inference then runs on the other
  // core beside the constriction (deterministic: neither reads what the other writes). When Auto
  // finds several rings the polygon is dropped, so the inference then cancels the engine: its
  // constriction, fallback and refinement would be work for nothing (on two concentric circles
  // of 10^5 points, 6 s of refinement after a 0.1 s inference).
  Status inferred = Status::ok(), single = Status::ok();
  std::atomic<bool> drop_polygon{false};
  const bool run_infer = o.topology == Topology2::Auto || o.infer_in_single;
  if (run_infer) {
    tbb::task_group side;
    PointSet engine_points;
    std::vector<int> to_input;
    Delaunay2 copy;
    bool shared = false;
    single = detail::reconstruct2_sharing(
        points, o.polygon, r.polygon, visitor,
        [&](const PointSet& p, const Delaunay2& dt, const std::vector<int>& ids) {
          // Copies only (the engine waits for them); the
          // adjacency is built on the other core.
          const auto t = Clock::now();
          copy = dt;
          engine_points = p;
          to_input = ids;
          shared = true;
          r.ms_infer = ms_since(t);
          side.run([&] {
            const auto adj = detail::rings_adjacency(std::move(copy));
            inferred = infer_shared(points, engine_points, *adj, to_input, o, r);
            if (!inferred || (o.topology == Topology2::Auto && r.inferred.several()))
              drop_polygon.store(true, std::memory_order_relaxed);
          });
        },
        &drop_polygon);
    side.wait();
    if (!shared && !single) return single;  // (the triangulation failed: the engine's error)
  } else {
    single = reconstruct2(points, o.polygon, r.polygon, visitor);
  }
  if (!inferred) return inferred;
  CONSTRICT_CHECK(!drop_polygon.load() || (o.topology == Topology2::Auto && r.inferred.several()),
                  "reconstruct_rings2 cancelled a polygon that it then needed");
  if (o.topology == Topology2::Auto && r.inferred.several()) {
    r.polygon = Polygon2Result{};
    r.rings = r.inferred.rings;
    r.from_polygon = false;
    r.validated = true;  // infer_rings2() validated them (exactly: validate_rings2())
    r.check = r.inferred.check;
    measure(points, r);
  } else {
    if (!single) return single;
    Ring2 shell;
    shell.indices = r.polygon.boundary;
    r.rings.push_back(std::move(shell));
    r.area = r.polygon.area;
    r.perimeter = r.polygon.perimeter;
  }
  if (!o.validate || !r.complete() || !r.from_polygon) return Status::ok();
  if (r.polygon.validated) {  // reconstruct2() validated it: a simple CCW polygon
    r.validated = true;
    r.check.reason = r.polygon.check.reason;
    r.check.indices_ok = r.polygon.check.indices_ok;
    r.check.all_points = r.polygon.check.all_points;
    r.check.simple = r.check.nested = r.polygon.check.simple;
    r.check.oriented = r.polygon.check.ccw;
    return Status::ok();
  }
  const auto t = Clock::now();
  const Status v = validate_rings2(points, r.rings, &r.check);
  r.validated = true;
  r.ms_validate = ms_since(t);
  if (!v) return {StatusCode::Internal, "the reconstructed rings failed validation (please report): " + r.check.reason};
  return Status::ok();
}

}  // namespace constrict
