// SPDX-License-Identifier: GPL-3.0-or-later
// Seeded random inputs: every reconstruct2() output must be a valid simple CCW polygon through all
// points; counts how often each fallback was needed. Seeds are printed on failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/validate.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace constrict {
namespace {

constexpr double kPi = 3.14159265358979323846;

PointSet dedup(const PointSet& p) { return merge_duplicates(p, nullptr); }

// Families: 0 uniform, 1 clustered, 2 noisy smooth closed curve, 3 polygonal curve, 4 integer grid.
PointSet make_points(int family, std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  PointSet p;
  p.dim = 2;
  auto add = [&](double x, double y) { p.coords.push_back(x); p.coords.push_back(y); };
  switch (family) {
    case 0:
      for (std::size_t i = 0; i < n; ++i) add(u(rng), u(rng));
      break;
    case 1: {
      const std::size_t k = 1 + rng() % 5;
      std::vector<std::array<double, 3>> c(k);
      for (auto& q : c) q = {{u(rng), u(rng), 0.01 + 0.1 * u(rng)}};
      for (std::size_t i = 0; i < n; ++i) {
        const auto& q = c[rng() % k];
        add(q[0] + q[2] * g(rng), q[1] + q[2] * g(rng));
      }
      break;
    }
    case 2: {
      const double a = 1 + u(rng), b = 0.5 + u(rng), w = 0.3 * u(rng), noise = 0.03 * u(rng);
      const int lobes = 2 + static_cast<int>(rng() % 5);
      for (std::size_t i = 0; i < n; ++i) {
        const double t = 2 * kPi * u(rng);
        const double r = 1 + w * std::sin(lobes * t);
        add(a * r * std::cos(t) + noise * g(rng), b * r * std::sin(t) + noise * g(rng));
      }
      break;
    }
    case 3: {
      const int m = 3 + static_cast<int>(rng() % 8);
      std::vector<std::array<double, 2>> v(static_cast<std::size_t>(m));
      for (int i = 0; i < m; ++i) {
        const double t = 2 * kPi * i / m, r = 0.4 + u(rng);
        v[static_cast<std::size_t>(i)] = {{r * std::cos(t), r * std::sin(t)}};
      }
      const double noise = (rng() % 2) ? 0.0 : 0.01 * u(rng);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t e = rng() % static_cast<std::size_t>(m);
        const auto& a = v[e];
        const auto& b = v[(e + 1) % static_cast<std::size_t>(m)];
        const double s = u(rng);
        add(a[0] + s * (b[0] - a[0]) + noise * g(rng), a[1] + s * (b[1] - a[1]) + noise * g(rng));
      }
      break;
    }
    default: {
      const int side = 2 + static_cast<int>(std::sqrt(static_cast<double>(n))) + static_cast<int>(rng() % 3);
      for (std::size_t i = 0; i < n; ++i)
        add(static_cast<double>(rng() % static_cast<unsigned>(side)),
            static_cast<double>(rng() % static_cast<unsigned>(side)));
      break;
    }
  }
  return dedup(p);
}

