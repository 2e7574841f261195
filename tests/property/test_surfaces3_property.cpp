// SPDX-License-Identifier: GPL-3.0-or-later
// 3D auto topology (issue 16; docs/topology.md §"3D") on generated objects with known answers:
// separate spheres, hollow spheres (an inner shell), tori and linked tori (handles) get the right
// number of surfaces, total genus and roles; genus-0 controls get the single-mode surface; every
// result passes the library's validation and the exact self-intersection test; the answer does not
// depend on the point order, on an exact rotation (a permutation of the axes) or on a power-of-two
// scale. Seeds are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "surfaces3_gen.hpp"

namespace constrict {
namespace {

using test::Family3;
using Coord3 = std::array<double, 3>;

const char* name(Family3 f) {
  switch (f) {
    case Family3::Torus: return "torus";
    case Family3::Spheres: return "spheres";
    case Family3::Hollow: return "hollow";
    case Family3::Links: return "links";
    case Family3::Sphere: return "sphere";
    case Family3::Ellipsoid: return "ellipsoid";
    case Family3::Peanut: return "peanut";
    case Family3::Window: return "window";
    case Family3::Block: return "block";
    case Family3::Plate: return "plate";
    case Family3::Stack: return "stack";
    case Family3::Comb: return "comb";
  }
  return "?";
}

Surfaces3Result run_auto(const PointSet& p) {
  Surfaces3Options o;
  o.topology = Topology3::Auto;
  o.surface.validate_self_intersections = true;
  Surfaces3Result r;
  const Status s = reconstruct_surfaces3(p, o, r);
  EXPECT_TRUE(s.is_ok()) << s.message();
  return r;
}

// The surfaces as sets of coordinate triangles (each rotated to start at its smallest corner),
// with a role per surface: independent of the point order.
std::set<std::array<Coord3, 3>> coordinate_triangles(const PointSet& p, const TriMesh3& m) {
  std::set<std::array<Coord3, 3>> s;
  for (const auto& t : m.triangles) {
    std::array<Coord3, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = {p[t[k]][0], p[t[k]][1], p[t[k]][2]};
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    s.insert(c);
  }
  return s;
}

PointSet transformed(const PointSet& p, unsigned seed, int axes_shift, int exp2) {
  std::vector<std::size_t> perm(p.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  PointSet q;
  q.dim = 3;
  for (std::size_t i : perm)
    for (int k = 0; k < 3; ++k) q.coords.push_back(std::ldexp(p[i][(k + axes_shift) % 3], exp2));
  return q;
}

// Brute force, independent of the validator: every directed edge used once and its reverse once
// (closed, oriented, edge-manifold), and per surface V - E + F = 2 - 2 genus.
void expect_closed_oriented(const Surfaces3Result& r, const std::string& what) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : r.mesh.mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, c] : directed) {
    ASSERT_EQ(c, 1) << what << ": edge " << e.first << "-" << e.second << " used " << c << " times";
    ASSERT_EQ(directed.count({e.second, e.first}), 1u) << what << ": border edge";
  }
  for (const Surface3& x : r.surfaces) {
    const long long F = static_cast<long long>(x.triangles.size()), E = 3 * F / 2, V = static_cast<long long>(x.points.size());
    EXPECT_EQ(V - E + F, 2 - 2 * x.genus) << what;
  }
}

void expect_topology(const test::Sample3& s, const Surfaces3Result& r, const std::string& what) {
  ASSERT_TRUE(r.valid()) << what << ": " << r.check;
  expect_closed_oriented(r, what);
  EXPECT_EQ(r.surfaces.size(), static_cast<std::size_t>(s.surfaces)) << what;
  EXPECT_EQ(r.genus, s.genus) << what;
  int inner = 0;
  for (const Surface3& x : r.surfaces) {
    if (x.role == SurfaceRole::Inner) {
      ++inner;
      ASSERT_GE(x.parent, 0) << what;
      EXPECT_EQ(r.surfaces[static_cast<std::size_t>(x.parent)].role, SurfaceRole::Outer) << what;
    }
  }
  EXPECT_EQ(inner, s.inner) << what;
  // Every point on exactly one surface.
  std::vector<int> count(s.points.size(), 0);
  for (const Surface3& x : r.surfaces)
    for (int v : x.points) ++count[static_cast<std::size_t>(v)];
  EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; })) << what;
  // The body's volume is the solid's: positive, and an inner shell takes its cavity away.
  EXPECT_GT(r.mesh.volume, 0) << what;
}

TEST(Surfaces3Property, GeneratedFamiliesGetTheirTopology) {
  struct Case {
    Family3 f;
    double gap;
  };
  const Case cases[] = {{Family3::Torus, 0}, {Family3::Spheres, 3}, {Family3::Spheres, 6}, {Family3::Hollow, 4},
                        {Family3::Hollow, 6}, {Family3::Links, 0}};
  for (const Case& c : cases)
    for (unsigned seed : {1u, 2u}) {
      const test::Sample3 s = test::make_surfaces3(c.f, c.gap, seed);
      const std::string what = std::string(name(c.f)) + " gap " + std::to_string(c.gap) + " seed " + std::to_string(seed) +
                               " (" + std::to_string(s.points.size()) + " points)";
      std::cout << "[ info ] " << what << "\n";
      expect_topology(s, run_auto(s.points), what);
    }
}

// Two unit spheres 6 spacings apart, each sampled uniformly at random (Poisson, not blue noise)
// and moved by normal noise of 0.3 spacings: some faces of one sphere's own tetrahedralization are
// not Delaunay faces of all points, so the parts' body cannot be assembled from the common
// tetrahedralization. Their bounding boxes are apart: the body is the union of the parts' own
// bodies (before: the whole engine on all points, one surface bridging the gap, 3 of 3 seeds).
TEST(Surfaces3Property, NoisyRandomSpheresApartAreTwoSurfaces) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 1);
    const int per = 3000;
    const double h = std::sqrt(4 * 3.14159265358979323846 / per);
    test::Sample3 s;
    s.surfaces = 2;
    s.points.dim = 3;
    for (int k = 0; k < 2 * per; ++k) {
      const auto v = test::detail_gen3::on_sphere(rng, {k < per ? 0 : 2 + 6 * h, 0, 0}, 1.0);
      for (double c : v) s.points.coords.push_back(c + 0.3 * h * g(rng));
    }
    const Surfaces3Result r = run_auto(s.points);
    expect_topology(s, r, "noisy random spheres seed " + std::to_string(seed));
  }
}

// A hollow ball sampled uniformly at random (outer radius 1, inner 0.7, 12 000 + 8 000 points,
// about 5 spacings between the shells). Every outer point is on the convex hull, and so is every
// face of the outer surface: the parts' body assembly met the exterior from no side and failed,
// the engine ran on all points, and the handle stage closed loops across the cavity (genus 5 on
// one sample, 10 on another). Now: the outer surface and the inner shell, genus 0. (About one
// random sample in seven still has a face that is not Delaunay in all points, and then gives one
// genus-0 surface: docs/topology.md §Limits.)
// Uniformly random points on two concentric spheres: the outer part's own surface can keep a few
// nearly coplanar triangles on the diagonals that the inner points exclude (not Delaunay faces of
// all points); they are flipped before the body is assembled (seed 5 fails without the flips).
TEST(Surfaces3Property, RandomHollowBallIsTwoSurfaces) {
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u}) {
    std::mt19937_64 rng(seed);
    PointSet p;
    p.dim = 3;
    for (int k = 0; k < 20000; ++k) {
      const auto v = test::detail_gen3::on_sphere(rng, {0, 0, 0}, k < 12000 ? 1.0 : 0.7);
      p.coords.insert(p.coords.end(), v.begin(), v.end());
    }
    test::Sample3 s;
    s.points = p;
    s.surfaces = 2;
    s.inner = 1;
    expect_topology(s, run_auto(p), "random hollow ball, seed " + std::to_string(seed));
  }
}

