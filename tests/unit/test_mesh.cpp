// SPDX-License-Identifier: GPL-3.0-or-later
// validate_mesh3 must accept closed genus-0 surfaces and reject every defect; writers round trip.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <utility>
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/surface_components.hpp"
#include "test_fixtures.hpp"

namespace constrict {
namespace {

using test::make3;

constexpr double kPi = 3.14159265358979323846;
const std::vector<std::array<double, 3>> kTet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
// Outward faces of the tetrahedron above.
const std::vector<std::array<int, 3>> kTetFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TriMesh3 mesh(std::vector<std::array<int, 3>> f) { return TriMesh3{std::move(f)}; }

TEST(MeshValidate, AcceptsTetrahedron) {
  const PointSet p = make3(kTet);
  MeshCheck mc;
  MeshCheckOptions mo;
  mo.self_intersections = true;
  ASSERT_TRUE(validate_mesh3(p, mesh(kTetFaces), &mc, mo).is_ok()) << mc.reason;
  EXPECT_EQ(mc.genus, 0);
  EXPECT_EQ(mc.euler, 2);
  EXPECT_TRUE(mc.no_self_intersections);
  EXPECT_NEAR(mc.volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(mesh_area(p, mesh(kTetFaces)), 1.5 + std::sqrt(3.0) / 2, 1e-12);
}

// Volumes far from the common origin (an adversarial sweep): two unit tetrahedra 10^9 apart came
// out wrong in the first digit, and a long thin body (a tetrahedron 10^9 long, 1 wide) with a
// volume 1 700 times too large, or negative.
TEST(MeshVolume, SurfacesFarFromEachOtherAndLongThinFacesKeepTheirDigits) {
  std::vector<std::array<double, 3>> two = kTet;
  for (const auto& q : kTet) two.push_back({q[0] + 1e9, q[1] - 3e8, q[2] + 7e8});
  std::vector<std::array<int, 3>> faces = kTetFaces;
  for (const auto& f : kTetFaces) faces.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  EXPECT_NEAR(mesh_volume(make3(two), mesh(faces)), 2.0 / 6.0, 1e-12);
  // A tetrahedron with a base of about unit size and its apex 2.4e9 away, the base 10^9 from the
  // centre of its box (as the bridge of one surface over two spheres 10^9 apart). Exact volume
  // from rational arithmetic (Python fractions); the old sum was 47 times too large.
  const std::vector<std::array<double, 3>> thin = {{1000000000.0856491, 200000000.2368105, -299999999.1987255},
                                                   {1000000000.582162, 200000000.09412864, -299999999.5668731},
                                                   {1000000000.4790514, 200000000.15973893, -299999999.2654228},
                                                   {-999999999.886328, 0.39122819049566204, 1000000000.5167402}};
  const double exact = 13880144.075372295;
  EXPECT_NEAR(mesh_volume(make3(thin), mesh(kTetFaces)), exact, 1e-5 * exact);
}

TEST(MeshValidate, RejectsOpen) {
  const PointSet p = make3(kTet);
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(p, mesh({kTetFaces[0], kTetFaces[1], kTetFaces[2]}), &mc).is_ok());
  EXPECT_FALSE(mc.closed);
}

TEST(MeshValidate, RejectsMisorientedAndInward) {
  const PointSet p = make3(kTet);
  auto f = kTetFaces;
  std::swap(f[0][1], f[0][2]);
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(p, mesh(f), &mc).is_ok());
  EXPECT_TRUE(mc.closed);
  EXPECT_FALSE(mc.oriented);
  for (auto& t : f) std::swap(t[1], t[2]);
  f[0] = kTetFaces[0];
  std::swap(f[0][1], f[0][2]);  // all inward now
  EXPECT_FALSE(validate_mesh3(p, mesh(f), &mc).is_ok());
  EXPECT_TRUE(mc.oriented);
  EXPECT_FALSE(mc.outward);
}

TEST(MeshValidate, RejectsMissingPointAndDegenerate) {
  auto pts = kTet;
  pts.push_back({{5, 5, 5}});
  const PointSet p = make3(pts);
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(p, mesh(kTetFaces), &mc).is_ok());
  EXPECT_EQ(mc.missing_point, 4);
  MeshCheckOptions mo;
  mo.require_all_points = false;
  EXPECT_TRUE(validate_mesh3(p, mesh(kTetFaces), &mc, mo).is_ok());
  // collinear face
  const PointSet q = make3({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}});
  EXPECT_FALSE(validate_mesh3(q, mesh({{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}), &mc).is_ok());
  EXPECT_FALSE(mc.non_degenerate);
  // bad index
  EXPECT_FALSE(validate_mesh3(make3(kTet), mesh({{0, 1, 7}}), &mc).is_ok());
  EXPECT_FALSE(mc.indices_ok);
}

