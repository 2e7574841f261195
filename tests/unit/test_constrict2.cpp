// SPDX-License-Identifier: GPL-3.0-or-later
// Hand cases for the 2D reconstruction (spec gamma-graph.md §5.1, §5.2, §6.2) and the validator.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/share2.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "constrict/validate.hpp"
#include "core/detail/quad_heap.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

using test::make2;

// Rotation so that the smallest index comes first (orientation kept).
std::vector<int> canon(std::vector<int> b) {
  std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
  return b;
}

const std::vector<std::array<double, 2>> kExampleA = {{0, 0}, {8, 0}, {8, 6}, {0, 6}, {3, 2}};
const std::vector<std::array<double, 2>> kExampleB = {{-8, 13}, {12, 13}, {20, -3}, {15, 20},
                                                      {8, 6},   {9, 11},  {4, 17}};
const std::vector<std::array<double, 2>> kN9 = {{12, 2},  {0, 0},   {-1, 12}, {-14, -3}, {0, -14},
                                                {1, 2},   {12, 15}, {-20, 4}, {8, -19}};

struct Recorder : Constrict2Visitor {
  std::vector<Constrict2Event> events;
  void on_event(const Constrict2Event& e) override { events.push_back(e); }
};

TEST(Constrict2Unit, ExampleA) {
  const PointSet p = make2(kExampleA);
  Polygon2Result r;
  Recorder rec;
  ASSERT_TRUE(reconstruct2(p, {}, r, &rec).is_ok());
  EXPECT_TRUE(r.complete);
  EXPECT_FALSE(r.locked_at_gamma0);
  EXPECT_EQ(r.method, "gamma");
  EXPECT_EQ(canon(r.boundary), (std::vector<int>{0, 4, 1, 2, 3}));
  EXPECT_EQ(r.removed_simplices, 1u);
  ASSERT_EQ(rec.events.size(), 2u);  // the removal, then the refinement's start
  EXPECT_NEAR(rec.events[0].criterion, 1.175958, 1e-6);
  EXPECT_EQ(rec.events[1].kind, Constrict2Event::Kind::StageBegin);
  EXPECT_EQ(rec.events[1].stage, "refine");
  EXPECT_NEAR(r.area, 48 - 8, 1e-9);  // rectangle minus triangle (0,1,4) of area 8
}

TEST(Constrict2Unit, ExampleBLocksAtGamma0) {
  const PointSet p = make2(kExampleB);
  Constrict2Options o;
  o.refine = Refine2::None;  // spec traces are the paper's algorithm
  o.fallback = Fallback::None;
  Polygon2Result r;
  Recorder rec;
  ASSERT_TRUE(reconstruct2(p, o, r, &rec).is_ok());
  EXPECT_FALSE(r.complete);
  EXPECT_TRUE(r.locked_at_gamma0);
  EXPECT_EQ(r.method, "locked");
  EXPECT_EQ(r.stuck_points, std::vector<int>{5});
  EXPECT_EQ(canon(r.boundary), (std::vector<int>{0, 4, 2, 1, 3, 6}));
  ASSERT_GE(rec.events.size(), 2u);
  EXPECT_NEAR(rec.events[0].criterion, 1.770961, 1e-6);
  EXPECT_NEAR(rec.events[1].criterion, 1.236614, 1e-6);
}

// A visitor that only counts (the CLI's progress) gets the same events, without their triangles
// and keys; the result is the same.
TEST(Constrict2Unit, CountingVisitorGetsTheEventsWithoutTriangles) {
  struct Counter final : Recorder {
    bool wants_triangles() const override { return false; }
  };
  const PointSet p = make2(kExampleB);
  Constrict2Options o;
  o.fallback = Fallback::Gamma0;  // removals, a lock, a stage, an insertion
  Polygon2Result full, counted;
  Recorder rec;
  Counter cnt;
  ASSERT_TRUE(reconstruct2(p, o, full, &rec).is_ok());
  ASSERT_TRUE(reconstruct2(p, o, counted, &cnt).is_ok());
  EXPECT_EQ(full.boundary, counted.boundary);
  ASSERT_EQ(rec.events.size(), cnt.events.size());
  std::size_t with_points = 0;
  for (std::size_t i = 0; i < rec.events.size(); ++i) {
    const Constrict2Event &a = rec.events[i], &b = cnt.events[i];
    EXPECT_EQ(a.kind, b.kind) << i;
    EXPECT_EQ(a.stage, b.stage) << i;
    if (a.kind == Constrict2Event::Kind::RemoveTriangle || a.kind == Constrict2Event::Kind::InsertPoint) {
      ++with_points;
      EXPECT_NE(a.triangle[0], -1) << i;
      EXPECT_EQ(b.triangle, (std::array<int, 3>{{-1, -1, -1}})) << i;
      EXPECT_EQ(b.criterion, 0.0) << i;
    } else {
      EXPECT_EQ(a.triangle, b.triangle) << i;
    }
  }
  EXPECT_GE(with_points, 3u);
}

TEST(Constrict2Unit, ExampleBGamma0Rescue) {
  const PointSet p = make2(kExampleB);
  Constrict2Options o;
  o.refine = Refine2::None;  // spec traces are the paper's algorithm
  o.fallback = Fallback::Gamma0;
  o.repair = false;
  Polygon2Result r;
  Recorder rec;
  ASSERT_TRUE(reconstruct2(p, o, r, &rec).is_ok());
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.method, "gamma0=-0.1");
  EXPECT_EQ(canon(r.boundary), (std::vector<int>{0, 4, 2, 5, 1, 3, 6}));
  EXPECT_NEAR(rec.events.back().criterion, 0.996962, 1e-6);
  EXPECT_EQ(r.fallback_edges, (std::vector<std::array<int, 2>>{{{2, 5}}}));
}

