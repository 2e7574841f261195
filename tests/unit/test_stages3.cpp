// SPDX-License-Identifier: GPL-3.0-or-later
// Unit tests of the 3D engine's stages one by one (src/constrict/detail/stages3.hpp,
// docs/architecture.md): each stage on a Body3 built here from the Delaunay tetrahedralization,
// with the body's invariants checked after it (positive tetrahedra, symmetric adjacency, a
// closed genus-0 2-manifold surface), and what the stage promises (labels on every tetrahedron,
// a growth that reaches every point, flips that lower the area, cavities that keep the volume).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/stages3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/bucket_sort.hpp"
#include "core/detail/rank_queue.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/validate.hpp"
#include "property/gaps3_gen.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

using detail::Body3;

// n points on a noisy ellipsoid shell (some inside the hull), seeded.
PointSet shell(std::size_t n, unsigned seed, double noise = 0.05) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  PointSet p;
  p.dim = 3;
  for (std::size_t k = 0; k < n; ++k) {
    double x = g(rng), y = g(rng), z = g(rng);
    const double r = std::sqrt(x * x + y * y + z * z) / (1 + noise * u(rng));
    p.coords.insert(p.coords.end(), {2 * x / r, y / r, 0.7 * z / r});
  }
  return p;
}

// A uniform cloud in the unit cube: many points inside, the constriction locks on some.
PointSet cloud(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  PointSet p;
  p.dim = 3;
  for (std::size_t k = 0; k < 3 * n; ++k) p.coords.push_back(u(rng));
  return p;
}

// The uniform clouds of Constrict3Unit.LockedCloudsAreCompletedByTheCavityFallback (splitmix64:
// the same points on every platform); the paper's constriction locks on them.
PointSet locking_cloud(std::uint64_t seed) {
  std::uint64_t s = seed;
  const auto next = [&s] { return test::splitmix64(s); };
  PointSet p;
  p.dim = 3;
  for (int i = 0; i < 3 * 150; ++i) p.coords.push_back(static_cast<double>(next() >> 11) * 0x1.0p-53);
  return p;
}

// The start state of a run: every Delaunay tetrahedron in the body, the hull points on it.
Body3 start_body(const PointSet& p) {
  Body3 b;
  Delaunay3 dt;
  EXPECT_TRUE(build_delaunay3(p, dt).is_ok());
  b.pts = &p;
  b.n = p.size();
  b.tets = std::move(dt.tets);
  b.nbr = std::move(dt.neighbors);
  b.T0 = b.tets.size();
  b.ver.assign(b.T0, 0);
  b.mark.assign(b.T0, 0);
  detail::Tets none;
  b.reset_to_hull(none);
  return b;
}

double body_volume(const Body3& b) {
  std::vector<std::array<int, 4>> t;
  for (std::size_t i = 0; i < b.tets.size(); ++i)
    if (b.state[i] == detail::kAlive) t.push_back(b.tets[i]);
  return test::tets_volume(*b.pts, t);
}

// The body's invariants: what every stage must keep.
void expect_valid_body(const Body3& b, bool all_points, const char* what) {
  EXPECT_NO_THROW(b.check_body()) << what;
  MeshCheckOptions mo;
  mo.require_all_points = all_points;
  MeshCheck mc;
  EXPECT_TRUE(validate_mesh3(*b.pts, b.surface(), &mc, mo).is_ok()) << what << ": " << mc.reason;
  EXPECT_EQ(b.surface().triangles.size(), 2 * (all_points ? b.n : b.n_onb) - 4) << what;
  if (all_points) {
    EXPECT_EQ(b.n_onb, b.n) << what;
  }
}

TEST(Stages3, StartBodyIsTheConvexHull) {
  const PointSet p = cloud(200, 1);
  const Body3 b = start_body(p);
  expect_valid_body(b, false, "hull");
  EXPECT_LT(b.n_onb, b.n);
  EXPECT_EQ(b.inside().size(), b.n - b.n_onb);
}

TEST(Stages3, LabelsReachEveryTetrahedronAndMostOfAShellIsInside) {
  const PointSet p = shell(600, 2, 0.01);
  const Body3 b = start_body(p);
  const auto labels = detail::compute_labels3(b);
  ASSERT_EQ(labels->label.size(), b.T0);
  std::size_t inside = 0, zero = 0;
  for (float l : labels->label) {
    inside += l < 0;
    zero += l == 0;
    EXPECT_LE(std::abs(l), 1.0f);
  }
  EXPECT_EQ(zero, 0u);  // every tetrahedron got a label
  EXPECT_GT(inside, b.T0 * 2 / 3) << inside << " of " << b.T0;
  // Deterministic: the same labels again.
  EXPECT_EQ(detail::compute_labels3(b)->label, labels->label);
  // Work run beside the propagation (the engine's spacing) has finished when the labels return,
  // and changes neither the labels nor its own result.
  std::vector<double> spacing;
  const auto beside = detail::compute_labels3(b, [&] { spacing = detail::nearest_spacing3(b); });
  EXPECT_EQ(beside->label, labels->label);
  EXPECT_EQ(beside->lrad, labels->lrad);
  EXPECT_EQ(spacing, detail::nearest_spacing3(b));
}