TEST(Constrict2Property, RandomInputsValidate) {
  std::map<std::string, int> method_count;
  std::map<std::string, int> stage_points;
  int runs = 0, locks = 0;
  std::size_t refine_moves = 0;
  const char* names[] = {"uniform", "clustered", "curve", "polyline", "grid"};
  for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
    std::mt19937_64 rng(seed);
    const int family = static_cast<int>(seed % 5);
    const std::size_t n = 3 + rng() % 198;
    const PointSet p = make_points(family, n, rng);
    Polygon2Result r;
    Status st;
    try {
      st = reconstruct2(p, {}, r);
    } catch (const std::exception& e) {
      FAIL() << "seed " << seed << " (" << names[family] << ", n=" << p.size() << "): " << e.what();
    }
    if (st.code() == StatusCode::Collinear || st.code() == StatusCode::TooFewPoints) continue;
    ASSERT_TRUE(st.is_ok()) << "seed " << seed << ": " << st.message();
    ++runs;
    locks += r.locked_at_gamma0;
    ++method_count[r.method];
    for (const auto& s : r.stages) stage_points[s.name] += static_cast<int>(s.placed);
    ASSERT_TRUE(r.complete) << "seed " << seed;
    PolygonCheck d;
    const Status v = validate_polygon(p, r.boundary, &d);
    ASSERT_TRUE(v.is_ok()) << "seed " << seed << " (" << names[family] << ", n=" << p.size()
                           << "): " << v.message();
    if (r.locked_at_gamma0) {
      // Exercise the other fallbacks on the locked inputs: degree-4 (+repair) and repair alone.
      Constrict2Options d4;
      d4.fallback = Fallback::Degree4;
      Constrict2Options rep;
      rep.fallback = Fallback::Gamma0;
      rep.gamma0_schedule.clear();
      for (const Constrict2Options* o : {&d4, &rep}) {
        Polygon2Result r2;
        ASSERT_TRUE(reconstruct2(p, *o, r2).is_ok()) << "seed " << seed;
        ASSERT_TRUE(r2.complete) << "seed " << seed;
        ASSERT_TRUE(validate_polygon(p, r2.boundary).is_ok()) << "seed " << seed;
        ++method_count[(o == &d4 ? "[degree4 run] " : "[repair run] ") + r2.method];
      }
    }
    // The refinement only shortens (it starts from the validated constriction result).
    ASSERT_LE(r.perimeter, r.perimeter_before_refine * (1 + 1e-12)) << "seed " << seed;
    refine_moves += r.refine_moves;
    if (seed % 8 == 0) {
      ASSERT_TRUE(validate_polygon_brute_force(p, r.boundary).is_ok()) << "seed " << seed;
    }
  }
  std::printf("[ Constrict2Property ] runs=%d locked_at_gamma0=%d refine_moves=%zu\n", runs, locks, refine_moves);
  EXPECT_GT(refine_moves, 0u);
  for (const auto& m : method_count) std::printf("  method %-14s %d\n", m.first.c_str(), m.second);
  for (const auto& m : stage_points) std::printf("  points placed by %-14s %d\n", m.first.c_str(), m.second);
}

// The comparison methods on the same inputs (docs/comparison-methods.md): the other criteria keep
// every guarantee of the engine (complete, valid); the Voronoi skeleton either reaches every point
// with a valid polygon or says it did not (incomplete, still simple over the points it reached).
// Fewer cases for the slow skeleton.
TEST(Constrict2Property, OtherMethodsOnTheSameInputs) {
  std::map<std::string, int> counts;
  for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
    if (seed % 4 != 0) continue;
    std::mt19937_64 rng(seed);
    const int family = static_cast<int>(seed % 5);
    const std::size_t n = 3 + rng() % 198;
    const PointSet p = make_points(family, n, rng);
    if (!check_points(p).is_ok()) continue;
    SCOPED_TRACE("seed " + std::to_string(seed) + " n " + std::to_string(p.size()));
    for (Criterion c : {Criterion::MinAreaChange, Criterion::Boissonnat}) {
      Constrict2Options o;
      o.criterion = c;
      Polygon2Result r;
      ASSERT_TRUE(reconstruct2(p, o, r).is_ok());
      ASSERT_TRUE(r.complete);
      ASSERT_TRUE(validate_polygon(p, r.boundary).is_ok());
      ++counts[std::string(criterion_name(c)) + " locked " + (r.locked_at_gamma0 ? "yes" : "no")];
    }
    if (seed % 40 != 0) continue;
    VoronoiSkeletonOptions vo;
    vo.seed_limit = 64;
    VoronoiSkeleton2Result v;
    ASSERT_TRUE(voronoi_skeleton2(p, vo, v).is_ok());
    ASSERT_TRUE(v.validated);
    ASSERT_TRUE(v.check.reason.empty()) << v.check.reason;
    ASSERT_EQ(v.boundary.size() + v.unplaced_points.size(), p.size());
    ASSERT_EQ(v.complete, v.unplaced_points.empty());
    if (v.complete) {
      ASSERT_TRUE(validate_polygon(p, v.boundary).is_ok());
    }
    ++counts[std::string("voronoi-skeleton ") + (v.complete ? "complete" : "incomplete")];
  }
  for (const auto& m : counts) std::printf("  [ methods ] %-28s %d\n", m.first.c_str(), m.second);
}

