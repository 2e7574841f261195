// SPDX-License-Identifier: GPL-3.0-or-later
// compare_meshes3 / compare_curves2 on cases with known answers, and read_mesh round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "constrict/compare.hpp"
#include "constrict/mesh.hpp"

using namespace constrict;

namespace {

PointSet pts3(std::initializer_list<double> c) {
  PointSet p;
  p.dim = 3;
  p.coords = c;
  return p;
}

// Unit cube, 8 vertices, 12 outward triangles.
void cube(double dx, PointSet& p, TriMesh3& m) {
  p = pts3({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1});
  for (std::size_t i = 0; i < 8; ++i) p.coords[3 * i] += dx;
  m.triangles = {{{0, 2, 1}}, {{0, 3, 2}}, {{4, 5, 6}}, {{4, 6, 7}}, {{0, 1, 5}}, {{0, 5, 4}},
                 {{1, 2, 6}}, {{1, 6, 5}}, {{2, 3, 7}}, {{2, 7, 6}}, {{3, 0, 4}}, {{3, 4, 7}}};
}

// Coarse sampling keeps the tests fast; the known answers are attained at grid nodes anyway.
DistanceOptions fast() {
  DistanceOptions o;
  o.relative_spacing = 0.02;
  return o;
}

std::string tmp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("constrict_test_compare_" + name)).string();
}

}  // namespace

TEST(CompareMeshes3, IdenticalMeshesHaveDistanceZeroAndFullRecovery) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(p, m, p, m, d, fast()));
  EXPECT_EQ(d.hausdorff, 0.0);
  EXPECT_EQ(d.mean, 0.0);
  EXPECT_EQ(d.triangle_recovery, 1.0);
  EXPECT_EQ(d.triangle_precision, 1.0);
  EXPECT_EQ(d.recovered_triangles, 12u);
  EXPECT_EQ(d.matched_vertices, 8u);
  EXPECT_TRUE(d.identical);
  EXPECT_DOUBLE_EQ(d.bbox_diagonal, std::sqrt(3.0));
  EXPECT_GT(d.samples_result, 1000u);
}

TEST(CompareMeshes3, MatchesTrianglesByPositionNotByIndex) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  // Same cube with the vertex list reversed and the triangles flipped (orientation is ignored).
  PointSet q = p;
  TriMesh3 r;
  for (std::size_t i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) q.coords[3 * i + static_cast<std::size_t>(k)] = p[7 - i][k];
  for (const auto& t : m.triangles) r.triangles.push_back({{7 - t[0], 7 - t[2], 7 - t[1]}});
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(q, r, p, m, d, fast()));
  EXPECT_TRUE(d.identical);
  EXPECT_EQ(d.triangle_recovery, 1.0);
  EXPECT_EQ(d.hausdorff, 0.0);
  // Dropping two triangles of the result: 10 of 12 recovered, the rest is still precise.
  r.triangles.resize(10);
  ASSERT_TRUE(compare_meshes3(q, r, p, m, d, fast()));
  EXPECT_FALSE(d.identical);
  EXPECT_EQ(d.recovered_triangles, 10u);
  EXPECT_DOUBLE_EQ(d.triangle_recovery, 10.0 / 12.0);
  EXPECT_EQ(d.triangle_precision, 1.0);
}

TEST(CompareMeshes3, SinglePrecisionMatchingForStl) {
  // A cube at coordinates no float holds (0.1 + ...), and its copy rounded to floats, as an STL
  // result of it would be: exact matching finds no vertex; float matching finds all, and the
  // distance is the rounding only.
  PointSet p;
  TriMesh3 m;
  cube(0.1, p, m);
  for (double& c : p.coords) c = c * 0.3 + 0.1;
  PointSet q = p;
  for (double& c : q.coords) c = static_cast<double>(static_cast<float>(c));
  ASSERT_NE(p.coords, q.coords);
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(q, m, p, m, d, fast()));
  EXPECT_EQ(d.matched_vertices, 0u);
  EXPECT_EQ(d.recovered_triangles, 0u);
  DistanceOptions o = fast();
  o.match_single_precision = true;
  ASSERT_TRUE(compare_meshes3(q, m, p, m, d, o));
  EXPECT_EQ(d.matched_vertices, 8u);
  EXPECT_EQ(d.recovered_triangles, 12u);
  EXPECT_TRUE(d.identical);
  EXPECT_GT(d.hausdorff, 0.0);  // the rounding is measured, not taken as a shared triangle
  EXPECT_LT(d.hausdorff, 1e-7);
}

