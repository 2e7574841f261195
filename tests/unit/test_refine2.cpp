// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D refinement post-pass (refine_polygon2, Refine2::LocalSearch): a hand case, rejection of
// invalid input, and random star polygons (many moves, many non-Delaunay edges) that must stay
// simple, get shorter, and be invariant under an exact rotation.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/refine2.hpp"
#include "constrict/validate.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

using test::make2;

double perimeter(const PointSet& p, const std::vector<int>& b) {
  double s = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double* a = p[static_cast<std::size_t>(b[i])];
    const double* c = p[static_cast<std::size_t>(b[(i + 1) % b.size()])];
    s += std::hypot(c[0] - a[0], c[1] - a[1]);
  }
  return s;
}

// Spec §5.2 example B after the degree-4 rescue: 0 5 4 2 1 3 6 (length 86.772). Moving point 5
// between 2 and 1 (an Or-opt move of one point) saves d(0,5) + d(5,4) - d(0,4) = 4.752 and costs
// d(2,5) + d(5,1) - d(2,1) = 3.521: 0 4 2 5 1 3 6, length 85.541, simple. No further move helps.
TEST(Refine2, HandOrOptMove) {
  const PointSet p = make2({{-8, 13}, {12, 13}, {20, -3}, {15, 20}, {8, 6}, {9, 11}, {4, 17}});
  std::vector<int> poly{0, 5, 4, 2, 1, 3, 6};
  Refine2Stats st;
  ASSERT_TRUE(refine_polygon2(p, poly, &st).is_ok());
  EXPECT_EQ(poly, (std::vector<int>{0, 4, 2, 5, 1, 3, 6}));
  EXPECT_EQ(st.moves_oropt + st.moves_2opt, 1u);
  EXPECT_NEAR(st.length_before, 86.7717, 1e-3);
  EXPECT_NEAR(st.length_after, 85.5407, 1e-3);
  EXPECT_TRUE(validate_polygon_brute_force(p, poly).is_ok());
}

// A convex polygon has no shortening move: the early exit (no candidate set-up) must still return
// the polygon counter-clockwise from its smallest index, with its length.
TEST(Refine2, OptimalPolygonIsOnlyNormalised) {
  std::vector<std::array<double, 2>> xy;
  for (int i = 0; i < 12; ++i) xy.push_back({{std::cos(0.5236 * i), std::sin(0.5236 * i)}});
  const PointSet p = make2(xy);
  std::vector<int> cw;
  for (int i = 0; i < 12; ++i) cw.push_back((15 - i) % 12);  // 3 2 1 0 11 10 ... (clockwise)
  Refine2Stats st;
  ASSERT_TRUE(refine_polygon2(p, cw, &st).is_ok());
  std::vector<int> ccw;
  for (int i = 0; i < 12; ++i) ccw.push_back(i);
  EXPECT_EQ(cw, ccw);
  EXPECT_EQ(st.moves_2opt + st.moves_oropt, 0u);
  EXPECT_NEAR(st.length_before, perimeter(p, ccw), 1e-12);
  EXPECT_EQ(st.length_before, st.length_after);
}