TEST(Constrict2Unit, ExampleBDegree4Rescue) {
  const PointSet p = make2(kExampleB);
  Constrict2Options o;
  o.refine = Refine2::None;  // spec traces are the paper's algorithm
  o.fallback = Fallback::Degree4;
  o.repair = false;
  Polygon2Result r;
  Recorder rec;
  ASSERT_TRUE(reconstruct2(p, o, r, &rec).is_ok());
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.method, "degree4");
  EXPECT_EQ(canon(r.boundary), (std::vector<int>{0, 5, 4, 2, 1, 3, 6}));
  EXPECT_NEAR(rec.events.back().criterion, 0.996779, 1e-6);
}

TEST(Constrict2Unit, N9LocksThenRescued) {
  const PointSet p = make2(kN9);
  {
    Constrict2Options o;
    o.refine = Refine2::None;  // spec traces are the paper's algorithm
    o.fallback = Fallback::None;
    Polygon2Result r;
    Recorder rec;
    ASSERT_TRUE(reconstruct2(p, o, r, &rec).is_ok());
    EXPECT_FALSE(r.complete);
    EXPECT_EQ(r.stuck_points, std::vector<int>{5});
    EXPECT_EQ(canon(r.boundary), canon({7, 3, 1, 4, 8, 0, 6, 2}));
    ASSERT_GE(rec.events.size(), 1u);
    EXPECT_NEAR(rec.events[0].criterion, 0.977802, 1e-6);
  }
  {
    Constrict2Options o;
    o.refine = Refine2::None;  // spec traces are the paper's algorithm
    o.fallback = Fallback::Gamma0;
    o.repair = false;
    Polygon2Result r;
    Recorder rec;
    ASSERT_TRUE(reconstruct2(p, o, r, &rec).is_ok());
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.method, "gamma0=-0.05");
    EXPECT_EQ(canon(r.boundary), canon({7, 3, 1, 4, 8, 0, 6, 5, 2}));
    EXPECT_NEAR(rec.events.back().criterion, 0.783111, 1e-6);
  }
  {
    Constrict2Options o;
    o.refine = Refine2::None;  // spec traces are the paper's algorithm
    o.fallback = Fallback::Degree4;
    o.repair = false;
    Polygon2Result r;
    ASSERT_TRUE(reconstruct2(p, o, r).is_ok());
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.method, "degree4");
    EXPECT_EQ(canon(r.boundary), canon({7, 3, 1, 4, 8, 0, 6, 2, 5}));  // spec §6.2
  }
  {
    Polygon2Result r;
    ASSERT_TRUE(reconstruct2(p, {}, r).is_ok());
    EXPECT_TRUE(r.complete);
    EXPECT_TRUE(r.locked_at_gamma0);
  }
}

TEST(Constrict2Unit, StepperAndStopAfter) {
  const PointSet p = make2(kExampleB);
  Constrictor2 c;
  ASSERT_TRUE(c.init(p, {}).is_ok());
  EXPECT_EQ(canon(c.boundary()), (std::vector<int>{0, 2, 3, 6}));
  EXPECT_TRUE(c.step());
  EXPECT_EQ(canon(c.boundary()), (std::vector<int>{0, 4, 2, 3, 6}));
  Constrict2Options o;
  o.stop_after = 1;
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, o, r).is_ok());
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.method, "stopped");
  EXPECT_EQ(r.removed_simplices, 1u);
}

// A noisy closed curve locks, is rescued by the fallback and refined: the run that frees the
// constriction's state and the adjacency before the refinement. Its fallback_edges must be
// exactly the polygon's edges that are not Delaunay edges (checked against a triangulation of
// its own), and a second finish() gives the same result.
TEST(Constrict2Unit, RefinedFallbackEdgesAreTheNonDelaunayEdges) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> along(0.0, 2 * M_PI);
    const int n = 3000;
    std::vector<std::array<double, 2>> xy;
    for (int i = 0; i < n; ++i) {
      const double t = along(rng), r = 1000 * (1 + 0.3 * std::cos(5 * t));
      const double h = 2 * M_PI * 1000 / n;  // about the spacing
      xy.push_back({r * std::cos(t) + h * noise(rng), r * std::sin(t) + h * noise(rng)});
    }
    const PointSet p = make2(xy);
    Constrictor2 c;
    ASSERT_TRUE(c.init(p, {}).is_ok());
    Polygon2Result r, again;
    ASSERT_TRUE(c.finish(r).is_ok());
    ASSERT_TRUE(r.complete);
    EXPECT_NE(r.method, "gamma");  // the case this test is for
    EXPECT_GT(r.refine_moves, 0u);
    Delaunay2 dt;
    ASSERT_TRUE(build_delaunay2(p, dt).is_ok());
    std::vector<std::array<int, 2>> dt_edges;
    for (const auto& t : dt.triangles)
      for (std::size_t k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        dt_edges.push_back({{std::min(a, b), std::max(a, b)}});
      }
    std::sort(dt_edges.begin(), dt_edges.end());
    std::vector<std::array<int, 2>> expected;
    const std::size_t m = r.boundary.size();
    for (std::size_t i = 0; i < m; ++i) {
      const int a = r.boundary[i], b = r.boundary[(i + 1) % m];
      const std::array<int, 2> e{{std::min(a, b), std::max(a, b)}};
      if (!std::binary_search(dt_edges.begin(), dt_edges.end(), e)) expected.push_back(e);
    }
    std::sort(expected.begin(), expected.end());
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(r.fallback_edges, expected);
    ASSERT_TRUE(c.finish(again).is_ok());
    EXPECT_EQ(again.boundary, r.boundary);
    EXPECT_EQ(again.fallback_edges, r.fallback_edges);
    EXPECT_EQ(c.boundary().size(), static_cast<std::size_t>(n));  // the stepping view still answers
  }
}

