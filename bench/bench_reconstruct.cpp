// SPDX-License-Identifier: GPL-3.0-or-later
// Whole 2D reconstruction (Delaunay, constriction, fallbacks, exact validation) next to CGAL's
// Delaunay_2 alone on the same points: points on a closed smooth curve (issue 3 speed goal:
// reconstruct2 <= 1.5x CGAL's Delaunay_2), plus a uniform cloud (many locks: fallback cost).
#include <benchmark/benchmark.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench_data.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/topology.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using namespace constrict;

PointSet make(std::size_t n, int kind) {
  return kind == 0 ? bench::curve_points2(n) : bench::points2(n, bench::Dist::Uniform);
}
const char* kind_name(int kind) { return kind == 0 ? "curve" : "uniform"; }

void BM_CgalDelaunay2Same(benchmark::State& state) {
  const auto pts = make(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
  std::vector<K::Point_2> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_2<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
  state.SetLabel(kind_name(static_cast<int>(state.range(1))));
}

void BM_Reconstruct2(benchmark::State& state) {
  const auto pts = make(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
  std::size_t stuck = 0;
  for (auto _ : state) {
    Polygon2Result r;
    if (!reconstruct2(pts, Constrict2Options{}, r) || !r.complete) state.SkipWithError("reconstruct2 failed");
    stuck = r.stuck_points.size();
    benchmark::DoNotOptimize(r.boundary.data());
    // Phases (the Delaunay time includes the input check and the export to index arrays).
    state.counters["ms_dt"] = r.ms_delaunay;
    state.counters["ms_constrict"] = r.ms_constrict;
    state.counters["ms_refine"] = r.ms_refine;
    state.counters["ms_validate"] = r.ms_validate;
  }
  state.counters["stuck"] = static_cast<double>(stuck);
  state.SetLabel(kind_name(static_cast<int>(state.range(1))));
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int kind : {0, 1})
    for (long n : {10000L, 100000L, 1000000L}) b->Args({n, kind});
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_CgalDelaunay2Same)->Apply(sizes);
BENCHMARK(BM_Reconstruct2)->Apply(sizes);

// 3D (issue 4 speed goal: reconstruct3 <= 2x CGAL's Delaunay_3 on 1e6 points of a closed
// surface): an ellipsoid sampled with tiny noise, the default pipeline (variants, flips,
// validation) against CGAL's Delaunay_3 built from the same points.
void BM_CgalDelaunay3Same(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), bench::Dist::Surface);
  std::vector<K::Point_3> v;
  for (std::size_t i = 0; i < pts.size(); ++i) v.emplace_back(pts[i][0], pts[i][1], pts[i][2]);
  for (auto _ : state) {
    CGAL::Delaunay_triangulation_3<K> dt(v.begin(), v.end());
    benchmark::DoNotOptimize(dt.number_of_cells());
  }
}

void BM_Reconstruct3(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), bench::Dist::Surface);
  for (auto _ : state) {
    Mesh3Result r;
    if (!reconstruct3(pts, Constrict3Options{}, r) || !r.complete) state.SkipWithError("reconstruct3 failed");
    benchmark::DoNotOptimize(r.mesh.triangles.data());
    // Which path ran (1: the growth reached every point, docs/reconstruction-3d.md §4.7) and its phases.
    state.counters["grown"] = r.method == Method3::Grow ? 1 : 0;
    state.counters["ms_dt_gamma"] = r.ms_delaunay;
    state.counters["ms_setup"] = r.ms_setup;
    state.counters["ms_grow"] = r.ms_grow;
    state.counters["ms_fill"] = r.ms_fill;
    state.counters["filled"] = static_cast<double>(r.filled);
  }
}

void sizes3(benchmark::internal::Benchmark* b) {
  for (long n : {10000L, 100000L, 1000000L}) b->Args({n});
  b->Unit(benchmark::kMillisecond)->Iterations(1);
}

// The auto topology (issue 16: within 1.3x of the single mode on the same input): on one closed
// surface it decides one part and shares the tetrahedralization with the engine.
void BM_Surfaces3Auto(benchmark::State& state) {
  const auto pts = bench::points3(static_cast<std::size_t>(state.range(0)), bench::Dist::Surface);
  Surfaces3Options o;
  o.topology = Topology3::Auto;
  for (auto _ : state) {
    Surfaces3Result r;
    if (!reconstruct_surfaces3(pts, o, r) || !r.valid()) state.SkipWithError("reconstruct_surfaces3 failed");
    benchmark::DoNotOptimize(r.mesh.mesh.triangles.data());
    state.counters["surfaces"] = static_cast<double>(r.surfaces.size());
    state.counters["ms_infer"] = r.ms_infer;
    state.counters["ms_validate"] = r.ms_validate;
  }
}

BENCHMARK(BM_CgalDelaunay3Same)->Apply(sizes3);
BENCHMARK(BM_Reconstruct3)->Apply(sizes3);
BENCHMARK(BM_Surfaces3Auto)->Apply(sizes3);

