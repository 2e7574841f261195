// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 20: every public function taking points checks finiteness first and returns NonFinite
// (validate_polygon used to feed an infinity to orient2 and fail a CGAL assertion).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "constrict/compare.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/render.hpp"
#include "constrict/validate.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace constrict {
namespace {

const double kBad[] = {std::numeric_limits<double>::quiet_NaN(), HUGE_VAL, -HUGE_VAL};

PointSet square_with(double bad) {
  PointSet p;
  p.dim = 2;
  p.coords = {0, 0, 4, 0, bad, 4, 0, 4};
  return p;
}

PointSet tetra_with(double bad) {
  PointSet p;
  p.dim = 3;
  p.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, bad};
  return p;
}

TriMesh3 tetra_mesh() {
  TriMesh3 m;
  m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{0, 3, 2}}};
  return m;
}

void expect_non_finite(const Status& st, const char* what) {
  EXPECT_EQ(st.code(), StatusCode::NonFinite) << what << ": " << st.message();
  EXPECT_EQ(st.message().find('\n'), std::string::npos) << what;
}

TEST(NonFinite, EveryPublicFunction2D) {
  for (double bad : kBad) {
    const PointSet p = square_with(bad);
    const std::vector<int> poly = {0, 1, 2, 3};
    expect_non_finite(validate_polygon(p, poly), "validate_polygon");
    expect_non_finite(validate_polygon_brute_force(p, poly), "validate_polygon_brute_force");
    expect_non_finite(validate_polygon_in_triangulation(p, poly, {{{0, 1, 2}}, {{0, 2, 3}}}),
                      "validate_polygon_in_triangulation");
    std::vector<int> q = poly;
    expect_non_finite(refine_polygon2(p, q), "refine_polygon2");
    Polygon2Result r2;
    expect_non_finite(reconstruct2(p, Constrict2Options{}, r2), "reconstruct2");
    Delaunay2 d2;
    expect_non_finite(build_delaunay2(p, d2), "build_delaunay2");
    DelaunayGamma2 g2;
    expect_non_finite(delaunay_gamma2(p, g2), "delaunay_gamma2");
    GammaFaces f;
    expect_non_finite(build_gamma_graph(p, GraphSpec::fixed(-0.1, -0.1), f), "build_gamma_graph");
    expect_non_finite(brute_force_gamma_faces(p, f), "brute_force_gamma_faces");
    VoronoiSkeleton2Result v2;
    expect_non_finite(voronoi_skeleton2(p, VoronoiSkeletonOptions{}, v2), "voronoi_skeleton2");
    Image img;
    RenderOptions2 ro;
    ro.width = ro.height = 16;
    expect_non_finite(render_sheet2(p, {Panel2{poly, nullptr}}, ro, img), "render_sheet2");
  }
}

TEST(NonFinite, EveryPublicFunction3D) {
  for (double bad : kBad) {
    const PointSet p = tetra_with(bad);
    const TriMesh3 m = tetra_mesh();
    expect_non_finite(validate_mesh3(p, m), "validate_mesh3");
    Mesh3Result r3;
    expect_non_finite(reconstruct3(p, Constrict3Options{}, r3), "reconstruct3");
    Delaunay3 d3;
    expect_non_finite(build_delaunay3(p, d3), "build_delaunay3");
    DelaunayGamma3 g3;
    expect_non_finite(delaunay_gamma3(p, g3), "delaunay_gamma3");
    GammaFaces f;
    expect_non_finite(build_gamma_graph(p, GraphSpec::fixed(0, 0), f), "build_gamma_graph");
    VoronoiSkeleton3Result v3;
    expect_non_finite(voronoi_skeleton3(p, VoronoiSkeletonOptions{}, v3), "voronoi_skeleton3");
    MeshDistance md;
    PointSet ok = tetra_with(1);
    expect_non_finite(compare_meshes3(p, m, ok, m, md), "compare_meshes3 (result)");
    expect_non_finite(compare_meshes3(ok, m, p, m, md), "compare_meshes3 (reference)");
    Image img;
    RenderOptions3 ro;
    ro.width = ro.height = 16;
    expect_non_finite(render_mesh3(p, m, {View{}}, ro, img), "render_mesh3");
  }
}

// mesh_volume / mesh_area near the double range: never NaN (the validation printed
// "signed volume -nan").
TEST(NonFinite, MeshVolumeAndAreaNeverNaN) {
  PointSet p;
  p.dim = 3;
  p.coords = {1e-317, 0, 0, 4e298, 0, 0, 0, 4e298, 0, 0, 0, 4e298};
  const TriMesh3 m = tetra_mesh();
  EXPECT_FALSE(std::isnan(mesh_volume(p, m)));
  EXPECT_FALSE(std::isnan(mesh_area(p, m)));
  p.coords = {-1.7e308, -1.7e308, -1.7e308, 1.7e308, -1.7e308, -1.7e308, -1.7e308, 1.7e308, -1.7e308,
              -1.7e308, -1.7e308, 1.7e308};
  EXPECT_FALSE(std::isnan(mesh_volume(p, m)));
  EXPECT_FALSE(std::isnan(mesh_area(p, m)));
  // Ordinary magnitudes: the unit tetrahedron (outward: volume +1/6).
  p.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_DOUBLE_EQ(std::fabs(mesh_volume(p, m)), 1.0 / 6);
}

}  // namespace
}  // namespace constrict