// Two tetrahedra glued at one vertex (bowtie): every edge has two faces, but the link of the
// shared vertex is two cycles.
TEST(MeshValidate, RejectsNonManifoldVertex) {
  std::vector<std::array<double, 3>> pts = kTet;
  for (const auto& q : kTet) pts.push_back({{-q[0], -q[1], -q[2]}});
  pts.erase(pts.begin() + 4);  // the mirrored origin is the shared vertex 0
  // mirrored points: 4=(-1,0,0), 5=(0,-1,0), 6=(0,0,-1); mirror flips orientation
  std::vector<std::array<int, 3>> f = kTetFaces;
  for (auto t : kTetFaces) {
    std::array<int, 3> u{};
    for (int k = 0; k < 3; ++k) u[static_cast<std::size_t>(k)] = t[static_cast<std::size_t>(k)] == 0 ? 0 : t[static_cast<std::size_t>(k)] + 3;
    std::swap(u[1], u[2]);
    f.push_back(u);
  }
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(make3(pts), mesh(f), &mc).is_ok()) << mc.reason;
  EXPECT_TRUE(mc.edge_manifold);
  EXPECT_FALSE(mc.vertex_manifold);
  EXPECT_EQ(mc.bad_vertex, 0);
}

// Two tetrahedra sharing an edge: that edge has four faces.
TEST(MeshValidate, RejectsNonManifoldEdge) {
  // tet A = 0,1,2,3 ; tet B = 0,1,4,5 on the other side sharing edge 01
  const PointSet p = make3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}});
  std::vector<std::array<int, 3>> f = kTetFaces;
  // B = (0,1,4,5): its outward faces, by the same pattern as for a positive tet (v0..v3):
  // (v1,v2,v3), (v0,v3,v2), (v0,v1,v3), (v0,v2,v1) if positive; orient(0,1,4,5) is positive here.
  f.push_back({{1, 4, 5}});
  f.push_back({{0, 5, 4}});
  f.push_back({{0, 1, 5}});
  f.push_back({{0, 4, 1}});
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(p, mesh(f), &mc).is_ok());
  EXPECT_TRUE(mc.closed);
  EXPECT_FALSE(mc.edge_manifold);
}