TEST(Constrict2Unit, BadInput) {
  Polygon2Result r;
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 1}}), {}, r).code(), StatusCode::TooFewPoints);
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 1}, {2, 2}}), {}, r).code(), StatusCode::Collinear);
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 0}, {0, 1}, {1, 0}}), {}, r).code(), StatusCode::Duplicate);
  // The duplicates are found by the triangulation, then named by index; they take precedence
  // over the other defects, as in check_points().
  const Status dup = reconstruct2(make2({{0, 0}, {1, 0}, {0, 1}, {1, 0}}), {}, r);
  EXPECT_NE(dup.message().find("points 1 and 3"), std::string::npos) << dup.message();
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 1}, {1, 1}}), {}, r).code(), StatusCode::Duplicate);
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {0, 0}}), {}, r).code(), StatusCode::Duplicate);
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 1}, {2, 2}, {1, 1}}), {}, r).code(), StatusCode::Duplicate);
  std::vector<std::array<double, 2>> many;
  for (int i = 0; i < 5000; ++i) many.push_back({{std::cos(i * 0.37) * (1 + i % 7), std::sin(i * 0.37) * (1 + i % 11)}});
  many[4321] = many[17];
  const Status big = reconstruct2(make2(many), {}, r);
  EXPECT_EQ(big.code(), StatusCode::Duplicate);
  EXPECT_NE(big.message().find("points 17 and 4321"), std::string::npos) << big.message();
  EXPECT_EQ(reconstruct2(make2({{0, 0}, {1, 0}, {std::nan(""), 1}}), {}, r).code(), StatusCode::NonFinite);
}

TEST(Constrict2Unit, CollinearHullPoints) {
  // Square with points on its sides and one inside.
  const PointSet p = make2({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}, {1, 1}});
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, {}, r).is_ok());
  EXPECT_TRUE(r.complete);
  EXPECT_TRUE(validate_polygon(p, r.boundary).is_ok());
}

// Two inputs of n points that lock and fall back: a uniform square and a circle with normal noise
// of one spacing (one generator, in that order; the seed is printed).
std::vector<PointSet> locking_inputs(unsigned seed, int n) {
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, 1);
  std::vector<PointSet> out;
  for (int shape = 0; shape < 2; ++shape) {
    std::vector<std::array<double, 2>> xy;
    for (int k = 0; k < n; ++k) {
      if (shape == 0) {
        xy.push_back({u(rng), u(rng)});
      } else {
        const double t = 2 * M_PI * u(rng), r = 1 + 2 * M_PI / n * noise(rng);
        xy.push_back({r * std::cos(t), r * std::sin(t)});
      }
    }
    out.push_back(test::make2(xy));
  }
  return out;
}

// The result does not depend on the thread count: inputs large enough for the parallel passes
// (canonical order, duplicate check, the refinement's gathered candidate lists, validation) to
// split into several blocks, a uniform square and a noisy circle (both lock, fall back and
// refine), each with one thread and with all.
TEST(Constrict2Unit, ThreadCountIndependent) {
  const unsigned seed = 23;
  const std::vector<PointSet> inputs = locking_inputs(seed, 60000);
  for (int shape = 0; shape < 2; ++shape) {
    const PointSet& p = inputs[static_cast<std::size_t>(shape)];
    Polygon2Result one, many;
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
      ASSERT_TRUE(reconstruct2(p, {}, one).is_ok());
    }
    ASSERT_TRUE(reconstruct2(p, {}, many).is_ok());
    EXPECT_TRUE(one.valid());
    EXPECT_NE(one.method, "gamma") << "shape " << shape << ": expected a lock (the fallback and refinement paths)";
    EXPECT_GT(one.refine_moves, 0u) << "shape " << shape;
    EXPECT_EQ(one.boundary, many.boundary) << "seed " << seed << " shape " << shape;
    EXPECT_EQ(one.refine_moves, many.refine_moves) << "seed " << seed << " shape " << shape;
  }
}

// finish() after steps by hand gives the result of one call: the Delaunay adjacency is built
// beside the rest of the constriction when finish() runs it, and by the fallback itself when the
// steps already ran into the lock. A uniform square and a noisy circle (both lock,
// fall back and refine), stepped 0, 1000 and all steps.
TEST(Constrict2Unit, SteppedThenFinishedIsTheWholeRun) {
  const unsigned seed = 31;
  const std::vector<PointSet> inputs = locking_inputs(seed, 20000);
  for (int shape = 0; shape < 2; ++shape) {
    const PointSet& p = inputs[static_cast<std::size_t>(shape)];
    Polygon2Result whole;
    ASSERT_TRUE(reconstruct2(p, {}, whole).is_ok());
    ASSERT_TRUE(whole.valid());
    ASSERT_GT(whole.fallback_insertions, 0u) << "shape " << shape << ": expected a lock";
    for (const std::size_t steps : {std::size_t{0}, std::size_t{1000}, ~std::size_t{0}}) {
      Constrictor2 c;
      ASSERT_TRUE(c.init(p, {}).is_ok());
      for (std::size_t k = 0; k < steps && c.step(); ++k) {}
      Polygon2Result r;
      ASSERT_TRUE(c.finish(r).is_ok());
      EXPECT_EQ(r.boundary, whole.boundary) << "seed " << seed << " shape " << shape << " steps " << steps;
      EXPECT_EQ(r.fallback_insertions, whole.fallback_insertions) << "shape " << shape << " steps " << steps;
      EXPECT_EQ(r.refine_moves, whole.refine_moves) << "shape " << shape << " steps " << steps;
    }
  }
}