// The sweep validator agrees with the brute-force check on random (mostly invalid) polygons.
TEST(Constrict2Property, ValidatorMatchesBruteForce) {
  int valid = 0;
  for (std::uint64_t seed = 1; seed <= 3000; ++seed) {
    std::mt19937_64 rng(seed);
    const std::size_t n = 3 + rng() % 12;
    const int side = 3 + static_cast<int>(rng() % 4);
    PointSet p;
    p.dim = 2;
    std::set<std::pair<int, int>> used;
    while (p.size() < n && used.size() < static_cast<std::size_t>(side * side)) {
      const int x = static_cast<int>(rng() % static_cast<unsigned>(side));
      const int y = static_cast<int>(rng() % static_cast<unsigned>(side));
      if (used.insert({x, y}).second) { p.coords.push_back(x); p.coords.push_back(y); }
    }
    std::vector<int> b(p.size());
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<int>(i);
    // Half of the time: angular order (often valid); otherwise random order.
    if (seed % 2) {
      Polygon2Result r;
      Constrict2Options o;
      if (reconstruct2(p, o, r).is_ok()) b = r.boundary;
      if (seed % 4 == 1 && b.size() > 3) std::swap(b[1], b[2]);
    } else {
      std::shuffle(b.begin(), b.end(), rng);
    }
    const bool fast = validate_polygon(p, b).is_ok();
    const bool slow = validate_polygon_brute_force(p, b).is_ok();
    ASSERT_EQ(fast, slow) << "seed " << seed;
    valid += fast;
    // The triangulation fast path (O(N) when every edge is a Delaunay edge) agrees too, also on
    // the clockwise copy.
    Delaunay2 dt;
    if (build_delaunay2(p, dt).is_ok()) {
      ASSERT_EQ(validate_polygon_in_triangulation(p, b, dt.triangles).is_ok(), slow) << "seed " << seed;
      std::vector<int> rev(b.rbegin(), b.rend());
      ASSERT_EQ(validate_polygon_in_triangulation(p, rev, dt.triangles).is_ok(),
                validate_polygon_brute_force(p, rev).is_ok()) << "seed " << seed;
    }
  }
  std::printf("[ Constrict2Property ] validator: %d valid polygons of 3000\n", valid);
}

// A local defect (a short reversal, or a swap of nearby vertices; rng draws them) in p's
// reconstructed polygon: validate_polygon_in_triangulation agrees with the brute-force validator,
// on it and on its clockwise copy, and accepts the polygon itself.
void check_local_defect(const PointSet& p, std::uint64_t seed, std::mt19937_64& rng, int& valid, int& invalid) {
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, {}, r).is_ok()) << "seed " << seed;
  std::vector<int> b = r.boundary;
  const std::size_t m = b.size(), i = rng() % m, len = 1 + rng() % 4;
  if (seed % 3 == 0) {
    std::swap(b[i], b[(i + 2 + rng() % 4) % m]);
  } else {
    for (std::size_t k = 0; k < (len + 1) / 2; ++k) std::swap(b[(i + k) % m], b[(i + len - k) % m]);
  }
  Delaunay2 dt;
  ASSERT_TRUE(build_delaunay2(p, dt).is_ok());
  ASSERT_TRUE(validate_polygon_in_triangulation(p, r.boundary, dt.triangles).is_ok()) << "seed " << seed;
  const bool slow = validate_polygon_brute_force(p, b).is_ok();
  ASSERT_EQ(validate_polygon_in_triangulation(p, b, dt.triangles).is_ok(), slow) << "seed " << seed;
  std::vector<int> rev(b.rbegin(), b.rend());
  ASSERT_EQ(validate_polygon_in_triangulation(p, rev, dt.triangles).is_ok(),
            validate_polygon_brute_force(p, rev).is_ok())
      << "seed " << seed;
  (slow ? valid : invalid)++;
}