// The same with normal noise of 0.3 spacings per coordinate: a point that noise moved off its
// shell leaves a tent of faces that are not Delaunay faces of all points, which no edge flip
// removes. The parts' surfaces are then put into the common tetrahedralization and the points
// where that body is not a surface are repaired (parts_body, SurfaceRepair in repair3.cpp).
// Before that, 1 of 8 numpy samples gave the two shells; now 7 of 8 (docs/topology.md §Limits).
TEST(Surfaces3Property, NoisyRandomHollowBallIsTwoSurfaces) {
  const double h = std::sqrt(4 * M_PI * (1.0 + 0.49) / 20000);  // mean spacing over both shells
  int right = 0;
  const std::vector<unsigned> seeds{1u, 2u, 3u, 4u, 5u, 6u};
  for (const unsigned seed : seeds) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 0.3 * h);
    PointSet p;
    p.dim = 3;
    for (int k = 0; k < 20000; ++k) {
      const auto v = test::detail_gen3::on_sphere(rng, {0, 0, 0}, k < 12000 ? 1.0 : 0.7);
      for (int c = 0; c < 3; ++c) p.coords.push_back(v[static_cast<std::size_t>(c)] + g(rng));
    }
    const std::string what = "noisy random hollow ball, seed " + std::to_string(seed);
    const Surfaces3Result r = run_auto(p);
    ASSERT_TRUE(r.valid()) << what << ": " << r.check;  // valid whatever the topology
    expect_closed_oriented(r, what);
    // Right: two surfaces, each holding exactly one shell's points, the inner one inside.
    bool ok = r.surfaces.size() == 2 && r.genus == 0;
    for (const Surface3& x : r.surfaces) {
      if (!ok) break;
      const bool inner = x.role == SurfaceRole::Inner;
      ok = x.points.size() == (inner ? 8000u : 12000u) &&
           std::all_of(x.points.begin(), x.points.end(), [&](int v) { return (v >= 12000) == inner; });
    }
    std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), decision " << to_string(r.decision)
              << ", " << r.repaired_tetrahedra << " tetrahedra repaired" << (ok ? "" : " (wrong)") << "\n";
    right += ok ? 1 : 0;
  }
  EXPECT_GE(right, 5) << "of " << seeds.size();
}

// A circle and its axis, 800 points each (two parts 1 apart, spacings 0.008 and 0.0025), with a
// little noise: a Delaunay tetrahedralization with hundreds of tetrahedra at every point, where
// the parts' surfaces are not Delaunay faces of all points. The point-by-point repair of their
// common body ran for more than 5 minutes (each link test reads every tetrahedron at its point);
// it now stops at its work bound and the single surface is used.
TEST(Surfaces3Property, CircleAndItsAxisStopTheRepairAtItsBound) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0, 1e-4);
  PointSet p;
  p.dim = 3;
  const int n = 800;
  for (int i = 0; i < 2 * n; ++i) {
    const double t = 2 * M_PI * (i % n) / n + 0.1234;
    const std::array<double, 3> v = i < n ? std::array<double, 3>{std::cos(t), std::sin(t), 0}
                                          : std::array<double, 3>{0, 0, -1 + 2.0 * (i - n) / (n - 1)};
    for (int c = 0; c < 3; ++c) p.coords.push_back(v[static_cast<std::size_t>(c)] + g(rng));
  }
  const Surfaces3Result r = run_auto(p);
  ASSERT_TRUE(r.valid()) << r.check;
  expect_closed_oriented(r, "circle and axis");
  EXPECT_EQ(r.parts, 2u);
  EXPECT_TRUE(r.repair_capped);
  EXPECT_EQ(r.decision, SurfacesDecision::NotDelaunay);
}

TEST(Surfaces3Property, GenusZeroControlsKeepTheSingleSurface) {
  for (Family3 f : {Family3::Sphere, Family3::Ellipsoid, Family3::Peanut})
    for (unsigned seed : {1u, 2u, 3u}) {
      const test::Sample3 s = test::make_surfaces3(f, 0, seed);
      const std::string what = std::string(name(f)) + " seed " + std::to_string(seed);
      std::cout << "[ info ] " << what << "\n";
      const Surfaces3Result a = run_auto(s.points);
      expect_topology(s, a, what);
      Mesh3Result single;
      ASSERT_TRUE(reconstruct3(s.points, Constrict3Options{}, single).is_ok());
      EXPECT_EQ(coordinate_triangles(s.points, a.mesh.mesh), coordinate_triangles(s.points, single.mesh)) << what;
    }
}

TEST(Surfaces3Property, NoisyAndSparseControlsStayOneSurface) {
  // Radial noise of 0.3 spacings, and a sparse sampling (spacing 0.3 on the unit sphere).
  for (unsigned seed : {4u, 5u}) {
    test::Sample3 s = test::make_surfaces3(Family3::Ellipsoid, 0, seed);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 1);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < s.points.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], s.points[i][k]);
        hi[k] = std::max(hi[k], s.points[i][k]);
      }
    const double h = 0.12 * (hi[0] - lo[0]) / 2.8;  // (the generator's spacing, after its scale)
    for (double& c : s.points.coords) c += 0.3 * h * g(rng) / std::sqrt(3.0);
    const std::string what = "noisy ellipsoid seed " + std::to_string(seed);
    std::cout << "[ info ] " << what << "\n";
    expect_topology(s, run_auto(s.points), what);
    const test::Sample3 sparse = test::make_surfaces3(Family3::Sphere, 0, seed, 0.3);
    expect_topology(sparse, run_auto(sparse.points), "sparse sphere seed " + std::to_string(seed));
  }
}

TEST(Surfaces3Property, DecisionIndependentOfOrderRotationAndScale) {
  for (Family3 f : {Family3::Torus, Family3::Spheres, Family3::Hollow}) {
    const unsigned seed = 7;
    const test::Sample3 s = test::make_surfaces3(f, 4, seed);
    const std::string what = std::string(name(f)) + " seed " + std::to_string(seed);
    std::cout << "[ info ] " << what << "\n";
    const Surfaces3Result a = run_auto(s.points);
    ASSERT_TRUE(a.valid()) << what;
    // Back-transform each triangle set into the original coordinates and compare.
    for (const auto& [shift, exp2] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {2, -20}, {0, 30}}) {
      const PointSet q = transformed(s.points, seed + static_cast<unsigned>(shift) + 11u, shift, exp2);
      const Surfaces3Result b = run_auto(q);
      ASSERT_TRUE(b.valid()) << what;
      EXPECT_EQ(b.surfaces.size(), a.surfaces.size()) << what << " shift " << shift << " 2^" << exp2;
      EXPECT_EQ(b.genus, a.genus) << what;
      std::set<std::array<Coord3, 3>> back;
      for (const auto& t : coordinate_triangles(q, b.mesh.mesh)) {
        std::array<Coord3, 3> c;
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) c[k][static_cast<std::size_t>((j + shift) % 3)] = std::ldexp(t[k][j], -exp2);
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        back.insert(c);
      }
      EXPECT_EQ(back, coordinate_triangles(s.points, a.mesh.mesh)) << what << " shift " << shift << " 2^" << exp2;
    }
  }
}

TEST(Surfaces3Property, SingleModeIsReconstruct3) {
  const test::Sample3 s = test::make_surfaces3(Family3::Spheres, 4, 3);
  Surfaces3Options o;
  Surfaces3Result r;
  ASSERT_TRUE(reconstruct_surfaces3(s.points, o, r).is_ok());
  Mesh3Result single;
  ASSERT_TRUE(reconstruct3(s.points, Constrict3Options{}, single).is_ok());
  EXPECT_EQ(r.mesh.mesh.triangles, single.mesh.triangles);
  ASSERT_EQ(r.surfaces.size(), 1u);  // the paper's answer: one genus-0 surface joining both spheres
  EXPECT_EQ(r.genus, 0);
}

