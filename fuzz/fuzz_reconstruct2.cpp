// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: reconstruct2() on small decoded point sets with decoded options
// (docs/fuzzing.md). Contract (constrict.hpp): the check_points() status for bad input, else Ok;
// an Ok result that is complete is a simple CCW polygon through every point, checked here again
// on the input's own coordinates (Shamos-Hoey sweep and the O(N^2) pair test); with any fallback
// but None (and the repair on) it is complete. refine_polygon2() of the result, reversed, stays
// valid; validate_polygon() refuses non-finite input without crashing. With the default fallbacks,
// reconstruct_rings2() in auto mode gives a ring set the brute-force checker accepts.
#include <numeric>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "constrict/constrict.hpp"
#include "constrict/topology.hpp"
#include "constrict/validate.hpp"
#include "fuzz_engine.hpp"

namespace {

using namespace constrict;
using constrict_fuzz::require;

Constrict2Options decode_options(constrict_fuzz::Bytes& in) {
  const std::uint8_t a = in.u8(), b = in.u8();
  Constrict2Options o;
  const char* const presets[] = {"default", "paper"};
  require(Constrict2Options::from_preset(presets[a & 1], o).is_ok(), "2D preset refused");
  const Fallback fallbacks[] = {Fallback::Auto, Fallback::Gamma0, Fallback::Degree4, Fallback::None};
  o.fallback = fallbacks[(a >> 1) & 3];
  const Criterion criteria[] = {Criterion::Gamma, Criterion::MinAreaChange, Criterion::Boissonnat};
  o.criterion = criteria[((a >> 3) & 3) % 3];
  o.repair = (a & 0x20) == 0;
  if (a & 0x40) o.fallback_needle_ratio = (a & 0x80) ? 1e-3 : 0;  // every insertion a needle, or no limit
  o.refine_multi_start = (b & 0x40) == 0;
  if (b & 1) o.refine_work_per_point = b >> 1;  // small refinement budgets, 0 included
  if (b & 0x80) o.gamma0_schedule = {-0.5};
  return o;
}

void check_complete(const PointSet& p, const Polygon2Result& r) {
  require(r.boundary.size() == p.size(), "complete polygon misses points");
  require(r.valid(), "complete Ok result not valid()", r.check.reason);
  PolygonCheck c;
  const Status v = validate_polygon(p, r.boundary, &c);
  require(v.is_ok(), "validate_polygon refuses the result", v.message());
  const Status vb = validate_polygon_brute_force(p, r.boundary);
  require(vb.is_ok(), "brute-force validation refuses the result", vb.message());
}

void check_incomplete(const PointSet& p, const Polygon2Result& r) {
  std::vector<int> seen(p.size(), 0);
  for (int v : r.boundary) {
    require(v >= 0 && static_cast<std::size_t>(v) < p.size(), "boundary index out of range");
    require(++seen[static_cast<std::size_t>(v)] == 1, "boundary repeats a point");
  }
  for (int v : r.stuck_points) {
    require(v >= 0 && static_cast<std::size_t>(v) < p.size(), "stuck point out of range");
    require(++seen[static_cast<std::size_t>(v)] == 1, "stuck point also on the boundary or repeated");
  }
  require(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }),
          "boundary and stuck points do not cover the input");
}

// reconstruct_rings2() in auto mode (the inference on the engine's triangulation, the open-arc
// rule): Ok, and a ring set valid by the brute-force checker; one ring is reconstruct2()'s polygon.
void check_rings(const PointSet& p, const Constrict2Options& options) {
  Rings2Options o;
  o.topology = Topology2::Auto;
  o.polygon = options;
  Rings2Result rr;
  Status st;
  constrict_fuzz::no_throw("reconstruct_rings2", [&] { st = reconstruct_rings2(p, o, rr); });
  require(st.is_ok(), "reconstruct_rings2 refuses valid input", st.message());
  require(rr.valid(), "auto rings not valid()", rr.check.reason);
  RingsCheck c;
  const Status v = validate_rings2_brute_force(p, rr.rings, &c);
  require(v.is_ok(), "brute-force ring check refuses the rings", c.reason);
  if (rr.rings.size() == 1) require(rr.from_polygon, "one ring that is not reconstruct2()'s polygon");
}

// refine_polygon2 on the reversed (clockwise) polygon: Ok, CCW, still through every point.
void check_refine(const PointSet& p, const Polygon2Result& r, std::size_t work) {
  std::vector<int> poly(r.boundary.rbegin(), r.boundary.rend());
  const Status st = refine_polygon2(p, poly, nullptr, work);
  require(st.is_ok(), "refine_polygon2 refuses a valid clockwise polygon", st.message());
  const Status v = validate_polygon(p, poly);
  require(v.is_ok(), "refine_polygon2 result invalid", v.message());
}

// The γ0 fallback's witness bound is a tuning knob only: one neighbour read per end gives the
// same polygon as the default (the pairs it leaves are tested when they come out of the queue).
void check_witness_reads(const PointSet& p, const Constrict2Options& options, const Polygon2Result& r) {
  if (r.fallback_insertions == 0) return;
  Constrict2Options o = options;
  o.fallback_witness_reads = 1;
  Polygon2Result one;
  const Status st = reconstruct2(p, o, one);
  require(st.is_ok(), "reconstruct2 with fallback_witness_reads = 1 failed", st.message());
  require(one.boundary == r.boundary, "fallback_witness_reads changed the polygon");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One thread: one fuzzer uses one core, and a finding reproduces without scheduling effects.
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  constrict_fuzz::Bytes in(data, size);
  const Constrict2Options options = decode_options(in);
  const constrict_fuzz::Decoded d = constrict_fuzz::decode_points(in, 2);
  constrict_fuzz::print_points(d);
  const PointSet& p = d.points;

  Status checked, st;
  Polygon2Result r;
  constrict_fuzz::no_throw("reconstruct2", [&] {
    checked = check_points(p);
    st = reconstruct2(p, options, r);
  });
  constrict_fuzz::require_one_line(st);
  if (!checked) {
    require(st.code() == checked.code(), "status differs from check_points()", st.message());
  } else {
    require(st.is_ok(), "valid input refused", st.message());
    const bool must_complete = options.fallback == Fallback::Auto ||
                               (options.fallback != Fallback::None && options.repair);
    require(r.complete || !must_complete, "incomplete although the fallbacks always complete");
    constrict_fuzz::no_throw("checks", [&] {
      if (r.complete) {
        check_complete(p, r);
        check_refine(p, r, options.refine_work_per_point);
        check_witness_reads(p, options, r);
      } else {
        check_incomplete(p, r);
      }
    });
    if (options.fallback == Fallback::Auto) check_rings(p, options);
  }
  if (d.has_non_finite && p.size() >= 3) {
    std::vector<int> all(p.size());
    std::iota(all.begin(), all.end(), 0);
    Status v;
    constrict_fuzz::no_throw("validate_polygon", [&] { v = validate_polygon(p, all); });
    require(!v.is_ok(), "validate_polygon accepts non-finite points");
  }
  return 0;
}