// A thick ring with a gap (a "C", the ground truth) and the polygon made of its two circles closing
// the gap, joined by a corridor of two parallel cross edges: the two circles cross the gap, the
// corridor crosses the band. Replacing the gap edges by the two caps, or the corridor by the two
// band edges, alone cuts the polygon in two (a splitting 2-exchange); the two exchanges interleave
// along the polygon, so together (a double bridge) they give the C. No 2-opt or Or-opt move
// applies; the deep phase must find the C.
TEST(Refine2, DoubleBridgeJoinsTwoInterleavedSplits) {
  const int m = 36, j = 18;  // m + 1 points per arc; the corridor between angles j and j + 1
  const double alpha = 0.2, step = (2 * M_PI - 2 * alpha) / m;
  std::vector<std::array<double, 2>> xy;
  for (const double r : {10.0, 8.0})
    for (int i = 0; i <= m; ++i) xy.push_back({{r * std::cos(alpha + step * i), r * std::sin(alpha + step * i)}});
  const PointSet p = make2(xy);
  const auto outer = [](int i) { return i; };
  const auto inner = [&](int i) { return m + 1 + i; };
  std::vector<int> c_shape, rings;
  for (int i = 0; i <= m; ++i) c_shape.push_back(outer(i));
  for (int i = m; i >= 0; --i) c_shape.push_back(inner(i));
  for (int i = 0; i <= j; ++i) rings.push_back(outer(i));
  for (int i = j; i >= 0; --i) rings.push_back(inner(i));
  for (int i = m; i > j; --i) rings.push_back(inner(i));
  for (int i = j + 1; i <= m; ++i) rings.push_back(outer(i));
  ASSERT_TRUE(validate_polygon_brute_force(p, rings).is_ok());
  ASSERT_LT(perimeter(p, c_shape), perimeter(p, rings));
  std::vector<int> poly = rings;
  Refine2Stats st;
  ASSERT_TRUE(refine_polygon2(p, poly, &st).is_ok());
  std::printf("[ Refine2 ] ring: 2opt=%zu oropt=%zu deep=%zu rejected=%zu %.4f -> %.4f (C %.4f)\n", st.moves_2opt,
              st.moves_oropt, st.moves_deep, st.rejected, st.length_before, st.length_after, perimeter(p, c_shape));
  EXPECT_EQ(poly, c_shape);
  EXPECT_EQ(st.moves_2opt + st.moves_oropt, 0u);
  EXPECT_GE(st.moves_deep, 1u);
  EXPECT_TRUE(validate_polygon_brute_force(p, poly).is_ok());
}

TEST(Refine2, RejectsInvalidPolygon) {
  const PointSet p = make2({{0, 0}, {4, 0}, {4, 4}, {0, 4}});
  std::vector<int> bowtie{0, 2, 1, 3};
  const std::vector<int> before = bowtie;
  EXPECT_EQ(refine_polygon2(p, bowtie).code(), StatusCode::InvalidArgument);
  EXPECT_EQ(bowtie, before);
  std::vector<int> missing{0, 1, 2};
  EXPECT_EQ(refine_polygon2(p, missing).code(), StatusCode::InvalidArgument);
}

// Random points joined in angular order around their mean: a simple but very long star polygon.
struct Star {
  PointSet points;
  std::vector<int> polygon;
};
Star random_star(std::uint64_t seed, bool grid) {
  std::mt19937_64 rng(seed);
  const std::size_t n = 4 + rng() % 297;
  std::uniform_real_distribution<double> u(-1, 1);
  Star s;
  s.points.dim = 2;
  for (std::size_t i = 0; i < n; ++i) {
    // Grid coordinates produce collinear and co-circular subsets (exact ties everywhere).
    const double x = grid ? std::floor(u(rng) * 12) : u(rng), y = grid ? std::floor(u(rng) * 12) : u(rng);
    s.points.coords.push_back(x);
    s.points.coords.push_back(y);
  }
  double cx = 0.01234, cy = -0.00567;  // off-lattice centre: no point on it
  std::vector<std::pair<double, int>> ang;
  for (std::size_t i = 0; i < n; ++i)
    ang.emplace_back(std::atan2(s.points[i][1] - cy, s.points[i][0] - cx), static_cast<int>(i));
  std::sort(ang.begin(), ang.end());
  for (const auto& a : ang) s.polygon.push_back(a.second);
  return s;
}

// The pre-test and the first sweep run on TBB: the result must not depend on the thread count.
TEST(Refine2, ThreadCountIndependent) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const Star s = random_star(seed, false);
    if (!validate_polygon(s.points, s.polygon).is_ok()) continue;
    std::vector<int> one = s.polygon, many = s.polygon;
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
      ASSERT_TRUE(refine_polygon2(s.points, one).is_ok());
    }
    ASSERT_TRUE(refine_polygon2(s.points, many).is_ok());
    EXPECT_EQ(one, many) << "seed " << seed;
  }
}