TEST(Surfaces3Property, GapOptionMovesTheSplit) {
  const test::Sample3 s = test::make_surfaces3(Family3::Spheres, 4, 5);
  Surfaces3Options o;
  o.topology = Topology3::Auto;
  o.topology_gap = 50;  // no gap this wide: one part
  Surfaces3Result r;
  ASSERT_TRUE(reconstruct_surfaces3(s.points, o, r).is_ok());
  EXPECT_EQ(r.parts, 1u);
  o.topology_gap = -1;
  EXPECT_EQ(reconstruct_surfaces3(s.points, o, r).code(), StatusCode::InvalidArgument);
}


TEST(Surfaces3Property, BodyCheckRejectsBrokenBodies) {
  const test::Sample3 s = test::make_surfaces3(Family3::Hollow, 4, 9);
  const Surfaces3Result r = run_auto(s.points);
  ASSERT_TRUE(r.valid());
  const TriMesh3& m = r.mesh.mesh;
  const auto& body = r.mesh.tets;
  EXPECT_TRUE(validate_body3(s.points, m, body).is_ok());
  TriMesh3 flipped = m;  // one surface triangle facing into the body
  std::swap(flipped.triangles[7][1], flipped.triangles[7][2]);
  EXPECT_NE(validate_body3(s.points, flipped, body).message().find("not oriented out"), std::string::npos);
  auto fewer = body;  // a tetrahedron gone: its faces become free but are not surface triangles
  fewer.erase(fewer.begin() + static_cast<std::ptrdiff_t>(fewer.size() / 2));
  EXPECT_FALSE(validate_body3(s.points, m, fewer).is_ok());
  auto twice = body;  // a tetrahedron twice: overlap
  twice.push_back(body[3]);
  EXPECT_FALSE(validate_body3(s.points, m, twice).is_ok());
  auto inverted = body;  // a negative tetrahedron
  std::swap(inverted[5][0], inverted[5][1]);
  EXPECT_NE(validate_body3(s.points, m, inverted).message().find("positively"), std::string::npos);
  TriMesh3 missing = m;  // a surface triangle dropped
  missing.triangles.pop_back();
  EXPECT_FALSE(validate_body3(s.points, missing, body).is_ok());
  // The message names the face in the caller's ids (the check renumbers the vertices inside).
  auto face = flipped.triangles[7];
  std::sort(face.begin(), face.end());
  const std::string name = "(" + std::to_string(face[0]) + ", " + std::to_string(face[1]) + ", " + std::to_string(face[2]) + ")";
  EXPECT_NE(validate_body3(s.points, flipped, body).message().find(name), std::string::npos);
  // The same verdicts and messages (up to the ids) with the points in another order.
  const unsigned seed = 23;
  std::printf("BodyCheckRejectsBrokenBodies: permutation seed %u\n", seed);
  std::vector<int> perm(s.points.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  PointSet moved = s.points;
  for (std::size_t v = 0; v < perm.size(); ++v)
    std::copy(s.points[v], s.points[v] + 3, &moved.coords[3 * static_cast<std::size_t>(perm[v])]);
  const auto mv_mesh = [&](TriMesh3 x) {
    for (auto& t : x.triangles)
      for (int& v : t) v = perm[static_cast<std::size_t>(v)];
    return x;
  };
  const auto mv_body = [&](std::vector<std::array<int, 4>> x) {
    for (auto& t : x)
      for (int& v : t) v = perm[static_cast<std::size_t>(v)];
    return x;
  };
  const auto kind = [](const Status& st) { return st.is_ok() ? std::string("ok") : st.message().substr(0, st.message().find('(')); };
  EXPECT_EQ(kind(validate_body3(moved, mv_mesh(m), mv_body(body))), "ok");
  EXPECT_EQ(kind(validate_body3(moved, mv_mesh(flipped), mv_body(body))), kind(validate_body3(s.points, flipped, body)));
  EXPECT_EQ(kind(validate_body3(moved, mv_mesh(m), mv_body(inverted))), kind(validate_body3(s.points, m, inverted)));
  EXPECT_EQ(kind(validate_body3(moved, mv_mesh(m), mv_body(twice))), kind(validate_body3(s.points, m, twice)));
  EXPECT_FALSE(validate_body3(moved, mv_mesh(m), mv_body(fewer)).is_ok());
  EXPECT_FALSE(validate_body3(moved, mv_mesh(missing), mv_body(body)).is_ok());
}

// validate_body3 against its definition on small random bodies, each face's occurrences collected
// in a std::map (the Delaunay tetrahedralization of random points and its hull, then one random
// fault or none): the same verdict, and a fault of the kind the definition finds.
TEST(Surfaces3Property, BodyCheckMatchesItsDefinition) {
  constexpr int kFaceOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // opposite vertex i, outward
  using Face = std::array<int, 3>;
  const auto uz = [](int i) { return static_cast<std::size_t>(i); };
  const auto sorted = [](Face f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  const auto even = [](const Face& f) { return ((f[0] > f[1]) + (f[0] > f[2]) + (f[1] > f[2])) % 2 == 0; };
  // The fault kinds of the definition (empty: a valid body).
  const auto brute = [&](const PointSet& p, const TriMesh3& m, const std::vector<std::array<int, 4>>& body) {
    std::set<std::string> faults;
    for (const auto& t : body)
      if (orient3(p[uz(t[0])], p[uz(t[1])], p[uz(t[2])], p[uz(t[3])]) <= 0) return std::set<std::string>{"body tetrahedron not positively oriented"};
    std::map<Face, std::vector<std::pair<bool, bool>>> occ;  // (from a tetrahedron, even)
    for (const auto& t : body)
      for (const auto& fo : kFaceOut) {
        const Face f{{t[uz(fo[0])], t[uz(fo[1])], t[uz(fo[2])]}};
        occ[sorted(f)].push_back({true, even(f)});
      }
    for (const auto& f : m.triangles) occ[sorted(f)].push_back({false, even(f)});
    for (const auto& [f, list] : occ) {
      int tets = 0, tris = 0;
      bool tet_even[2] = {false, false}, tri_even = false;
      for (const auto& [is_tet, e] : list) {
        if (is_tet && tets < 2) tet_even[tets] = e;
        if (!is_tet) tri_even = e;
        (is_tet ? tets : tris) += 1;
      }
      if (tris > 1) faults.insert("surface triangle appears twice");
      else if (tets > 2) faults.insert("face shared by more than two body tetrahedra");
      else if (tets == 2 && tris) faults.insert("surface triangle lies inside the body");
      else if (tets == 2 && tet_even[0] == tet_even[1]) faults.insert("face has body tetrahedra on the same side");
      else if (tets == 1 && !tris) faults.insert("free face of the body is not a surface triangle");
      else if (tets == 1 && tri_even != tet_even[0]) faults.insert("surface triangle is not oriented out of the body");
      else if (tets == 0 && tris) faults.insert("surface triangle is not a face of the body");
    }
    return faults;
  };
  const auto kind = [](const std::string& msg) {  // the message without the face's ids
    const auto a = msg.find(" ("), b = msg.find(')');
    return a == std::string::npos ? msg : msg.substr(0, a) + msg.substr(b + 1);
  };
  int faulty = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const int n = 8 + static_cast<int>(rng() % 120);
    PointSet p;
    p.dim = 3;
    for (int i = 0; i < 3 * n; ++i) p.coords.push_back(u(rng));
    Delaunay3 dt;
    ASSERT_TRUE(build_delaunay3(p, dt).is_ok());
    auto body = dt.tets;
    TriMesh3 m;
    for (std::size_t t = 0; t < dt.tets.size(); ++t)
      for (int i = 0; i < 4; ++i)
        if (dt.neighbors[t][uz(i)] < 0)
          m.triangles.push_back({{dt.tets[t][uz(kFaceOut[i][0])], dt.tets[t][uz(kFaceOut[i][1])], dt.tets[t][uz(kFaceOut[i][2])]}});
    const std::size_t T = body.size(), F = m.triangles.size();
    const int fault = static_cast<int>(rng() % 9);
    switch (fault) {
      case 0: break;
      case 1: body.erase(body.begin() + static_cast<std::ptrdiff_t>(rng() % T)); break;
      case 2: body.push_back(body[rng() % T]); break;
      case 3: { auto& t = body[rng() % T]; std::swap(t[0], t[1]); break; }
      case 4: { auto& f = m.triangles[rng() % F]; std::swap(f[1], f[2]); break; }
      case 5: m.triangles.erase(m.triangles.begin() + static_cast<std::ptrdiff_t>(rng() % F)); break;
      case 6: m.triangles.push_back(m.triangles[rng() % F]); break;
      case 7: { const auto& t = body[rng() % T]; m.triangles.push_back({{t[0], t[1], t[2]}}); break; }  // an inner face
      case 8: m.triangles.erase(m.triangles.begin() + static_cast<std::ptrdiff_t>(rng() % F)); body.erase(body.begin()); break;
    }
    std::rotate(body.begin(), body.begin() + static_cast<std::ptrdiff_t>(rng() % body.size()), body.end());
    const std::set<std::string> expected = brute(p, m, body);
    const Status got = validate_body3(p, m, body);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", fault " + std::to_string(fault) + ": " + got.message());
    EXPECT_EQ(got.is_ok(), expected.empty());
    if (!got.is_ok()) {
      EXPECT_EQ(expected.count(kind(got.message())), 1u);
      ++faulty;
    }
  }
  std::printf("BodyCheckMatchesItsDefinition: seeds 1-60, %d faulty bodies\n", faulty);
  EXPECT_GE(faulty, 40);
}