// A visitor that throws in the middle of the constriction: the exception reaches the caller
// (after the adjacency built beside the constriction has finished, not a terminate), and the
// next run on the same input gives the usual polygon.
TEST(Constrict2Unit, AVisitorsExceptionReachesTheCaller) {
  const unsigned seed = 37;
  const PointSet p = locking_inputs(seed, 20000)[0];
  struct Throwing final : Constrict2Visitor {
    std::size_t removals = 0;
    void on_event(const Constrict2Event& e) override {
      if (e.kind == Constrict2Event::Kind::RemoveTriangle && ++removals == 5000) throw std::runtime_error("stop");
    }
  } throwing;
  Polygon2Result before, r, after;
  ASSERT_TRUE(reconstruct2(p, {}, before).is_ok());
  ASSERT_GT(before.fallback_insertions, 0u) << "expected a lock (the adjacency is built beside)";
  EXPECT_THROW((void)reconstruct2(p, {}, r, &throwing), std::runtime_error);
  EXPECT_EQ(throwing.removals, 5000u);
  ASSERT_TRUE(reconstruct2(p, {}, after).is_ok());
  EXPECT_TRUE(after.valid());
  EXPECT_EQ(after.boundary, before.boundary) << "seed " << seed;
}

// The γ0 fallback tests the graph edges of the next candidates side by side
// (Constrict2Options::fallback_tests_ahead). A test's answer is a property of the pair and the
// stage, so the insertions must be those of testing each candidate as it comes out (width 0),
// whatever the width: the same polygon, stages and counts for 1, 2, 16 and 64 candidates ahead. A uniform square and
// a noisy circle, both of which lock and fall back; the refinement is off, so the fallback's
// polygon is compared as it is.
TEST(Constrict2Unit, FallbackTestsAheadDoNotChangeTheResult) {
  const unsigned seed = 29;
  const std::vector<PointSet> inputs = locking_inputs(seed, 40000);
  for (int shape = 0; shape < 2; ++shape) {
    const PointSet& p = inputs[static_cast<std::size_t>(shape)];
    Constrict2Options o = Constrict2Options::paper();
    o.fallback_tests_ahead = 0;
    Polygon2Result one;
    ASSERT_TRUE(reconstruct2(p, o, one).is_ok());
    ASSERT_TRUE(one.valid());
    ASSERT_GT(one.fallback_insertions, 100u) << "shape " << shape << ": expected the γ0 fallback to place many points";
    ASSERT_EQ(one.stages.size() > 1 ? one.stages[1].name.rfind("gamma0=", 0) : 1u, 0u) << "shape " << shape;
    for (const std::size_t ahead : {std::size_t{1}, std::size_t{2}, std::size_t{16}, std::size_t{64}}) {
      o.fallback_tests_ahead = ahead;
      Polygon2Result r;
      ASSERT_TRUE(reconstruct2(p, o, r).is_ok());
      EXPECT_EQ(r.boundary, one.boundary) << "seed " << seed << " shape " << shape << " ahead " << ahead;
      ASSERT_EQ(r.stages.size(), one.stages.size()) << "shape " << shape << " ahead " << ahead;
      for (std::size_t i = 0; i < r.stages.size(); ++i) {
        EXPECT_EQ(r.stages[i].name, one.stages[i].name);
        EXPECT_EQ(r.stages[i].placed, one.stages[i].placed)
            << "shape " << shape << " ahead " << ahead << " stage " << i;
      }
    }
  }
}

// n points on the unit circle and m outliers uniform in the box [-1.2, 1.2]^2 (seed printed): an
// outlier inside the circle is a Delaunay neighbour of a long arc.
PointSet circle_with_outliers(int n, int m, unsigned seed) {
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), box(-1.2, 1.2);
  std::vector<std::array<double, 2>> xy;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * u(rng);
    xy.push_back({std::cos(t), std::sin(t)});
  }
  for (int k = 0; k < m; ++k) xy.push_back({box(rng), box(rng)});
  return test::make2(xy);
}

// The γ0 fallback's cheap witness test reads at most Constrict2Options::fallback_witness_reads
// neighbours of each end of a pair; a pair it does not rule out is tested exactly when it comes
// out of the queue, so the polygon, the stages and their counts must not depend on the value.
// A circle with 2 % outliers in its box: each outlier inside is a Delaunay neighbour of a long
// arc (hundreds of neighbours), the case the bound is for; the refinement is off, so the
// fallback's polygon is compared as it is. Seeds printed.
TEST(Constrict2Unit, FallbackWitnessReadsDoNotChangeTheResult) {
  for (const unsigned seed : {51u, 52u, 53u}) {
    const PointSet p = circle_with_outliers(4000, 80, seed);
    Constrict2Options o = Constrict2Options::paper();
    o.fallback_witness_reads = 0;  // every neighbour
    Polygon2Result all;
    ASSERT_TRUE(reconstruct2(p, o, all).is_ok());
    ASSERT_TRUE(all.valid());
    ASSERT_GT(all.fallback_insertions, 50u) << "seed " << seed << ": expected the γ0 fallback to place many points";
    for (const std::size_t reads : {std::size_t{1}, std::size_t{4}, std::size_t{32}}) {
      o.fallback_witness_reads = reads;
      Polygon2Result r;
      ASSERT_TRUE(reconstruct2(p, o, r).is_ok());
      EXPECT_EQ(r.boundary, all.boundary) << "seed " << seed << " reads " << reads;
      ASSERT_EQ(r.stages.size(), all.stages.size()) << "seed " << seed << " reads " << reads;
      for (std::size_t i = 0; i < r.stages.size(); ++i) {
        EXPECT_EQ(r.stages[i].name, all.stages[i].name);
        EXPECT_EQ(r.stages[i].placed, all.stages[i].placed) << "seed " << seed << " reads " << reads << " stage " << i;
      }
    }
  }
}