// The edge checks against their definition, on random corruptions of a subdivided octahedron
// (a face dropped, flipped, doubled, or a face added on an existing edge): closed = every edge has
// two faces or more, edge-manifold = none has more than two, oriented = every two-face edge is
// used once each way (in that order of precedence, as validate_mesh3 reports), and the edge count.
TEST(MeshValidate, EdgeChecksMatchTheirDefinition) {
  // Octahedron, each face split into 4, three times: 512 faces, outward.
  std::vector<std::array<double, 3>> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<int, 3>> f = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < 3; ++level) {
    std::map<std::pair<int, int>, int> mid;
    const auto middle = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      std::array<double, 3> m{};
      for (int k = 0; k < 3; ++k) m[k] = 0.5 * (v[a][k] + v[b][k]);
      const double r = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      for (double& c : m) c /= r;
      v.push_back(m);
      return mid[key] = static_cast<int>(v.size() - 1);
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& t : f) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      g.push_back({t[0], ab, ca});
      g.push_back({ab, t[1], bc});
      g.push_back({ca, bc, t[2]});
      g.push_back({ab, bc, ca});
    }
    f.swap(g);
  }
  const PointSet p = make3(v);
  {
    MeshCheck mc;
    ASSERT_TRUE(validate_mesh3(p, mesh(f), &mc).is_ok()) << mc.reason;
    EXPECT_EQ(mc.edges, static_cast<long long>(3 * f.size() / 2));
  }
  const unsigned seed = 3;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  int failed = 0;
  for (int round = 0; round < 300; ++round) {
    std::vector<std::array<int, 3>> g = f;
    for (int c = 0, changes = 1 + static_cast<int>(rng() % 3); c < changes; ++c) {
      const std::size_t k = rng() % g.size();
      switch (rng() % 4) {
        case 0: g.erase(g.begin() + static_cast<std::ptrdiff_t>(k)); break;
        case 1: std::swap(g[k][1], g[k][2]); break;
        case 2: g.push_back(g[k]); break;
        default: {  // a new face on edge (g[k][0], g[k][1]) with a vertex of another face
          const int w = g[rng() % g.size()][0];
          if (w != g[k][0] && w != g[k][1]) g.push_back({g[k][1], g[k][0], w});
        }
      }
    }
    std::map<std::pair<int, int>, std::array<int, 2>> use;  // (min, max) -> faces (min->max, max->min)
    for (const auto& t : g)
      for (int e = 0; e < 3; ++e) {
        const int a = t[e], b = t[(e + 1) % 3];
        ++use[{std::min(a, b), std::max(a, b)}][a < b ? 0 : 1];
      }
    bool closed = true, manifold = true, oriented = true;
    for (const auto& [edge, c] : use) {
      closed = closed && c[0] + c[1] >= 2;
      manifold = manifold && c[0] + c[1] <= 2;
      oriented = oriented && (c[0] + c[1] != 2 || (c[0] == 1 && c[1] == 1));
    }
    MeshCheck mc;
    const bool ok = validate_mesh3(p, mesh(g), &mc).is_ok();
    failed += !ok;
    ASSERT_EQ(mc.closed, closed) << "seed " << seed << " round " << round;
    if (!closed) continue;
    ASSERT_EQ(mc.edge_manifold, manifold) << "seed " << seed << " round " << round;
    if (!manifold) continue;
    ASSERT_EQ(mc.oriented, oriented) << "seed " << seed << " round " << round;
    if (oriented) {
      EXPECT_EQ(mc.edges, static_cast<long long>(use.size())) << "seed " << seed << " round " << round;
    }
  }
  EXPECT_GT(failed, 250);
}

// A triangulated torus (genus 1): closed, manifold, oriented, but χ = 0.
TEST(MeshValidate, RejectsTorus) {
  const int nu = 6, nv = 5;
  std::vector<std::array<double, 3>> pts;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      pts.push_back({{(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)}});
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      f.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      f.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(make3(pts), mesh(f), &mc).is_ok());
  EXPECT_TRUE(mc.vertex_manifold);
  EXPECT_EQ(mc.euler, 0);
  EXPECT_EQ(mc.genus, 1);
}

TEST(MeshValidate, RejectsTwoComponents) {
  std::vector<std::array<double, 3>> pts = kTet;
  for (const auto& q : kTet) pts.push_back({{q[0] + 5, q[1], q[2]}});
  std::vector<std::array<int, 3>> f = kTetFaces;
  for (auto t : kTetFaces) f.push_back({{t[0] + 4, t[1] + 4, t[2] + 4}});
  MeshCheck mc;
  EXPECT_FALSE(validate_mesh3(make3(pts), mesh(f), &mc).is_ok());
  EXPECT_EQ(mc.components, 2);
}