// A handle's cut in a noisy sample: the points near the cut lie a little inside the tube, and
// closing the loop leaves a few of them buried or pinched; the handle stage repairs those by
// single toggles (carve3.cpp local_search with dimples) instead of undoing the loop.
TEST(Surfaces3Property, NoisyHandlesAreClosed) {
  int right = 0, over = 0;
  const unsigned seeds[] = {1u, 2u, 3u, 4u, 5u, 6u};
  for (unsigned seed : seeds) {
    test::Sample3 s = test::make_surfaces3(Family3::Window, 0, seed, 0.024);
    // Normal noise of 0.3 spacings per coordinate (the generator's spacing after its scale).
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 1);
    const Surfaces3Result clean = run_auto(s.points);
    const std::string what = "window seed " + std::to_string(seed) + " (" + std::to_string(s.points.size()) + " points)";
    expect_topology(s, clean, what + ", clean");
    double ext = 0;  // the bounding box's longest side is the frame's length 2 + 2 r, scaled
    {
      double l[3] = {1e300, 1e300, 1e300}, h3[3] = {-1e300, -1e300, -1e300};
      for (std::size_t i = 0; i < s.points.size(); ++i)
        for (int k = 0; k < 3; ++k) {
          l[k] = std::min(l[k], s.points[i][k]);
          h3[k] = std::max(h3[k], s.points[i][k]);
        }
      ext = std::sqrt((h3[0] - l[0]) * (h3[0] - l[0]) + (h3[1] - l[1]) * (h3[1] - l[1]) + (h3[2] - l[2]) * (h3[2] - l[2]));
    }
    const double h = 0.024 * ext / std::sqrt(2.24 * 2.24 + 1.24 * 1.24 + 0.24 * 0.24);
    for (double& c : s.points.coords) c += 0.3 * h * g(rng);
    const Surfaces3Result noisy = run_auto(s.points);
    std::cout << "[ info ] " << what << ": noisy -> " << noisy.surfaces.size() << " surface(s), genus " << noisy.genus << "\n";
    right += noisy.surfaces.size() == 1 && noisy.genus == 2;
    over += noisy.genus > 2;
  }
  std::cout << "[ info ] noisy windows right: " << right << " of 6\n";
  EXPECT_EQ(over, 0);
  EXPECT_GE(right, 3);  // (0 of 6 before the repair; the others miss one handle)
}

// Tubes about two spacings in radius (the dart radius h): the cut the genus-0 growth leaves across
// such a tube has few or no faces 4 spacings long, but closing it turns a worst bridge ratio of 3
// or more into an even sample (docs/topology.md, "Sparse samples"). Linked tori of radius 0.25
// at h = 0.114 (2.2 h) and tori of radius 0.35 at h = 0.15 (2.3 h); before the thin-tube rule
// 2 of these 8 had every handle.
TEST(Surfaces3Property, ThinTubesKeepTheirHandles) {
  int right = 0, over = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    for (const auto& [f, h] : {std::pair<Family3, double>{Family3::Links, 0.19}, {Family3::Torus, 0.15}}) {
      const test::Sample3 s = test::make_surfaces3(f, 0, seed, h);
      const Surfaces3Result r = run_auto(s.points);
      const std::string what = std::string(name(f)) + " h " + std::to_string(h) + " seed " + std::to_string(seed) +
                               " (" + std::to_string(s.points.size()) + " points)";
      std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus << "\n";
      expect_closed_oriented(r, what);
      right += static_cast<int>(r.surfaces.size()) == s.surfaces && r.genus == s.genus;
      over += r.genus > s.genus;
      // What decided each loop the rule kept is in the report: a long loop.
      long long delta = 0;
      for (const Handle3Change& c : r.mesh.handle_changes) {
        if (c.kind == Handle3Change::Kind::CloseLoop && c.bridges_before < 4) {
          EXPECT_GE(c.loop_spacings, 16.0) << what;
        }
        delta += c.delta_faces;
      }
      // One part grows as one genus-0 surface (F = 2N - 4); the kept changes account for the rest
      // of F = 2N - 4c + 4g (the report counts the loops closed from them).
      if (r.decision == SurfacesDecision::OnePart) {
        EXPECT_EQ(static_cast<long long>(r.mesh.mesh.triangles.size()) - 2LL * static_cast<long long>(s.points.size()) + 4,
                  delta)
            << what;
      }
    }
  }
  std::cout << "[ info ] thin tubes right: " << right << " of 8\n";
  EXPECT_EQ(over, 0);
  EXPECT_GE(right, 6);
}

// Hollow balls whose shell is 2-2.5 dart radii thick: the gap rule (2 local spacings, about
// 2.7 radii here) keeps them one part, the engine joins the shells by a channel, and the handle
// stage's seal of that channel encloses the cavity: one large, wide void, kept as an inner shell
// (small voids between noisy sheets are not). Before: one surface in all 6.
TEST(Surfaces3Property, SparseHollowBallKeepsItsCavity) {
  int right = 0;
  for (double gap : {2.0, 2.5})
    for (unsigned seed : {1u, 2u, 3u}) {
      const test::Sample3 s = test::make_surfaces3(Family3::Hollow, gap, seed, 0.2);
      const Surfaces3Result r = run_auto(s.points);
      const std::string what = "hollow gap " + std::to_string(gap) + " seed " + std::to_string(seed) + " (" +
                               std::to_string(s.points.size()) + " points)";
      std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus << "\n";
      expect_closed_oriented(r, what);
      EXPECT_LE(r.surfaces.size(), 2u) << what;
      EXPECT_EQ(r.genus, 0) << what;
      if (r.surfaces.size() == 2) {
        expect_topology(s, r, what);
        ++right;
      }
    }
  std::cout << "[ info ] sparse hollow balls right: " << right << " of 6\n";
  EXPECT_GE(right, 5);
}