TEST(Stages3, EveryRemovalOfTheConstrictionKeepsAValidBody) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const PointSet p = cloud(60, seed);
    Body3 b = start_body(p);
    auto dg = std::make_shared<DelaunayGamma3>();
    ASSERT_TRUE(delaunay_gamma3(p, *dg, false).is_ok());
    detail::Keys3 keys;
    keys.terms = detail::compute_face_terms3(b, *dg);
    keys.dg = dg;
    detail::Constriction3State st;
    const Constrict3Options opt = Constrict3Options::paper();
    detail::HullConstriction3 hc(b, st, keys, opt, nullptr);
    hc.start_heap();
    std::size_t steps = 0;
    while (b.n_onb < b.n && hc.pop_and_remove(-1e300, Stage3::Gamma)) {
      ++steps;
      expect_valid_body(b, false, "after a removal");
      if (::testing::Test::HasFailure()) {
        std::cout << "seed " << seed << " step " << steps << '\n';
        return;
      }
    }
    EXPECT_GT(steps, 0u) << "seed " << seed;
    EXPECT_EQ(st.removed, st.removed1 + st.removed2);
  }
}

TEST(Stages3, BodyCavityKeepsTheVolumeAndOpensAFaceForTheStuckPoint) {
  std::size_t tried = 0, placed = 0;
  for (std::uint64_t seed : {78u, 151u, 189u, 284u}) {
    const PointSet p = locking_cloud(seed);
    Body3 b = start_body(p);
    auto dg = std::make_shared<DelaunayGamma3>();
    ASSERT_TRUE(delaunay_gamma3(p, *dg, false).is_ok());
    detail::Keys3 keys;
    keys.dg = dg;
    keys.terms = detail::compute_face_terms3(b, *dg);
    detail::Constriction3State st;
    const Constrict3Options opt = Constrict3Options::paper();
    detail::HullConstriction3 hc(b, st, keys, opt, nullptr);
    hc.start_heap();
    while (b.n_onb < b.n && hc.pop_and_remove(-1e300, Stage3::Gamma)) {
    }
    if (b.n_onb == b.n) continue;  // no lock on this seed
    ++tried;
    detail::CavityState3 cs;
    detail::Cavity3 cav(b, cs, opt, detail::CavitySide::Body, nullptr);
    cav.index_vertices();
    for (int q : b.inside()) {
      const double v0 = body_volume(b);
      detail::CavityMade made;
      if (!cav.place(q, made)) continue;
      ++placed;
      EXPECT_NEAR(body_volume(b), v0, 1e-12 * (1 + std::abs(v0))) << "seed " << seed;
      bool opened = false;  // a cone over a surface face with apex q
      for (int t : made.created) opened = opened || (b.tets[detail::uz(t)][3] == q && b.boundary_face(t, 3));
      EXPECT_TRUE(opened) << "seed " << seed;
      expect_valid_body(b, false, "after a cavity");
      break;
    }
  }
  EXPECT_EQ(tried, 4u) << "the clouds no longer lock";
  EXPECT_GT(placed, 0u);
}

TEST(Stages3, GrowthReachesEveryPointOfAShellAndFillKeepsItValid) {
  const PointSet p = shell(800, 3);
  Body3 b = start_body(p);
  const auto labels = detail::compute_labels3(b);
  detail::Growth3Stats gs;
  detail::Tets nbr0;
  ASSERT_TRUE(detail::grow_body3(b, *labels, Constrict3Options{}, nullptr, gs, nbr0));
  expect_valid_body(b, true, "grown");
  std::size_t alive = 0;
  for (auto s : b.state) alive += s == detail::kAlive;
  EXPECT_EQ(alive, gs.grown);
  detail::Carve3Stats fs;
  const std::size_t filled = detail::fill_inside3(b, *labels, 0.5, fs);
  expect_valid_body(b, true, "filled");
  EXPECT_EQ(filled, fs.changed);
}

