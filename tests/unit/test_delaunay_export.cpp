// SPDX-License-Identifier: GPL-3.0-or-later
// The 3D Delaunay export that gives CGAL's cells back while it copies them out (build_delaunay3
// from 2^21 tetrahedra on, forced here from 0; src/cgal/delaunay.cpp, export_released3) against
// the plain export of the same triangulation (build_delaunay3_local with a local mesh, which
// reads every cell while the triangulation is whole): the same tetrahedra and neighbours, in the
// same order, at sizes from one block of CGAL's container to hundreds of them, on any thread and
// on many threads at once.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cgal/detail/delaunay_local.hpp"
#include "constrict/delaunay.hpp"
#include "core/detail/tet_order.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

// n points: kind 0 in a cube, 1 on a sphere (every point on the hull), 2 on a jittered lattice.
PointSet sample(std::size_t n, int kind, std::uint64_t seed) {
  std::uint64_t s = seed;
  const auto u = [&] { return static_cast<double>(test::splitmix64(s) >> 11) * 0x1.0p-53; };
  PointSet p;
  p.dim = 3;
  const auto side = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(n))));
  for (std::size_t i = 0; i < n; ++i) {
    if (kind == 0) {
      p.coords.insert(p.coords.end(), {u(), u(), u()});
    } else if (kind == 1) {
      const double z = 2 * u() - 1, a = 6.283185307179586 * u(), r = std::sqrt(1 - z * z);
      p.coords.insert(p.coords.end(), {r * std::cos(a), r * std::sin(a), z});
    } else {
      const double x = static_cast<double>(i % side), y = static_cast<double>(i / side % side),
                   z = static_cast<double>(i / side / side);
      p.coords.insert(p.coords.end(), {x + 1e-3 * u(), y + 1e-3 * u(), z + 1e-3 * u()});
    }
  }
  return p;
}

void expect_same_export(const PointSet& p, const char* what) {
  Delaunay3 released, plain;
  ASSERT_TRUE(detail::build_delaunay3_local(p, released, nullptr, 0).is_ok()) << what;
  detail::LocalMesh<3> local;
  ASSERT_TRUE(detail::build_delaunay3_local(p, plain, &local).is_ok()) << what;
  EXPECT_EQ(released.n_vertices, p.size()) << what;
  ASSERT_EQ(released.tets.size(), plain.tets.size()) << what;
  EXPECT_TRUE(released.tets == plain.tets) << what;
  EXPECT_TRUE(released.neighbors == plain.neighbors) << what;
  // And the neighbours are what the definition says: t and u = neighbors[t][i] share the face
  // opposite t's vertex i, and u names t back.
  const auto T = static_cast<int>(released.tets.size());
  int bad = 0;
  for (int t = 0; t < T; ++t)
    for (std::size_t i = 0; i < 4; ++i) {
      const int u = released.neighbors[static_cast<std::size_t>(t)][i];
      if (u < 0) continue;
      int back = 0, shared = 0;
      for (std::size_t j = 0; j < 4; ++j) {
        back += released.neighbors[static_cast<std::size_t>(u)][j] == t;
        for (std::size_t k = 0; k < 4; ++k)
          shared += k != i && released.tets[static_cast<std::size_t>(t)][k] == released.tets[static_cast<std::size_t>(u)][j];
      }
      bad += u >= T || back != 1 || shared != 3;
    }
  EXPECT_EQ(bad, 0) << what;
}

TEST(DelaunayExport3, ReleasedExportIsThePlainExport) {
  // (On another CGAL cell layout build_delaunay3 would fall back to the plain export, and this
  // test would compare it with itself.)
  ASSERT_TRUE(detail::released_export3_available());
  for (const std::size_t n : {5u, 40u, 2000u, 40000u})
    for (int kind = 0; kind < 3; ++kind) {
      const std::uint64_t seed = 1000 * n + static_cast<std::uint64_t>(kind);
      SCOPED_TRACE("n " + std::to_string(n) + " kind " + std::to_string(kind) + " seed " + std::to_string(seed));
      expect_same_export(sample(n, kind, seed), "one build");
    }
}

TEST(DelaunayExport3, BuildsAfterAReleasedOneAndAfterAFailedOne) {
  // The flag that lets a released triangulation be destroyed without reading its cells must not
  // outlive it: the next triangulations on the thread are built and exported as usual.
  const PointSet a = sample(20000, 0, 7), b = sample(3000, 1, 8);
  expect_same_export(a, "first");
  PointSet dup = b;
  dup.coords.insert(dup.coords.end(), b.coords.begin(), b.coords.begin() + 3);
  Delaunay3 out;
  EXPECT_EQ(build_delaunay3(dup, out).code(), StatusCode::Duplicate);
  expect_same_export(b, "after a duplicate");
  expect_same_export(a, "again");
}