TEST(CompareMeshes3, ParallelCopyAtKnownDistance) {
  // A square of two triangles and its copy lifted by 0.25 along its normal: every point is at
  // exactly 0.25 from the other copy.
  const PointSet a = pts3({0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0});
  const PointSet b = pts3({0, 0, 0.25, 2, 0, 0.25, 2, 2, 0.25, 0, 2, 0.25});
  TriMesh3 m;
  m.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(a, m, b, m, d, fast()));
  EXPECT_NEAR(d.hausdorff, 0.25, 1e-12);
  EXPECT_NEAR(d.mean_result_to_reference, 0.25, 1e-12);
  EXPECT_NEAR(d.mean_reference_to_result, 0.25, 1e-12);
  EXPECT_EQ(d.recovered_triangles, 0u);
  EXPECT_EQ(d.matched_vertices, 0u);
}

TEST(CompareMeshes3, TranslatedCubeHasHausdorffEqualToTheShift) {
  PointSet p, q;
  TriMesh3 m, n;
  cube(0, p, m);
  cube(0.1, q, n);
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, d, fast()));
  EXPECT_NEAR(d.hausdorff, 0.1, 1e-12);
  EXPECT_NEAR(d.hausdorff_result_to_reference, 0.1, 1e-12);
  EXPECT_NEAR(d.hausdorff_reference_to_result, 0.1, 1e-12);
  EXPECT_NEAR(d.relative_hausdorff, 0.1 / std::sqrt(3.0), 1e-12);
  EXPECT_GT(d.mean, 0.0);
  EXPECT_LT(d.mean, 0.1);
}

// Far from 1 in magnitude the squared lengths overflowed (inf, then NaN samples per triangle: a
// loop of 2^63 steps from 1e154 on) or underflowed (hostile-input sweep, 2026-12-05). The same
// cubes at 2^±1000 give the same answer, scaled.
TEST(CompareMeshes3, ScaleFreeFarFromOne) {
  PointSet p, q;
  TriMesh3 m, n;
  cube(0, p, m);
  cube(0.1, q, n);
  MeshDistance ref;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, ref, fast()));
  for (int e : {1000, 600, -1000}) {
    PointSet ps = p, qs = q;
    for (double& x : ps.coords) x = std::ldexp(x, e);
    for (double& x : qs.coords) x = std::ldexp(x, e);
    MeshDistance d;
    ASSERT_TRUE(compare_meshes3(qs, n, ps, m, d, fast())) << e;
    EXPECT_EQ(d.relative_hausdorff, ref.relative_hausdorff) << e;
    EXPECT_EQ(d.relative_mean, ref.relative_mean) << e;
    EXPECT_EQ(d.hausdorff, std::ldexp(ref.hausdorff, e)) << e;
    EXPECT_EQ(d.recovered_triangles, ref.recovered_triangles) << e;
    EXPECT_EQ(d.samples_result, ref.samples_result) << e;
  }
}