// An outlier inside a sampled circle is a Delaunay neighbour of a long arc (a hub). The γ0
// stages offer the two new edges of an insertion to the stuck points within two hops, but not
// through a hub: else every insertion at a hub offered its whole arc again (a circle of 10^6
// points with 1 % outliers: over 10 minutes). Measured by the stages' candidate counts (a work
// count, not a time): at most 30 per stuck point here (7.5-10.6), where expanding through hubs
// queued 129-217. The polygon stays valid and complete. Seeds printed.
TEST(Constrict2Unit, FallbackDoesNotOfferAHubsWholeArc) {
  for (const unsigned seed : {61u, 62u, 63u}) {
    const PointSet p = circle_with_outliers(20000, 400, seed);
    Polygon2Result r;
    ASSERT_TRUE(reconstruct2(p, Constrict2Options::paper(), r).is_ok());
    ASSERT_TRUE(r.valid()) << r.check.reason;
    std::size_t queued = 0;
    for (const Constrict2Stage& st : r.stages)
      if (st.name.rfind("gamma0=", 0) == 0) queued += st.candidates;
    const std::size_t stuck = r.stuck_points.size();
    std::printf("  %zu stuck points, %zu candidates queued by the gamma0 stages\n", stuck, queued);
    ASSERT_GT(stuck, 500u) << "seed " << seed << ": expected a lock with many points inside";
    EXPECT_LE(queued, 30 * stuck) << "seed " << seed;
  }
}

// A spiral of the given turns (radius 1 + θ/2π, so turns 1 apart) through n points at uniform
// random angles, with Gaussian noise of 1e-4 (seed printed). The channel between its turns is
// many spacings wide: it locks, and uses the whole γ0 schedule and often the repair.
PointSet noisy_spiral(int n, int turns, unsigned seed) {
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, 1e-4);
  std::vector<double> turn(static_cast<std::size_t>(n));
  for (double& v : turn) v = 2 * M_PI * turns * u(rng);
  std::sort(turn.begin(), turn.end());
  std::vector<std::array<double, 2>> xy;
  for (const double t : turn) {
    const double r = 1 + t / (2 * M_PI);
    xy.push_back({r * std::cos(t) + noise(rng), r * std::sin(t) + noise(rng)});
  }
  return test::make2(xy);
}

// A run that its caller cancels (detail::reconstruct2_sharing, as the auto topology does once it
// found several rings) returns cancelled_status() and no result, wherever the cancel comes: in
// the constriction, at a fallback stage's start, in its insertions, after its last one. A cancel
// flag that is never set changes nothing. The cancel is set by the visitor at its K-th event, so
// the point is the same on every run. Noisy spirals that lock (seeds printed).
class CancelAt : public Constrict2Visitor {
 public:
  CancelAt(std::size_t k, std::atomic<bool>* flag) : k_(k), flag_(flag) {}
  void on_event(const Constrict2Event& e) override {
    if (e.kind == Constrict2Event::Kind::StageBegin && first_stage == 0) first_stage = events + 1;
    if (++events == k_) flag_->store(true);
  }
  std::size_t events = 0, first_stage = 0;

 private:
  std::size_t k_;
  std::atomic<bool>* flag_;
};

TEST(Constrict2Unit, CancelledRunReturnsNoResultWhereverItStops) {
  for (const unsigned seed : {91u, 92u}) {
    const PointSet p = noisy_spiral(12000, 10, seed);
    const Constrict2Options o;  // the default: fallback and refinement
    Polygon2Result ref;
    std::atomic<bool> never{false};
    CancelAt count(0, &never);
    ASSERT_TRUE(reconstruct2(p, o, ref, &count).is_ok());
    ASSERT_TRUE(ref.valid() && ref.fallback_insertions > 0) << "seed " << seed << ": expected a lock";
    const std::size_t total = count.events;
    Polygon2Result same;
    CancelAt none(0, &never);
    ASSERT_TRUE(detail::reconstruct2_sharing(p, o, same, &none, {}, &never).is_ok());
    EXPECT_EQ(same.boundary, ref.boundary) << "seed " << seed;
    EXPECT_EQ(same.refine_moves, ref.refine_moves) << "seed " << seed;
    for (const std::size_t k :
         {std::size_t{1}, total / 3, count.first_stage, std::min(count.first_stage + 300, total), total}) {
      std::atomic<bool> flag{false};
      CancelAt at(k, &flag);
      Polygon2Result r;
      const Status s = detail::reconstruct2_sharing(p, o, r, &at, {}, &flag);
      EXPECT_EQ(s.code(), StatusCode::Incomplete) << "seed " << seed << ", cancelled at event " << k << " of " << total;
      EXPECT_EQ(s.message().rfind("cancelled", 0), 0u) << s.message();
      EXPECT_LE(at.events, total) << "seed " << seed;
      EXPECT_TRUE(r.boundary.empty()) << "seed " << seed << ": a cancelled run gave a polygon";
    }
  }
}

// The repair's first round tests its candidates side by side (first_heap): the same polygon on
// one thread and on all. Noisy spirals whose paper-mode fallback reaches the repair.
TEST(Constrict2Unit, RepairFirstHeapThreadCountIndependent) {
  std::size_t repaired = 0;
  for (const unsigned seed : {81u, 82u, 83u}) {
    const PointSet p = noisy_spiral(40000, 3, seed);
    const Constrict2Options o = Constrict2Options::paper();
    Polygon2Result one, many;
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
      ASSERT_TRUE(reconstruct2(p, o, one).is_ok());
    }
    ASSERT_TRUE(reconstruct2(p, o, many).is_ok());
    ASSERT_TRUE(one.valid()) << "seed " << seed;
    EXPECT_EQ(one.boundary, many.boundary) << "seed " << seed;
    for (const Constrict2Stage& st : one.stages)
      if (st.name == "repair") repaired += st.placed;
  }
  std::printf("%zu points placed by the repair\n", repaired);
  EXPECT_GT(repaired, 0u) << "expected the repair to place points";
}