// A tube around a figure eight (genus 2; the tube g(x, y)^2 + z^2 = c around the curve g = 0),
// sampled very unevenly: random points of a box pulled onto the surface by Newton steps, dense on
// the top and bottom of the tube and up to 8 times sparser on its sides. Closing a handle's loop
// there can end with one pinched point (its body tetrahedra in two fans) that no single toggle
// repairs; the handle stage's moves at pinches (carve3.cpp star_moves) join the fans.
PointSet eight_by_projection(std::size_t n, unsigned seed, double c) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(-0.5, 2.5), uy(-1.0, 1.0), uz(-0.6, 0.6);
  const auto g = [](double x, double y) { return x * (x - 1) * (x - 1) * (x - 2) + y * y; };
  const auto gx = [](double x) { return (x - 1) * (x - 1) * (2 * x - 2) + 2 * x * (x - 1) * (x - 2); };
  PointSet p;
  p.dim = 3;
  while (p.size() < n) {
    double x = ux(rng), y = uy(rng), z = uz(rng), f = 0;
    for (int it = 0; it < 30; ++it) {
      const double gg = g(x, y);
      f = gg * gg + z * z - c;
      const double dx = 2 * gg * gx(x), dy = 2 * gg * 2 * y, dz = 2 * z, d = dx * dx + dy * dy + dz * dz + 1e-300;
      x -= f / d * dx;
      y -= f / d * dy;
      z -= f / d * dz;
    }
    const double gg = g(x, y);
    if (std::abs(gg * gg + z * z - c) < 1e-12) p.coords.insert(p.coords.end(), {x, y, z});
  }
  return p;
}

TEST(Surfaces3Property, UnevenHandlesAreClosedAtPinches) {
  // Samples of this family (80 of them: seeds 1-40, 20 000 and 30 000 points) whose loop closing
  // ended at a pinch: genus 1, 3 and 1 without the moves at pinches. Seeds 12 and 35 close their
  // second loop through a move; seed 27's false loop came from the single toggles' end state, from
  // which a region whose moves fail no longer settles. Over all 80: 60 right before, 63 now,
  // overcounts 14 -> 13 (docs/topology.md).
  for (const auto& [n, seed] : {std::pair<std::size_t, unsigned>{20000, 12}, {30000, 27}, {30000, 35}}) {
    const PointSet pts = eight_by_projection(n, seed, 0.02);
    const Surfaces3Result r = run_auto(pts);
    const std::string what = "figure-eight tube, " + std::to_string(n) + " points, seed " + std::to_string(seed);
    std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus << "\n";
    expect_closed_oriented(r, what);
    EXPECT_EQ(r.surfaces.size(), 1u) << what;
    EXPECT_EQ(r.genus, 2) << what;
    int pinched = 0;
    for (const Handle3Change& c : r.mesh.handle_changes) pinched += c.pinched;
    if (seed != 27) {
      EXPECT_GE(pinched, 1) << what << ": a loop closed through a move at a pinch";
    }
  }
}

// Machined parts: flat faces, sharp edges, a through hole, rotated in double precision (the points
// of a face coplanar up to rounding). Regions of inside labels along a sharp edge closed false
// loops there, leaving long faces about as long as the worst they found: blocks seeds 3 and 5
// came out with genus 2 and 1, plates seeds 3 and 4 with genus 2 and 4. On an even sample a
// closing must now leave no long face (handles3.cpp, kUnevenSample), and the faces' crust of
// tetrahedra coplanar up to rounding passes no labels along itself (labels3.cpp, kCoplanarRatio;
// with the first rule alone plate seed 5 lost its hole).
TEST(Surfaces3Property, MachinedPartsGetNoFalseHandles) {
  for (const auto& [f, h] : {std::pair<Family3, double>{Family3::Block, 0.06}, {Family3::Plate, 0.06}})
    for (unsigned seed = 1; seed <= 6; ++seed) {
      const test::Sample3 s = test::make_surfaces3(f, 0, seed, h);
      const std::string what = std::string(name(f)) + " seed " + std::to_string(seed) + ", " +
                               std::to_string(s.points.size()) + " points";
      const Surfaces3Result r = run_auto(s.points);
      std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus << "\n";
      ASSERT_TRUE(r.valid()) << what << ": " << r.check;
      expect_closed_oriented(r, what);
      EXPECT_EQ(r.surfaces.size(), 1u) << what;
      EXPECT_LE(r.genus, s.genus) << what << ": a handle that is not there";
      EXPECT_EQ(r.genus, s.genus) << what;
    }
}

// Two boxes stacked with a gap of 2.5-3 spacings between their large faces: the gap rule (T = 2
// local spacings, the third-nearest-neighbour distance) joins them, and the engine then made one
// surface with a bridge across the gap and, where its labels left cuts in the gap, false handles
// (without the labels these six came out as one surface of genus 2, 0, 1, 1, 0, 1). The gap is labelled
// outside but for label noise: parts that the narrower rule (3/4 T) keeps apart stay apart unless
// tetrahedra labelled inside join them (parts3.cpp, split_by_labels).
TEST(Surfaces3Property, StackedBoxesAFewSpacingsApartStayTwoParts) {
  for (const double gap : {2.5, 3.0})
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const test::Sample3 s = test::make_surfaces3(Family3::Stack, gap, seed, 0.08);
      const std::string what = "stack gap " + std::to_string(gap) + " seed " + std::to_string(seed) + ", " +
                               std::to_string(s.points.size()) + " points";
      const Surfaces3Result r = run_auto(s.points);
      std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus
                << ", split by labels " << r.parts_split_by_labels << "\n";
      ASSERT_TRUE(r.valid()) << what << ": " << r.check;
      expect_closed_oriented(r, what);
      EXPECT_EQ(r.surfaces.size(), 2u) << what;
      EXPECT_EQ(r.genus, 0) << what;
    }
}

// The labels' split does not depend on the file order, a power-of-two scale or a cyclic permutation
// of the axes: the same two parts (the engine's canonical order and the labels' arithmetic see the
// same points); without the axis permutation, the same triangles.
TEST(Surfaces3Property, LabelSplitIndependentOfOrderAxesAndScale) {
  const test::Sample3 s = test::make_surfaces3(Family3::Stack, 2.5, 2, 0.08);
  const Surfaces3Result a = run_auto(s.points);
  ASSERT_TRUE(a.valid()) << a.check;
  ASSERT_EQ(a.parts_split_by_labels, 1u);
  for (const auto& [shift, exp2] : std::vector<std::pair<int, int>>{{0, 0}, {0, -20}, {1, 0}, {2, 30}}) {
    const std::string what = "shift " + std::to_string(shift) + " 2^" + std::to_string(exp2);
    const PointSet q = transformed(s.points, 40u + static_cast<unsigned>(shift), shift, exp2);
    const Surfaces3Result b = run_auto(q);
    ASSERT_TRUE(b.valid()) << what << ": " << b.check;
    EXPECT_EQ(b.parts_split_by_labels, 1u) << what;
    EXPECT_EQ(b.surfaces.size(), 2u) << what;
    EXPECT_EQ(b.genus, 0) << what;
    std::vector<std::size_t> sizes_a, sizes_b;
    for (const auto& x : a.surfaces) sizes_a.push_back(x.points.size());
    for (const auto& x : b.surfaces) sizes_b.push_back(x.points.size());
    std::sort(sizes_a.begin(), sizes_a.end());
    std::sort(sizes_b.begin(), sizes_b.end());
    EXPECT_EQ(sizes_a, sizes_b) << what;
    if (shift == 0) {  // (a power-of-two scale keeps the canonical order: the same triangles)
      std::set<std::array<Coord3, 3>> back;
      for (auto t : coordinate_triangles(q, b.mesh.mesh)) {
        for (auto& c : t)
          for (double& x : c) x = std::ldexp(x, -exp2);
        back.insert(t);
      }
      EXPECT_EQ(back, coordinate_triangles(s.points, a.mesh.mesh)) << what;
    }
  }
}