// The growth's inside phase against its definition, written out with an ordered set: the inside
// tetrahedra are examined largest key first (kInsideKeyBase + ln r clamped, equal keys by the
// smallest sorted vertex ids), each once per neighbour added, and join by the one-face rule (the
// vertex opposite the glued face not yet in the body) or the two-face rule (the edge between the
// vertices opposite the glued faces not yet in the body). The growth ranks the tetrahedra and pops
// the smallest rank of a bit set: the bodies must be the same. Shells of random points, and points
// on a sphere on a latitude-longitude grid (every circumball the same up to rounding: ties).
TEST(Stages3, GrowthTakesTheInsideTetrahedraInKeyOrder) {
  struct Case {
    const char* name;
    PointSet p;
  };
  std::vector<Case> cases;
  for (const unsigned seed : {3u, 11u}) cases.push_back({"shell", shell(1500, seed, 0.0)});
  cases.push_back(
      {"large shell", shell(25000, 5, 0.0)});  // (more inside tetrahedra than bucket_sort sorts in one piece)
  {
    PointSet g;
    g.dim = 3;
    g.coords = {0, 0, 1, 0, 0, -1};
    for (int i = 1; i < 12; ++i)
      for (int j = 0; j < 16; ++j) {
        const double th = M_PI * i / 12, ph = 2 * M_PI * j / 16;
        g.coords.insert(g.coords.end(), {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
      }
    cases.push_back({"sphere grid", g});
  }
  {
    PointSet box;
    box.dim = 3;
    for (int x = 0; x <= 6; ++x)
      for (int y = 0; y <= 5; ++y)
        for (int z = 0; z <= 4; ++z)
          if (x == 0 || x == 6 || y == 0 || y == 5 || z == 0 || z == 4)
            box.coords.insert(box.coords.end(), {double(x), double(y), double(z)});
    cases.push_back({"lattice box", box});
    PointSet torus;
    torus.dim = 3;
    for (int i = 0; i < 24; ++i)
      for (int j = 0; j < 10; ++j) {
        const double u = 2 * M_PI * i / 24, v = 2 * M_PI * j / 10;
        torus.coords.insert(torus.coords.end(),
                            {(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
      }
    cases.push_back({"grid torus", torus});
  }
  for (const Case& c : cases) {
    Body3 b = start_body(c.p);
    const auto labels = detail::compute_labels3(b);
    Constrict3Options none;
    none.fallback = Fallback3::None;
    detail::Growth3Stats gs;
    detail::Tets nbr0;
    detail::grow_body3(b, *labels, none, nullptr, gs, nbr0);
    ASSERT_EQ(gs.grown_outside, 0u) << c.name << ": the reference covers the inside phase only";

    // The definition.
    const std::size_t T0 = b.T0;
    const auto key = [&](std::size_t t) { return 1000.0 + std::max(-500.0, labels->lrad[t]); };
    const auto before = [&](int x, int y) {  // x is examined before y
      if (key(static_cast<std::size_t>(x)) != key(static_cast<std::size_t>(y)))
        return key(static_cast<std::size_t>(x)) > key(static_cast<std::size_t>(y));
      return detail::sorted4(b.tets[static_cast<std::size_t>(x)]) <
             detail::sorted4(b.tets[static_cast<std::size_t>(y)]);
    };
    std::set<int, decltype(before)> queue(before);
    std::vector<char> alive(T0, 0), queued(T0, 0), onb(b.n, 0);
    std::set<std::pair<int, int>> edges;
    const auto edge = [](int u, int v) { return std::make_pair(std::min(u, v), std::max(u, v)); };
    const auto add = [&](int t) {
      alive[static_cast<std::size_t>(t)] = 1;
      const auto& v = b.tets[static_cast<std::size_t>(t)];
      for (int i = 0; i < 4; ++i) {
        onb[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])] = 1;
        for (int j = i + 1; j < 4; ++j)
          edges.insert(edge(v[static_cast<std::size_t>(i)], v[static_cast<std::size_t>(j)]));
      }
      for (int m : b.nbr[static_cast<std::size_t>(t)])
        if (m >= 0 && !alive[static_cast<std::size_t>(m)] && !queued[static_cast<std::size_t>(m)] &&
            labels->label[static_cast<std::size_t>(m)] < 0) {
          queued[static_cast<std::size_t>(m)] = 1;
          queue.insert(m);
        }
    };
    int seed = -1;
    for (std::size_t t = 0; t < T0; ++t)
      if (labels->label[t] < 0 && labels->lrad[t] > detail::kFlatLogRadius &&
          (seed < 0 || labels->lrad[t] > labels->lrad[static_cast<std::size_t>(seed)] ||
           (labels->lrad[t] == labels->lrad[static_cast<std::size_t>(seed)] &&
            detail::sorted4(b.tets[t]) < detail::sorted4(b.tets[static_cast<std::size_t>(seed)]))))
        seed = static_cast<int>(t);
    ASSERT_GE(seed, 0) << c.name;
    add(seed);
    std::size_t ties = 0;
    while (!queue.empty()) {
      const int t = *queue.begin();
      queue.erase(queue.begin());
      if (!queue.empty() && key(static_cast<std::size_t>(*queue.begin())) == key(static_cast<std::size_t>(t))) ++ties;
      queued[static_cast<std::size_t>(t)] = 0;
      const auto& v = b.tets[static_cast<std::size_t>(t)];
      int glued[4], ng = 0;
      for (int i = 0; i < 4; ++i) {
        const int m = b.nbr[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)];
        if (m >= 0 && alive[static_cast<std::size_t>(m)]) glued[ng++] = i;
      }
      const bool joins =
          (ng == 1 && !onb[static_cast<std::size_t>(v[static_cast<std::size_t>(glued[0])])]) ||
          (ng == 2 && !edges.count(edge(v[static_cast<std::size_t>(glued[0])], v[static_cast<std::size_t>(glued[1])])));
      if (joins) add(t);
    }
    std::size_t differ = 0, grown = 0;
    for (std::size_t t = 0; t < T0; ++t) {
      differ += (b.state[t] == detail::kAlive) != (alive[t] != 0);
      grown += alive[t];
    }
    EXPECT_EQ(differ, 0u) << c.name << ": " << grown << " tetrahedra grown by the definition";
    EXPECT_EQ(grown, gs.grown) << c.name;
    std::cout << c.name << ": " << grown << " tetrahedra grown, " << ties << " pops tied with the next\n";
  }
}

// Sparse fingers whose growth closes its front around a pocket labelled inside with a point in it
// (docs/reconstruction-3d.md §4.13): without cavities the growth leaves the point; the fill in its
// reaching mode takes the pocket with it, and every state is a closed genus-0 2-manifold through
// the points in the body.
TEST(Stages3, FillBeforeTheCavitiesBringsInThePointOfAPocket) {
  const double h = 2 / std::sqrt(0.35);
  const PointSet p =
      test::random_subset(test::make_gap_object(test::GapShape::Fingers, 2 * h, 4 * h, 2, 6), 0.35, 6).points;
  Body3 b = start_body(p);
  const auto labels = detail::compute_labels3(b);
  const std::vector<double> spacing = detail::nearest_spacing3(b);
  Constrict3Options none;
  none.fallback = Fallback3::None;
  detail::Growth3Stats gs;
  detail::Tets nbr0;
  EXPECT_FALSE(detail::grow_body3(b, *labels, none, nullptr, gs, nbr0, &spacing));
  const std::size_t left = b.n - b.n_onb;
  EXPECT_GE(left, 1u);
  expect_valid_body(b, false, "grown, points left");
  // The ordinary fill needs every point in the body: it does nothing here.
  detail::Carve3Stats plain;
  EXPECT_EQ(detail::fill_inside3(b, *labels, 0.5, plain), 0u);
  detail::Carve3Stats fs;
  const std::size_t filled = detail::fill_inside3(b, *labels, 0.5, fs, /*reach=*/true);
  std::cout << "[ pocket ] points left by the growth " << left << ", tetrahedra filled " << filled << "\n";
  EXPECT_GT(filled, 0u);
  expect_valid_body(b, true, "pocket filled");
}

TEST(Stages3, CarveAndFlipsKeepEveryPointOnAValidSurface) {
  const PointSet p = shell(500, 4);
  Body3 b = start_body(p);
  auto dg = std::make_shared<DelaunayGamma3>();
  ASSERT_TRUE(delaunay_gamma3(p, *dg, false).is_ok());
  detail::Keys3 keys;
  keys.dg = dg;
  keys.terms = detail::compute_face_terms3(b, *dg);
  keys.labels = detail::compute_labels3(b);
  detail::Constriction3State st;
  Constrict3Options opt = Constrict3Options::paper();
  detail::HullConstriction3 hc(b, st, keys, opt, nullptr);
  hc.start_heap();
  while (b.n_onb < b.n && hc.pop_and_remove(-1e300, Stage3::Gamma)) {
  }
  if (b.n_onb < b.n) GTEST_SKIP() << "locked (the lock fallback is tested above)";
  detail::Carve3Stats cs;
  detail::carve_outside3(b, *keys.labels, 0.5, cs);
  expect_valid_body(b, true, "carved");
  const double a0 = mesh_area(p, b.surface());
  detail::Flips3Stats fl;
  detail::flip_pass3(b, Refine3::Area, fl);
  expect_valid_body(b, true, "flipped");
  EXPECT_GT(fl.added + fl.removed, 0u);
  EXPECT_LT(mesh_area(p, b.surface()), a0);
}

// Points on a line and two off it: one edge (the two off the line) lies in every tetrahedron, and
// every tetrahedron is a flip candidate whose test walks around that edge. Such a candidate is
// not tried past kMaxFlipRing tetrahedra around its edge (the walks made 10^5 points take 67 s),
// and the surface stays valid; on an ordinary sample none is skipped.
TEST(Stages3, FlipsSkipEdgesInVeryManyTetrahedra) {
  PointSet p;
  p.dim = 3;
  for (int i = 0; i < 3000; ++i) p.coords.insert(p.coords.end(), {double(i), 0.0, 0.0});
  p.coords.insert(p.coords.end(), {0.0, 1.0, 0.0, 0.0, 0.0, 1.0});
  Body3 b = start_body(p);
  detail::Flips3Stats fl;
  detail::flip_pass3(b, Refine3::Circumradius, fl);  // (by area no flip gains: the walk is not reached)
  expect_valid_body(b, false, "flipped");
  EXPECT_GT(fl.long_rings, 0u);
  const PointSet q = shell(500, 4);
  Body3 c = start_body(q);
  detail::Flips3Stats fq;
  detail::flip_pass3(c, Refine3::Circumradius, fq);
  expect_valid_body(c, false, "flipped");
  EXPECT_EQ(fq.long_rings, 0u);
}

// Integer points on the sphere x² + y² + z² = r2 (exactly cospherical: every Delaunay
// tetrahedron is one of many of the same circumsphere), and the lattice points on the surface of
// the cube [0, k]³ (coplanar and cospherical groups): degenerate inputs for the stages' counts.
PointSet lattice_sphere(int r2) {
  PointSet p;
  p.dim = 3;
  const int r = static_cast<int>(std::sqrt(r2)) + 1;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z == r2) p.coords.insert(p.coords.end(), {double(x), double(y), double(z)});
  return p;
}
PointSet lattice_cube_surface(int k) {
  PointSet p;
  p.dim = 3;
  for (int x = 0; x <= k; ++x)
    for (int y = 0; y <= k; ++y)
      for (int z = 0; z <= k; ++z)
        if (x == 0 || y == 0 || z == 0 || x == k || y == k || z == k)
          p.coords.insert(p.coords.end(), {double(x), double(y), double(z)});
  return p;
}

// The growth sizes its per-vertex edge lists by the Delaunay degree from Euler's formula on the
// vertex star (it throws when a list overflows), and the carve takes its edge flips without
// evaluating the links: both on degenerate inputs, with the body checked after each stage.
TEST(Stages3, GrowthAndCarveOnCosphericalLattices) {
  const std::vector<std::pair<std::string, PointSet>> inputs = {
      {"sphere r2=169", lattice_sphere(169)}, {"sphere r2=325", lattice_sphere(325)},
      {"cube surface 6", lattice_cube_surface(6)}, {"cube surface 9", lattice_cube_surface(9)}};
  for (const auto& [name, p] : inputs) {
    SCOPED_TRACE(name);
    ASSERT_GT(p.size(), 30u);
    {  // the growth from the inside
      Body3 b = start_body(p);
      const auto labels = detail::compute_labels3(b);
      detail::Growth3Stats gs;
      detail::Tets nbr0;
      bool grown = false;
      ASSERT_NO_THROW(grown = detail::grow_body3(b, *labels, Constrict3Options{}, nullptr, gs, nbr0));
      expect_valid_body(b, grown, "grown");
    }
    {  // every point is on the hull: the carve from the convex hull
      Body3 b = start_body(p);
      if (b.n_onb < b.n) continue;  // (the cube's face points are inside its hull's faces' planes)
      const auto labels = detail::compute_labels3(b);
      detail::Carve3Stats cs;
      ASSERT_NO_THROW(detail::carve_outside3(b, *labels, 0.5, cs));
      expect_valid_body(b, true, "carved");
    }
  }
}

TEST(Stages3, VariantSelectionKeepsTheSmallestCompleteSurface) {
  const PointSet p = cloud(150, 7);
  Constrict3Options both;
  both.grow = false;
  Mesh3Result r;
  ASSERT_TRUE(reconstruct3(p, both, r).is_ok());
  ASSERT_EQ(r.candidates.size(), both.variants.size());
  double best = HUGE_VAL;
  TriMesh3 best_mesh;
  for (const Constrict3Variant& v : both.variants) {
    Constrict3Options one = both;
    one.variants = {v};
    Mesh3Result s;
    ASSERT_TRUE(reconstruct3(p, one, s).is_ok());
    ASSERT_TRUE(s.valid());
    if (s.surface_area < best) {
      best = s.surface_area;
      best_mesh = s.mesh;
    }
  }
  EXPECT_EQ(r.surface_area, best);
  EXPECT_EQ(r.mesh.triangles, best_mesh.triangles);
  EXPECT_TRUE(r.valid());
}

TEST(Stages3, PresetsAndNames) {
  Constrict3Options o;
  ASSERT_TRUE(Constrict3Options::from_preset("paper", o).is_ok());
  EXPECT_EQ(o.two_face_key, TwoFaceKey::Sum);
  EXPECT_FALSE(o.grow);
  EXPECT_TRUE(o.variants.empty());
  EXPECT_EQ(o.size_bias, 0);
  EXPECT_EQ(o.label_weight, 0);
  EXPECT_EQ(o.refine, Refine3::None);
  EXPECT_FALSE(Constrict3Options::from_preset("fastest", o).is_ok());
  Fallback3 f = Fallback3::Auto;
  EXPECT_TRUE(fallback3_from_name("none", f));
  EXPECT_EQ(f, Fallback3::None);
  EXPECT_FALSE(fallback3_from_name("degree4", f));
  EXPECT_STREQ(to_string(Stage3::Candidates), "candidates");
  EXPECT_STREQ(to_string(Method3::VoronoiSkeleton), "voronoi-skeleton");
  Fallback g = Fallback::Auto;
  EXPECT_TRUE(fallback_from_name("degree4", g));
  EXPECT_EQ(g, Fallback::Degree4);
  EXPECT_STREQ(to_string(Fallback::Gamma0), "gamma0");
}

}  // namespace
}  // namespace constrict