// Every insertion of a γ0 stage joins its apex by two edges of that stage's graph: Δ >= γ0 by
// brute force over all points (spec §2.1, §2.2: a point on the open segment blocks; else each
// side's smallest apex value, and Δ = filtration_value). At γ0 = -1 the engine skips the graph
// test (graph_implied: only a blocked pair is out, and its point would lie in the triangle that
// the insertion requires empty), so this also checks that shortcut. A noisy spiral of 10 turns
// and 12 000 points locks (the channel between its turns is 100 spacings wide) and uses the whole
// schedule down to -1; the refinement is off. Seeds printed.
TEST(Constrict2Unit, GammaZeroInsertionsAreInTheirStagesGraph) {
  std::size_t at_minus_one = 0, checked = 0;
  for (const unsigned seed : {71u, 72u, 73u, 74u, 75u, 76u}) {
    std::printf("seed %u\n", seed);
    const PointSet p = noisy_spiral(12000, 10, seed);
    Recorder rec;
    Polygon2Result r;
    ASSERT_TRUE(reconstruct2(p, Constrict2Options::paper(), r, &rec).is_ok());
    ASSERT_TRUE(r.valid()) << "seed " << seed;
    auto delta = [&](int i, int j) {
      double ga = 1, gb = 1;
      for (std::size_t q = 0; q < p.size(); ++q) {
        if (static_cast<int>(q) == i || static_cast<int>(q) == j) continue;
        const int o = orient2(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)], p[q]);
        if (o == 0) {
          if (diametral_side2(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)], p[q]) < 0)
            return -HUGE_VAL;
          continue;
        }
        const double g = apex_gamma2(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)], p[q]);
        (o > 0 ? ga : gb) = std::min(o > 0 ? ga : gb, g);
      }
      return filtration_value(ga, gb);
    };
    for (const Constrict2Event& e : rec.events) {
      if (e.kind != Constrict2Event::Kind::InsertPoint || e.stage.rfind("gamma0=", 0) != 0) continue;
      const double g0 = std::stod(e.stage.substr(7));
      for (const int end : {e.triangle[0], e.triangle[1]})
        EXPECT_GE(delta(end, e.triangle[2]), g0)
            << "seed " << seed << " stage " << e.stage << " pair " << end << ' ' << e.triangle[2];
      ++checked;
      at_minus_one += g0 == -1;
    }
  }
  std::printf("%zu insertions checked, %zu of them at gamma0 = -1\n", checked, at_minus_one);
  EXPECT_GT(checked, 50u);
  EXPECT_GT(at_minus_one, 0u) << "expected the stage gamma0 = -1 to place points";
}

// The γ0 and degree-4 stages leave needles to the repair (Constrict2Options::fallback_needle_ratio).
// On a five-petal curve with noise of one spacing (the 10⁶ benchmark's shape, 20 000 points), points
// locked inside the band have Delaunay neighbours across the whole figure, and the fallback joined
// some of them to a boundary edge on the far side: without the limit the paper-mode polygon has
// edges of 0.74–0.78 (the figure is 2.6 wide) and a perimeter 1.3–1.5 times the limited one's. With
// it, no insertion of those stages has an edge longer than 4 |ab| (exact), no polygon edge is
// longer than 0.05 and the perimeter is shorter. Seeds printed.
TEST(Constrict2Unit, FallbackLeavesNeedlesToTheRepair) {
  for (const unsigned seed : {41u, 42u, 43u}) {
    std::printf("seed %u\n", seed);
    const int n = 20000;
    const PointSet p = test::noisy_petal_curve(n, seed, 2 * M_PI * 1.25 / n);
    const auto longest = [&](const std::vector<int>& b) {
      double m = 0;
      for (std::size_t i = 0; i < b.size(); ++i) {
        const double* p0 = p[static_cast<std::size_t>(b[i])];
        const double* p1 = p[static_cast<std::size_t>(b[(i + 1) % b.size()])];
        m = std::max(m, std::hypot(p0[0] - p1[0], p0[1] - p1[1]));
      }
      return m;
    };
    Constrict2Options o = Constrict2Options::paper();
    o.fallback_needle_ratio = 0;
    Polygon2Result off;
    ASSERT_TRUE(reconstruct2(p, o, off).is_ok());
    ASSERT_TRUE(off.valid()) << "seed " << seed;
    o.fallback_needle_ratio = 4;
    Polygon2Result on;
    Recorder rec;
    ASSERT_TRUE(reconstruct2(p, o, on, &rec).is_ok());
    ASSERT_TRUE(on.valid()) << "seed " << seed;
    std::printf("seed %u: longest edge %.4f -> %.4f, perimeter %.3f -> %.3f, method %s -> %s\n", seed,
                longest(off.boundary), longest(on.boundary), off.perimeter, on.perimeter, off.method.c_str(),
                on.method.c_str());
    std::size_t checked = 0;
    for (const Constrict2Event& e : rec.events) {
      if (e.kind != Constrict2Event::Kind::InsertPoint || e.stage == "repair") continue;
      const double* a = p[static_cast<std::size_t>(e.triangle[0])];
      const double* b = p[static_cast<std::size_t>(e.triangle[1])];
      const double* z = p[static_cast<std::size_t>(e.triangle[2])];
      EXPECT_LE(compare_gap2(z, a, &a, &b, 1, 4.0), 0) << "seed " << seed << " stage " << e.stage;
      EXPECT_LE(compare_gap2(z, b, &a, &b, 1, 4.0), 0) << "seed " << seed << " stage " << e.stage;
      ++checked;
    }
    EXPECT_GT(checked, 10u) << "seed " << seed << ": expected the γ0 stages to place points";
    EXPECT_GT(longest(off.boundary), 0.5) << "seed " << seed << ": the input no longer shows the needles";
    EXPECT_LT(longest(on.boundary), 0.05) << "seed " << seed;
    EXPECT_LT(on.perimeter, off.perimeter) << "seed " << seed;
    // A tiny ratio makes every insertion a needle: the γ0 and degree-4 stages place nothing, the
    // repair places all (the ladder stays total); without the repair the result is incomplete.
    o.fallback_needle_ratio = 1e-3;
    Polygon2Result all_needles;
    ASSERT_TRUE(reconstruct2(p, o, all_needles).is_ok());
    EXPECT_TRUE(all_needles.valid()) << "seed " << seed;
    EXPECT_EQ(all_needles.method, "repair") << "seed " << seed;
    o.fallback = Fallback::Gamma0;
    o.repair = false;
    Polygon2Result no_repair;
    ASSERT_TRUE(reconstruct2(p, o, no_repair).is_ok());
    EXPECT_FALSE(no_repair.complete) << "seed " << seed;
  }
}

