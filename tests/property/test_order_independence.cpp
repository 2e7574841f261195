// SPDX-License-Identifier: GPL-3.0-or-later
// The same points in any file order give the same result (STYLE.md; issue 20): 3D the same set of
// coordinate triangles (and the same volume, bit for bit), 2D the same polygon as a cyclic sequence
// of coordinates. Families with many ties: integer lattices, exactly co-spherical / co-circular
// integer points, Gaussian blobs (volume clouds), uniform clouds, noisy spheres and curves.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/io.hpp"
#include "unit/test_fixtures.hpp"
#include "core/detail/canonical_order.hpp"
#include "thin_walls3_gen.hpp"

namespace constrict {
namespace {

using Coord3 = std::array<double, 3>;

PointSet shuffled(const PointSet& p, unsigned seed) {
  std::vector<std::size_t> perm(p.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  PointSet q;
  q.dim = p.dim;
  for (std::size_t i : perm) q.coords.insert(q.coords.end(), p[i], p[i] + p.dim);
  return q;
}

std::set<std::array<Coord3, 3>> coordinate_triangles(const PointSet& p, const TriMesh3& m) {
  std::set<std::array<Coord3, 3>> s;
  for (const auto& t : m.triangles) {
    std::array<Coord3, 3> c{};
    for (int k = 0; k < 3; ++k) std::copy(p[static_cast<std::size_t>(t[k])], p[static_cast<std::size_t>(t[k])] + 3, c[k].begin());
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());  // orientation kept
    s.insert(c);
  }
  return s;
}

std::vector<std::array<double, 2>> coordinate_polygon(const PointSet& p, const std::vector<int>& b) {
  std::vector<std::array<double, 2>> c;
  for (int v : b) c.push_back({{p[static_cast<std::size_t>(v)][0], p[static_cast<std::size_t>(v)][1]}});
  if (!c.empty()) std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

PointSet make(int dim, const std::vector<double>& coords) {
  PointSet p;
  p.dim = dim;
  p.coords = coords;
  return p;
}

// ---- 3D families ---------------------------------------------------------------------------------

std::vector<std::pair<std::string, PointSet>> families3() {
  std::vector<std::pair<std::string, PointSet>> f;
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  {
    std::vector<double> c;
    for (int x = 0; x < 5; ++x)
      for (int y = 0; y < 5; ++y)
        for (int z = 0; z < 5; ++z) c.insert(c.end(), {double(x), double(y), double(z)});
    f.push_back({"lattice 5^3", make(3, c)});
  }
  {
    std::vector<double> c;  // every integer point with x² + y² + z² = 75: exactly co-spherical
    for (int x = -9; x <= 9; ++x)
      for (int y = -9; y <= 9; ++y)
        for (int z = -9; z <= 9; ++z)
          if (x * x + y * y + z * z == 75) c.insert(c.end(), {double(x), double(y), double(z)});
    f.push_back({"co-spherical integer", make(3, c)});
  }
  {
    std::vector<double> c;
    for (int b = 0; b < 5; ++b) {
      const double cx = 3 * g(rng), cy = 3 * g(rng), cz = 3 * g(rng);
      for (int k = 0; k < 80; ++k) c.insert(c.end(), {cx + g(rng), cy + g(rng), cz + g(rng)});
    }
    f.push_back({"gaussian blobs", make(3, c)});
  }
  {
    std::vector<double> c;
    for (int k = 0; k < 300; ++k) c.insert(c.end(), {u(rng), u(rng), u(rng)});
    f.push_back({"uniform cube", make(3, c)});
  }
  {
    std::vector<double> c;
    for (int k = 0; k < 400; ++k) {
      double x = g(rng), y = g(rng), z = g(rng);
      const double r = std::sqrt(x * x + y * y + z * z) / (1 + 0.05 * u(rng));
      c.insert(c.end(), {x / r, y / r, z / r});
    }
    f.push_back({"noisy sphere", make(3, c)});
  }
  // A plate the labels miss, entered by outside steps along two faces (its sheets came from them).
  f.push_back({"thin plate", test::make_thin_wall(12, 0.8, 8, 12, 2).points});
  return f;
}

TEST(OrderIndependence, SameSurfaceInAnyFileOrder3D) {
  Constrict3Options no_grow;
  no_grow.grow = false;
  const std::vector<std::pair<std::string, Constrict3Options>> modes = {
      {"default", Constrict3Options{}}, {"no-grow", no_grow}, {"paper", Constrict3Options::paper()}};
  for (const auto& [name, p] : families3())
    for (const auto& [mode, opt] : modes) {
      Mesh3Result base;
      ASSERT_TRUE(reconstruct3(p, opt, base).is_ok()) << name;
      const auto tri = coordinate_triangles(p, base.mesh);
      for (unsigned seed = 1; seed <= 3; ++seed) {
        const PointSet q = shuffled(p, seed);
        Mesh3Result r;
        ASSERT_TRUE(reconstruct3(q, opt, r).is_ok()) << name;
        EXPECT_EQ(coordinate_triangles(q, r.mesh), tri) << name << ", " << mode << ", shuffle seed " << seed;
        EXPECT_EQ(r.volume, base.volume) << name << ", " << mode << ", shuffle seed " << seed;
        EXPECT_EQ(to_string(r.method), std::string(to_string(base.method))) << name;
      }
    }
}

// The fill's second try (docs/reconstruction-3d.md §4.16) peels by circumradius, ties by the
// tetrahedra's canonical order: the regression set that needs it, shuffled.
TEST(OrderIndependence, FillSecondTryInAnyFileOrder) {
  PointSet p;
  ASSERT_TRUE(test::read_regression3("ears_noisy_plate_pocket_beside_gap.xyz", p).is_ok());
  Mesh3Result base;
  ASSERT_TRUE(reconstruct3(p, Constrict3Options{}, base).is_ok());
  const auto tri = coordinate_triangles(p, base.mesh);
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const PointSet q = shuffled(p, seed);
    Mesh3Result r;
    ASSERT_TRUE(reconstruct3(q, Constrict3Options{}, r).is_ok());
    EXPECT_EQ(coordinate_triangles(q, r.mesh), tri) << "shuffle seed " << seed;
  }
}

TEST(OrderIndependence, SharedModelsInAnyFileOrder) {
  for (const char* name : {"knight_sparse", "spot"}) {
    PointSet p;
    const std::string path = std::string(CONSTRICT_SHARED_DIR) + "/data/3d/" + name + ".xyz";
    if (!read_points(path, {}, p)) GTEST_SKIP() << path << " not found";
    Mesh3Result base;
    ASSERT_TRUE(reconstruct3(p, Constrict3Options{}, base).is_ok());
    const PointSet q = shuffled(p, 5);
    Mesh3Result r;
    ASSERT_TRUE(reconstruct3(q, Constrict3Options{}, r).is_ok());
    EXPECT_EQ(coordinate_triangles(q, r.mesh), coordinate_triangles(p, base.mesh)) << name;
  }
}

// ---- 2D families ---------------------------------------------------------------------------------

std::vector<std::pair<std::string, PointSet>> families2() {
  std::vector<std::pair<std::string, PointSet>> f;
  std::mt19937 rng(12);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  {
    std::vector<double> c;
    for (int x = 0; x < 12; ++x)
      for (int y = 0; y < 12; ++y) c.insert(c.end(), {double(x), double(y)});
    f.push_back({"lattice 12^2", make(2, c)});
  }
  {
    std::vector<double> c;  // integer points with x² + y² = 5525 (= 5²·13·17): co-circular
    for (int x = -75; x <= 75; ++x)
      for (int y = -75; y <= 75; ++y)
        if (x * x + y * y == 5525) c.insert(c.end(), {double(x), double(y)});
    c.insert(c.end(), {0.0, 0.0, 10.0, 3.0, -20.0, 7.0});  // and a few inside
    f.push_back({"co-circular integer", make(2, c)});
  }
  {
    std::vector<double> c;
    for (int b = 0; b < 4; ++b) {
      const double cx = 3 * g(rng), cy = 3 * g(rng);
      for (int k = 0; k < 80; ++k) c.insert(c.end(), {cx + g(rng), cy + g(rng)});
    }
    f.push_back({"gaussian blobs", make(2, c)});
  }
  {
    std::vector<double> c;
    for (int k = 0; k < 300; ++k) {
      const double t = 2 * M_PI * k / 300, r = 1 + 0.3 * std::sin(5 * t) + 0.01 * g(rng);
      c.insert(c.end(), {r * std::cos(t), r * std::sin(t)});
    }
    f.push_back({"noisy flower curve", make(2, c)});
  }
  return f;
}

TEST(OrderIndependence, SamePolygonInAnyFileOrder2D) {
  const std::vector<std::pair<std::string, Constrict2Options>> modes = {{"default", Constrict2Options{}},
                                                                        {"paper", Constrict2Options::paper()}};
  for (const auto& [name, p] : families2())
    for (const auto& [mode, opt] : modes) {
      Polygon2Result base;
      ASSERT_TRUE(reconstruct2(p, opt, base).is_ok()) << name;
      ASSERT_TRUE(base.valid()) << name;
      const auto poly = coordinate_polygon(p, base.boundary);
      for (unsigned seed = 1; seed <= 3; ++seed) {
        const PointSet q = shuffled(p, seed);
        Polygon2Result r;
        ASSERT_TRUE(reconstruct2(q, opt, r).is_ok()) << name;
        EXPECT_EQ(coordinate_polygon(q, r.boundary), poly) << name << ", " << mode << ", shuffle seed " << seed;
        EXPECT_EQ(r.method, base.method) << name;
      }
    }
}

TEST(OrderIndependence, CanonicalOrderDependsOnTheCoordinatesOnly) {
  // Points far apart and a cluster inside one Morton cell (ties decided lexicographically).
  std::vector<double> c = {-1e6, -1e6, 1e6, 1e6, 0.0, 0.0};
  for (int k = 0; k < 20; ++k) c.insert(c.end(), {1e-9 * (k % 5), 1e-9 * (k / 5)});
  const PointSet p = make(2, c);
  const auto o = detail::canonical_order(p);
  const PointSet a = detail::permuted(p, o);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const PointSet q = shuffled(p, seed);
    EXPECT_EQ(detail::permuted(q, detail::canonical_order(q)).coords, a.coords) << "shuffle seed " << seed;
  }
}

}  // namespace
}  // namespace constrict