namespace constrict {
namespace {

// The parallel gathers and scans of the engine's last steps against their sequential definitions,
// on bodies large enough for several blocks (ordered_pack: 2^15 items, first_index: 2^14).

// nearest_spacing3 (parallel, squared lengths, one root) is the shortest Delaunay edge at each
// point, bit for bit.
TEST(Stages3, NearestSpacingIsTheShortestDelaunayEdgeAtEveryPoint) {
  for (const std::size_t n : {std::size_t{50}, std::size_t{20000}}) {
    const PointSet p = cloud(n, 7);
    const Body3 b = start_body(p);
    std::vector<double> want(b.n, HUGE_VAL);
    for (std::size_t t = 0; t < b.T0; ++t)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const int x = b.tets[t][static_cast<std::size_t>(i)], y = b.tets[t][static_cast<std::size_t>(j)];
          const double dx = b.P(x)[0] - b.P(y)[0], dy = b.P(x)[1] - b.P(y)[1], dz = b.P(x)[2] - b.P(y)[2];
          const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
          want[static_cast<std::size_t>(x)] = std::min(want[static_cast<std::size_t>(x)], l);
          want[static_cast<std::size_t>(y)] = std::min(want[static_cast<std::size_t>(y)], l);
        }
    EXPECT_EQ(detail::nearest_spacing3(b), want) << n << " points";
  }
}

// Body3::side_connected against its definition, a search: kAlive, one face-connected piece;
// kOutside, every outside piece reaches the convex hull. States: random (mostly broken), a piece
// grown by a search from one tetrahedron (whole; the rest then outside, a void only where the
// growth enclosed one), and that piece with one tetrahedron taken out (split or not).
TEST(Stages3, SideConnectedIsTheSearchDefinition) {
  const auto reference = [](const Body3& b, std::uint8_t side) {
    std::vector<char> seen(b.tets.size(), 0);
    std::vector<int> st;
    for (std::size_t t = 0; t < b.tets.size(); ++t) {
      if (b.state[t] != side) continue;
      bool start = side == detail::kAlive;
      for (int m : b.nbr[t]) start = start || m < 0;
      if (!start) continue;
      seen[t] = 1;
      st.push_back(static_cast<int>(t));
      if (side == detail::kAlive) break;
    }
    if (side == detail::kAlive && st.empty()) return false;
    while (!st.empty()) {
      const int t = st.back();
      st.pop_back();
      for (int m : b.nbr[static_cast<std::size_t>(t)])
        if (m >= 0 && b.state[static_cast<std::size_t>(m)] == side && !seen[static_cast<std::size_t>(m)]) {
          seen[static_cast<std::size_t>(m)] = 1;
          st.push_back(m);
        }
    }
    for (std::size_t t = 0; t < b.tets.size(); ++t)
      if (b.state[t] == side && !seen[t]) return false;
    return true;
  };
  int agreed[2][2] = {{0, 0}, {0, 0}};  // [side][answer]
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const PointSet p = cloud(300, seed);
    Body3 b = start_body(p);
    std::mt19937 rng(seed);
    const std::size_t nt = b.tets.size();
    for (int trial = 0; trial < 12; ++trial) {
      const int kind = trial % 3;
      if (kind == 0) {
        const double keep = std::uniform_real_distribution<double>(0.5, 1.0)(rng);
        for (std::size_t t = 0; t < nt; ++t)
          b.state[t] = std::uniform_real_distribution<double>(0, 1)(rng) < keep ? detail::kAlive : detail::kOutside;
      } else {
        std::fill(b.state.begin(), b.state.end(), detail::kOutside);
        const std::size_t want = std::uniform_int_distribution<std::size_t>(1, nt)(rng);
        std::vector<int> st{static_cast<int>(std::uniform_int_distribution<std::size_t>(0, nt - 1)(rng))};
        b.state[static_cast<std::size_t>(st[0])] = detail::kAlive;
        std::vector<int> grown = st;
        while (!st.empty() && grown.size() < want) {
          const int t = st.back();
          st.pop_back();
          for (int m : b.nbr[static_cast<std::size_t>(t)])
            if (m >= 0 && b.state[static_cast<std::size_t>(m)] != detail::kAlive && grown.size() < want) {
              b.state[static_cast<std::size_t>(m)] = detail::kAlive;
              grown.push_back(m);
              st.push_back(m);
            }
        }
        if (kind == 2 && grown.size() > 2)
          b.state[static_cast<std::size_t>(grown[std::uniform_int_distribution<std::size_t>(1, grown.size() - 1)(rng)])] =
              detail::kOutside;
      }
      for (const std::uint8_t side : {detail::kAlive, detail::kOutside}) {
        const bool want = reference(b, side);
        ASSERT_EQ(b.side_connected(side), want) << "seed " << seed << ", trial " << trial << ", side " << int(side);
        ++agreed[side == detail::kAlive ? 0 : 1][want ? 1 : 0];
      }
    }
  }
  // Both answers met on both sides (a check that cannot fail on one answer is no check).
  for (const auto& a : agreed) {
    EXPECT_GT(a[0], 0);
    EXPECT_GT(a[1], 0);
  }
}