// validate_polygon_in_triangulation with a few non-Delaunay edges sweeps only the edges near
// them: local defects in large valid polygons, against the brute-force validator.
TEST(Constrict2Property, TriangulationValidatorFindsLocalDefects) {
  int valid = 0, invalid = 0;
  for (std::uint64_t seed = 1; seed <= 250; ++seed) {
    std::mt19937_64 rng(seed);
    const PointSet p = make_points(seed % 2 ? 2 : 0, 200 + rng() % 300, rng);
    check_local_defect(p, seed, rng, valid, invalid);
  }
  std::printf("[ Constrict2Property ] local defects: %d valid, %d invalid\n", valid, invalid);
  EXPECT_GT(valid, 20);
  EXPECT_GT(invalid, 40);
}

// The same on heavy-tailed inputs (Cauchy-distributed points, a few far out and most near the
// centre): the candidate grid of the non-Delaunay edges is cut at their quantiles, not uniformly
// over the polygon's box (which put them all in one cell: 27 s at 10^6 points).
TEST(Constrict2Property, TriangulationValidatorFindsLocalDefectsOnHeavyTails) {
  int valid = 0, invalid = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    std::mt19937_64 rng(seed);
    std::cauchy_distribution<double> c(0, 1);
    PointSet p;
    p.dim = 2;
    for (std::size_t k = 300 + rng() % 300; k > 0; --k) {
      p.coords.push_back(c(rng));
      p.coords.push_back(c(rng));
    }
    check_local_defect(p, seed, rng, valid, invalid);
  }
  std::printf("[ Constrict2Property ] heavy tails, local defects: %d valid, %d invalid\n", valid, invalid);
  EXPECT_GT(valid, 1);
  EXPECT_GT(invalid, 10);
}

// The engine works on ranked vertex ids (CGAL's spatial insertion order) and maps every tie and
// every output back to input ids, and the refinement starts at a geometric vertex. In general
// position (no ties) a permuted (and rotated) input must therefore give exactly the permuted
// polygon, fallbacks and refinement included.
TEST(Constrict2Property, PermutedInputGivesThePermutedPolygon) {
  int compared = 0, locked = 0;
  for (std::uint64_t seed = 1; seed <= 600; ++seed) {
    std::mt19937_64 rng(seed);
    const int family = static_cast<int>(seed % 4);  // not the grid: it has ties
    const std::size_t n = 3 + rng() % 198;
    const PointSet p = make_points(family, n, rng);
    std::vector<int> perm(p.size());  // input i goes to position perm[i]
    for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
    std::shuffle(perm.begin(), perm.end(), rng);
    // Permuted, and every other seed also rotated by exactly 90° ((x, y) -> (-y, x): every
    // distance, angle and orientation is computed to the same bits).
    const bool rotate = seed % 2 == 0;
    PointSet q = p;
    for (std::size_t i = 0; i < p.size(); ++i) {
      double* d = q[static_cast<std::size_t>(perm[i])];
      d[0] = rotate ? -p[i][1] : p[i][0];
      d[1] = rotate ? p[i][0] : p[i][1];
    }
    Polygon2Result a, b;
    const Status sa = reconstruct2(p, {}, a);
    const Status sb = reconstruct2(q, {}, b);
    ASSERT_EQ(sa.code(), sb.code()) << "seed " << seed;
    if (!sa) continue;
    std::vector<int> inv(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) inv[static_cast<std::size_t>(perm[i])] = static_cast<int>(i);
    std::vector<int> mapped;
    for (int v : b.boundary) mapped.push_back(inv[static_cast<std::size_t>(v)]);
    std::rotate(mapped.begin(), std::min_element(mapped.begin(), mapped.end()), mapped.end());
    ASSERT_EQ(a.boundary, mapped) << "seed " << seed << " family " << family << " n=" << p.size();
    ASSERT_EQ(a.method, b.method) << "seed " << seed;
    std::vector<int> stuck;
    for (int v : b.stuck_points) stuck.push_back(inv[static_cast<std::size_t>(v)]);
    std::sort(stuck.begin(), stuck.end());
    ASSERT_EQ(a.stuck_points, stuck) << "seed " << seed;
    ++compared;
    locked += a.locked_at_gamma0;
  }
  std::printf("[ Constrict2Property ] permutation: %d inputs compared, %d of them locked\n", compared, locked);
  EXPECT_GT(locked, 0);
}

