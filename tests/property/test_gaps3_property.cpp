// SPDX-License-Identifier: GPL-3.0-or-later
// Bridges between parts that nearly touch (issue 17, docs/reconstruction-3d.md §4.9): genus-0
// objects of capsules whose parts come within g = 1-4 sample spacings of each other (fingers,
// legs, an ear beside a ball, a hook along a body), the close parts sampled as densely as the rest
// or half as densely. The default reconstruction must stay a valid closed genus-0 surface through
// every point, and from a gap of 2 spacings on no triangle may lie farther from the true surface
// than a bound in spacings (a sheet across a gap of g lies about g/2 away; a cut through a part of
// radius r about r). Seeds and the measured table are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "constrict/constrict3.hpp"
#include "constrict/validate.hpp"
#include "gaps3_gen.hpp"
#include "thin_walls3_gen.hpp"
#include "surface_distance.hpp"

namespace constrict {
namespace {

// Largest distance from the surface to the true surface, over a barycentric grid of each triangle.
double surface_to_truth(const test::GapObject& o, const TriMesh3& m) {
  return test::max_distance_over_surface(
      m,
      [&](int v) {
        const double* p = o.points[static_cast<std::size_t>(v)];
        return std::array<double, 3>{p[0], p[1], p[2]};
      },
      [&](const std::array<double, 3>& q) { return test::gap_object_distance(o, q); });
}

// The default reconstruction, complete, checked by the validator and of genus 0.
void reconstruct_valid_genus0(const PointSet& points, Mesh3Result& r) {
  ASSERT_TRUE(reconstruct3(points, {}, r).is_ok());
  ASSERT_TRUE(r.complete);
  MeshCheck mc;
  EXPECT_TRUE(validate_mesh3(points, r.mesh, &mc).is_ok()) << mc.reason;
  EXPECT_EQ(mc.genus, 0);
}

struct Case {
  test::GapShape shape;
  double sparse;  // spacing of the close parts, in h
};

// Gaps and radii in units of the close parts' own spacing (sparse · h): from a gap of 2 of those
// on, the surface stays within 1.5 of them from the true surface (measured: at most 1.0; a sheet
// across the gap or a cut through a part lies 2-12 spacings away, docs/reconstruction-3d.md §4.9).
TEST(Gaps3Property, NoBridgesFromTwoSpacings) {
  const Case cases[] = {{test::GapShape::Fingers, 1}, {test::GapShape::Fingers, 2}, {test::GapShape::Legs, 1},
                        {test::GapShape::Legs, 2},    {test::GapShape::Ear, 1},     {test::GapShape::Ear, 2},
                        {test::GapShape::Hook, 1},    {test::GapShape::Hook, 2}};
  constexpr double kRadius = 4;  // part radius, in the close parts' spacings
  const std::uint64_t seed = 1;
  std::cout << "| shape | close parts sampled at | gap / their spacing | points | surface → truth / their spacing "
               "| bridge faces |\n";
  for (const Case& c : cases)
    for (double gap : {1.0, 2.0, 3.0, 4.0}) {
      const test::GapObject o = test::make_gap_object(c.shape, gap * c.sparse, kRadius * c.sparse, c.sparse, seed);
      const std::string what = std::string(test::gap_shape_name(c.shape)) + " sparse " + std::to_string(c.sparse) +
                               " gap " + std::to_string(gap) + " seed " + std::to_string(seed);
      SCOPED_TRACE(what);
      if (const char* dir = std::getenv("CONSTRICT_GAPS_DUMP")) {  // the point sets, for other tools
        char name[256];
        std::snprintf(name, sizeof name, "%s/%s_s%g_g%g.xyz", dir, test::gap_shape_name(c.shape), c.sparse, gap);
        std::FILE* f = std::fopen(name, "w");
        for (std::size_t i = 0; f && i < o.points.size(); ++i)
          std::fprintf(f, "%.17g %.17g %.17g\n", o.points[i][0], o.points[i][1], o.points[i][2]);
        if (f) std::fclose(f);
      }
      Mesh3Result r;
      reconstruct_valid_genus0(o.points, r);
      if (HasFatalFailure()) return;
      EXPECT_EQ(r.mesh.triangles.size(), 2 * o.points.size() - 4);
      const double d = surface_to_truth(o, r.mesh) / c.sparse;
      std::printf("| %s | %g h | %g | %zu | %.2f | %zu |\n", test::gap_shape_name(c.shape), c.sparse, gap, o.points.size(),
                  d, r.bridge_faces);
      if (gap >= 2) {
        EXPECT_LE(d, 1.5);
      }
    }
}

}  // namespace
}  // namespace constrict