// Two boxes 2 spacings apart are one part for both gap rules: one surface, joined across the gap
// where the growth took outside steps to reach the second box. Its labels are right (the gap
// outside), and the genus-0 growth left cuts inside the second box between those steps: closing
// them made handles whose every loop runs through the outside steps (before: genus 3, 1, 1, 1 on
// these four). A closing must now close a loop through tetrahedra labelled inside
// (handles3.cpp, loop_through_inside).
TEST(Surfaces3Property, StackedBoxesTwoSpacingsApartGetNoFalseHandle) {
  for (const auto& [h, seed] : {std::pair<double, unsigned>{0.08, 1}, {0.06, 1}, {0.06, 3}, {0.06, 5}}) {
    const test::Sample3 s = test::make_surfaces3(Family3::Stack, 2.0, seed, h);
    const std::string what = "stack gap 2, h " + std::to_string(h) + " seed " + std::to_string(seed) + ", " +
                             std::to_string(s.points.size()) + " points";
    const Surfaces3Result r = run_auto(s.points);
    std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surface(s), genus " << r.genus << "\n";
    ASSERT_TRUE(r.valid()) << what << ": " << r.check;
    expect_closed_oriented(r, what);
    EXPECT_EQ(r.genus, 0) << what << ": a handle that is not there";
  }
}

// The points of a regression file of tests/data/topology3 (empty, with a failure, if unreadable).
PointSet regression_points(const std::string& name) {
  PointSet p;
  ReadOptions ro;
  ro.dim = 3;
  EXPECT_TRUE(read_points(std::string(CONSTRICT_TEST_DATA_DIR) + "/topology3/" + name, ro, p).is_ok()) << name;
  return p;
}

// A regression file of tests/data/topology3 in auto mode: one closed, oriented surface.
Surfaces3Result run_regression_file(const std::string& name, const char* what) {
  const PointSet p = regression_points(name);
  const Surfaces3Result r = run_auto(p);
  expect_closed_oriented(r, what);
  EXPECT_EQ(r.surfaces.size(), 1u) << what;
  return r;
}

// Two rotated plates 4 spacings apart (bench/near_parts3.py, plates at 3 000 points, gap 4, seed
// 3, written with 9 digits): the gap rule finds the two parts, but their faces are coplanar up to
// rounding, each part's own tetrahedralization triangulates them otherwise than that of all
// points, the common body cannot be repaired, and the parts' bounding boxes overlap (rotated): the
// decision fell back to one part, one surface with a bridge. A plane separates them
// (assemble3.cpp, planes_apart), so each keeps its own body.
TEST(Surfaces3Property, RotatedPlatesApartKeepTheirOwnBodies) {
  const PointSet p = regression_points("plates_rotated_gap4.xyz");
  ASSERT_GT(p.size(), 0u);
  const Surfaces3Result r = run_auto(p);
  expect_closed_oriented(r, "two rotated plates");
  EXPECT_EQ(r.parts, 2u);
  EXPECT_EQ(r.surfaces.size(), 2u);
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.decision, SurfacesDecision::Parts);
}

// Noise under a surface makes small tunnels: a region of inside labels closing a loop of a few
// spacings around one, whose bridge ratios pass the thin-tube test (3.30 -> 1.81, no bridge face).
// The thin-tube rule asks for a loop of at least 16 spacings (handles3.cpp shortest_loop; this
// one is 11.3). Regression file: spot (shared data) with normal noise of 0.4 of its median
// nearest-neighbour distance per coordinate (numpy seed [4, 4]); genus 1 without the rule.
TEST(Surfaces3Property, NoisySpotGetsNoSmallTunnelHandle) {
  const Surfaces3Result r = run_regression_file("spot_noisy_tunnel.xyz", "noisy spot");
  EXPECT_EQ(r.genus, 0);
}

// A region that closes several loops at once and leaves long faces must close long ones
// (handles3.cpp, kSeveralLoopMin). Regression file (hostile handle sweep, 2026-12-05): a mug
// (a cup with walls about 8 spacings thick and one handle), 20 000 points drawn uniformly at random
// with a density changing 4x across it and normal noise of 0.25 spacings, written with 5 decimals.
// The growth leaves cracks in the noisy wall; one region a few spacings wide closed 8 loops of
// 18 spacings through them and left 71 of its 629 long faces: genus 9 before the rule. (The
// handle itself is cut by the same cracks and stays open: genus 0, no invented handle.)
TEST(Surfaces3Property, NoisyRandomMugGetsNoHandlesThroughItsWall) {
  const Surfaces3Result r = run_regression_file("mug_random_noisy_wall.xyz", "noisy random mug");
  EXPECT_LE(r.genus, 1) << "handles that are not there";
}

// On an even sample a closing region may leave long faces only if it takes nearly all of them
// away and closes a long loop (handles3.cpp, kCutLeftShare). Regression file (decimated-mesh
// sweep, 2026-12-05): the 10 000 vertices of a genus-3 pretzel (three tori of tube 0.4 in a row,
// blended) meshed densely and decimated by edge collapse (Lindstrom-Turk), rotated, written with
// 7 digits. Decimation leaves long triangles where the surface is gently curved: closing the
// third handle's cut took 52 long faces down to 1 and was undone by the even-sample rule
// (genus 2).
TEST(Surfaces3Property, DecimatedPretzelKeepsItsThirdHandle) {
  const Surfaces3Result r = run_regression_file("pretzel3_decimated.xyz", "decimated pretzel");
  EXPECT_EQ(r.genus, 3);
  int long_loops = 0;
  for (const Handle3Change& c : r.mesh.handle_changes)
    if (c.kind == Handle3Change::Kind::CloseLoop && c.bridges_after > 0) {
      EXPECT_GE(c.loop_spacings, 16.0) << "a closing that leaves long faces closes a long loop";
      EXPECT_LE(8 * c.bridges_after, c.bridges_before);
      ++long_loops;
    }
  EXPECT_EQ(long_loops, 1);
}

// Patches of one surface (parts3.cpp join_patches; docs/topology.md, "Decimated meshes"). The
// vertices of decimated machined parts are dense at fillets and rounded corners and sparse on the
// flat faces around them (long triangles), so a fillet can lie more than T local spacings from the
// rest of its own surface: a part of its own. Regression files from the decimated-mesh sweep
// (CGAL's Surface_mesher mesh of an implicit shape, decimated by edge collapse, rotated and
// shuffled, 17 digits): a plate 3 x 1.6 x 0.3 with two holes and rounded edges, 1 499 vertices
// (Lindstrom-Turk), where a 19-point corner became a second surface; and an L-bracket with a hole
// in each leg, 999 vertices (Garland-Heckbert), where a 147-point fillet did, and the bracket got
// genus 1 for 2.
TEST(Surfaces3Property, DecimatedPlateCornerIsNoPartOfItsOwn) {
  const Surfaces3Result r = run_regression_file("plate2_decimated_corner_patch.xyz", "decimated plate");
  EXPECT_EQ(r.genus, 2);
  EXPECT_EQ(r.parts, 1u);
  EXPECT_EQ(r.patches_joined, 1u);
}

TEST(Surfaces3Property, DecimatedBracketFilletIsNoPartOfItsOwn) {
  const Surfaces3Result r = run_regression_file("lbracket2_decimated_fillet_patch.xyz", "decimated bracket");
  EXPECT_EQ(r.genus, 2);
  EXPECT_EQ(r.patches_joined, 1u);
}

// Concentric spheres sampled uniformly at random (not blue noise: clumps and holes), radius 1 with
// n points, each next one g area spacings (sqrt(4 pi / n)) further out with as many points per
// area. Between 3 and 4 spacings the narrower gap rule splits the shells but the labels of the
// wall between them are inside: until 2026-12-07 the pieces were joined as one object, and the
// handle stage failed to seal the inner shell (one surface of genus 0-2). A piece around a void
// of tetrahedra labelled outside now stays a part of its own (parts3.cpp,
// pieces_around_voids); the nesting of the parts' surfaces gives the roles.
PointSet random_shells(int shells, double gap, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  PointSet p;
  p.dim = 3;
  const double s = std::sqrt(4 * M_PI / n);
  for (int k = 0; k < shells; ++k) {
    const double r = 1 + k * gap * s;
    const int m = static_cast<int>(n * r * r);
    for (int i = 0; i < m; ++i) {
      double v[3] = {normal(rng), normal(rng), normal(rng)};
      const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (double c : v) p.coords.push_back(r * c / len);
    }
  }
  return p;
}