TEST(MeshValidate, TriangleIntersections) {
  const PointSet p = make3({{0, 0, 0}, {4, 0, 0}, {0, 4, 0},      // 0..2 triangle in z=0
                            {1, 1, -1}, {1, 1, 1}, {3, 3, 1},     // 3..5 pierces it
                            {1, 1, 2}, {2, 1, 2}, {1, 2, 2},      // 6..8 above, disjoint
                            {1, 1, 0}, {2, 2, 0}, {-1, 1, 0}});   // 9..11 coplanar overlap
  EXPECT_TRUE(triangles_intersect_improperly(p, {{0, 1, 2}}, {{3, 4, 5}}));
  EXPECT_FALSE(triangles_intersect_improperly(p, {{0, 1, 2}}, {{6, 7, 8}}));
  EXPECT_TRUE(triangles_intersect_improperly(p, {{0, 1, 2}}, {{9, 10, 11}}));
  // shared edge, coplanar, same side -> overlap; other side -> fine
  const PointSet q = make3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, -1, 0}, {0.5, 0.5, 1}});
  EXPECT_TRUE(triangles_intersect_improperly(q, {{0, 1, 2}}, {{0, 1, 3}}));
  EXPECT_FALSE(triangles_intersect_improperly(q, {{0, 1, 2}}, {{0, 1, 4}}));
  EXPECT_FALSE(triangles_intersect_improperly(q, {{0, 1, 2}}, {{0, 1, 5}}));
  // shared vertex: coplanar wedges overlapping vs. disjoint
  // shares edge 0-3, coplanar, opposite sides -> proper
  EXPECT_FALSE(triangles_intersect_improperly(q, {{0, 1, 3}}, {{0, 2, 3}}));
  const PointSet r = make3({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {3, 1, 0}, {-1, -1, 0}, {-2, 0, 0}});
  EXPECT_TRUE(triangles_intersect_improperly(r, {{0, 1, 2}}, {{0, 3, 4}}));   // wedge overlap
  EXPECT_FALSE(triangles_intersect_improperly(r, {{0, 1, 2}}, {{0, 5, 6}}));  // opposite wedge
}

TEST(MeshValidate, SelfIntersectingSurface) {
  // Bipyramid whose lower apex is pulled through an upper face.
  const PointSet p = make3({{3, 0, 0}, {-1, 2, 0}, {-1, -2, 0}, {0, 0, 2}, {4, 0, 1.5}});
  std::vector<std::array<int, 3>> f = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}};
  MeshCheckOptions mo;
  mo.self_intersections = true;
  MeshCheck mc;
  Status s = validate_mesh3(p, mesh(f), &mc, mo);
  if (mc.oriented && !mc.outward) {
    for (auto& t : f) std::swap(t[1], t[2]);
    s = validate_mesh3(p, mesh(f), &mc, mo);
  }
  EXPECT_FALSE(s.is_ok());
  EXPECT_TRUE(mc.self_intersection_checked);
  EXPECT_FALSE(mc.no_self_intersections);
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(MeshWrite, FormatsRoundTripVertices) {
  const PointSet p = make3({{0, 0, 0}, {1.5, 0, 0}, {0, 1, 0}, {0, 0, 0.1}});
  const TriMesh3 m = mesh(kTetFaces);
  const std::string dir = ::testing::TempDir();
  for (const std::string ext : {"off", "obj", "ply"}) {
    for (bool ascii : {false, true}) {
      const std::string path = dir + "/constrict_mesh_test." + ext;
      MeshWriteOptions wo;
      wo.ply_ascii = ascii;
      ASSERT_TRUE(write_mesh(path, p, m, wo).is_ok()) << ext;
      PointSet q;
      ReadOptions ro;
      ASSERT_TRUE(read_points(path, ro, q).is_ok()) << ext;
      EXPECT_EQ(q.coords, p.coords) << ext;
      std::remove(path.c_str());
    }
  }
  const std::string stl = dir + "/constrict_mesh_test.stl";
  ASSERT_TRUE(write_mesh(stl, p, m).is_ok());
  EXPECT_EQ(slurp(stl).size(), 84u + 50u * 4u);
  std::remove(stl.c_str());
  const std::string off = slurp((write_mesh(dir + "/m.off", p, m), dir + "/m.off"));
  EXPECT_NE(off.find("3 0 2 1\n"), std::string::npos);
  EXPECT_EQ(write_mesh(dir + "/m.xyz", p, m).code(), StatusCode::WriteFailed);
  EXPECT_EQ(write_mesh("/nonexistent-dir/x.off", p, m).code(), StatusCode::WriteFailed);
  const std::string vtk = dir + "/b.vtk";
  ASSERT_TRUE(write_body_vtk(vtk, p, {{{0, 1, 2, 3}}}).is_ok());
  const std::string v = slurp(vtk);
  EXPECT_NE(v.find("CELLS 1 5\n4 0 1 2 3\n"), std::string::npos);
  EXPECT_NE(v.find("CELL_TYPES 1\n10\n"), std::string::npos);
}