namespace constrict {
namespace {

// Two separate parts a few spacings apart (an arm beside a body, not joined), in the default single
// mode: one genus-0 surface must join them, and the growth reaches the second part by tetrahedra
// labelled outside. It used to take those steps by the smallest bridge ratio over the whole gap, so
// that several crossings began along it and each reached the arm: the surface then had one neck per
// crossing and, between two necks, a wall across the arm (3-9 spacings from the truth, up to 450
// bridge faces). A crossing toward a part labelled inside now goes on from its own steps until it
// reaches that part's inside (docs/reconstruction-3d.md §4.14): one neck across the gap, which lies
// about g/2 from the true surface.
TEST(Gaps3Property, SeparatePartsAreJoinedByOneNeck) {
  std::cout << "| gap / h | seed | points | surface → truth / h | bridge faces | outside steps |\n";
  for (double gap : {2.0, 3.0, 4.0})
    for (std::uint64_t seed : {1, 2, 3}) {
      const test::GapObject o = test::make_gap_object(test::GapShape::Apart, gap, 4, 1, seed);
      SCOPED_TRACE("apart gap " + std::to_string(gap) + " seed " + std::to_string(seed));
      Mesh3Result r;
      reconstruct_valid_genus0(o.points, r);
      if (HasFatalFailure()) return;
      const double d = surface_to_truth(o, r.mesh);
      std::printf("| %g | %llu | %zu | %.2f | %zu | %zu |\n", gap, static_cast<unsigned long long>(seed),
                  o.points.size(), d, r.bridge_faces, r.grown_outside);
      EXPECT_LE(d, gap / 2 + 1.5);
    }
}

// A ball with a plate 0.8-1.25 spacings thick standing out of it (an ear, a fin): the labels see
// no inside in the plate, so the growth reaches its points by tetrahedra labelled outside. It must
// enter the plate along itself (docs/reconstruction-3d.md §4.11): no triangle farther than a
// spacing from the true surface and no bridge face. Before, 9 of these 18 sets had sheets of long
// faces from the plate to the ball (1.1-4.0 spacings away, bridge ratios up to 20).
TEST(Gaps3Property, ThinPlatesAreEnteredAlongThemselves) {
  std::cout << "| plate thickness / h | length / h | seed | points | surface → truth / h | bridge faces | "
               "outside steps | of them two-face |\n";
  for (double thickness : {0.8, 1.0, 1.25})
    for (double length : {8.0, 16.0})
      for (std::uint64_t seed : {1, 2, 3}) {
        const test::ThinWallObject o = test::make_thin_wall(12, thickness, length, 12, seed);
        SCOPED_TRACE("thickness " + std::to_string(thickness) + " length " + std::to_string(length) + " seed " +
                     std::to_string(seed));
        Mesh3Result r;
        ASSERT_TRUE(reconstruct3(o.points, {}, r).is_ok());
        ASSERT_TRUE(r.valid());
        MeshCheck mc;
        EXPECT_TRUE(validate_mesh3(o.points, r.mesh, &mc).is_ok()) << mc.reason;
        EXPECT_EQ(mc.genus, 0);
        const double d = test::max_distance_over_surface(
            r.mesh,
            [&](int v) {
              const double* p = o.points[static_cast<std::size_t>(v)];
              return std::array<double, 3>{p[0], p[1], p[2]};
            },
            [&](const std::array<double, 3>& q) { return std::abs(test::thin_wall_distance(o, q)); });
        std::printf("| %g | %g | %llu | %zu | %.2f | %zu | %zu | %zu |\n", thickness, length,
                    static_cast<unsigned long long>(seed), o.points.size(), d, r.bridge_faces, r.grown_outside,
                    r.grown_crawled);
        EXPECT_LE(d, 1.0);
        EXPECT_EQ(r.bridge_faces, 0u);
      }
}

}  // namespace
}  // namespace constrict