// Each surface holds the points of one sphere of random_shells (the first n of the innermost,
// then the next sphere's), and the roles alternate from the outside: outer, inner, outer.
void expect_one_surface_per_shell(int shells, double gap, int n, unsigned seed) {
  const PointSet p = random_shells(shells, gap, n, seed);
  SCOPED_TRACE(std::to_string(shells) + " shells, gap " + std::to_string(gap) + " spacings, " + std::to_string(n) +
               " points on the innermost, seed " + std::to_string(seed));
  std::printf("random shells: %d, gap %.1f, %zu points, seed %u\n", shells, gap, p.size(), seed);
  const Surfaces3Result r = run_auto(p);
  expect_closed_oriented(r, "random shells");
  ASSERT_EQ(r.surfaces.size(), static_cast<std::size_t>(shells));
  EXPECT_EQ(r.genus, 0);
  std::vector<std::pair<int, const Surface3*>> by_first;
  for (const Surface3& sf : r.surfaces) by_first.emplace_back(sf.points.front(), &sf);
  std::sort(by_first.begin(), by_first.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  int first = 0;
  for (int k = 0; k < shells; ++k) {
    const double radius = 1 + k * gap * std::sqrt(4 * M_PI / n);
    const int m = static_cast<int>(n * radius * radius);
    const Surface3& sf = *by_first[static_cast<std::size_t>(k)].second;
    EXPECT_EQ(sf.points.size(), static_cast<std::size_t>(m)) << "sphere " << k;
    EXPECT_EQ(sf.points.front(), first) << "sphere " << k;
    EXPECT_EQ(sf.points.back(), first + m - 1) << "sphere " << k;
    const bool outer = (shells - 1 - k) % 2 == 0;
    EXPECT_EQ(sf.role, outer ? SurfaceRole::Outer : SurfaceRole::Inner) << "sphere " << k;
    first += m;
  }
}

TEST(Surfaces3Property, RandomlySampledShellsKeepTheirCavities) {
  struct Case {
    int shells;
    double gap;
    unsigned seed;
  };
  for (const Case c : {Case{2, 3.0, 1}, Case{2, 3.5, 2}, Case{2, 4.0, 3}, Case{3, 4.0, 4}})
    expect_one_surface_per_shell(c.shells, c.gap, 3000, c.seed);
}

// A point in a hole of a uniformly random sample has a spacing about twice its neighbours': its
// edges to the next shell, 3 area spacings away, passed the narrower gap rule, and one to a few
// of them joined two shells into one piece. The narrower rule now joins pieces across such edges
// only where enough points on each side have them (docs/topology.md, "Inner shells of random
// samples"). Of the 48 sets of 3 and 4 shells with 500, 2 000 and 8 000 points on the innermost,
// seeds 1-8, 21 failed before, 2 with this rule (below) and none with the large void's rule; six
// of the fixed ones run here (each fails without the rule).
TEST(Surfaces3Property, RandomShellsThreeSpacingsApartAreNotJoinedAtASparseSpot) {
  struct Case {
    int shells, n;
    unsigned seed;
  };
  for (const Case c : {Case{3, 500, 8}, Case{3, 2000, 5}, Case{3, 8000, 1}, Case{4, 500, 3}, Case{4, 2000, 5}, Case{4, 8000, 1}})
    expect_one_surface_per_shell(c.shells, 3.0, c.n, c.seed);
}

// ... and a cavity 3 spacings thick is a void even where no tetrahedron in it is 5 spacings across
// (4.83 and 4.99 in these two; the middle shells' pieces were joined by the wall's inside labels,
// and the engine on the joined part closed two false handles instead of sealing the cavity).
TEST(Surfaces3Property, RandomShellsThreeSpacingsApartKeepAThinCavity) {
  for (const auto& c : {std::array<int, 3>{3, 500, 3}, std::array<int, 3>{4, 500, 1}})
    expect_one_surface_per_shell(c[0], 3.0, c[1], static_cast<unsigned>(c[2]));
}

// A noisy hollow ball, uniformly random (2 913 points: an inner sphere of 402 off-centre in an outer
// one of 2 511, 3.25 area spacings apart, noise 0.31 spacing; a differential sweep's set, seed 20).
// Its parts are found, their surfaces are not Delaunay faces of all points, and the repair of the
// common body made a valid pair of surfaces in which one inner point sat on the outer surface
// (2 512 and 401 points, three faces across the wall). The repair now first asks every surface
// face to lie within one part.
TEST(Surfaces3Property, NoisyHollowBallRepairKeepsEachPointOnItsShell) {
  const PointSet p = regression_points("hollow_noisy_repair_crossing.xyz");
  ASSERT_GT(p.size(), 0u);
  const Surfaces3Result r = run_auto(p);
  expect_closed_oriented(r, "noisy hollow ball");
  ASSERT_EQ(r.surfaces.size(), 2u);
  EXPECT_EQ(r.genus, 0);
  std::vector<std::size_t> sizes;
  for (const Surface3& sf : r.surfaces) sizes.push_back(sf.points.size());
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<std::size_t>{402, 2511}));
  EXPECT_GT(r.repaired_tetrahedra, 0u);  // (the repair's path, not a fallback's)
}

// ... but an inner shell sampled more sparsely than the outer one, within that gap of it, is no
// patch: every tetrahedron between the shells is labelled inside (the object's wall), none outside.
// And small separate objects beside a big one: only tetrahedra labelled outside between them.
// Fibonacci spheres (deterministic, even).
TEST(Surfaces3Property, SparseInnerShellAndSmallPartsAreNoPatches) {
  const auto fib = [](PointSet& p, int n, double r, double cx, double cy, double cz) {
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) / n, phi = std::acos(1 - 2 * t), th = M_PI * (1 + std::sqrt(5.0)) * (i + 0.5);
      p.coords.insert(p.coords.end(), {cx + r * std::cos(th) * std::sin(phi), cy + r * std::sin(th) * std::sin(phi), cz + r * std::cos(phi)});
    }
  };
  for (const auto& [ri, ni] : {std::pair<double, int>{0.7, 300}, {0.65, 150}, {0.6, 200}}) {
    PointSet p;
    p.dim = 3;
    fib(p, 3000, 1.0, 0, 0, 0);
    fib(p, ni, ri, 0.01, 0.02, -0.03);
    SCOPED_TRACE("inner shell r " + std::to_string(ri) + ", " + std::to_string(ni) + " points");
    const Surfaces3Result r = run_auto(p);
    expect_closed_oriented(r, "hollow ball");
    ASSERT_EQ(r.surfaces.size(), 2u);
    EXPECT_EQ(r.patches_joined, 0u);
    int inner = 0;
    for (const Surface3& s : r.surfaces) inner += s.role == SurfaceRole::Inner;
    EXPECT_EQ(inner, 1);
  }
  // A ball of 3 000 points (spacing about 0.065) with balls of 20 and 40 points 0.15 to 0.25 from it.
  PointSet p;
  p.dim = 3;
  fib(p, 3000, 1.0, 0, 0, 0);
  fib(p, 20, 0.1, 1.25, 0, 0);
  fib(p, 40, 0.14, 0, 1.35, 0);
  fib(p, 20, 0.1, 0, 0, -1.27);
  const Surfaces3Result r = run_auto(p);
  expect_closed_oriented(r, "ball and small balls");
  EXPECT_EQ(r.surfaces.size(), 4u);
  EXPECT_EQ(r.patches_joined, 0u);
}