// Hostile-input sweep (2026-12-07): meshes of very different sizes or positions. Each side's
// sample spacing grows up to its own longest edge (a cube 10^10 times the reference's, or with
// one vertex far off, was sampled at the reference's scale: 10^12 samples per triangle, a hang),
// far samples are measured to the other side's box, and the search runs in doubles (a cube 10^15
// from the other took minutes in exact comparisons). Sizes 2^200 apart are refused by name.
TEST(CompareMeshes3, MeshesOfVeryDifferentSizesAndPlaces) {
  PointSet p, q;
  TriMesh3 m, n;
  cube(0, p, m);
  for (double size : {1e10, 1e-10}) {
    cube(0, q, n);
    for (double& x : q.coords) x *= size;
    MeshDistance d;
    ASSERT_TRUE(compare_meshes3(q, n, p, m, d)) << size;  // (the default spacing and budget)
    EXPECT_LE(d.samples_result, DistanceOptions{}.max_samples) << size;
    EXPECT_LE(d.samples_reference, DistanceOptions{}.max_samples) << size;
    // The farthest corner of the larger cube from the smaller one.
    EXPECT_NEAR(d.hausdorff, std::sqrt(3.0) * std::max(size, 1.0) - (size > 1 ? std::sqrt(3.0) : 0.0),
                1e-9 * std::max(size, 1.0)) << size;
  }
  // One vertex 1e17 off: its triangles are measured, the rest as before.
  cube(0, q, n);
  q.coords[3 * 6] = 1e17;
  MeshDistance far;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, far));
  EXPECT_NEAR(far.hausdorff_result_to_reference, 1e17, 1e11);
  EXPECT_LT(far.hausdorff_reference_to_result, 1.0);
  // 10^15 apart: the distance is the shift (within the coordinates' rounding there).
  cube(1e15, q, n);
  MeshDistance shifted;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, shifted, fast()));
  EXPECT_NEAR(shifted.hausdorff, 1e15, 1.0);
  EXPECT_NEAR(shifted.mean, 1e15, 2.0);
  // A vertex no triangle uses, far off, changes nothing (it made every triangle "tiny").
  cube(0.1, q, n);
  q.coords.insert(q.coords.end(), {1e70, 0, 0});
  MeshDistance stray;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, stray, fast()));
  EXPECT_NEAR(stray.hausdorff, 0.1, 1e-12);
  // A spacing that rounds to 0: the grid's cap, not 5e11 samples per triangle.
  DistanceOptions zero = fast();
  zero.relative_spacing = 4.9e-324;
  cube(0.1, q, n);
  MeshDistance z;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, z, zero));
  EXPECT_LE(z.samples_result, zero.max_samples);
  // Distances beyond the largest double: refused, not inf.
  PointSet hp = p, hq = p;
  for (double& x : hp.coords) x *= 1.5e308;
  for (double& x : hq.coords) x = -x * 1.5e308;
  MeshDistance h;
  EXPECT_EQ(compare_meshes3(hq, m, hp, m, h).code(), StatusCode::NonFinite);
  // 2^300 apart in size: no common frame for the distance search.
  for (double size : {1e100, 1e-100}) {
    cube(0, q, n);
    for (double& x : q.coords) x *= size;
    MeshDistance d;
    const Status st = compare_meshes3(q, n, p, m, d);
    EXPECT_EQ(st.code(), StatusCode::InvalidArgument) << size;
    EXPECT_NE(st.message().find("not at comparable scales"), std::string::npos) << st.message();
  }
}

// A polygon face read as a fan (every triangle from one vertex) gave CGAL's distance search
// thousands of equal reference points: its Kd-tree recursed once per triangle and overflowed the
// stack at 50 000 (hostile-input sweep, 2026-12-05). A fan of 60 000 slivers over a disc.
TEST(CompareMeshes3, FanOfSliversDoesNotRecurseDeeply) {
  const int k = 60000;
  PointSet p;
  p.dim = 3;
  p.coords = {0, 0, 0};
  for (int i = 0; i < k; ++i) {
    const double a = 2 * M_PI * i / k;
    p.coords.insert(p.coords.end(), {std::cos(a), std::sin(a), 0});
  }
  p.coords.insert(p.coords.end(), {0, 0, -1});
  TriMesh3 fan;  // a cone: the fan on top, a second fan below
  for (int i = 0; i < k; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % k;
    fan.triangles.push_back({{0, a, b}});
    fan.triangles.push_back({{k + 1, b, a}});
  }
  DistanceOptions o;
  o.max_samples = 200000;
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(p, fan, p, fan, d, o));
  EXPECT_TRUE(d.identical);
}

TEST(CompareMeshes3, SampleBudgetCoarsensTheSpacing) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  DistanceOptions o;
  o.max_samples = 500;
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(p, m, p, m, d, o));
  EXPECT_LE(d.samples_result, 500u);
  EXPECT_GT(d.spacing_result, 1e-3 * std::sqrt(3.0));
}

// One face repeated 300 000 times overflowed the stack the same way (one reference point each,
// all equal; hostile-input sweep, third round): a repeated triangle is in the distance tree once.
TEST(CompareMeshes3, RepeatedFaceIsInTheTreeOnce) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  TriMesh3 many = m;
  for (int i = 0; i < 300000; ++i) many.triangles.push_back(m.triangles[0]);
  DistanceOptions o;
  o.max_samples = 100000;
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(p, many, p, m, d, o));
  EXPECT_EQ(d.hausdorff, 0.0);
  EXPECT_EQ(d.recovered_triangles, m.triangles.size());
}

// A relative spacing far below any budget (1e-30) stopped widening after 200 steps (1.25^200 ~
// 1e19) and sampled 10^12 points per triangle: the budget now always holds.
TEST(CompareMeshes3, TinySpacingStillKeepsTheBudget) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  for (double spacing : {1e-30, 1e-300, 5e-324}) {
    DistanceOptions o;
    o.relative_spacing = spacing;
    o.max_samples = 1000;
    MeshDistance d;
    ASSERT_TRUE(compare_meshes3(p, m, p, m, d, o)) << spacing;
    EXPECT_LE(d.samples_result, 1000u) << spacing;
    EXPECT_LE(d.samples_reference, 1000u) << spacing;
  }
}

