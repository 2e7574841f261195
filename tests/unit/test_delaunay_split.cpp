// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D Delaunay triangulation made in two halves on both cores and joined
// (detail::build_delaunay2_split, used by build_delaunay2_ranked from 2^17 points on; here forced
// at any size): against the sequential construction (the same triangles, as sets of input
// indices, wherever the triangulation is unique) and against the definition (a triangulation
// whose every edge is locally Delaunay, by the exact in-circle test) on inputs with many
// co-circular points, where it may also decline and leave the work to the sequential one.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "cgal/detail/delaunay_local.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/predicates.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

// n points of kind 0 uniform in a square, 1 in three Gaussian clusters, 2 on a lattice (co-circular
// quadruples everywhere), 3 on a circle with normal noise (curve-like), 4 in an annulus.
PointSet sample(std::size_t n, int kind, std::uint64_t seed) {
  std::uint64_t s = seed;
  const auto u = [&] { return static_cast<double>(test::splitmix64(s) >> 11) * 0x1.0p-53; };
  const auto g = [&] { return std::sqrt(-2 * std::log(1 - u())) * std::cos(6.283185307179586 * u()); };
  PointSet p;
  p.dim = 2;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (std::size_t i = 0; i < n; ++i) {
    double x = 0, y = 0;
    if (kind == 0) {
      x = u(), y = u();
    } else if (kind == 1) {
      const double c = static_cast<double>(i % 3);
      x = c + 0.2 * g(), y = 0.5 * c + 0.1 * g();
    } else if (kind == 2) {
      x = static_cast<double>(i % side), y = static_cast<double>(i / side);
    } else if (kind == 3) {
      const double a = 6.283185307179586 * u(), r = 1 + 1e-3 * g();
      x = r * std::cos(a), y = r * std::sin(a);
    } else {
      const double a = 6.283185307179586 * u(), r = 1 + u();
      x = r * std::cos(a), y = r * std::sin(a);
    }
    p.coords.insert(p.coords.end(), {x, y});
  }
  return p;
}

// The triangles as sorted triples of input indices.
std::set<std::array<int, 3>> triangle_set(const Delaunay2& dt, const std::vector<int>* id) {
  std::set<std::array<int, 3>> out;
  for (const auto& t : dt.triangles) {
    std::array<int, 3> k{};
    for (std::size_t j = 0; j < 3; ++j) k[j] = id ? (*id)[static_cast<std::size_t>(t[j])] : t[j];
    std::sort(k.begin(), k.end());
    out.insert(k);
  }
  return out;
}

// The definition: counter-clockwise triangles, neighbours that name each other across the shared
// edge, 2n - 2 - h triangles, and every interior edge locally Delaunay (exact in-circle).
void expect_delaunay(const PointSet& ranked, const Delaunay2& dt, const char* what) {
  const auto T = dt.triangles.size();
  std::size_t hull = 0;
  int bad_orient = 0, bad_nb = 0, bad_delaunay = 0;
  const auto P = [&](int v) { return ranked[static_cast<std::size_t>(v)]; };
  for (std::size_t t = 0; t < T; ++t) {
    const auto& tr = dt.triangles[t];
    bad_orient += orient2(P(tr[0]), P(tr[1]), P(tr[2])) <= 0;
    for (std::size_t i = 0; i < 3; ++i) {
      const int u = dt.neighbors[t][i];
      if (u < 0) {
        ++hull;
        continue;
      }
      const auto& ut = dt.triangles[static_cast<std::size_t>(u)];
      const auto& un = dt.neighbors[static_cast<std::size_t>(u)];
      int back = -1, shared = 0;
      for (std::size_t j = 0; j < 3; ++j) {
        if (un[j] == static_cast<int>(t)) back = static_cast<int>(j);
        for (std::size_t k = 0; k < 3; ++k) shared += k != i && tr[k] == ut[j];
      }
      if (back < 0 || shared != 2) {
        ++bad_nb;
        continue;
      }
      bad_delaunay += in_circle_ccw(P(tr[0]), P(tr[1]), P(tr[2]), P(ut[static_cast<std::size_t>(back)])) > 0;
    }
  }
  EXPECT_EQ(bad_orient, 0) << what;
  EXPECT_EQ(bad_nb, 0) << what;
  EXPECT_EQ(bad_delaunay, 0) << what;
  EXPECT_EQ(T + 2 + hull, 2 * ranked.size()) << what;
}

TEST(DelaunaySplit2, SameTrianglesAsTheSequentialConstruction) {
  for (const std::size_t n : {40u, 3000u, 40000u})
    for (const int kind : {0, 1, 3, 4}) {
      const std::uint64_t seed = 7919 * n + static_cast<std::uint64_t>(kind);
      SCOPED_TRACE("n " + std::to_string(n) + " kind " + std::to_string(kind) + " seed " + std::to_string(seed));
      const PointSet p = sample(n, kind, seed);
      Delaunay2 seq, split;
      ASSERT_TRUE(build_delaunay2(p, seq).is_ok());
      PointSet ranked;
      std::vector<int> id;
      Status st;
      ASSERT_TRUE(detail::build_delaunay2_split(p, split, ranked, id, st, false));
      ASSERT_TRUE(st.is_ok()) << st.message();
      EXPECT_EQ(split.n_vertices, n);
      EXPECT_TRUE(triangle_set(split, &id) == triangle_set(seq, nullptr));
      expect_delaunay(ranked, split, "random");
      // The ranks hold the input's coordinates.
      int bad = 0;
      for (std::size_t k = 0; k < n; ++k)
        bad += ranked[k][0] != p[static_cast<std::size_t>(id[k])][0] ||
               ranked[k][1] != p[static_cast<std::size_t>(id[k])][1];
      EXPECT_EQ(bad, 0);
    }
}

