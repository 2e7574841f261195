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

}  // namespace
}  // namespace constrict