TEST(DelaunayExport3, ConcurrentBuildsGiveTheSequentialExports) {
  std::vector<PointSet> inputs;
  for (unsigned k = 0; k < 8; ++k) inputs.push_back(sample(8000 + 1000 * k, static_cast<int>(k % 3), 50 + k));
  std::vector<Delaunay3> alone(inputs.size()), together(inputs.size());
  for (std::size_t k = 0; k < inputs.size(); ++k) ASSERT_TRUE(detail::build_delaunay3_local(inputs[k], alone[k], nullptr, 0).is_ok());
  tbb::parallel_for(std::size_t{0}, inputs.size(), [&](std::size_t k) { (void)detail::build_delaunay3_local(inputs[k], together[k], nullptr, 0); });
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    EXPECT_TRUE(together[k].tets == alone[k].tets) << "input " << k;
    EXPECT_TRUE(together[k].neighbors == alone[k].neighbors) << "input " << k;
  }
}

// Points along curves in space have a quadratic tetrahedralization (3 000 points of a circle and
// 3 001 of its axis: about 9 million tetrahedra, 2.5 GB and 32 s before): the insertion stops
// early with Unsupported and a message that says why, instead of running for minutes or out of
// memory. A surface sample of the same size builds.
TEST(DelaunayExport3, QuadraticTetrahedralizationsAreRefusedEarly) {
  PointSet p;
  p.dim = 3;
  for (int i = 0; i < 3000; ++i) {
    const double t = 2 * M_PI * i / 3000;
    p.coords.insert(p.coords.end(), {std::cos(t), std::sin(t), 0.0});
  }
  for (int i = 0; i <= 3000; ++i) p.coords.insert(p.coords.end(), {0.0, 0.0, -1 + 2.0 * i / 3000});
  Delaunay3 dt;
  const Status s = build_delaunay3(p, dt);
  EXPECT_EQ(s.code(), StatusCode::Unsupported);
  EXPECT_NE(s.message().find("quadratically many"), std::string::npos) << s.message();
  EXPECT_EQ(s.message().find('\n'), std::string::npos);
  PointSet q;
  q.dim = 3;
  for (int i = 0; i < 6001; ++i) {  // a Fibonacci sphere of the same size
    const double z = 1 - 2 * (i + 0.5) / 6001, r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
    q.coords.insert(q.coords.end(), {r * std::cos(phi), r * std::sin(phi), z});
  }
  EXPECT_TRUE(build_delaunay3(q, dt).is_ok());
}

// The engine's tetrahedra by their smallest vertex (core/detail/tet_order.hpp): the same
// tetrahedra, keys ascending, CGAL's order kept among equal keys, neighbours that name each other
// across their shared face, rows of a side array moved along, and the same arrays on one thread
// and on many.
TEST(TetOrder, SortsByTheSmallestVertexStablyWithItsNeighbours) {
  for (int kind = 0; kind < 3; ++kind)
    for (std::size_t n : {std::size_t{5}, std::size_t{300}, std::size_t{20000}}) {
      const std::string what = "kind " + std::to_string(kind) + ", " + std::to_string(n) + " points";
      const PointSet p = sample(n, kind, 7 + n);
      Delaunay3 dt;
      ASSERT_TRUE(build_delaunay3(p, dt).is_ok()) << what;
      const Delaunay3 before = dt;
      std::vector<std::array<int, 4>> rows(dt.tets.size());
      for (std::size_t t = 0; t < rows.size(); ++t) rows[t] = {{static_cast<int>(t), 0, 0, 0}};  // its old index
      detail::order_tets_by_vertex(dt, &rows);
      Delaunay3 one = before;
      {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        detail::order_tets_by_vertex(one);
      }
      EXPECT_TRUE(one.tets == dt.tets && one.neighbors == dt.neighbors) << what << ": thread count";
      const auto key = [](const std::array<int, 4>& t) { return *std::min_element(t.begin(), t.end()); };
      const auto T = static_cast<int>(dt.tets.size());
      int bad = 0;
      for (int t = 0; t < T; ++t) {
        const auto ut = static_cast<std::size_t>(t);
        const int old = rows[ut][0];
        bad += dt.tets[ut] != before.tets[static_cast<std::size_t>(old)];  // the row moved with it
        if (t > 0) {
          const int k0 = key(dt.tets[ut - 1]), k1 = key(dt.tets[ut]);
          bad += k0 > k1 || (k0 == k1 && rows[ut - 1][0] > old);  // ascending, stable
        }
        for (int i = 0; i < 4; ++i) {
          const int u = dt.neighbors[ut][static_cast<std::size_t>(i)];
          const int was = before.neighbors[static_cast<std::size_t>(old)][static_cast<std::size_t>(i)];
          if (u < 0) {
            bad += was >= 0;
            continue;
          }
          bad += rows[static_cast<std::size_t>(u)][0] != was;  // the same neighbour, renumbered
          const auto& nu = dt.neighbors[static_cast<std::size_t>(u)];
          bad += std::count(nu.begin(), nu.end(), t) != 1;
        }
      }
      EXPECT_EQ(bad, 0) << what;
    }
}

}  // namespace
}  // namespace constrict