TEST(CompareMeshes3, RejectsBadInput) {
  PointSet p;
  TriMesh3 m;
  cube(0, p, m);
  TriMesh3 bad = m;
  bad.triangles[0][1] = 9;
  MeshDistance d;
  EXPECT_EQ(compare_meshes3(p, bad, p, m, d).code(), StatusCode::InvalidArgument);
  TriMesh3 flat;
  flat.triangles = {{{0, 1, 1}}};
  EXPECT_EQ(compare_meshes3(p, flat, p, m, d).code(), StatusCode::InvalidArgument);
  DistanceOptions o;
  o.relative_spacing = 0;
  EXPECT_EQ(compare_meshes3(p, m, p, m, d, o).code(), StatusCode::InvalidArgument);
}

TEST(CompareCurves2, IdenticalAndTranslatedSquares) {
  Polyline2 a{{0, 0, 1, 0, 1, 1, 0, 1}, true};
  CurveDistance2 d;
  ASSERT_TRUE(compare_curves2({a}, {a}, d, fast()));
  EXPECT_EQ(d.hausdorff, 0.0);
  EXPECT_EQ(d.mean, 0.0);
  // The same square listed from another vertex and reversed: still exactly 0.
  ASSERT_TRUE(compare_curves2({Polyline2{{1, 1, 1, 0, 0, 0, 0, 1}, true}}, {a}, d, fast()));
  EXPECT_EQ(d.hausdorff, 0.0);
  Polyline2 b = a;
  for (std::size_t i = 0; i < b.xy.size(); i += 2) b.xy[i] += 0.2;
  ASSERT_TRUE(compare_curves2({b}, {a}, d, fast()));
  EXPECT_NEAR(d.hausdorff, 0.2, 1e-12);
  EXPECT_NEAR(d.relative_hausdorff, 0.2 / std::sqrt(2.0), 1e-12);
  // An open polyline lies on the square; the square's edge it leaves out is up to 0.5 away.
  Polyline2 open{{0, 0, 1, 0, 1, 1, 0, 1}, false};
  ASSERT_TRUE(compare_curves2({open}, {a}, d, fast()));
  EXPECT_NEAR(d.hausdorff_result_to_reference, 0.0, 1e-15);
  EXPECT_NEAR(d.hausdorff_reference_to_result, 0.5, 1e-12);
}

// Curves far from 1 in magnitude are measured as 3D meshes are (the squared distances overflowed
// near 1e200: a Hausdorff distance of 0 and a mean of NaN; hostile-input sweep 2026-12-07).
TEST(CompareCurves2, ScaleFreeFarFromOne) {
  const Polyline2 a{{0, 0, 1, 0, 1, 1, 0, 1}, true};
  Polyline2 b = a;
  for (std::size_t i = 0; i < b.xy.size(); i += 2) b.xy[i] += 0.2;
  CurveDistance2 ref;
  ASSERT_TRUE(compare_curves2({b}, {a}, ref, fast()));
  for (int e : {700, 1000, -700, -1000}) {
    Polyline2 as = a, bs = b;
    for (double& x : as.xy) x = std::ldexp(x, e);
    for (double& x : bs.xy) x = std::ldexp(x, e);
    CurveDistance2 d;
    ASSERT_TRUE(compare_curves2({bs}, {as}, d, fast())) << e;
    EXPECT_EQ(d.relative_hausdorff, ref.relative_hausdorff) << e;
    EXPECT_EQ(d.relative_mean, ref.relative_mean) << e;
    EXPECT_EQ(d.hausdorff, std::ldexp(ref.hausdorff, e)) << e;
  }
}

TEST(CompareCurves2, FromIndices) {
  PointSet p;
  p.dim = 2;
  p.coords = {0, 0, 4, 0, 4, 4, 0, 4, 2, 1};
  Reference2 ref;
  ref.closed = {{0, 1, 2, 3}};
  CurveDistance2 d;
  ASSERT_TRUE(compare_curves2({polygon_polyline2(p, {0, 4, 1, 2, 3})}, reference_polylines2(p, ref), d, fast()));
  EXPECT_NEAR(d.hausdorff_result_to_reference, 1.0, 1e-12);  // the dent at (2,1)
  EXPECT_NEAR(d.hausdorff_reference_to_result, 2 / std::sqrt(5.0), 1e-9);  // (2,0) to the dent's sides
  EXPECT_EQ(compare_curves2({}, reference_polylines2(p, ref), d).code(), StatusCode::InvalidArgument);
}