// STL keeps 32-bit floats: a surface whose coordinates leave their range, vanish in them, or whose
// triangle corners round to one point is refused (with the formats that keep doubles), not
// written as infinities, zeros or degenerate triangles (found by a hostile-input sweep).
// Points built by hand (the library, Python) can hold NaN or infinity: the writers put "nan" into
// the files (an adversarial sweep of the Python module), and the body went to any extension.
TEST(MeshWrite, NonFiniteCoordinatesAndWrongBodyExtensionAreRefused) {
  PointSet p = make3({{0, 0, 0}, {1.5, 0, 0}, {0, 1, 0}, {0, 0, 0.1}});
  const TriMesh3 m = mesh(kTetFaces);
  const std::string dir = ::testing::TempDir();
  const std::vector<std::array<int, 4>> tets = {{0, 1, 2, 3}};
  EXPECT_TRUE(write_body_vtk(dir + "/constrict_body.vtk", p, tets).is_ok());
  EXPECT_EQ(write_body_vtk(dir + "/constrict_body.foo", p, tets).code(), StatusCode::InvalidArgument);
  p.coords[7] = std::nan("");
  for (const std::string ext : {"off", "obj", "ply", "stl"}) {
    const std::string path = dir + "/constrict_nan." + ext;
    std::remove(path.c_str());
    EXPECT_EQ(write_mesh(path, p, m).code(), StatusCode::InvalidArgument) << ext;
    EXPECT_FALSE(std::ifstream(path).good()) << ext << ": nothing written";
  }
  EXPECT_EQ(write_body_vtk(dir + "/constrict_body.vtk", p, tets).code(), StatusCode::InvalidArgument);
  PointSet q;
  q.dim = 2;
  q.coords = {0, 0, 1, 0, 0, HUGE_VAL};
  EXPECT_EQ(write_polygon2(dir + "/constrict_inf.csv", q, {0, 1, 2}).code(), StatusCode::InvalidArgument);
  EXPECT_EQ(write_rings2(dir + "/constrict_inf.wkt", q, {Ring2{RingRole::Shell, -1, {0, 1, 2}}}).code(),
            StatusCode::InvalidArgument);
}

