// SPDX-License-Identifier: GPL-3.0-or-later
// Delaunay + all γ-values (the library's delaunay_gamma2/3) next to CGAL's Delaunay alone on the
// same points. Goal (issue 2): the γ-values add at most 25% on top of the Delaunay time.
// Results and what is compared: docs/benchmarks.md.
//   BM_CgalDelaunay*      CGAL Delaunay_triangulation_2/3<Epick> (default TDS), range insertion
//                         of the points (its spatial sort). The headline reference.
//   BM_CgalDelaunayInfo*  the triangulation type the wrapper builds (int info in vertices and
//                         faces/cells), range insertion of (point, index) pairs: CGAL's cost of
//                         keeping the ids.
//   BM_BuildDelaunay*     build_delaunay2/3: the wrapper, exported to index arrays.
//   BM_DelaunayGamma*     delaunay_gamma2/3; last argument = threads (1 = sequential).
#include <benchmark/benchmark.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/global_control.h>

#include <utility>
#include <vector>

#include "bench_data.hpp"
#include "constrict/gamma_graph.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using namespace constrict;
using constrict::bench::Dist;

using Tds2Info = CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_with_info_2<int, K>,
                                                      CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds3Info = CGAL::Triangulation_data_structure_3<
    CGAL::Triangulation_vertex_base_with_info_3<int, K>,
    CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>>;

Dist dist_of(const benchmark::State& state) { return static_cast<Dist>(state.range(1)); }
std::size_t n_of(const benchmark::State& state) { return static_cast<std::size_t>(state.range(0)); }

void BM_CgalDelaunay2(benchmark::State& state) {
  const auto pts = bench::points2(n_of(state), dist_of(state));
  std::vector<K::Point_2> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_2<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_CgalDelaunayInfo2(benchmark::State& state) {
  const auto pts = bench::points2(n_of(state), dist_of(state));
  std::vector<std::pair<K::Point_2, int>> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(K::Point_2(pts[i][0], pts[i][1]), static_cast<int>(i));
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_2<K, Tds2Info> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_BuildDelaunay2(benchmark::State& state) {
  const auto pts = bench::points2(n_of(state), dist_of(state));
  for (auto _ : state) {
    Delaunay2 dt;
    if (!build_delaunay2(pts, dt)) state.SkipWithError("build_delaunay2 failed");
    benchmark::DoNotOptimize(dt.triangles.size());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_DelaunayGamma2(benchmark::State& state) {
  const auto pts = bench::points2(n_of(state), dist_of(state));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(2)));
  for (auto _ : state) {
    DelaunayGamma2 dg;
    if (!delaunay_gamma2(pts, dg)) state.SkipWithError("delaunay_gamma2 failed");
    benchmark::DoNotOptimize(dg.faces.size());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_CgalDelaunay3(benchmark::State& state) {
  const auto pts = bench::points3(n_of(state), dist_of(state));
  std::vector<K::Point_3> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1], pts[i][2]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_3<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_cells());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_CgalDelaunayInfo3(benchmark::State& state) {
  const auto pts = bench::points3(n_of(state), dist_of(state));
  std::vector<std::pair<K::Point_3, int>> v;
  for (std::size_t i = 0; i < pts.size(); ++i)
    v.emplace_back(K::Point_3(pts[i][0], pts[i][1], pts[i][2]), static_cast<int>(i));
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_3<K, Tds3Info> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_cells());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_BuildDelaunay3(benchmark::State& state) {
  const auto pts = bench::points3(n_of(state), dist_of(state));
  for (auto _ : state) {
    Delaunay3 dt;
    if (!build_delaunay3(pts, dt)) state.SkipWithError("build_delaunay3 failed");
    benchmark::DoNotOptimize(dt.tets.size());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void BM_DelaunayGamma3(benchmark::State& state) {
  const auto pts = bench::points3(n_of(state), dist_of(state));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(2)));
  for (auto _ : state) {
    DelaunayGamma3 dg;
    if (!delaunay_gamma3(pts, dg)) state.SkipWithError("delaunay_gamma3 failed");
    benchmark::DoNotOptimize(dg.faces.size());
  }
  state.SetLabel(bench::dist_name(dist_of(state)));
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int d : {0, 1})
    for (long n : {10'000L, 100'000L, 1'000'000L}) b->Args({n, d});
  b->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
}
void sizes_threads(benchmark::internal::Benchmark* b) {
  for (int d : {0, 1})
    for (long n : {10'000L, 100'000L, 1'000'000L})
      for (int t : {1, 2}) b->Args({n, d, t});
  b->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.5);
}

BENCHMARK(BM_CgalDelaunay2)->Apply(sizes);
BENCHMARK(BM_CgalDelaunayInfo2)->Apply(sizes);
BENCHMARK(BM_BuildDelaunay2)->Apply(sizes);
BENCHMARK(BM_DelaunayGamma2)->Apply(sizes_threads);
BENCHMARK(BM_CgalDelaunay3)->Apply(sizes);
BENCHMARK(BM_CgalDelaunayInfo3)->Apply(sizes);
BENCHMARK(BM_BuildDelaunay3)->Apply(sizes);
BENCHMARK(BM_DelaunayGamma3)->Apply(sizes_threads);
}  // namespace