// Two interleaved logarithmic spirals (13 decades of scale in 20 000 points): the grid of the
// simplicity tests has cells of the median edge, and the centre's thousands of edges fill one
// cell, so every move near it tested them all (600 M tests here, 30 000 per point; 146 s at 10^5
// points, found by an adversarial sweep). The tests are bounded: the search stops between two
// visits once they pass 256 · N + 2^22, with a valid polygon.
TEST(Refine2, SimplicityTestsStayWithinTheirBound) {
  const std::size_t m = 10000;
  PointSet p;
  p.dim = 2;
  for (int arm = 0; arm < 2; ++arm)
    for (std::size_t i = arm; i < m; ++i) {  // (the second arm without the shared centre point)
      const double th = 200.0 * static_cast<double>(i) / static_cast<double>(m - 1), r = std::exp(-0.15 * th);
      p.coords.push_back(r * std::cos(th + arm * M_PI));
      p.coords.push_back(r * std::sin(th + arm * M_PI));
    }
  Constrict2Options opt;
  opt.refine = Refine2::None;
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, opt, r).is_ok());
  std::vector<int> poly = r.boundary;
  Refine2Stats st;
  ASSERT_TRUE(refine_polygon2(p, poly, &st).is_ok());
  const std::size_t bound = 256 * p.size() + (std::size_t{1} << 22);
  std::printf("simplicity tests %zu (bound %zu), moves %zu, perimeter %.6g -> %.6g\n", st.simplicity_tests, bound,
              st.moves_2opt + st.moves_oropt + st.moves_deep, st.length_before, st.length_after);
  EXPECT_TRUE(st.budget_hit);
  EXPECT_GT(st.simplicity_tests, bound);
  EXPECT_LE(st.simplicity_tests, bound + bound / 16);  // (one visit past the bound)
  EXPECT_TRUE(validate_polygon(p, poly).is_ok());
  EXPECT_LE(st.length_after, st.length_before);
}

// The pretest (an O(N) pass that skips the search when no move can apply) must never hide a move:
// with and without it the same polygon. A circle of points in order is optimal; one more point q
// just inside the circle, near point 0, is spliced in far from there (at position `at`: a spike
// across the disc), which the search repairs. The pretest computes its Or-opt gains block by
// block (8 192 positions) and around the polygon's wrap, so `at` runs over the block edges and
// both ends, and the small circles (4 to 9 points) allow only short segments. (The spike is also
// seen by the pretest's 2-opt test, so this checks the pretest as a whole; its gains were checked
// value for value against the per-vertex loop they replaced on the shared data, docs/benchmarks.md.)
TEST(Refine2, PretestNeverHidesAMove) {
  for (const int n : {4, 5, 6, 9, 20000}) {
    std::vector<std::array<double, 2>> xy;
    const double step = 2 * M_PI / n;
    for (int i = 0; i < n; ++i) xy.push_back({{std::cos(step * i), std::sin(step * i)}});
    const double depth = n > 100 ? 1e-5 : 0.3;  // inside the chords next to point 0
    xy.push_back({{(1 - depth) * std::cos(0.3 * step), (1 - depth) * std::sin(0.3 * step)}});
    const PointSet p = make2(xy);
    Delaunay2 dt;
    ASSERT_TRUE(build_delaunay2(p, dt).is_ok());
    std::vector<int> ats = {n / 2, n - 1, n};
    if (n > 8192) ats = {5, 8190, 8191, 8192, 8193, n - 1, n, n / 2 + 3};
    for (const int at : ats) {
      std::vector<int> poly;
      for (int i = 0; i < n; ++i) {
        if (i == at) poly.push_back(n);
        poly.push_back(i);
      }
      if (at == n) poly.push_back(n);
      if (!validate_polygon(p, poly).is_ok()) continue;  // (tiny circles: q's spike may cross)
      std::vector<int> with = poly, without = poly;
      Refine2Stats s1, s2;
      const bool ran = detail::refine_polygon2(p, dt, with, 1000 * p.size(), s1, nullptr, {}, true);
      detail::refine_polygon2(p, dt, without, 1000 * p.size(), s2, nullptr, {}, false);
      EXPECT_EQ(with, without) << "n " << n << ", q at " << at;
      EXPECT_TRUE(ran) << "n " << n << ", q at " << at;
      EXPECT_GT(s2.moves_oropt + s2.moves_2opt + s2.moves_deep, 0u) << "n " << n << ", q at " << at;
      EXPECT_LT(s1.length_after, s1.length_before) << "n " << n << ", q at " << at;
    }
  }
}