// bucket_sort (core/detail/bucket_sort.hpp) gives the order of its comparator, on one thread and
// on several: keys spread over the whole range, clustered in a few values (long runs of equal keys
// that the comparator's second field decides), all equal, and with extremes (0 and 2^64 - 1).
TEST(Stages3, BucketSortIsTheComparatorsOrderOnAnyThreadCount) {
  struct Item {
    std::uint64_t key;
    int id;
  };
  const auto less = [](const Item& x, const Item& y) { return x.key != y.key ? x.key < y.key : x.id > y.id; };
  for (const std::size_t n :
       {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{70000}, std::size_t{400000}})
    for (int kind = 0; kind < 4; ++kind) {
      const std::uint64_t seed = 1000 * n + static_cast<std::uint64_t>(kind);
      std::uint64_t s = seed;
      std::vector<Item> items(n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t r = test::splitmix64(s);
        const std::uint64_t k = kind == 0   ? r
                                : kind == 1 ? (r % 7) * 1000003
                                : kind == 2 ? 42
                                            : (r & 1 ? ~std::uint64_t{0} : r % 3);
        items[i] = {k, static_cast<int>(i)};
      }
      std::vector<Item> want = items;
      std::sort(want.begin(), want.end(), less);
      for (const int threads : {1, 2}) {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        detail::BigArray<Item> got;
        got.allocate(n);
        std::copy(items.begin(), items.end(), got.data());
        detail::bucket_sort(
            got, [](const Item& x) { return x.key; }, less);
        std::size_t bad = 0;
        for (std::size_t i = 0; i < n; ++i) bad += got[i].id != want[i].id;
        EXPECT_EQ(bad, 0u) << "n " << n << ", keys " << kind << ", seed " << seed << ", threads " << threads;
      }
    }
}