TEST(ReadMesh, RoundTripEveryFormat) {
  PointSet p;
  TriMesh3 m;
  cube(0.5, p, m);
  p.coords[0] = 0.1;  // a non-representable decimal must survive
  for (const char* ext : {"off", "obj", "ply", "stl"}) {
    for (bool ascii : {false, true}) {
      const std::string path = tmp(std::string("rt_") + (ascii ? "a." : "b.") + ext);
      MeshWriteOptions wo;
      wo.ply_ascii = ascii;
      ASSERT_TRUE(write_mesh(path, p, m, wo)) << path;
      PointSet q;
      TriMesh3 n;
      MeshReadReport rep;
      const Status s = read_mesh(path, q, n, &rep);
      ASSERT_TRUE(s) << s.message();
      EXPECT_EQ(rep.polygons, 12u);
      if (std::string(ext) == "stl") {
        // float32 coordinates; shared corners are merged by position
        EXPECT_EQ(q.size(), 8u);
        EXPECT_EQ(n.triangles.size(), 12u);
      } else {
        EXPECT_EQ(q.coords, p.coords) << path;
        EXPECT_EQ(n.triangles, m.triangles) << path;
        MeshDistance d;
        ASSERT_TRUE(compare_meshes3(q, n, p, m, d, fast()));
        EXPECT_TRUE(d.identical);
      }
      std::remove(path.c_str());
    }
  }
}

TEST(ReadMesh, QuadsAreSplitAndErrorsNameTheLine) {
  const std::string path = tmp("quad.off");
  {
    std::ofstream f(path);
    f << "OFF\n# a comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  }
  PointSet q;
  TriMesh3 n;
  MeshReadReport rep;
  ASSERT_TRUE(read_mesh(path, q, n, &rep));
  EXPECT_EQ(n.triangles.size(), 2u);
  EXPECT_EQ(rep.split_polygons, 1u);
  {
    std::ofstream f(path);
    f << "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n";
  }
  Status s = read_mesh(path, q, n);
  EXPECT_EQ(s.code(), StatusCode::ParseError);
  EXPECT_NE(s.message().find("quad.off:6: vertex index 3 out of range"), std::string::npos) << s.message();
  const std::string obj = tmp("bad.obj");
  {
    std::ofstream f(obj);
    f << "v 0 0 0\nv 1 0 0\nv 1 x 0\n";
  }
  s = read_mesh(obj, q, n);
  EXPECT_EQ(s.code(), StatusCode::ParseError);
  EXPECT_NE(s.message().find("bad.obj:3:"), std::string::npos) << s.message();
  EXPECT_EQ(read_mesh(tmp("missing.off"), q, n).code(), StatusCode::FileNotFound);
  EXPECT_EQ(read_mesh(tmp("x.xyz"), q, n).code(), StatusCode::ParseError);
  std::remove(path.c_str());
  std::remove(obj.c_str());
}

TEST(ReadMesh, ReadsTheSharedGroundTruth) {
  const std::string gt = std::string(CONSTRICT_SHARED_DIR) + "/data/3d/knight_sparse_gt.off";
  if (!std::filesystem::exists(gt)) GTEST_SKIP() << "shared data not found";
  PointSet q;
  TriMesh3 n;
  ASSERT_TRUE(read_mesh(gt, q, n));
  EXPECT_EQ(q.size(), 502u);
  EXPECT_EQ(n.triangles.size(), 2u * 502u - 4u);
  MeshCheck chk;
  EXPECT_TRUE(validate_mesh3(q, n, &chk)) << chk.reason;
}

// The worst error is located: one corner of the result cube pulled out by 0.5 along z; the farthest
// result sample is that corner, on a triangle holding vertex 6.
TEST(CompareMeshes3, WorstErrorIsLocatedOnTheDisplacedCorner) {
  PointSet p, q;
  TriMesh3 m, n;
  cube(0, p, m);
  cube(0, q, n);
  q.coords[3 * 6 + 2] += 0.5;
  MeshDistance d;
  ASSERT_TRUE(compare_meshes3(q, n, p, m, d, fast()));
  EXPECT_NEAR(d.hausdorff_result_to_reference, 0.5, 1e-12);
  ASSERT_GE(d.worst_result_element, 0);
  const auto& f = n.triangles[static_cast<std::size_t>(d.worst_result_element)];
  EXPECT_TRUE(f[0] == 6 || f[1] == 6 || f[2] == 6);
  EXPECT_GE(d.worst_reference_element, 0);
}
