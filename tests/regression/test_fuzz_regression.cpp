// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs found by the engine fuzz targets (fuzz/fuzz_reconstruct2.cpp, fuzz_reconstruct3.cpp,
// fuzz_surfaces3.cpp, fuzz_gamma_graph.cpp; docs/fuzzing.md "Findings so far"), each with its expected outcome.
// Files: tests/data/regression/, named for the defect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"
#include "constrict/validate.hpp"

namespace constrict {
namespace {

PointSet load(const std::string& name) {
  PointSet p;
  ReadOptions ro;
  const Status st = read_points(std::string(CONSTRICT_TEST_DATA_DIR) + "/regression/" + name, ro, p);
  EXPECT_TRUE(st.is_ok()) << st.message();
  return p;
}

bool has_face(const GammaFaces& g, const std::vector<int>& ids, std::size_t* at = nullptr) {
  for (std::size_t f = 0; f < g.size(); ++f) {
    bool same = true;
    for (int j = 0; j < g.dim; ++j) same = same && g.vertex(f, j) == ids[static_cast<std::size_t>(j)];
    if (same) {
      if (at) *at = f;
      return true;
    }
  }
  return false;
}

// A sliver a few ulps from collinear (fuzz_gamma_graph, first run). Exact rational arithmetic
// gives face (0,2,5) the side values -1 + 5e-13 (points 3, 4) and 1 - 5e-13 (point 1), so it is a
// member of γ(g0, g1) only for g0 <= -1 + 5e-13; face (0,1,2) has -0.8456 and 0.6653. The double
// magnitudes of TriangleFrame3 lost every digit on such slivers (e1 x e2 cancels): -0.099 / +0.042
// and -6e-27 / 7e-30, so γ(-0.5,-0.5) held (0,2,5) (`constrict graph --gamma=-0.5,-0.5`). Slivers
// are now evaluated exactly (cgal/detail/exact_apex3.hpp); the signs were always exact.
TEST(FuzzRegressionGraph, SliverNearCollinearMagnitudesExact) {
  const PointSet p = load("gamma3_sliver_near_collinear_oracle_inexact.xyz");
  ASSERT_EQ(p.dim, 3);
  ASSERT_EQ(p.size(), 6u);
  for (double g : {-0.05, -0.5, -0.999}) {
    GammaFaces graph;
    ASSERT_TRUE(build_gamma_graph(p, GraphSpec::fixed(g, g), graph).is_ok());
    EXPECT_FALSE(has_face(graph, {0, 2, 5})) << g;
  }
  GammaFaces all;
  ASSERT_TRUE(build_gamma_graph(p, GraphSpec::fixed(-1, -1), all).is_ok());
  std::size_t f = 0;
  ASSERT_TRUE(has_face(all, {0, 2, 5}, &f));
  EXPECT_LT(std::min(all.gamma_a[f], all.gamma_b[f]), -0.999999);
  EXPECT_GT(std::max(all.gamma_a[f], all.gamma_b[f]), 0.999999);
  ASSERT_TRUE(has_face(all, {0, 1, 2}, &f));
  EXPECT_NEAR(std::min(all.gamma_a[f], all.gamma_b[f]), -0.845607450744, 1e-9);
  EXPECT_NEAR(std::max(all.gamma_a[f], all.gamma_b[f]), 0.665327520881, 1e-9);
  // The oracle (side_values_scan, same apex values) agrees.
  double ga = 0, gb = 0;
  bool blocked = false;
  const int ids[3] = {0, 1, 2};
  side_values_scan(p, ids, ga, gb, blocked);
  EXPECT_NEAR(std::min(ga, gb), -0.845607450744, 1e-9);
}

// A threshold near -1 makes nearly every pair an edge, each with its ball queries: 20 000 uniform
// points at -0.95 ran for more than 15 minutes (an adversarial sweep of the command line). The
// point tests of the queries and the pairs visited now count toward the lens search's budget:
// refused with its message after a few seconds, whatever the input's size; -0.5 still runs.
TEST(FuzzRegressionGraph, ThresholdNearMinusOneIsRefusedNotEndless) {
  PointSet p;
  p.dim = 2;
  std::uint64_t s = 12345;  // (a fixed LCG: the same points everywhere)
  const auto next = [&s] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < 2 * 3000; ++i) p.coords.push_back(next());
  GammaFaces graph;
  const Status st = build_gamma_graph(p, GraphSpec::fixed(-0.99, -0.99), graph);
  EXPECT_EQ(st.code(), StatusCode::Unsupported) << st.message();
  EXPECT_NE(st.message().find("threshold closer to 0"), std::string::npos) << st.message();
  GammaFaces half;
  ASSERT_TRUE(build_gamma_graph(p, GraphSpec::fixed(-0.5, -0.5), half).is_ok());
}

// Points of magnitude 1e300 (fuzz_surfaces3, first run): the auto topology shares its
// tetrahedralization with the engine, but the engine works on a power-of-two rescaled copy, and
// CGAL's spatial sort of that copy inserted in another order: when the growth failed, the γ pass
// (built on the copy) no longer matched the shared tetrahedra and the engine threw ("the γ pass did
// not reproduce the tetrahedralization"). The engine now uses a shared tetrahedralization only
// without rescaling.
TEST(FuzzRegressionSurfaces, SharedTetrahedralizationNotUsedAfterRescaling) {
  const PointSet p = load("surfaces3_shared_dt_rescaled_1e300.xyz");
  ASSERT_EQ(p.size(), 12u);
  for (bool handles : {false, true}) {
    Surfaces3Options o;
    o.topology = Topology3::Auto;
    o.handles = handles;
    Surfaces3Result r;
    const Status st = reconstruct_surfaces3(p, o, r);
    ASSERT_TRUE(st.is_ok()) << st.message();
    EXPECT_TRUE(r.valid()) << r.check;
    EXPECT_TRUE(validate_surfaces3(p, r.mesh.mesh, r.mesh.tets, true).is_ok());
  }
}

// 16 points spanning 1e-38 ... 9e20 (fuzz_reconstruct2, the first 30 s after the refinement got
// its sparse edge grid). The median polygon edge was far below the area-sized cell, so the grid
// went sparse with cells near the 2^-28 floor, and a move's long new edge was looked up along its
// strip: 2^28 rows (a hang). A query that would cross more cells than are stored now reads the
// stored cells (SparseSegments::cells). The polygon is the one of the dense grid.
TEST(FuzzRegression2, RefineSparseGridLongQuery) {
  const PointSet p = load("refine2_sparse_long_query_mixed_magnitudes.xy");
  ASSERT_EQ(p.size(), 16u);
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, {}, r).is_ok());
  ASSERT_TRUE(r.complete);
  EXPECT_TRUE(validate_polygon(p, r.boundary).is_ok());
  EXPECT_LE(r.perimeter, r.perimeter_before_refine);
}

}  // namespace
}  // namespace constrict