// Closed curves sampled at a spacing h with noise of about h normal to them (the inputs of the
// noisy-curve benchmark, small): they lock, the fallback tests long thin candidate triangles
// (strip cell queries), stops side searches early (partial entries) and the refinement runs on
// its sparse edge grid (edges far shorter than area-sized cells). The result must be valid, no
// longer than before the refinement, and the same polygon for the points permuted and rotated by
// exactly 90° (every predicate then sees the same numbers).
TEST(Constrict2Property, NoisyCurvesAtSpacingScale) {
  int locked = 0;
  std::size_t refined = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(1000 + seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> g(0, 1);
    const std::size_t n = 2000 + rng() % 8000;
    const int lobes = 3 + static_cast<int>(rng() % 4);
    const double h = 2 * kPi * 1.3 / static_cast<double>(n), noise = (0.5 + u(rng)) * h;
    PointSet p;
    p.dim = 2;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = 2 * kPi * u(rng), r = 1 + 0.3 * std::cos(lobes * t);
      p.coords.push_back(r * std::cos(t) + noise * g(rng));
      p.coords.push_back(r * std::sin(t) + noise * g(rng));
    }
    std::vector<int> perm(n);
    for (std::size_t i = 0; i < n; ++i) perm[i] = static_cast<int>(i);
    std::shuffle(perm.begin(), perm.end(), rng);
    PointSet q = p;
    for (std::size_t i = 0; i < n; ++i) {
      double* d = q[static_cast<std::size_t>(perm[i])];
      d[0] = -p[i][1];
      d[1] = p[i][0];
    }
    Polygon2Result a, b;
    ASSERT_TRUE(reconstruct2(p, {}, a).is_ok()) << "seed " << seed;
    ASSERT_TRUE(reconstruct2(q, {}, b).is_ok()) << "seed " << seed;
    ASSERT_TRUE(a.complete) << "seed " << seed;
    ASSERT_TRUE(validate_polygon(p, a.boundary).is_ok()) << "seed " << seed << " n=" << n;
    ASSERT_LE(a.perimeter, a.perimeter_before_refine * (1 + 1e-12)) << "seed " << seed;
    std::vector<int> inv(n);
    for (std::size_t i = 0; i < n; ++i) inv[static_cast<std::size_t>(perm[i])] = static_cast<int>(i);
    std::vector<int> mapped;
    for (int v : b.boundary) mapped.push_back(inv[static_cast<std::size_t>(v)]);
    std::rotate(mapped.begin(), std::min_element(mapped.begin(), mapped.end()), mapped.end());
    ASSERT_EQ(a.boundary, mapped) << "seed " << seed << " n=" << n;
    locked += a.locked_at_gamma0;
    refined += a.refine_moves;
  }
  std::printf("[ Constrict2Property ] noisy curves: 6 inputs, %d locked, %zu refinement moves\n", locked, refined);
  EXPECT_GT(locked, 0);
  EXPECT_GT(refined, 0u);
}

TEST(Constrict2Property, LargeInputIsFast) {
  std::mt19937_64 rng(12345);
  const PointSet p = make_points(0, 100000, rng);
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, {}, r).is_ok());
  EXPECT_TRUE(r.complete);
  std::printf("[ Constrict2Property ] N=100000 method=%s dt=%.1fms constrict=%.1fms fallback=%.1fms validate=%.1fms\n",
              r.method.c_str(), r.ms_delaunay, r.ms_constrict, r.ms_fallback, r.ms_validate);
}

}  // namespace
}  // namespace constrict