TEST(DelaunaySplit2, CoCircularPointsGiveADelaunayTriangulationOrDecline) {
  // A lattice: every unit square is four co-circular points, and the squares on the split line
  // belong to both halves. Either the join is a Delaunay triangulation or it declines (false) and
  // the sequential construction runs; build_delaunay2_ranked gives a Delaunay triangulation either way.
  for (const std::size_t n : {100u, 10000u}) {
    const PointSet p = sample(n, 2, 1);
    PointSet ranked;
    std::vector<int> id;
    Delaunay2 split;
    Status st;
    if (detail::build_delaunay2_split(p, split, ranked, id, st, false)) {
      ASSERT_TRUE(st.is_ok()) << st.message();
      expect_delaunay(ranked, split, "lattice, split");
    }
    Delaunay2 any;
    ASSERT_TRUE(detail::build_delaunay2_ranked(p, any, ranked, id).is_ok());
    expect_delaunay(ranked, any, "lattice, ranked");
  }
}

TEST(DelaunaySplit2, SameResultOnOneThreadAndOnTwo) {
  const PointSet p = sample(60000, 0, 42);
  Delaunay2 a, b;
  PointSet ra, rb;
  std::vector<int> ia, ib;
  Status sa, sb;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    ASSERT_TRUE(detail::build_delaunay2_split(p, a, ra, ia, sa, false));
  }
  ASSERT_TRUE(detail::build_delaunay2_split(p, b, rb, ib, sb, false));
  EXPECT_TRUE(a.triangles == b.triangles);
  EXPECT_TRUE(a.neighbors == b.neighbors);
  EXPECT_TRUE(ia == ib);
}

TEST(DelaunaySplit2, DuplicatesAreFoundInEitherHalf) {
  for (const std::size_t at : {0u, 2999u, 5999u}) {
    PointSet p = sample(6000, 0, 3);
    p.coords[2 * at] = p.coords[2 * 1234];
    p.coords[2 * at + 1] = p.coords[2 * 1234 + 1];
    Delaunay2 dt;
    PointSet ranked;
    std::vector<int> id;
    Status st;
    ASSERT_TRUE(detail::build_delaunay2_split(p, dt, ranked, id, st, false)) << at;
    EXPECT_EQ(st.code(), StatusCode::Duplicate) << at;
  }
}

TEST(DelaunaySplit2, CurvesAreLeftToTheSequentialConstruction) {
  // On a curve the interior triangles' circumdisks cross the split: the sample says so, and the
  // split declines; in a square it goes ahead.
  PointSet ranked;
  std::vector<int> id;
  Delaunay2 dt;
  Status st;
  EXPECT_FALSE(detail::build_delaunay2_split(sample(200000, 3, 5), dt, ranked, id, st, true));
  EXPECT_TRUE(detail::build_delaunay2_split(sample(200000, 0, 5), dt, ranked, id, st, true));
  EXPECT_TRUE(st.is_ok());
}

// Points on a line and one off it (the third hostile-input sweep): while every point inserted so
// far is on one line CGAL's triangulation has dimension 1 and locates by a walk along the line, so
// when the point off the line came late in the sorted order the construction was quadratic
// (199 999 + 1 points: 36 s). Now that point is inserted first; the triangulation is the fan from
// it (n - 2 triangles), through both the sequential and the split paths.
TEST(DelaunaySplit2, PointsOnALineAndOneOffItAreNotQuadratic) {
  const std::size_t n = 150001;
  PointSet p;
  p.dim = 2;
  for (std::size_t i = 0; i + 1 < n; ++i) p.coords.insert(p.coords.end(), {static_cast<double>(i), 0.0});
  p.coords.insert(p.coords.end(), {0.5 * static_cast<double>(n), 1.0});
  // (shuffled by a fixed permutation: the file order must not matter)
  std::uint64_t s = 12345;
  for (std::size_t i = n - 1; i > 0; --i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::size_t j = static_cast<std::size_t>((s >> 33) % (i + 1));
    std::swap(p.coords[2 * i], p.coords[2 * j]);
    std::swap(p.coords[2 * i + 1], p.coords[2 * j + 1]);
  }
  Delaunay2 dt;
  PointSet ranked;
  std::vector<int> id;
  ASSERT_TRUE(detail::build_delaunay2_ranked(p, dt, ranked, id).is_ok());
  EXPECT_EQ(dt.triangles.size(), n - 2);
  Delaunay2 local;
  ASSERT_TRUE(build_delaunay2(p, local).is_ok());
  EXPECT_EQ(local.triangles.size(), n - 2);
}

}  // namespace
}  // namespace constrict