// Inside reconstruct2() the refinement gathers its candidate lists from the engine's adjacency
// (after a lock); the public refine_polygon2() builds them from the triangles. Both must give the
// same polygon: noisy circles (they lock, the refinement moves) and jittered grids (distance ties
// between candidates, ordered by id).
TEST(Refine2, InsideReconstructionSameAsAlone) {
  int moved = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0, 1);
    std::vector<std::array<double, 2>> xy;
    const int n = 200 + static_cast<int>(rng() % 800);
    if (seed % 3 == 0) {
      for (int k = 0; k < n; ++k) xy.push_back({static_cast<double>(rng() % 64), static_cast<double>(rng() % 64)});
      std::sort(xy.begin(), xy.end());
      xy.erase(std::unique(xy.begin(), xy.end()), xy.end());
    } else {
      const double h = 2 * M_PI / n;
      for (int k = 0; k < n; ++k) {
        const double t = k * h, r = 1 + 0.5 * h * noise(rng);
        xy.push_back({r * std::cos(t), r * std::sin(t)});
      }
    }
    const PointSet pts = make2(xy);
    Constrict2Options with, without;
    without.refine = Refine2::None;
    Polygon2Result a, b;
    ASSERT_TRUE(reconstruct2(pts, with, a).is_ok()) << "seed " << seed;
    ASSERT_TRUE(reconstruct2(pts, without, b).is_ok()) << "seed " << seed;
    std::vector<int> alone = b.boundary;
    ASSERT_TRUE(refine_polygon2(pts, alone).is_ok()) << "seed " << seed;
    EXPECT_EQ(a.boundary, alone) << "seed " << seed << " (n=" << pts.size() << ", " << a.method << ")";
    moved += a.refine_moves > 0 && a.method != "gamma";
  }
  std::printf("[ Refine2 ] %d of 30 runs locked and moved\n", moved);
  EXPECT_GT(moved, 5);
}

