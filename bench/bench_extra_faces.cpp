// SPDX-License-Identifier: GPL-3.0-or-later
// detail::lens_faces: non-Delaunay members of γ-graphs with a negative threshold m.
// Fixed seeds; the Delaunay faces are computed outside the timed loop.
// Counters: faces = output size, tested = faces sent to the exact lens test.
// (main() comes from benchmark::benchmark_main, see bench/CMakeLists.txt.)
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "constrict/gamma_graph.hpp"
#include "constrict/points.hpp"
#include "gamma/detail/extra_faces.hpp"

namespace {

using namespace constrict;

PointSet uniform2(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  PointSet ps;
  ps.dim = 2;
  for (int i = 0; i < 2 * n; ++i) ps.coords.push_back(uni(rng));
  return ps;
}

// Open wavy curve with noise 1e-3 (a closed convex curve has Θ(N^2) lens edges).
PointSet curve2(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PointSet ps;
  ps.dim = 2;
  for (int i = 0; i < n; ++i) {
    const double t = 20.0 * uni(rng);
    ps.coords.push_back(t);
    ps.coords.push_back(0.3 * std::sin(t) + 0.1 * std::sin(3.1 * t) + 1e-3 * gauss(rng));
  }
  return ps;
}

PointSet uniform3(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  PointSet ps;
  ps.dim = 3;
  for (int i = 0; i < 3 * n; ++i) ps.coords.push_back(uni(rng));
  return ps;
}

PointSet sphere3(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PointSet ps;
  ps.dim = 3;
  for (int i = 0; i < n; ++i) {
    double p[3], l = 0;
    for (double& x : p) {
      x = gauss(rng);
      l += x * x;
    }
    l = std::sqrt(l);
    for (double x : p) ps.coords.push_back(x / l);
  }
  return ps;
}

void run(benchmark::State& state, const PointSet& ps, double m) {
  GammaFaces del;
  if (ps.dim == 2) {
    DelaunayGamma2 dg;
    if (!delaunay_gamma2(ps, dg)) {
      state.SkipWithError("delaunay failed");
      return;
    }
    del = std::move(dg.faces);
  } else {
    DelaunayGamma3 dg;
    if (!delaunay_gamma3(ps, dg)) {
      state.SkipWithError("delaunay failed");
      return;
    }
    del = std::move(dg.faces);
  }
  std::size_t faces = 0, tested = 0;
  for (auto _ : state) {
    GammaFaces out;
    out.dim = ps.dim;
    const Status s = detail::lens_faces(ps, m, del, out, &tested);
    if (!s) {
      state.SkipWithError(s.message().c_str());
      return;
    }
    faces = out.size();
    benchmark::DoNotOptimize(out.gamma_a.data());
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["tested"] = static_cast<double>(tested);
  state.counters["delaunay"] = static_cast<double>(del.size());
}

// m is passed in thousandths.
void BM_Uniform2(benchmark::State& state) {
  run(state, uniform2(static_cast<int>(state.range(0)), 1), -static_cast<double>(state.range(1)) / 1000);
}
void BM_Curve2(benchmark::State& state) {
  run(state, curve2(static_cast<int>(state.range(0)), 2), -static_cast<double>(state.range(1)) / 1000);
}
void BM_Uniform3(benchmark::State& state) {
  run(state, uniform3(static_cast<int>(state.range(0)), 3), -static_cast<double>(state.range(1)) / 1000);
}
void BM_Sphere3(benchmark::State& state) {
  run(state, sphere3(static_cast<int>(state.range(0)), 4), -static_cast<double>(state.range(1)) / 1000);
}

BENCHMARK(BM_Uniform2)->ArgsProduct({{10000, 100000}, {50, 200}})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Curve2)->ArgsProduct({{10000, 100000}, {50, 200}})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Uniform3)->ArgsProduct({{1000, 3000, 10000}, {50}})->Unit(benchmark::kMillisecond)->Iterations(1);
// Points on a sphere: every triangle whose circumcircle is within distance ~0.31 of the centre is
// a member at m = -0.05 (Θ(N^3) output), so this is expected to report the Unsupported status
// for large N; 100 points show the growth.
BENCHMARK(BM_Sphere3)->ArgsProduct({{100, 10000}, {50}})->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