// RankQueue (core/detail/rank_queue.hpp) pops the smallest rank in the set, against std::set: random
// pushes and pops, pushes that all go below the last pop (descending), and sizes at the ends of
// its words and levels.
TEST(Stages3, RankQueuePopsTheSmallestRank) {
  for (const std::size_t n :
       {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{65}, std::size_t{4097}, std::size_t{262145}})
    for (int pattern = 0; pattern < 3; ++pattern) {
      std::uint64_t s = 77 * n + static_cast<std::uint64_t>(pattern);
      detail::RankQueue q;
      q.reset(n);
      std::set<std::uint32_t> want;
      std::vector<char> in(n, 0);
      std::size_t bad = 0, ops = 0;
      std::uint32_t next_down = static_cast<std::uint32_t>(n);
      for (std::size_t step = 0; step < 3 * n + 10; ++step) {
        const std::uint64_t r = test::splitmix64(s);
        const bool push = pattern == 1 ? next_down > 0 && r % 3 != 0 : r % 2 == 0;
        if (push) {
          std::uint32_t k = pattern == 1 ? --next_down : static_cast<std::uint32_t>((r >> 8) % n);
          if (pattern == 2)
            k = static_cast<std::uint32_t>(((r >> 8) % 2 ? n - 1 - (r >> 16) % 64 % n : (r >> 16) % 64 % n));
          if (in[k]) continue;
          in[k] = 1;
          q.push(k);
          want.insert(k);
        } else if (!want.empty()) {
          ASSERT_FALSE(q.empty());
          const std::uint32_t got = q.pop();
          bad += got != *want.begin();
          in[*want.begin()] = 0;
          want.erase(want.begin());
        }
        ++ops;
        bad += q.empty() != want.empty();
      }
      while (!want.empty()) {
        bad += q.pop() != *want.begin();
        want.erase(want.begin());
      }
      EXPECT_TRUE(q.empty());
      EXPECT_EQ(bad, 0u) << "n " << n << ", pattern " << pattern << ", " << ops << " operations";
    }
}