// A reversal of the refinement's tour of at least 65 536 positions runs in blocks on both cores
// (refine2.cpp, reverse_positions). A uniform square of 150 000 points makes 28 of them; its
// polygon must be the one of the sequential reversals, recorded here as a hash (the boundary in
// input ids, h = h * 1000003 + id mod 2^64) with its perimeter, and the same on one core. (One
// core runs the same blocks in sequence, so the recorded hash is the check; it was taken from the
// build before the blocks. If the threshold of 65 536 is raised, make the input larger.)
TEST(Constrict2Unit, LongReversalsGiveTheSequentialPolygon) {
  const unsigned seed = 31;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 2>> xy;
  for (int k = 0; k < 150000; ++k) xy.push_back({u(rng), u(rng)});
  const PointSet p = test::make2(xy);
  const auto hash = [](const std::vector<int>& b) {
    std::uint64_t h = 0;
    for (const int v : b) h = h * 1000003u + static_cast<std::uint64_t>(v);
    return h;
  };
  // The fallback as it was when the hash was recorded (before the needle limit): the refinement's
  // start, and so its reversals, are those of that build.
  Constrict2Options o;
  o.fallback_needle_ratio = 0;
  Polygon2Result one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    ASSERT_TRUE(reconstruct2(p, o, one).is_ok());
  }
  ASSERT_TRUE(reconstruct2(p, o, many).is_ok());
  ASSERT_TRUE(many.valid());
  EXPECT_EQ(many.refine_moves, 5803u);
  EXPECT_EQ(hash(many.boundary), 0x2596565fef8f8652u);
  EXPECT_EQ(many.perimeter, 316.9667057986449);
  EXPECT_EQ(one.boundary, many.boundary);
}