TEST(Refine2, RandomStarPolygonsStaySimpleAndShorten) {
  int runs = 0;
  std::size_t moves = 0, deep = 0, rejected = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const bool grid = seed % 3 == 0;
    Star s = random_star(seed, grid);
    if (!check_points(s.points).is_ok()) continue;  // duplicates on the grid
    if (!validate_polygon(s.points, s.polygon).is_ok()) continue;  // angle ties
    ++runs;
    std::vector<int> poly = s.polygon;
    Refine2Stats st;
    ASSERT_TRUE(refine_polygon2(s.points, poly, &st).is_ok()) << "seed " << seed;
    const Status v = validate_polygon_brute_force(s.points, poly);
    ASSERT_TRUE(v.is_ok()) << "seed " << seed << " (grid=" << grid << ", n=" << s.points.size() << "): " << v.message();
    EXPECT_LE(perimeter(s.points, poly), perimeter(s.points, s.polygon) * (1 + 1e-12)) << "seed " << seed;
    EXPECT_NEAR(st.length_after, perimeter(s.points, poly), 1e-9 * st.length_after) << "seed " << seed;
    moves += st.moves_2opt + st.moves_oropt + st.moves_deep;
    deep += st.moves_deep;
    rejected += st.rejected;
    // Deterministic, and invariant under the exact rotation (x, y) -> (-y, x): distances and
    // orientations are unchanged, so is every decision.
    std::vector<int> again = s.polygon;
    ASSERT_TRUE(refine_polygon2(s.points, again).is_ok());
    EXPECT_EQ(again, poly) << "seed " << seed;
    if (!grid) {
      PointSet rot = s.points;
      for (std::size_t i = 0; i < rot.size(); ++i) {
        rot.coords[2 * i] = -s.points[i][1];
        rot.coords[2 * i + 1] = s.points[i][0];
      }
      std::vector<int> r = s.polygon;
      ASSERT_TRUE(refine_polygon2(rot, r).is_ok());
      EXPECT_EQ(r, poly) << "seed " << seed;
    }
    // A tiny work bound stops early, still valid.
    std::vector<int> bounded = s.polygon;
    Refine2Stats bs;
    ASSERT_TRUE(refine_polygon2(s.points, bounded, &bs, 0).is_ok());
    ASSERT_TRUE(validate_polygon(s.points, bounded).is_ok()) << "seed " << seed;
    if (st.moves_2opt + st.moves_oropt + st.moves_deep > 0) {
      EXPECT_TRUE(bs.budget_hit) << "seed " << seed;
    }
    EXPECT_LE(bs.moves_2opt + bs.moves_oropt + bs.moves_deep, 1u) << "seed " << seed;
  }
  std::printf("[ Refine2 ] star polygons=%d moves=%zu (deep %zu) rejected(non-simple)=%zu\n", runs, moves, deep, rejected);
  EXPECT_GT(runs, 250);
  EXPECT_GT(deep, 0u);  // the deep phase (k-opt moves, double bridges) is exercised
  EXPECT_GT(rejected, 0u);  // the exact simplicity test is exercised
}

// A cancel flag (the auto topology's, detail::reconstruct2_sharing) set before the search stops it
// at the first vertex it visits: no move, and the polygon stays simple and through all points. A
// flag that is never set changes nothing. Random star polygons (seeds in the messages).
TEST(Refine2, CancelledSearchStopsWithAValidPolygon) {
  int runs = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const Star s = random_star(seed, false);
    if (!validate_polygon(s.points, s.polygon).is_ok()) continue;
    Delaunay2 dt;
    ASSERT_TRUE(build_delaunay2(s.points, dt).is_ok());
    std::vector<int> plain = s.polygon, unset = s.polygon, stopped = s.polygon;
    Refine2Stats a, b, c;
    std::atomic<bool> no{false}, yes{true};
    const std::size_t budget = 64 * s.points.size();
    detail::refine_polygon2(s.points, dt, plain, budget, a);
    detail::refine_polygon2(s.points, dt, unset, budget, b, nullptr, {}, true, nullptr, true, &no);
    detail::refine_polygon2(s.points, dt, stopped, budget, c, nullptr, {}, true, nullptr, true, &yes);
    EXPECT_EQ(unset, plain) << "seed " << seed;
    EXPECT_EQ(b.moves_2opt + b.moves_oropt + b.moves_deep, a.moves_2opt + a.moves_oropt + a.moves_deep);
    EXPECT_EQ(c.moves_2opt + c.moves_oropt + c.moves_deep, 0u) << "seed " << seed;
    const Status v = validate_polygon_brute_force(s.points, stopped);
    EXPECT_TRUE(v.is_ok()) << "seed " << seed << ": " << v.message();
    runs += a.moves_2opt + a.moves_oropt + a.moves_deep > 0;
  }
  EXPECT_GT(runs, 30) << "expected polygons that the search moves";
}

// refine_polygon2's contract: the result is counter-clockwise, a triangle too.
TEST(RefineContract, ClockwiseTriangleComesBackCounterClockwise) {
  PointSet p;
  p.dim = 2;
  p.coords = {0, 0, 4, 0, 1, 3};
  std::vector<int> poly = {0, 2, 1};  // clockwise
  ASSERT_TRUE(refine_polygon2(p, poly).is_ok());
  EXPECT_EQ(poly, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(validate_polygon(p, poly).is_ok());
}

}  // namespace
}  // namespace constrict
