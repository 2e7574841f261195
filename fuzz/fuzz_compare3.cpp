// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: compare_meshes3() on a small decoded mesh against a fixed unit octahedron, both
// ways, and against itself (docs/fuzzing.md). Layout: [triangle count][triangle index bytes][the
// engine targets' point layout (fuzz_engine.hpp): mode, count, parameters, points]. The decoder's
// huge, tiny, subnormal and mixed magnitudes give meshes far larger, smaller or farther off than
// the other, the cases that hung or were refused wrongly (hostile-input sweep, 2026-12-07).
// Contract (compare.hpp): Ok with finite, non-negative distances, at most the sample budget per
// side (plus the fewest samples per triangle), identical for a mesh against itself; or
// InvalidArgument / NonFinite with a one-line message. A timeout is a finding too.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "constrict/compare.hpp"
#include "fuzz_engine.hpp"

namespace {

using namespace constrict;
using constrict_fuzz::require;

void check(const Status& st, const MeshDistance& d, const DistanceOptions& o, std::size_t triangles_a,
           std::size_t triangles_b) {
  if (!st) {
    require(st.code() == StatusCode::InvalidArgument || st.code() == StatusCode::NonFinite,
            "undocumented status code", st.message());
    constrict_fuzz::require_one_line(st);
    return;
  }
  for (double v : {d.hausdorff, d.hausdorff_result_to_reference, d.hausdorff_reference_to_result, d.mean,
                   d.mean_result_to_reference, d.mean_reference_to_result, d.bbox_diagonal})
    require(std::isfinite(v) && v >= 0, "a distance is not finite and non-negative");
  require(d.hausdorff == std::max(d.hausdorff_result_to_reference, d.hausdorff_reference_to_result),
          "hausdorff is not the larger one-sided value");
  // Every triangle has at least its three corners as samples, whatever the budget.
  require(d.samples_result <= std::max<std::size_t>(o.max_samples, 3 * triangles_a), "result samples over the budget");
  require(d.samples_reference <= std::max<std::size_t>(o.max_samples, 3 * triangles_b),
          "reference samples over the budget");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  constrict_fuzz::Bytes in(data, size);
  const std::size_t nt = 1 + in.u8() % 24;
  std::vector<std::array<std::uint8_t, 3>> raw(nt);
  for (auto& t : raw)
    for (auto& v : t) v = in.u8();
  const constrict_fuzz::Decoded dec = constrict_fuzz::decode_points(in, 3);
  constrict_fuzz::print_points(dec);
  const PointSet& p = dec.points;
  if (p.size() < 3) return 0;
  TriMesh3 m;
  for (const auto& t : raw)
    m.triangles.push_back({{static_cast<int>(t[0] % p.size()), static_cast<int>(t[1] % p.size()),
                            static_cast<int>(t[2] % p.size())}});
  PointSet octa;
  octa.dim = 3;
  octa.coords = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  TriMesh3 om;
  om.triangles = {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}}, {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}};
  DistanceOptions o;
  o.max_samples = 1000;  // (many executions per second; the spacing coarsens to fit)
  MeshDistance d;
  Status st;
  constrict_fuzz::no_throw("compare_meshes3", [&] { st = compare_meshes3(p, m, octa, om, d, o); });
  check(st, d, o, m.triangles.size(), om.triangles.size());
  constrict_fuzz::no_throw("compare_meshes3", [&] { st = compare_meshes3(octa, om, p, m, d, o); });
  check(st, d, o, om.triangles.size(), m.triangles.size());
  constrict_fuzz::no_throw("compare_meshes3", [&] { st = compare_meshes3(p, m, p, m, d, o); });
  check(st, d, o, m.triangles.size(), m.triangles.size());
  if (st) {
    require(d.identical, "a mesh against itself is not identical");
    require(d.hausdorff == 0 && d.mean == 0, "a mesh against itself has a distance");
  }
  return 0;
}
