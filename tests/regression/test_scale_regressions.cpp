// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 20: inputs of extreme magnitude. Each must give the result of the same points scaled to 1
// (the engines work on an exact power-of-two rescaling, so the combinatorics and the amount of
// work are those of the unit-scale run), validated on the input's own coordinates, or a one-line
// error. Files: tests/data/regression/, named for the defect.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/mesh.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/points.hpp"
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

PointSet scaled_to_one(const PointSet& in) {
  PointSet out = in;
  const int e = max_coordinate_exponent(in);
  for (double& c : out.coords) c = std::ldexp(c, -e);
  return out;
}

void expect_same_as_unit_scale(const std::string& file, Fallback fb) {
  const PointSet tiny = load(file);
  const PointSet unit = scaled_to_one(tiny);
  Constrict2Options opt;
  opt.fallback = fb;
  Polygon2Result rt, ru;
  ASSERT_TRUE(reconstruct2(tiny, opt, rt).is_ok());
  ASSERT_TRUE(reconstruct2(unit, opt, ru).is_ok());
  EXPECT_TRUE(rt.complete);
  EXPECT_EQ(rt.boundary, ru.boundary);
  EXPECT_EQ(rt.method, ru.method);
  // Same stages with the same counts: the same work as at scale 1.
  ASSERT_EQ(rt.stages.size(), ru.stages.size());
  for (std::size_t s = 0; s < rt.stages.size(); ++s) {
    EXPECT_EQ(rt.stages[s].name, ru.stages[s].name);
    EXPECT_EQ(rt.stages[s].placed, ru.stages[s].placed);
  }
  EXPECT_EQ(rt.refine_moves, ru.refine_moves);
  // Checked on the input's own coordinates.
  EXPECT_TRUE(validate_polygon(tiny, rt.boundary).is_ok());
  const int e = max_coordinate_exponent(tiny);
  EXPECT_EQ(rt.area, std::ldexp(ru.area, 2 * e));
  EXPECT_EQ(rt.perimeter, std::ldexp(ru.perimeter, e));
}

TEST(ScaleRegression2, TinyLockCurveDefault) { expect_same_as_unit_scale("tiny_lock_curve_1e-287.xy", Fallback::Auto); }
TEST(ScaleRegression2, TinyLockCurveDegree4) { expect_same_as_unit_scale("tiny_lock_curve_1e-263.xy", Fallback::Degree4); }
TEST(ScaleRegression2, TinyLockCurveGamma0) { expect_same_as_unit_scale("tiny_lock_curve_1e-263.xy", Fallback::Gamma0); }

// Not rescalable (a 1e-300 coordinate among 1e308 ones) and the box is wider than the double
// range: the fallback grid must stay defined (no NaN -> int) and the polygon valid.
TEST(ScaleRegression2, HugeLockBoxOverflow) {
  const PointSet p = load("huge_lock_box_overflow.xy");
  PointSet scaled;
  int e = 0;
  EXPECT_EQ(exact_power_of_two_scale(p, scaled, e).code(), StatusCode::Unsupported);
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, Constrict2Options{}, r).is_ok());
  EXPECT_TRUE(r.complete);
  EXPECT_TRUE(r.locked_at_gamma0);
  EXPECT_TRUE(validate_polygon(p, r.boundary).is_ok());
}


// γ0 < 0 graphs: the lens search grew a ball forever (radius NaN for a near-collinear triple at
// ordinary magnitudes; overflow at 1e308; a radius that underflowed to 0 at 1e-323).
void expect_graph_as_unit_scale(const std::string& file, double g) {
  const PointSet p = load(file);
  const PointSet unit = scaled_to_one(p);
  GammaFaces a, b;
  GraphStats sa, sb;
  ASSERT_TRUE(build_gamma_graph(p, GraphSpec::fixed(g, g), a, &sa).is_ok());
  ASSERT_TRUE(build_gamma_graph(unit, GraphSpec::fixed(g, g), b, &sb).is_ok());
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.gamma_a, b.gamma_a);
  EXPECT_EQ(a.gamma_b, b.gamma_b);
  EXPECT_EQ(sa.extra_candidates, sb.extra_candidates);  // the same work
}

TEST(ScaleRegressionGraph, Huge1e308) { expect_graph_as_unit_scale("lens_huge_1e308.xyz", -0.1); }
TEST(ScaleRegressionGraph, Subnormal1e323) { expect_graph_as_unit_scale("lens_subnormal_1e-323.xyz", -0.1); }