TEST(Constrict2Validator, Basics) {
  const PointSet sq = make2({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  PolygonCheck d;
  EXPECT_TRUE(validate_polygon(sq, {0, 1, 2, 3}, &d).is_ok());
  EXPECT_TRUE(d.simple && d.ccw && d.all_points);
  EXPECT_FALSE(validate_polygon(sq, {0, 3, 2, 1}, &d).is_ok());  // clockwise
  EXPECT_TRUE(d.simple);
  EXPECT_FALSE(d.ccw);
  EXPECT_FALSE(validate_polygon(sq, {0, 2, 1, 3}, &d).is_ok());  // bow tie
  EXPECT_FALSE(d.simple);
  EXPECT_FALSE(validate_polygon(sq, {0, 1, 2}, &d).is_ok());  // missing
  EXPECT_EQ(d.missing_point, 3);
  EXPECT_EQ(d.reason, "point 3 is missing");
  EXPECT_TRUE(d.simple && d.ccw);  // over its own vertices (the flags were false: a report said so)
  const PointSet five = make2({{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 3}});
  std::vector<std::array<int, 3>> fan{{0, 1, 2}, {0, 2, 3}, {3, 2, 4}};
  for (const bool in_triangulation : {false, true}) {
    const auto check = [&](const std::vector<int>& b) {
      return in_triangulation ? validate_polygon_in_triangulation(five, b, fan, &d) : validate_polygon(five, b, &d);
    };
    EXPECT_FALSE(check({0, 1, 2, 3}).is_ok());  // point 4 missing, the square simple and CCW
    EXPECT_TRUE(d.simple && d.ccw && !d.all_points) << in_triangulation;
    EXPECT_FALSE(check({0, 2, 1, 3}).is_ok());  // missing, and a bow tie
    EXPECT_EQ(d.reason, "point 4 is missing");
    EXPECT_FALSE(d.simple) << in_triangulation;
    EXPECT_FALSE(check({0, 3, 2, 1}).is_ok());  // missing, and clockwise
    EXPECT_TRUE(d.simple && !d.ccw) << in_triangulation;
  }
  EXPECT_FALSE(validate_polygon(sq, {0, 1, 2, 3, 1}, &d).is_ok());  // repeated
  EXPECT_EQ(d.repeated_point, 1);
  EXPECT_FALSE(validate_polygon(sq, {0, 1, 2, 7}, &d).is_ok());  // out of range
}

TEST(Constrict2Validator, TouchingAndCollinear) {
  // Vertex 4 touches edge (0,1) from inside: invalid.
  const PointSet t = make2({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}});
  EXPECT_FALSE(validate_polygon(t, {0, 1, 2, 3, 4}).is_ok());
  // 180° vertex allowed.
  const PointSet c = make2({{0, 0}, {1, 0}, {2, 0}, {1, 1}});
  EXPECT_TRUE(validate_polygon(c, {0, 1, 2, 3}).is_ok());
  // Fold back along a line: invalid.
  EXPECT_FALSE(validate_polygon(c, {0, 2, 1, 3}).is_ok());
  // Collinear overlap of non-adjacent edges.
  const PointSet o = make2({{0, 0}, {3, 0}, {3, 2}, {2, 0}, {1, 0}, {0, 2}});
  EXPECT_FALSE(validate_polygon(o, {0, 1, 2, 3, 4, 5}).is_ok());
  // Vertical edges.
  const PointSet v = make2({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {1, 3}, {0, 3}});
  PolygonCheck d1, d2;
  const Status s1 = validate_polygon(v, {0, 1, 2, 3, 4, 5}, &d1);
  const Status s2 = validate_polygon_brute_force(v, {0, 1, 2, 3, 4, 5}, &d2);
  EXPECT_EQ(s1.is_ok(), s2.is_ok());
}

// QuadHeap and TwoTierHeap (core/detail/quad_heap.hpp, the 2D constriction's queue) pop what
// std::priority_queue pops under a strict total order: random pushes and pops with keys drawn from
// a few values (ties broken by a second field through a comparator with state, as the
// constriction's are), runs of pushes across the growth steps, draining, and a move mid-way.
// Returns the largest hot heap seen (TwoTierHeap) or 0.
struct HeapItem {
  double key;
  std::uint32_t id;
};
struct HeapItemLess {
  const int* sign = nullptr;  // state: the tie order
  bool operator()(const HeapItem& l, const HeapItem& r) const {
    if (l.key != r.key) return l.key < r.key;
    return *sign * static_cast<int>(l.id) < *sign * static_cast<int>(r.id);
  }
};
template <class Heap>
std::size_t pops_like_a_std_heap() {
  std::size_t hot_max = 0;
  for (const int sign : {1, -1})
    for (const std::size_t keys : {std::size_t{3}, std::size_t{1000000}})
      for (const std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", keys " + std::to_string(keys) + ", sign " +
                     std::to_string(sign));
        std::uint64_t s = seed;
        Heap q(HeapItemLess{&sign});
        std::priority_queue<HeapItem, std::vector<HeapItem>, HeapItemLess> want(HeapItemLess{&sign});
        std::uint32_t next_id = 0;
        std::size_t bad = 0;
        for (int round = 0; round < 6; ++round) {
          // push-heavy, pop-heavy, then balanced phases: the size crosses 1021, 2045, 4093, ...
          const std::uint64_t push_share = round % 3 == 0 ? 9 : round % 3 == 1 ? 2 : 5;
          for (int step = 0; step < 20000; ++step) {
            const std::uint64_t r = test::splitmix64(s);
            if (r % 10 < push_share || want.empty()) {
              const HeapItem it{static_cast<double>((r >> 8) % keys) * 0.25, next_id++};
              q.push(it);
              want.push(it);
            } else {
              EXPECT_FALSE(q.empty());
              if (q.empty()) return hot_max;
              bad += q.top().id != want.top().id;
              q.pop();
              want.pop();
            }
            bad += q.size() != want.size();
            if constexpr (!std::is_same_v<Heap, detail::QuadHeap<HeapItem, HeapItemLess>>) {
              hot_max = std::max(hot_max, q.hot_size());
              bad += q.hot_size() > 0 && q.hot_size() == q.size();  // hot entries over an empty main heap
            }
          }
          if (round == 3) {
            Heap moved(HeapItemLess{&sign});
            moved = std::move(q);
            q = std::move(moved);
          }
        }
        while (!want.empty()) {
          EXPECT_FALSE(q.empty());
          if (q.empty()) return hot_max;
          bad += q.top().id != want.top().id;
          q.pop();
          want.pop();
        }
        EXPECT_TRUE(q.empty());
        EXPECT_EQ(bad, 0u);
      }
  return hot_max;
}

TEST(Constrict2Unit, QuadHeapPopsInTheOrderOfAStdHeap) {
  pops_like_a_std_heap<detail::QuadHeap<HeapItem, HeapItemLess>>();
}

// The hot tier must be used (pushes above the top are frequent with random keys), or the test
// says nothing about it.
TEST(Constrict2Unit, TwoTierHeapPopsInTheOrderOfAStdHeap) {
  EXPECT_GT((pops_like_a_std_heap<detail::TwoTierHeap<HeapItem, HeapItemLess>>()), 10u);
}

// The area of a polygon far from the origin (an adversarial sweep): a unit circle at 10^12 came
// out wrong in its first digit (the shoelace terms a x b cancel). Now about its first vertex.
TEST(Constrict2Unit, AreaOfAPolygonFarFromTheOrigin) {
  constexpr int n = 64;
  const double kPi = 3.14159265358979323846;
  std::vector<std::array<double, 2>> c;
  for (int k = 0; k < n; ++k) c.push_back({1e12 + std::cos(2 * kPi * k / n), -3e12 + std::sin(2 * kPi * k / n)});
  const PointSet p = make2(c);
  const double regular = 0.5 * n * std::sin(2 * kPi / n);  // (the rounding of the corners at 1e12: 1e-4)
  Polygon2Result r;
  ASSERT_TRUE(reconstruct2(p, Constrict2Options{}, r).is_ok());
  ASSERT_TRUE(r.complete);
  EXPECT_NEAR(r.area, regular, 1e-3);
  Rings2Options o;
  o.topology = Topology2::Auto;
  Rings2Result rr;
  ASSERT_TRUE(reconstruct_rings2(p, o, rr).is_ok());
  EXPECT_NEAR(rr.area, regular, 1e-3);
}

}  // namespace
}  // namespace constrict