// The growth's room for each vertex's body edges (prepare_growth3, by Euler's formula from the
// vertex's star) is its number of Delaunay edges, on a shell (hull and inner points) and a cloud.
TEST(Stages3, GrowthEdgeRoomIsTheDelaunayDegree) {
  for (const PointSet& p : {shell(3000, 5), cloud(3000, 9)}) {
    const Body3 b = start_body(p);
    std::set<std::pair<int, int>> edges;
    for (std::size_t t = 0; t < b.T0; ++t)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const int u = b.tets[t][static_cast<std::size_t>(i)], v = b.tets[t][static_cast<std::size_t>(j)];
          edges.insert({std::min(u, v), std::max(u, v)});
        }
    std::vector<std::size_t> degree(b.n, 0);
    for (const auto& e : edges) {
      ++degree[static_cast<std::size_t>(e.first)];
      ++degree[static_cast<std::size_t>(e.second)];
    }
    const detail::GrowthPrep3 prep = detail::prepare_growth3(b);
    ASSERT_EQ(prep.edge_room.size(), b.n + 1);
    std::size_t bad = 0;
    for (std::size_t v = 0; v < b.n; ++v) bad += prep.edge_room[v + 1] - prep.edge_room[v] != degree[v];
    EXPECT_EQ(bad, 0u) << b.n << " points";
  }
}