TEST(MeshWrite, StlRefusesWhatFloatsCannotHold) {
  const TriMesh3 m = mesh(kTetFaces);
  const std::string path = ::testing::TempDir() + "/constrict_mesh_float.stl";
  struct Case {
    std::vector<std::array<double, 3>> pts;
    const char* says;
  };
  const Case cases[] = {
      {{{0, 0, 0}, {1e300, 0, 0}, {0, 1e300, 0}, {0, 0, 1e300}}, "point 1 has a coordinate (1e+300) beyond the range"},
      {{{0, 0, 0}, {1e-320, 0, 0}, {0, 1e-320, 0}, {0, 0, 1e-320}}, "too close to 0"},
      {{{1, 1, 1}, {1 + 1e-12, 1, 1}, {1, 2, 1}, {1, 1, 2}}, "points 0 and 1 become one point"},
  };
  for (const Case& c : cases) {
    std::remove(path.c_str());
    const Status st = write_mesh(path, make3(c.pts), m);
    EXPECT_EQ(st.code(), StatusCode::WriteFailed) << c.says;
    EXPECT_NE(st.message().find(c.says), std::string::npos) << st.message();
    EXPECT_NE(st.message().find("write .ply, .off or .obj"), std::string::npos) << st.message();
    EXPECT_FALSE(std::ifstream(path).good()) << "no file is written: " << c.says;
    // The formats with doubles keep them.
    EXPECT_TRUE(write_mesh(::testing::TempDir() + "/constrict_mesh_float.ply", make3(c.pts), m).is_ok());
  }
  // Float-representable coordinates (and a shift that floats round but keep apart) are written.
  EXPECT_TRUE(write_mesh(path, make3({{1e30, 0, 0}, {1e30, 1e25, 0}, {1e30, 0, 1e25}, {1.1e30, 0, 0}}), m).is_ok());
  std::remove(path.c_str());
}

// The outward test is exact: a tetrahedron's surface at scales where the double volume overflows
// (2^1000), underflows (2^-1000, and subnormal coordinates), and far from the origin (cancellation).
// The mesh check sums the volume and the orientation filter in one pass, over the surfaces of its
// own union-find: the same bits as mesh_volume() and signed_volume_estimate() apart, on several
// surfaces (one far away) and at scales where mesh_volume rescales the coordinates.
TEST(MeshVolume, OnePassGivesTheBitsOfTheTwoPasses) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    for (const int k : {0, 700, -700}) {
      std::vector<std::array<double, 3>> all;
      std::vector<std::array<int, 3>> faces;
      for (const double shift : {0.0, 3.0, 1e6}) {
        std::vector<std::array<double, 3>> sphere;
        for (int i = 0; i < 150; ++i) {
          double v[3] = {g(rng), g(rng), g(rng)};
          const double r = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
          sphere.push_back({std::ldexp(v[0] / r + shift, k), std::ldexp(v[1] / r, k), std::ldexp(v[2] / r - shift, k)});
        }
        Mesh3Result r;
        ASSERT_TRUE(reconstruct3(make3(sphere), Constrict3Options{}, r).is_ok()) << "seed " << seed;
        const int base = static_cast<int>(all.size());
        for (const auto& f : r.mesh.triangles) faces.push_back({f[0] + base, f[1] + base, f[2] + base});
        all.insert(all.end(), sphere.begin(), sphere.end());
      }
      const PointSet p = make3(all);
      const TriMesh3 m = mesh(faces);
      VolumeEstimate est;
      const double v = detail::mesh_volume_of_surfaces(p, m, detail::surface_of_vertex(p.size(), m), &est);
      const VolumeEstimate apart = signed_volume_estimate(p.coords.data(), m.triangles[0].data(), m.triangles.size());
      // (bit for bit: at 2^700 the filter's sums overflow to NaN, at 2^-700 the volume is 0)
      const auto bits = [](double x) {
        std::uint64_t u;
        std::memcpy(&u, &x, sizeof u);
        return u;
      };
      EXPECT_EQ(bits(v), bits(mesh_volume(p, m))) << "seed " << seed << " 2^" << k;
      if (k == 0) {
        EXPECT_GT(v, 0) << "seed " << seed;
      }
      EXPECT_EQ(bits(est.sum6), bits(apart.sum6)) << "seed " << seed << " 2^" << k;
      EXPECT_EQ(bits(est.bound6), bits(apart.bound6)) << "seed " << seed << " 2^" << k;
      EXPECT_EQ(est.valid, apart.valid) << "seed " << seed << " 2^" << k;
      MeshCheck mc;
      MeshCheckOptions mo;
      mo.any_topology = true;
      ASSERT_TRUE(validate_mesh3(p, m, &mc, mo).is_ok()) << mc.reason;
      EXPECT_EQ(mc.components, 3);
      if (!mc.volume_exact) {
        EXPECT_EQ(mc.volume, v) << "seed " << seed << " 2^" << k;
      }
    }
  }
}

