// SPDX-License-Identifier: GPL-3.0-or-later
// Constriction time per selection criterion, Delaunay excluded (seed paper §6: "the γ criterion
// is about 17 % faster because its key is cheaper"). Manual time = the constriction stage only
// (Polygon2Result::ms_constrict / Mesh3Result::ms_constrict: heap, removability, keys; not the
// fallbacks), on points of a closed curve / an ellipsoid surface. 3D runs the paper's options
// (no Refine3 post-pass) so that only the constriction is compared. Also the shortest Voronoi
// skeleton growth (all seeds, 2D) at small sizes for the "orders of magnitude slower" check.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "bench_data.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace {
using namespace constrict;

const Criterion kCriteria[] = {Criterion::Gamma, Criterion::MinAreaChange, Criterion::Boissonnat};

// Manual time = the constriction stage only; removals and the time per removal as counters.
void record_constriction(benchmark::State& state, double ms_constrict, std::size_t removals) {
  state.SetIterationTime(ms_constrict / 1000.0);
  state.counters["removals"] = static_cast<double>(removals);
  state.counters["ns_per_removal"] = 1e6 * ms_constrict / static_cast<double>(std::max<std::size_t>(1, removals));
}

void BM_Constrict2Criterion(benchmark::State& state) {
  const auto pts = bench::curve_points2(static_cast<std::size_t>(state.range(0)));
  Constrict2Options o;
  o.criterion = kCriteria[state.range(1)];
  o.validate = false;
  for (auto _ : state) {
    Polygon2Result r;
    if (!reconstruct2(pts, o, r) || !r.complete) state.SkipWithError("reconstruct2 failed");
    record_constriction(state, r.ms_constrict, r.removed_simplices);
  }
  state.SetLabel(criterion_name(o.criterion));
}

void BM_Constrict3Criterion(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), bench::Dist::Surface);
  Constrict3Options o = Constrict3Options::paper();
  o.criterion = kCriteria[state.range(1)];
  o.validate = false;
  for (auto _ : state) {
    Mesh3Result r;
    if (!reconstruct3(pts, o, r) || !r.complete) state.SkipWithError("reconstruct3 failed");
    record_constriction(state, r.ms_constrict, r.removed_one_face + r.removed_two_face);
  }
  state.SetLabel(criterion_name(o.criterion));
}

void BM_VoronoiSkeleton2(benchmark::State& state) {
  const auto pts = bench::points2(static_cast<std::size_t>(state.range(0)), bench::Dist::Surface);
  VoronoiSkeletonOptions o;
  o.validate = false;
  for (auto _ : state) {
    VoronoiSkeleton2Result r;
    if (!voronoi_skeleton2(pts, o, r)) state.SkipWithError("voronoi_skeleton2 failed");
    state.SetIterationTime(r.stats.ms_grow / 1000.0);
    state.counters["complete"] = r.complete;
    state.counters["pruned"] = static_cast<double>(r.stats.seeds_pruned);
  }
}

void criteria_sizes2(benchmark::internal::Benchmark* b) {
  for (long n : {100000L, 1000000L})
    for (long c : {0L, 1L, 2L}) b->Args({n, c});
  b->Unit(benchmark::kMillisecond)->UseManualTime();
}
void criteria_sizes3(benchmark::internal::Benchmark* b) {
  for (long n : {100000L})
    for (long c : {0L, 1L, 2L}) b->Args({n, c});
  b->Unit(benchmark::kMillisecond)->UseManualTime();
}

BENCHMARK(BM_Constrict2Criterion)->Apply(criteria_sizes2);
BENCHMARK(BM_Constrict3Criterion)->Apply(criteria_sizes3);
BENCHMARK(BM_VoronoiSkeleton2)->Arg(1000)->Arg(4000)->Unit(benchmark::kMillisecond)->UseManualTime();
}  // namespace
