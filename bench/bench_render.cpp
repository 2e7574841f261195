// SPDX-License-Identifier: GPL-3.0-or-later
// Rendering speed of render_mesh3(): a latitude-longitude sphere of about 1e5 and 1e6 triangles
// at 2048×2048 (flat shading; with and without wireframe), and compare_meshes3() of a sphere with
// a slightly rotated copy at default sampling. Results: docs/rendering.md, docs/evaluation.md.
// Link with benchmark::benchmark_main (this file has no main()).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>

#include "constrict/compare.hpp"
#include "constrict/render.hpp"

namespace {

// seg × rings sphere: 2 poles + rings·seg vertices, 2·seg·rings triangles (outward).
void sphere(int seg, int rings, double twist, constrict::PointSet& p, constrict::TriMesh3& m) {
  p = {};
  p.dim = 3;
  m = {};
  p.coords.insert(p.coords.end(), {0, 0, 1});
  for (int r = 1; r <= rings; ++r) {
    const double th = M_PI * r / (rings + 1);
    for (int s = 0; s < seg; ++s) {
      const double ph = 2 * M_PI * s / seg + twist;
      p.coords.insert(p.coords.end(), {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  }
  p.coords.insert(p.coords.end(), {0, 0, -1});
  const int south = 1 + rings * seg;
  const auto v = [seg](int r, int s) { return 1 + (r - 1) * seg + (s % seg); };
  for (int s = 0; s < seg; ++s) {
    m.triangles.push_back({{0, v(1, s), v(1, s + 1)}});
    m.triangles.push_back({{south, v(rings, s + 1), v(rings, s)}});
    for (int r = 1; r < rings; ++r) {
      m.triangles.push_back({{v(r, s), v(r + 1, s), v(r + 1, s + 1)}});
      m.triangles.push_back({{v(r, s), v(r + 1, s + 1), v(r, s + 1)}});
    }
  }
}

void BM_RenderSphere(benchmark::State& state) {
  const int seg = static_cast<int>(state.range(0)), rings = seg / 2;
  constrict::PointSet p;
  constrict::TriMesh3 m;
  sphere(seg, rings, 0, p, m);
  constrict::RenderOptions3 o;
  o.width = o.height = 2048;
  o.wireframe = state.range(1) != 0;
  constrict::Image img;
  for (auto _ : state) {
    if (!constrict::render_mesh3(p, m, {}, o, img)) state.SkipWithError("render failed");
    benchmark::DoNotOptimize(img.rgb.data());
  }
  state.counters["triangles"] = static_cast<double>(m.n_faces());
}
// seg² triangles: 316 -> 99856, 1000 -> 1000000
BENCHMARK(BM_RenderSphere)->Args({316, 0})->Args({316, 1})->Args({1000, 0})->Args({1000, 1})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompareSpheres(benchmark::State& state) {
  const int seg = static_cast<int>(state.range(0)), rings = seg / 2;
  constrict::PointSet p, q;
  constrict::TriMesh3 m, n;
  sphere(seg, rings, 0, p, m);
  sphere(seg, rings, 0.5 * 2 * M_PI / seg, q, n);  // half a step around the axis
  constrict::MeshDistance d;
  for (auto _ : state) {
    if (!constrict::compare_meshes3(q, n, p, m, d)) state.SkipWithError("compare failed");
    benchmark::DoNotOptimize(d.hausdorff);
  }
  state.counters["triangles"] = static_cast<double>(m.n_faces());
  state.counters["rel_hausdorff"] = d.relative_hausdorff;
}
BENCHMARK(BM_CompareSpheres)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