TEST(MeshVolumeSign, ExactAtAnyScale) {
  const int out[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};  // outward for the points below
  for (const int k : {0, 1000, -1000, -1070}) {
    for (const double shift : {0.0, 1e15}) {
      std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
      for (double& c : xyz) c = std::ldexp(c, k) + (k == 0 ? shift : 0.0);
      std::vector<int> tris, rev;
      for (const auto& f : out) {
        tris.insert(tris.end(), {f[0], f[1], f[2]});
        rev.insert(rev.end(), {f[0], f[2], f[1]});
      }
      EXPECT_EQ(signed_volume_sign(xyz.data(), tris.data(), 4), 1) << "2^" << k << " shift " << shift;
      EXPECT_EQ(signed_volume_sign(xyz.data(), rev.data(), 4), -1) << "2^" << k << " shift " << shift;
    }
  }
  // A flat closed "surface" (two copies of one triangle, opposite orientations) has volume 0.
  const std::vector<double> flat = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<int> two = {0, 1, 2, 0, 2, 1};
  EXPECT_EQ(signed_volume_sign(flat.data(), two.data(), 2), 0);
}

// signed_volume_checked(): a well-conditioned sum keeps the double value; the unit tetrahedron at
// any scale and far from the origin with a wrong approximation gives the exact 1/6 (rounded); and a
// needle of 500 near-collinear points (a hostile-geometry sweep, 2026-12-06), whose body's double
// volume sum cancels to -5.5e-23 while the exact volume is +6.2e-35: the result's volume is the
// exact one (reconstruct3's check, and the CLI's).
TEST(MeshVolumeSign, ExactVolumeWhereTheDoubleSumCancels) {
  const int out[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<int> tris;
  for (const auto& f : out) tris.insert(tris.end(), {f[0], f[1], f[2]});
  for (const int k : {0, 300, -300}) {
    std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (double& c : xyz) c = std::ldexp(c, k);
    const double sixth = std::ldexp(1.0, 3 * k) / 6.0;
    bool exact = true;
    EXPECT_EQ(signed_volume_checked(xyz.data(), tris.data(), 4, 0.9 * sixth, &exact), 0.9 * sixth) << "2^" << k;
    EXPECT_FALSE(exact);
    EXPECT_EQ(signed_volume_checked(xyz.data(), tris.data(), 4, -sixth, &exact), sixth) << "2^" << k;
    EXPECT_TRUE(exact);
    for (std::size_t i = 0; i < xyz.size(); i += 3) xyz[i] += std::ldexp(1.0, k + 40);  // (far along x)
    EXPECT_EQ(signed_volume_checked(xyz.data(), tris.data(), 4, 0.0), sixth) << "2^" << k << " moved";
  }
  PointSet p;
  ASSERT_TRUE(test::read_regression3("needle3d_near_collinear_volume_sign.xyz", p).is_ok());
  Mesh3Result r;
  ASSERT_TRUE(reconstruct3(p, Constrict3Options{}, r).is_ok());
  ASSERT_TRUE(r.valid());
  const double approx = mesh_volume(p, r.mesh);
  EXPECT_LE(approx, 0) << "the double sum no longer cancels here: the case says nothing";
  bool exact = false;
  const double v =
      signed_volume_checked(p.coords.data(), r.mesh.triangles[0].data(), r.mesh.triangles.size(), approx, &exact);
  EXPECT_TRUE(exact);
  EXPECT_GT(v, 0);
  EXPECT_EQ(r.volume, v);
}

}  // namespace
}  // namespace constrict