// A noisy sample whose loop closing ends with a pinched point only after the single toggles: the
// peel leaves 7 bad points, and the toggles used to settle by taking back the tetrahedra that
// closed the loop (a valid genus-0 state, so the region was undone: genus 0). They are now kept
// from opening the loop again and end at one pinched point, which a move of several tetrahedra
// joins. Such a region must still close a long loop (a pocket of a noisy armadillo closed one of
// 2.5 spacings through a pinch). Regression file: the shared t3_torus_05 (1 462 points) with
// normal noise of 0.5 of its median nearest-neighbour distance per coordinate; genus 0 without.
TEST(Surfaces3Property, NoisyTorusIsClosedAtAPinchAfterTheSingleToggles) {
  const Surfaces3Result r = run_regression_file("torus_noisy_pinch.xyz", "noisy torus");
  EXPECT_EQ(r.genus, 1);
  int pinched = 0;
  for (const Handle3Change& c : r.mesh.handle_changes)
    if (c.kind == Handle3Change::Kind::CloseLoop) {
      pinched += c.pinched;
      EXPECT_GE(c.loop_spacings, 16.0) << "a loop closed through a pinch is long";
    }
  EXPECT_EQ(pinched, 1);
}

// A closing region must not enclose a void. Regression file: a chain of four overlapping rings
// (tori of radius 0.5, tube 0.1, centres 0.9 apart: genus 4), 7 977 points pulled onto the union
// by Newton steps, thinned on a grid and moved by normal noise of 0.3 of the grid cell (rounded to
// 4 decimals). The last ring's closing region closed two loops and sealed a one-tetrahedron void
// at once (dF = 8 - 4 passed as one loop): genus 5 and an inner surface of 4 points. Now that
// region is undone: genus 3, one surface, no invented topology.
TEST(Surfaces3Property, ClosingRegionsDoNotSealVoids) {
  const Surfaces3Result r = run_regression_file("ring_chain_noisy_void.xyz", "noisy chain of four rings");
  EXPECT_LE(r.genus, 4) << "more handles than the truth";
  EXPECT_GE(r.genus, 3);
}

// A noisy tube has neither a wall of long faces at its cut nor an even sample after closing it,
// so neither ratio test kept its closing regions; a region that closes one long loop (48
// spacings or more) and lowers the worst ratio by 15 % or more without a long face is now kept.
// Regression file: a tube around a figure eight (((x^2 + y^2)^2 - x^2 + y^2)^2 + z^2 = 0.01,
// genus 2), 3 035 points pulled onto it by Newton steps, thinned on a grid, normal noise of 0.3 of
// the cell (5 decimals). Genus 0 without the rule; 1 with it (the other loop's region lowers the
// worst ratio by 3 % only, as false tunnels under noisy genus-0 surfaces do: 2-9 %).
TEST(Surfaces3Property, NoisyTubeClosesItsLongLoops) {
  const Surfaces3Result r = run_regression_file("eight_tube_noisy.xyz", "noisy figure-eight tube");
  EXPECT_GE(r.genus, 1);
  EXPECT_LE(r.genus, 2) << "more handles than the truth";
  for (const Handle3Change& c : r.mesh.handle_changes)
    if (c.kind == Handle3Change::Kind::CloseLoop && c.bridges_before == 0) {
      EXPECT_GE(c.loop_spacings, 48.0) << "a loop closed without a long face is long";
    }
}

// ... and so is one that leaves a few long faces where the sample is sparse, if it leaves fewer
// than it found. Regression file: bench/handles_sweep3.py's eightn, c = 0.02, 3 000 points, seed
// 2 (the tube x(x-1)^2(x-2) + y^2 = g, g^2 + z^2 = c, genus 2, from random points of a box pulled
// onto it by Newton steps: up to 8x sparser on its sides; 5 decimals). One closing region went
// from 3 long faces to 2 and its worst ratio from 10.5 to 4.2; it was undone (genus 1).
TEST(Surfaces3Property, UnevenTubeClosesALoopThatLeavesFewerLongFaces) {
  const Surfaces3Result r = run_regression_file("eight_tube_uneven.xyz", "unevenly sampled figure-eight tube");
  EXPECT_EQ(r.genus, 2);
  for (const Handle3Change& c : r.mesh.handle_changes)
    if (c.kind == Handle3Change::Kind::CloseLoop && c.bridges_before < 4) {
      EXPECT_TRUE(c.bridges_after == 0 || c.bridges_after < c.bridges_before);
      EXPECT_GE(c.loop_spacings, 48.0) << "a loop closed across few long faces is long";
    }
}

// A region that closes two loops at once across a wall of long faces, one of them false (2.8
// spacings), was undone whole. It is now asked for again without its tetrahedra on one end of
// the short loop, the patch with fewer contact faces (and without those at the points that leaves
// non-manifold): the rest
// closes the one true loop. Regression file: bench/handles_sweep3.py's eightn, c = 0.035, 3 000
// points, seed 2 (6 decimals); genus 1 before.
TEST(Surfaces3Property, RegionClosingATrueAndAFalseLoopIsTrimmedToTheTrueOne) {
  const Surfaces3Result r = run_regression_file("eight_tube_two_loops.xyz", "figure-eight tube, two loops at once");
  EXPECT_EQ(r.genus, 2);
}

// A comb (a box with five fingers on it) whose fingers are a few spacings apart, blue noise as mesh
// vertices are: one genus-0 surface. A bridge across a slot between two fingers closes a loop
// through the object. On an even sample the handle stage's thin-tube and noisy-tube rules now keep
// a closing only when it leaves an even surface and does not fold where it meets the surface
// around it (handles3.cpp, folds_at_seam): before, 5 of these 64 sets had genus 1 (spacing 0.12:
// gap 2 seeds 2 and 7, gap 2.5 seed 3; spacing 0.09: gap 1.5 seed 3, gap 2 seed 6), their
// closings bending 92-180 degrees at the seam.
// A torso with an arm hanging beside it two spacings away, 4 000 uniformly random points
// (bench/limbs3.py, arm, gap 2, seed 1, written with 7 digits): one genus-0 surface in truth. A
// bridge from the arm to the torso ended even and passed the thin-tube rule, its new faces meeting
// the old ones at 134 degrees across the seam; the rule now asks for no fold on any sample. Genus 2
// before; the other false handle here is the noisy-tube rule's on an uneven sample (6.21 -> 2.89:
// docs/topology.md, "Limbs that nearly touch", open).
TEST(Surfaces3Property, ThinTubeClosingThatFoldsAtItsSeamIsRefused) {
  const Surfaces3Result r = run_regression_file("limbs_arm_random_fold.xyz", "arm beside a torso, random points");
  EXPECT_LE(r.genus, 1);
  for (const Handle3Change& c : r.mesh.handle_changes) {
    if (c.kind != Handle3Change::Kind::CloseLoop) continue;
    const bool thin_tube = c.bridges_after == 0 && c.worst_ratio_before >= 3.0 && c.worst_ratio_after <= 2.25;
    EXPECT_FALSE(thin_tube) << "a thin-tube closing is left (" << c.worst_ratio_before << " -> " << c.worst_ratio_after << ")";
  }
}

// (One of the 64 gets a second surface instead: at spacing 0.09, gap 1.5, seed 8 the handle stage
// seals a void in a slot bridged all round, before and after the change; docs/topology.md.)
TEST(Surfaces3Property, CombFingersAFewSpacingsApartHaveNoHandle) {
  int more_surfaces = 0;
  for (const double h : {0.12, 0.09})
    for (const double gap : {1.5, 2.0, 2.5, 3.0})
      for (unsigned seed = 1; seed <= 8; ++seed) {
        const test::Sample3 s = test::make_surfaces3(Family3::Comb, gap, seed, h);
        const std::string what = "comb spacing " + std::to_string(h) + " gap " + std::to_string(gap) + " seed " +
                                 std::to_string(seed) + ", " + std::to_string(s.points.size()) + " points";
        const Surfaces3Result r = run_auto(s.points);
        ASSERT_TRUE(r.valid()) << what << ": " << r.check;
        expect_closed_oriented(r, what);
        EXPECT_EQ(r.genus, 0) << what;
        ASSERT_GE(r.surfaces.size(), 1u) << what;
        if (r.surfaces.size() != 1) {
          std::cout << "[ info ] " << what << ": " << r.surfaces.size() << " surfaces\n";
          ++more_surfaces;
        }
      }
  EXPECT_LE(more_surfaces, 1);
}

}  // namespace
}  // namespace constrict
