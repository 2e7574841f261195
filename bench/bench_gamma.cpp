// SPDX-License-Identifier: GPL-3.0-or-later
// Delaunay + all γ-values (the library's delaunay_gamma2/3) next to CGAL's Delaunay alone on the
// same points (CGAL's own range insertion with its spatial sort). Goal (issue 2): the γ-values
// add at most 25% on top of the Delaunay time. Results: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "bench_data.hpp"
#include "constrict/gamma_graph.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using namespace constrict;
using constrict::bench::Dist;

void BM_CgalDelaunay2(benchmark::State& state) {
  const auto pts = bench::points2(static_cast<std::size_t>(state.range(0)), static_cast<Dist>(state.range(1)));
  std::vector<K::Point_2> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_2<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
  state.SetLabel(bench::dist_name(static_cast<Dist>(state.range(1))));
}

void BM_DelaunayGamma2(benchmark::State& state) {
  const auto pts = bench::points2(static_cast<std::size_t>(state.range(0)), static_cast<Dist>(state.range(1)));
  for (auto _ : state) {
    DelaunayGamma2 dg;
    if (!delaunay_gamma2(pts, dg)) state.SkipWithError("delaunay_gamma2 failed");
    benchmark::DoNotOptimize(dg.faces.size());
  }
  state.SetLabel(bench::dist_name(static_cast<Dist>(state.range(1))));
}

void BM_CgalDelaunay3(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), static_cast<Dist>(state.range(1)));
  std::vector<K::Point_3> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1], pts[i][2]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_3<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_cells());
  }
  state.SetLabel(bench::dist_name(static_cast<Dist>(state.range(1))));
}

void BM_DelaunayGamma3(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), static_cast<Dist>(state.range(1)));
  for (auto _ : state) {
    DelaunayGamma3 dg;
    if (!delaunay_gamma3(pts, dg)) state.SkipWithError("delaunay_gamma3 failed");
    benchmark::DoNotOptimize(dg.faces.size());
  }
  state.SetLabel(bench::dist_name(static_cast<Dist>(state.range(1))));
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int d : {0, 1})
    for (long n : {10'000L, 100'000L, 1'000'000L}) b->Args({n, d});
  b->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
}

BENCHMARK(BM_CgalDelaunay2)->Apply(sizes);
BENCHMARK(BM_DelaunayGamma2)->Apply(sizes);
BENCHMARK(BM_CgalDelaunay3)->Apply(sizes);
BENCHMARK(BM_DelaunayGamma3)->Apply(sizes);
}  // namespace