// No exact rescaling exists (1e308 beside 1e-323): the Delaunay graph is built; a γ0 < 0 graph is
// refused at once with a message naming the cause (its exact scans carry the whole exponent span:
// 34 such points took 3.5 s, tests/data/regression/lens_mixed_magnitudes_1e-317_1e305_slow.xyz).
TEST(ScaleRegressionGraph, MixedMagnitudesFinishOrAreRefused) {
  for (const char* name : {"lens_mixed_1e308_1e-323.xyz", "lens_mixed_magnitudes_1e-317_1e305_slow.xyz"}) {
    const PointSet p = load(name);
    GammaFaces g;
    const Status dt = build_gamma_graph(p, GraphSpec::fixed(0, 0), g);
    ASSERT_TRUE(dt.is_ok()) << name << ": " << dt.message();
    EXPECT_GT(g.size(), 0u) << name;
    const Status lens = build_gamma_graph(p, GraphSpec::fixed(-0.1, -0.1), g);
    EXPECT_EQ(lens.code(), StatusCode::Unsupported) << name;
    EXPECT_NE(lens.message().find("orders of magnitude"), std::string::npos) << lens.message();
  }
}

// Ordinary magnitudes: the graph equals the oracle's (brute force filtered by in_graph).
TEST(ScaleRegressionGraph, NearCollinearTripleMatchesOracle) {
  const PointSet p = load("lens_hang_near_collinear.xyz");
  for (double g : {-0.1, -0.5, -0.9}) {
    const GraphSpec spec = GraphSpec::fixed(g, g);
    GammaFaces got, all;
    ASSERT_TRUE(build_gamma_graph(p, spec, got).is_ok());
    ASSERT_TRUE(brute_force_gamma_faces(p, all).is_ok());
    std::vector<int> want;
    for (std::size_t f = 0; f < all.size(); ++f)
      if (in_graph(spec, all.gamma_a[f], all.gamma_b[f], (all.flags[f] & kFaceBlocked) != 0))
        for (int k = 0; k < 3; ++k) want.push_back(all.vertex(f, k));
    EXPECT_EQ(got.vertices, want) << "gamma " << g;
  }
}


// 3D, mixed magnitudes (1e-312 .. 2e260): no exact power-of-two rescaling exists; the engine's
// inexact rescaling made a self-intersecting / inward surface that passed the validation of the
// rescaled copy, and underflowed distinct coordinates into false duplicates.
const char* const kMixed3D[] = {"mixed3d_self_intersecting_1e-312_2e260.xyz", "mixed3d_tetra_inward_1e-169_5e237.xyz",
                                "mixed3d_false_duplicate_1e300_5e-324.xyz"};

TEST(ScaleRegression3, MixedMagnitudesHaveNoExactRescaling) {
  for (const char* f : kMixed3D) {
    const PointSet p = load(f);
    ASSERT_TRUE(check_points(p).is_ok()) << f;  // all distinct
    PointSet scaled;
    int e = 0;
    const Status st = exact_power_of_two_scale(p, scaled, e);
    EXPECT_EQ(st.code(), StatusCode::Unsupported) << f;
  }
}

// The contract once Constrictor3::init calls exact_power_of_two_scale (the lead's restructuring of
// constrict3.cpp; enable then): a surface valid on the input's own coordinates, or a one-line
// refusal naming the magnitudes, never a false Duplicate or an internal error.
TEST(ScaleRegression3, MixedMagnitudesValidOnInputOrRefused) {
  for (const char* f : kMixed3D) {
    const PointSet p = load(f);
    Mesh3Result r;
    Status st;
    ASSERT_NO_THROW(st = reconstruct3(p, Constrict3Options{}, r)) << f;
    if (!st) {
      EXPECT_EQ(st.code(), StatusCode::Unsupported) << f << ": " << st.message();
      EXPECT_NE(st.message().find("orders of magnitude"), std::string::npos) << st.message();
      continue;
    }
    MeshCheckOptions mo;
    mo.self_intersections = true;
    const Status v = validate_mesh3(p, r.mesh, nullptr, mo);
    EXPECT_TRUE(v.is_ok()) << f << ": " << v.message();
  }
}

}  // namespace
}  // namespace constrict