// Body3::surface (ordered_pack) gives the faces of the sequential loop in the same order.
TEST(Stages3, SurfaceIsGatheredInTetrahedronOrder) {
  const PointSet p = shell(20000, 3, 0.05);
  Body3 b = start_body(p);
  // Some tetrahedra out of the body (a surface with faces all through the index range); the
  // gather must follow the state whatever it is.
  for (std::size_t t = 0; t < b.T0; t += 7) b.state[t] = detail::kOutside;
  std::vector<std::array<int, 3>> want;
  for (std::size_t t = 0; t < b.tets.size(); ++t) {
    if (b.state[t] != detail::kAlive) continue;
    for (int i = 0; i < 4; ++i)
      if (b.boundary_face(static_cast<int>(t), i)) {
        const auto& v = b.tets[t];
        want.push_back(
            {{v[static_cast<std::size_t>(detail::kFaceOut[i][0])], v[static_cast<std::size_t>(detail::kFaceOut[i][1])],
              v[static_cast<std::size_t>(detail::kFaceOut[i][2])]}});
      }
  }
  ASSERT_GT(b.T0, std::size_t{1} << 16);
  EXPECT_EQ(b.surface().triangles, want);
}

// check_body reports the first broken invariant, also when it lies in a late block of the
// parallel scan.
TEST(Stages3, BodyCheckFindsABrokenTetrahedronAnywhere) {
  const PointSet p = cloud(20000, 5);
  const Body3 good = start_body(p);
  ASSERT_NO_THROW(good.check_body());
  const auto message = [](const Body3& b) {
    try {
      b.check_body();
    } catch (const InternalError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const std::size_t t : {std::size_t{3}, good.T0 / 2, good.T0 - 2}) {
    Body3 flipped = good;                               // a negative tetrahedron
    std::swap(flipped.tets[t][0], flipped.tets[t][1]);  // (with its neighbours: only the sign breaks)
    std::swap(flipped.nbr[t][0], flipped.nbr[t][1]);
    EXPECT_NE(message(flipped).find("not positive"), std::string::npos) << t;
    Body3 cut = good;  // a neighbour that does not point back
    const int m = cut.nbr[t][0] >= 0 ? cut.nbr[t][0] : cut.nbr[t][1];
    ASSERT_GE(m, 0);
    for (int& back : cut.nbr[static_cast<std::size_t>(m)])
      if (back == static_cast<int>(t)) back = -1;
    EXPECT_NE(message(cut).find("not symmetric"), std::string::npos) << t;
    // Out of the body, a broken tetrahedron is not the body's.
    flipped.state[t] = detail::kOutside;
    EXPECT_EQ(message(flipped), "") << t;
  }
}

// The bridge measure: none on an evenly sampled sphere; the paper's constriction from the hull
// leaves the bridges the growth avoids (bunny: 1,115 against 19 faces), and the measure sees them.
TEST(Stages3, BridgeMeasureSeesTheBridgesOfTheHullConstriction) {
  PointSet s;
  s.dim = 3;
  const int n = 500;
  for (int k = 0; k < n; ++k) {  // Fibonacci sphere: even spacing
    const double z = 1 - (2 * k + 1.0) / n, r = std::sqrt(1 - z * z), phi = k * 2.399963229728653;
    s.coords.insert(s.coords.end(), {r * std::cos(phi), r * std::sin(phi), z});
  }
  Mesh3Result rs;
  ASSERT_TRUE(reconstruct3(s, Constrict3Options{}, rs).is_ok());
  EXPECT_EQ(rs.bridge_faces, 0u);
  EXPECT_LT(rs.max_bridge_ratio, 2.0);
  PointSet p;
  const std::string path = std::string(CONSTRICT_SHARED_DIR) + "/data/3d/bunny_closed.xyz";
  if (!read_points(path, {}, p)) GTEST_SKIP() << path << " not found";
  Mesh3Result grown, paper;
  ASSERT_TRUE(reconstruct3(p, Constrict3Options{}, grown).is_ok());
  ASSERT_TRUE(reconstruct3(p, Constrict3Options::paper(), paper).is_ok());
  EXPECT_GT(paper.bridge_faces, 10 * grown.bridge_faces);
  EXPECT_GT(paper.bridge_area, 10 * grown.bridge_area);
  EXPECT_GE(paper.max_bridge_ratio, Mesh3Result::kBridgeRatio);
}

}  // namespace
}  // namespace constrict