// A volume: points of a thick noisy shell (radius 1 to 1.2, uniform in it), 10^5 and 3*10^5. The
// growth's pushes often outrank its last pop here (366 967 times at 3*10^5), the case that made a
// forward scan over the rank queue's bits rescan 648 million words (2026-12-06; the queue is a
// tree of words since: core/detail/rank_queue.hpp). ms_grow is the growth stage.
void BM_Reconstruct3ThickShell(benchmark::State& state) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  PointSet pts;
  pts.dim = 3;
  for (long i = 0; i < state.range(0); ++i) {
    const double x = g(rng), y = g(rng), z = g(rng), r = std::sqrt(x * x + y * y + z * z), s = (1 + 0.2 * u(rng)) / r;
    pts.coords.insert(pts.coords.end(), {x * s, y * s, z * s});
  }
  for (auto _ : state) {
    Mesh3Result r;
    if (!reconstruct3(pts, Constrict3Options{}, r) || !r.complete) state.SkipWithError("reconstruct3 failed");
    state.counters["ms_grow"] = r.ms_grow;
    state.counters["grown_outside"] = static_cast<double>(r.grown_outside);
  }
}
BENCHMARK(BM_Reconstruct3ThickShell)->Arg(100000)->Arg(300000)->Unit(benchmark::kMillisecond)->Iterations(1);

// Hostile 3D inputs whose Delaunay tetrahedra meet by the thousand at some points (found by
// sweeps of 2026-12-04; docs/reconstruction-3d.md §4.10): the passes stop at their work bounds.
// Before the bounds: thin rod 2 000 points 10 s, circle and axis (auto) more than 10 minutes,
// circle and axis point 77 s (auto). Kinds: 0 thin rod, 1 circle and its axis (800 + 800),
// 2 circle and one point on its axis (4 000), 3 10^5 points on a line and two off it (one edge in
// every tetrahedron: the refinement's edge walks, 67 s before kMaxFlipRing, 2026-12-05);
// range(1): 0 single, 1 auto.
PointSet hostile3(int kind) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  std::normal_distribution<double> g(0, kind == 2 ? 1e-6 : 1e-4);
  PointSet p;
  p.dim = 3;
  const auto add = [&](double x, double y, double z) { p.coords.insert(p.coords.end(), {x, y, z}); };
  if (kind == 0)
    for (int i = 0; i < 2000; ++i) add(i / 1999.0, u(rng), u(rng));
  if (kind == 1)
    for (int i = 0; i < 1600; ++i) {
      const double t = 2 * M_PI * (i % 800) / 800 + 0.1234;
      if (i < 800) add(std::cos(t) + g(rng), std::sin(t) + g(rng), g(rng));
      else add(g(rng), g(rng), -1 + 2.0 * (i - 800) / 799 + g(rng));
    }
  if (kind == 2) {
    for (int i = 0; i < 3999; ++i) {
      const double t = 2 * M_PI * i / 3999;
      add(std::cos(t) + g(rng), std::sin(t) + g(rng), g(rng));
    }
    add(g(rng), g(rng), 0.7 + g(rng));
  }
  if (kind == 3) {
    for (int i = 0; i < 100000; ++i) add(i, 0, 0);
    add(0, 1, 0);
    add(0, 0, 1);
  }
  return p;
}

void BM_Hostile3(benchmark::State& state) {
  const PointSet pts = hostile3(static_cast<int>(state.range(0)));
  Surfaces3Options o;
  o.topology = state.range(1) ? Topology3::Auto : Topology3::Single;
  for (auto _ : state) {
    Surfaces3Result r;
    if (!reconstruct_surfaces3(pts, o, r) || !r.valid()) state.SkipWithError("reconstruct_surfaces3 failed");
    state.counters["cavity_capped"] = r.mesh.cavity_capped;
    state.counters["carve_capped"] = r.mesh.carve_capped;
    state.counters["repair_capped"] = r.repair_capped;
  }
  static const char* const names[] = {"thin rod", "circle and axis", "circle and axis point", "line and two points"};
  state.SetLabel(std::string(names[state.range(0)]) + (state.range(1) ? ", auto" : ", single"));
}
BENCHMARK(BM_Hostile3)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond)->Iterations(1);

// A 2D fan: 2·10^5 points on a line and one off it, whose Delaunay neighbours are all the others
// (the refinement's neighbour lists: insertion-sorted, quadratic, 11 s until 2026-12-05).
void BM_Hostile2Fan(benchmark::State& state) {
  PointSet p;
  p.dim = 2;
  for (int i = 0; i < 200000; ++i) p.coords.insert(p.coords.end(), {double(i), 0.0});
  p.coords.insert(p.coords.end(), {100000.0, 7.0});
  for (auto _ : state) {
    Polygon2Result r;
    if (!reconstruct2(p, Constrict2Options{}, r) || !r.valid()) state.SkipWithError("reconstruct2 failed");
    state.counters["ms_refine"] = r.ms_refine;
  }
}
BENCHMARK(BM_Hostile2Fan)->Unit(benchmark::kMillisecond)->Iterations(1);
}  // namespace