namespace constrict {
namespace {

// Random subsets of the close-part objects (each point kept with probability ½ or 0.4): clumps
// and holes like the random halves of bench/close_parts.sh. Gaps and radii in the subset's
// spacing. Two of these sets had the surface cut through a part: a pocket of tetrahedra labelled
// inside that the growth left out, whose full addition pinched a point or two, was left out by the
// fill as well (fingers ½ gap 3 seed 1: 2.94 spacings from the truth; ear 0.4 gap 3 seed 4: 2.97).
// The fill now repairs such pinches with moves of several tetrahedra (docs/reconstruction-3d.md
// §4.12); measured on 1 536 such sets, 2 fixed, none changed otherwise.
TEST(Gaps3Property, RandomSubsetsOfClosePartsKeepTheirParts) {
  struct Family {
    test::GapShape shape;
    double sparse, keep;
  };
  const Family families[] = {{test::GapShape::Fingers, 2, 0.5}, {test::GapShape::Ear, 1, 0.4}};
  std::cout << "| shape | close parts sampled at | kept | gap / subset spacing | seed | points | surface → truth / "
               "subset spacing |\n";
  for (const Family& f : families)
    for (double gap : {2.0, 3.0, 4.0})
      for (std::uint64_t seed : {1, 2, 3, 4}) {
        const double h = f.sparse / std::sqrt(f.keep);  // the subset's spacing on the close parts
        const test::GapObject o =
            test::random_subset(test::make_gap_object(f.shape, gap * h, 4 * h, f.sparse, seed), f.keep, seed);
        SCOPED_TRACE(std::string(test::gap_shape_name(f.shape)) + " keep " + std::to_string(f.keep) + " gap " +
                     std::to_string(gap) + " seed " + std::to_string(seed));
        Mesh3Result r;
        reconstruct_valid_genus0(o.points, r);
        if (HasFatalFailure()) return;
        const double d = surface_to_truth(o, r.mesh) / h;
        std::printf("| %s | %g h | %g | %g | %llu | %zu | %.2f |\n", test::gap_shape_name(f.shape), f.sparse, f.keep,
                    gap, static_cast<unsigned long long>(seed), o.points.size(), d);
        EXPECT_LE(d, 1.5);
      }
}

// Sparse fingers whose growth closed its front around a pocket of tetrahedra labelled inside with
// a point in it (docs/reconstruction-3d.md §4.13): the point was placed by a mirrored star cavity
// inside the pocket, the fill could then not take the pocket (it closed a handle through the
// cavity), and the surface cut through the finger (2.33, 1.61, 2.84 and 2.63 subset spacings from
// the truth). The fill during the growth takes the pocket with the point.
TEST(Gaps3Property, PointsLeftInAPocketAreReachedByTheFill) {
  struct Set {
    double keep, gap;
    std::uint64_t seed;
  };
  for (const Set& c : {Set{0.35, 2, 6}, Set{0.3, 3, 2}, Set{0.3, 3, 4}, Set{0.4, 2, 6}}) {
    const double h = 2 / std::sqrt(c.keep);
    const test::GapObject o = test::random_subset(
        test::make_gap_object(test::GapShape::Fingers, c.gap * h, 4 * h, 2, c.seed), c.keep, c.seed);
    SCOPED_TRACE("fingers, sparse 2, keep " + std::to_string(c.keep) + " gap " + std::to_string(c.gap) + " seed " +
                 std::to_string(c.seed));
    Mesh3Result r;
    reconstruct_valid_genus0(o.points, r);
    if (HasFatalFailure()) return;
    const double d = surface_to_truth(o, r.mesh) / h;
    std::printf(
        "fingers keep %g gap %g seed %llu: pocket points %zu, tetrahedra %zu, cavities %zu, surface -> truth %.2f h\n",
        c.keep, c.gap, static_cast<unsigned long long>(c.seed), r.grow_pocket_points, r.grow_pocket_filled,
        r.grow_cavities, d);
    EXPECT_GE(r.grow_pocket_points, 1u);
    EXPECT_EQ(r.grow_cavities, 0u);
    EXPECT_LE(d, 1.5);
  }
}

}  // namespace
}  // namespace constrict

namespace constrict {
namespace {

// The sweep behind docs/reconstruction-3d.md §4.12 (disabled; run with
// --gtest_also_run_disabled_tests --gtest_filter='*RandomSubsetSweep*'): every shape, close parts
// as dense as the rest or 2× sparser, gaps 2-4 in the subset's spacing, kept fractions 0.5, 0.45,
// 0.4, 0.35, 0.3 and 0.25, seeds 1..CONSTRICT_SWEEP_SEEDS (default 8). Prints one row per set and
// the sets farther than 1.5 subset spacings from the truth; asserts only validity.
TEST(Gaps3Property, DISABLED_RandomSubsetSweep) {
  const char* env = std::getenv("CONSTRICT_SWEEP_SEEDS");
  const std::uint64_t seeds = env ? std::strtoull(env, nullptr, 10) : 8;
  std::size_t sets = 0, far = 0;
  for (double keep : {0.5, 0.45, 0.4, 0.35, 0.3, 0.25})
    for (test::GapShape shape :
         {test::GapShape::Fingers, test::GapShape::Legs, test::GapShape::Ear, test::GapShape::Hook})
      for (double sparse : {1.0, 2.0})
        for (double gap : {2.0, 3.0, 4.0})
          for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
            const double h = sparse / std::sqrt(keep);
            const test::GapObject o =
                test::random_subset(test::make_gap_object(shape, gap * h, 4 * h, sparse, seed), keep, seed);
            Mesh3Result r;
            reconstruct_valid_genus0(o.points, r);
            if (HasFatalFailure()) return;
            const double d = surface_to_truth(o, r.mesh) / h;
            ++sets;
            far += d > 1.5;
            std::printf("%s sparse %g keep %g gap %g seed %llu points %zu d %.2f%s\n", test::gap_shape_name(shape),
                        sparse, keep, gap, static_cast<unsigned long long>(seed), o.points.size(), d,
                        d > 1.5 ? "  <<" : "");
          }
  std::printf("farther than 1.5 spacings: %zu of %zu sets\n", far, sets);
}

}  // namespace
}  // namespace constrict
