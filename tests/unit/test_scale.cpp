// SPDX-License-Identifier: GPL-3.0-or-later
// exact_power_of_two_scale(): the scaled copy round-trips exactly, the largest magnitude lands in
// [1/2, 1), and inputs whose tiny coordinates would lose bits are refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/points.hpp"
#include "constrict/predicates.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace {

PointSet make(int dim, std::vector<double> coords) {
  PointSet p;
  p.dim = dim;
  p.coords = std::move(coords);
  return p;
}

double max_abs(const PointSet& p) {
  double m = 0;
  for (double c : p.coords) m = std::max(m, std::fabs(c));
  return m;
}

void expect_exact(const PointSet& in, const PointSet& out, int e) {
  ASSERT_EQ(out.dim, in.dim);
  ASSERT_EQ(out.coords.size(), in.coords.size());
  for (std::size_t i = 0; i < in.coords.size(); ++i) EXPECT_EQ(std::ldexp(out.coords[i], e), in.coords[i]) << i;
  const double m = max_abs(out);
  if (m > 0) {
    EXPECT_GE(m, 0.5);
    EXPECT_LT(m, 1.0);
  }
}

TEST(ExactScale, TinyCurveScalesUp) {
  const PointSet in = make(2, {1e-287, 0, 0, 3e-287, -2e-287, 5e-288, 4.9e-324, 1e-290});
  PointSet out;
  int e = 0;
  ASSERT_TRUE(exact_power_of_two_scale(in, out, e).is_ok());
  EXPECT_LT(e, -900);
  expect_exact(in, out, e);
  // Subnormal inputs scale up exactly too.
  const PointSet sub = make(2, {4.9e-324, 0, 0, 1e-323, -2e-323, 3e-323});
  ASSERT_TRUE(exact_power_of_two_scale(sub, out, e).is_ok());
  expect_exact(sub, out, e);
}

TEST(ExactScale, HugeScalesDownWhenNothingUnderflows) {
  const PointSet in = make(3, {1e308, -1e308, 0, 1.7e308, 3, -1e300, 1, 2, 3});
  PointSet out;
  int e = 0;
  ASSERT_TRUE(exact_power_of_two_scale(in, out, e).is_ok());
  EXPECT_EQ(e, 1024);
  expect_exact(in, out, e);
}

TEST(ExactScale, OrdinaryAndZero) {
  PointSet out;
  int e = 7;
  const PointSet zero = make(2, {0, 0, 0, 0});
  ASSERT_TRUE(exact_power_of_two_scale(zero, out, e).is_ok());
  EXPECT_EQ(e, 0);
  EXPECT_EQ(out.coords, zero.coords);
  const PointSet unit = make(2, {0.75, -0.5, 0.25, 0});
  ASSERT_TRUE(exact_power_of_two_scale(unit, out, e).is_ok());
  EXPECT_EQ(e, 0);
  EXPECT_EQ(out.coords, unit.coords);
}

TEST(ExactScale, MixedMagnitudesRefused) {
  // The 3D reports: 1e-193 .. 4e291 and 1e-317 .. 4e298, and 1e300 with 5e-324.
  for (const PointSet& in : {make(3, {1e-193, 0, 0, 4e291, 1, 0, 0, 2e-150, 7, 0, 0, 1}),
                             make(3, {1e-317, 0, 0, 0, 4e298, 0, 0, 0, 1, 3, 3, 3}),
                             make(3, {1e300, 5e-324, 0, 1e300, 0, 0, 0, 1e300, 0, 0, 0, 1e300})}) {
    PointSet out;
    int e = 5;
    const Status st = exact_power_of_two_scale(in, out, e);
    EXPECT_EQ(st.code(), StatusCode::Unsupported);
    EXPECT_NE(st.message().find("too many orders of magnitude"), std::string::npos) << st.message();
    EXPECT_EQ(st.message().find('\n'), std::string::npos);
    EXPECT_EQ(e, 0);
    EXPECT_TRUE(out.coords.empty());
  }
}

// reconstruct3 checks the rescaling on its own (canonical) order of the points; the message must
// still name the caller's point (an adversarial sweep found "point 653" for a tiny point at row 2000).
TEST(ExactScale, ReconstructionNamesTheCallersPoint) {
  for (std::size_t at : {std::size_t{0}, std::size_t{37}, std::size_t{80}}) {
    PointSet p;
    p.dim = 3;
    for (std::size_t i = 0; i <= 80; ++i) {
      if (i == at) {
        p.coords.insert(p.coords.end(), {1e-300, 3e-300, 0});
        continue;
      }
      const double t = 0.7 * static_cast<double>(i), z = 1 - 2 * (static_cast<double>(i) + 0.5) / 81;
      const double r = std::sqrt(1 - z * z);
      p.coords.insert(p.coords.end(), {1e300 * r * std::cos(t), 1e300 * r * std::sin(t), 1e300 * z});
    }
    Mesh3Result r;
    const Status st = reconstruct3(p, {}, r);
    EXPECT_EQ(st.code(), StatusCode::Unsupported);
    EXPECT_NE(st.message().find("point " + std::to_string(at) + " would lose bits"), std::string::npos) << st.message();
  }
}

TEST(ExactScale, NonFinite) {
  PointSet out;
  int e = 0;
  EXPECT_EQ(exact_power_of_two_scale(make(2, {0, 1, std::nan(""), 2}), out, e).code(), StatusCode::NonFinite);
  EXPECT_EQ(exact_power_of_two_scale(make(2, {0, 1, HUGE_VAL, 2}), out, e).code(), StatusCode::NonFinite);
}

TEST(ExactScale, PredicatesUnchanged) {
  // Every orientation of the scaled copy is the input's (the point of an exact scaling).
  const PointSet in = make(2, {1e-300, 1e-300, 3e-300, 1.0000000000000002e-300, 2e-300, 2e-300, -1e-301, 7e-300});
  PointSet out;
  int e = 0;
  ASSERT_TRUE(exact_power_of_two_scale(in, out, e).is_ok());
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 4; ++b)
      for (std::size_t c = 0; c < 4; ++c) EXPECT_EQ(orient2(in[a], in[b], in[c]), orient2(out[a], out[b], out[c]));
}

}  // namespace
}  // namespace constrict
