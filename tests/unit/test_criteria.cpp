// SPDX-License-Identifier: GPL-3.0-or-later
// Selection criteria (criterion.hpp, docs/comparison-methods.md): hand-computed keys and the
// orderings they imply on small cases, 2D and 3D. Hand values below were computed independently
// (plain trigonometry / cross products, written out in the comments).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/criterion.hpp"
#include "constrict/validate.hpp"

namespace constrict {
namespace {

TEST(Criteria, NamesRoundTrip) {
  for (Criterion c : {Criterion::Gamma, Criterion::MinAreaChange, Criterion::Boissonnat}) {
    Criterion back = Criterion::Gamma;
    ASSERT_TRUE(criterion_from_name(criterion_name(c), back));
    EXPECT_EQ(back, c);
  }
  Criterion x = Criterion::MinAreaChange;
  EXPECT_FALSE(criterion_from_name("voronoi-skeleton", x));
  EXPECT_EQ(x, Criterion::MinAreaChange);
}

// 2D keys. Boundary edge a=(0,0) -> b=(2,0).
//  y1 = (1,1): right angle at y1, r/R = sin 90° = 1 -> 1-γ = 1.
//     |ay| = |yb| = √2, |ab| = 2: ratio (2√2-2)/(2√2+2) = (√2-1)^2 = 3-2√2 = 0.171573.
//  y2 = (0.1,0.5): cos φ = ((-0.1)(1.9)+(-0.5)(-0.5)) / (|(-0.1,-0.5)| |(1.9,-0.5)|)
//     = 0.06 / (0.509902 * 1.964688) = 0.059892 -> φ = 86.566°, acute: 1-γ = sin φ = 0.998205.
//     ratio = (0.509902 + 1.964688 - 2) / (0.509902 + 1.964688 + 2) = 0.474590/4.474590 = 0.106063.
//  So γ prefers y1 (1 > 0.998205) and min-area-change prefers y2 (0.106063 < 0.171573): the two
//  criteria order these triangles differently (γ: widest angle; area change: nearest in the
//  ellipse sense |ay| + |yb|).
TEST(Criteria, Keys2DHandValues) {
  const double a[2] = {0, 0}, b[2] = {2, 0}, y1[2] = {1, 1}, y2[2] = {0.1, 0.5};
  EXPECT_NEAR(criterion_key2(Criterion::Gamma, a, b, y1), 1.0, 1e-12);
  EXPECT_NEAR(criterion_key2(Criterion::Gamma, a, b, y2), 0.998205, 1e-6);
  EXPECT_NEAR(area_change_ratio2(a, b, y1), 3 - 2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(area_change_ratio2(a, b, y2), 0.106063, 1e-6);
  EXPECT_NEAR(criterion_key2(Criterion::MinAreaChange, a, b, y2), -0.106063, 1e-6);
  // Boissonnat 84a = γ in 2D.
  EXPECT_EQ(criterion_key2(Criterion::Boissonnat, a, b, y2), criterion_key2(Criterion::Gamma, a, b, y2));
  // Orderings.
  EXPECT_GT(criterion_key2(Criterion::Gamma, a, b, y1), criterion_key2(Criterion::Gamma, a, b, y2));
  EXPECT_LT(criterion_key2(Criterion::MinAreaChange, a, b, y1), criterion_key2(Criterion::MinAreaChange, a, b, y2));
  // y = (1, 0.5): obtuse, cos φ = (-1+0.25)/1.25 = -0.6, sin φ = 0.8 -> γ = -0.2, 1-γ = 1.2;
  // ratio (2·1.118034 - 2)/(2·1.118034 + 2) = 0.236068/4.236068 = 0.055728.
  const double y3[2] = {1, 0.5};
  EXPECT_NEAR(criterion_key2(Criterion::Gamma, a, b, y3), 1.2, 1e-12);
  EXPECT_NEAR(area_change_ratio2(a, b, y3), 0.055728, 1e-6);
}

class FirstRemoval2 final : public Constrict2Visitor {
 public:
  void on_event(const Constrict2Event& e) override {
    if (e.kind == Constrict2Event::Kind::RemoveTriangle) events.push_back(e);
  }
  std::vector<Constrict2Event> events;
};

// Box A(0,0) B(6,0) C(6,3) D(0,3), interior y1 = (3,1) (index 4) and y2 = (0.5,2.6) (index 5).
// Delaunay hull triangles (their circumcircles contain no other point: (A,B,y1) has centre
// (3,-4), R 5; (C,D,y2) centre (3,6.2375), R 4.414). Candidates of the first step, by hand:
//   edge   apex  1-γ         area-change ratio
//   A->B   y1    1.400000    0.026334   (φ = 143.13°, sin φ = 0.6; |Ay1| = √10)
//   C->D   y2    1.320310    0.012739   (φ = 137.18°, sin φ = 0.6799)
//   D->A   y2    1.115210    0.045794
//   B->C   y1    0.789352    0.385739   (or y2: 0.491831 / 0.588988)
// γ removes (A,B,y1) first; min-area-change removes (C,D,y2) first.
TEST(Criteria, Engine2DFirstRemovalFollowsTheCriterion) {
  PointSet p;
  p.dim = 2;
  p.coords = {0, 0, 6, 0, 6, 3, 0, 3, 3, 1, 0.5, 2.6};
  struct Case { Criterion c; int apex; double key; };
  const Case cases[] = {{Criterion::Gamma, 4, 1.4},
                        {Criterion::Boissonnat, 4, 1.4},
                        {Criterion::MinAreaChange, 5, -0.012738852}};
  std::vector<int> gamma_boundary;
  for (const Case& k : cases) {
    SCOPED_TRACE(criterion_name(k.c));
    Constrict2Options o;
    o.criterion = k.c;
    FirstRemoval2 v;
    Polygon2Result r;
    ASSERT_TRUE(reconstruct2(p, o, r, &v).is_ok());
    EXPECT_TRUE(r.complete);
    EXPECT_TRUE(validate_polygon(p, r.boundary).is_ok());
    ASSERT_FALSE(v.events.empty());
    EXPECT_EQ(v.events[0].triangle[2], k.apex);
    EXPECT_NEAR(v.events[0].criterion, k.key, 1e-6);
    if (k.c == Criterion::Gamma) gamma_boundary = r.boundary;
    if (k.c == Criterion::Boissonnat) {
      EXPECT_EQ(r.boundary, gamma_boundary);
    }
  }
}

// 3D keys. Right-corner tetrahedron O(0,0,0), X(1,0,0), Y(0,1,0), Z(0,0,1): the three leg faces
// have area 1/2, the hypotenuse face √3/2.
//  one boundary face = hypotenuse: (3/2 - √3/2)/(3/2 + √3/2) = (3-√3)/(3+√3) = 2 - √3 = 0.267949
//  one boundary face = a leg:      (1 + √3/2 - 1/2)/(3/2 + √3/2) = 1/√3 = 0.577350
//  two boundary faces = two legs:  (1/2 + √3/2 - 1)/(3/2 + √3/2) = (√3-1)/(3+√3) = 0.154701
// Regular tetrahedron (all areas equal): one face 2/4 = 0.5, two faces 0.
TEST(Criteria, AreaChangeRatio3HandValues) {
  const double O[3] = {0, 0, 0}, X[3] = {1, 0, 0}, Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1};
  const double hyp = triangle_area3(X, Y, Z), leg = triangle_area3(O, X, Y);
  EXPECT_NEAR(hyp, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(leg, 0.5, 1e-12);
  const double areas[4] = {hyp, leg, leg, leg};
  const bool hyp_bd[4] = {true, false, false, false}, leg_bd[4] = {false, true, false, false},
             two_legs[4] = {false, true, true, false};
  EXPECT_NEAR(area_change_ratio3(areas, hyp_bd), 2 - std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(area_change_ratio3(areas, leg_bd), 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(area_change_ratio3(areas, two_legs), (std::sqrt(3.0) - 1) / (3 + std::sqrt(3.0)), 1e-12);
  const double eq[4] = {1, 1, 1, 1};
  const bool one[4] = {true, false, false, false}, two[4] = {true, true, false, false};
  EXPECT_DOUBLE_EQ(area_change_ratio3(eq, one), 0.5);
  EXPECT_DOUBLE_EQ(area_change_ratio3(eq, two), 0.0);
}

class FirstRemoval3 final : public Constrict3Visitor {
 public:
  void on_event(const Constrict3Event& e) override {
    if (e.kind == Constrict3Event::Kind::RemoveTet) events.push_back(e);
  }
  std::vector<Constrict3Event> events;
};

// Hull V0(0,0,0) V1(4,0,0) V2(0,4,0) V3(0,0,4) and one interior point p = (0.6,0.7,1.0) (index
// 4): the Delaunay tetrahedralization is the four cones from p over the hull faces; each is
// removable by the one-face rule, and the first removal puts p on the surface (the run ends).
// Hand values per hull face (1-γ from the circumsphere of face + p and the face's circumcircle;
// areas by cross products, listed as hull face, then the three faces at p):
//   face     1-γ        ratio      areas
//   (0,1,2)  1.139561   0.152075   8, 2.441311, 6.095900, 2.332381
//   (0,1,3)  1.343512   0.084538   8, 2.441311, 5.192302, 1.843909
//   (0,2,3)  1.434491   0.063196   8, 2.332381, 4.903060, 1.843909
//   (1,2,3)  1.445300   0.077705   13.856406, 6.095900, 4.903060, 5.192302
// γ (and Boissonnat) remove the cone over (1,2,3); min-area-change the cone over (0,2,3).
TEST(Criteria, Engine3DFirstRemovalFollowsTheCriterion) {
  PointSet p;
  p.dim = 3;
  p.coords = {0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, 4, 0.6, 0.7, 1.0};
  struct Case { Criterion c; std::array<int, 4> tet; double key; };
  const Case cases[] = {{Criterion::Gamma, {{1, 2, 3, 4}}, 1.445300381},
                        {Criterion::Boissonnat, {{1, 2, 3, 4}}, 1.445300381},
                        {Criterion::MinAreaChange, {{0, 2, 3, 4}}, -0.063196194}};
  for (const Case& k : cases) {
    SCOPED_TRACE(criterion_name(k.c));
    Constrict3Options o = Constrict3Options::paper();
    o.criterion = k.c;
    FirstRemoval3 v;
    Mesh3Result r;
    ASSERT_TRUE(reconstruct3(p, o, r, &v).is_ok());
    EXPECT_TRUE(r.complete);
    ASSERT_EQ(v.events.size(), 1u);
    auto t = v.events[0].tet;
    std::sort(t.begin(), t.end());
    EXPECT_EQ(t, k.tet);
    EXPECT_EQ(v.events[0].boundary_faces, 1);
    EXPECT_NEAR(v.events[0].criterion, k.key, 1e-6);
  }
}

// Two-face tetrahedra: Boissonnat 84a ranks one by its better face (max of 1-γ), the paper's γ by
// the sum. With equal one-face keys, Boissonnat must equal Gamma with TwoFaceKey::Max exactly,
// and every two-face key of Boissonnat lies in [0, 2] (the one-face scale), while Gamma/Sum keys
// of two-face removals are in [0, 4].
TEST(Criteria, Boissonnat3DIsGammaWithMaxTwoFaceKey) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  PointSet p;
  p.dim = 3;
  for (int i = 0; i < 400; ++i) {
    double v[3] = {g(rng), g(rng), g(rng)};
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double r = 1 + 0.05 * g(rng);
    for (double x : v) p.coords.push_back(r * x / l);
  }
  Constrict3Options bo = Constrict3Options::paper(), gm = Constrict3Options::paper();
  bo.criterion = Criterion::Boissonnat;
  gm.two_face_key = TwoFaceKey::Max;
  FirstRemoval3 vb, vg;
  Mesh3Result rb, rg;
  ASSERT_TRUE(reconstruct3(p, bo, rb, &vb).is_ok());
  ASSERT_TRUE(reconstruct3(p, gm, rg, &vg).is_ok());
  EXPECT_EQ(rb.mesh.triangles, rg.mesh.triangles);
  ASSERT_EQ(vb.events.size(), vg.events.size());
  std::size_t two = 0;
  for (std::size_t i = 0; i < vb.events.size(); ++i) {
    EXPECT_EQ(vb.events[i].tet, vg.events[i].tet);
    EXPECT_EQ(vb.events[i].criterion, vg.events[i].criterion);
    if (vb.events[i].boundary_faces == 2) {
      ++two;
      EXPECT_LE(vb.events[i].criterion, 2.0);
    }
  }
  EXPECT_GT(two, 0u) << "no two-face removal: the case does not exercise the rule";
}

}  // namespace
}  // namespace constrict
