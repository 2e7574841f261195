// SPDX-License-Identifier: GPL-3.0-or-later
// Rendering: golden images with a tolerance (a tetrahedron, a square with a dent), hidden surfaces
// stay hidden whatever the triangle order, thread-count independence, PNG round trip, and the SVG
// writer produces well-formed XML. Regenerate the golden files with CONSTRICT_UPDATE_GOLDEN=1.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/render.hpp"

using namespace constrict;

namespace {

const std::string kGolden = std::string(CONSTRICT_TEST_DATA_DIR) + "/render/";

std::string tmp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("constrict_test_render_" + name)).string();
}

// Share of pixels whose largest channel difference exceeds `tol`.
double differing(const Image& a, const Image& b, int tol) {
  if (a.width != b.width || a.height != b.height) return 1.0;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    int d = 0;
    for (std::size_t k = 0; k < 3; ++k) d = std::max(d, std::abs(int(a.rgb[i + k]) - int(b.rgb[i + k])));
    bad += d > tol;
  }
  return static_cast<double>(bad) / static_cast<double>(a.rgb.size() / 3);
}

void expect_golden(const Image& img, const std::string& name) {
  const std::string path = kGolden + name;
  if (std::getenv("CONSTRICT_UPDATE_GOLDEN")) {
    ASSERT_TRUE(write_png(path, img));
  }
  Image ref;
  const Status s = read_png(path, ref);
  ASSERT_TRUE(s) << s.message();
  // Tolerance: 0.5 % of the pixels may differ by more than 16 levels (edge pixels, rounding of
  // another libm); the images here are produced with exact arithmetic on small integers.
  EXPECT_LE(differing(img, ref, 16), 0.005) << name;
}

PointSet tetra_points() {
  PointSet p;
  p.dim = 3;
  p.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  return p;
}
TriMesh3 tetra_mesh() {
  TriMesh3 m;
  m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
  return m;
}

std::size_t count_colour(const Image& img, std::array<std::uint8_t, 3> c, int tol) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const auto p = img.at(x, y);
      n += std::abs(p[0] - c[0]) <= tol && std::abs(p[1] - c[1]) <= tol && std::abs(p[2] - c[2]) <= tol;
    }
  return n;
}

// A square with a dent at point 4 (polygon 0 4 1 2 3), drawn over its Delaunay graph with point 4
// and edge 0-4 highlighted: the 2D picture and the SVG writer are checked on the same scene.
struct DentedSquare {
  PointSet p;
  GammaFaces dt;
  PolygonSvgLayers layers;  // points into dt: fill in place, do not copy
};

void make_dented_square(DentedSquare& sq) {
  sq.p.dim = 2;
  sq.p.coords = {0, 0, 4, 0, 4, 4, 0, 4, 2, 1};
  GraphSpec spec;
  ASSERT_TRUE(GraphSpec::from_preset("delaunay", spec));
  ASSERT_TRUE(build_gamma_graph(sq.p, spec, sq.dt));
  sq.layers.graph = &sq.dt;
  sq.layers.highlight_points = {4};
  sq.layers.highlight_edges = {{{0, 4}}};
}

}  // namespace

TEST(Render3, TetrahedronGolden) {
  RenderOptions3 o;
  o.width = o.height = 64;
  Image img;
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {}, o, img));
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.at(0, 0), o.background);
  EXPECT_NE(img.at(32, 32), o.background);
  expect_golden(img, "tetra_64.png");
  o.wireframe = true;
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {View{35, 25}, View{215, -25}}, o, img));
  expect_golden(img, "tetra_wire_2views_64.png");
}

// Far from 1 the normals' cross products overflowed or underflowed: a blank picture at 1e-100
// and 1e200, a flat dark one at 1e100 (hostile-input sweep, 2026-12-05). The picture is the same
// at any power-of-two scale.
TEST(Render3, SamePictureFarFromOne) {
  RenderOptions3 o;
  o.width = o.height = 64;
  Image ref;
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {}, o, ref));
  for (int e : {-400, 300, 700}) {
    PointSet p = tetra_points();
    for (double& x : p.coords) x = std::ldexp(x, e);
    Image img;
    ASSERT_TRUE(render_mesh3(p, tetra_mesh(), {}, o, img)) << e;
    EXPECT_EQ(img.rgb, ref.rgb) << e;
  }
}

// Hostile-argument sweep of render (2026-12-07): an unused vertex far off scaled the picture by its
// exponent (a unit tetrahedron beside an unused vertex at 1e100 drew blank); a view angle of
// 6e307 degrees overflowed in the conversion to radians (blank); a mesh of degenerate triangles
// drew nothing and was accepted. Now: the same picture as without the unused vertex, the same as
// the angle reduced to a turn, and a refusal.
TEST(Render3, UnusedVerticesAndHugeAnglesDrawTheSamePicture) {
  RenderOptions3 o;
  o.width = o.height = 64;
  Image ref;
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {}, o, ref));
  for (double far : {1e100, -1e300, 1e-200}) {
    PointSet p = tetra_points();
    p.coords.insert(p.coords.end(), {far, 0, 0});
    Image img;
    ASSERT_TRUE(render_mesh3(p, tetra_mesh(), {}, o, img)) << far;
    EXPECT_EQ(img.rgb, ref.rgb) << far;
  }
  const double turns = 6e307;  // fmod(6e307, 360) is exact
  const View reduced{std::fmod(turns, 360.0), std::fmod(-turns, 360.0)};
  Image a, b;
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {View{turns, -turns}}, o, a));
  ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {reduced}, o, b));
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_GT(count_colour(a, o.background, 0), 0u);
  EXPECT_LT(count_colour(a, o.background, 0), static_cast<std::size_t>(64 * 64));  // not blank
  PointSet line;
  line.dim = 3;
  line.coords = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
  TriMesh3 flat;
  flat.triangles = {{{0, 1, 2}}, {{1, 2, 3}}, {{0, 0, 3}}};
  const Status s = render_mesh3(line, flat, {}, o, a);
  EXPECT_EQ(s.code(), StatusCode::InvalidArgument);
  EXPECT_NE(s.message().find("no triangle with a positive area"), std::string::npos) << s.message();
}

// A face repeated (same orientation, any cyclic start) draws as once: the same picture, wireframe
// too (a face repeated 3·10^5 times took minutes, each copy rasterised over the whole picture). A
// repeat with the opposite orientation is another face and is kept.
TEST(Render3, RepeatedFacesDrawAsOnce) {
  RenderOptions3 o;
  o.width = o.height = 64;
  for (bool wire : {false, true}) {
    o.wireframe = wire;
    Image ref, img;
    ASSERT_TRUE(render_mesh3(tetra_points(), tetra_mesh(), {}, o, ref));
    TriMesh3 rep = tetra_mesh();
    const auto faces = rep.triangles;
    for (int k = 0; k < 50; ++k)
      for (const auto& f : faces) rep.triangles.push_back(k % 2 ? f : std::array<int, 3>{{f[1], f[2], f[0]}});
    ASSERT_TRUE(render_mesh3(tetra_points(), rep, {}, o, img));
    EXPECT_EQ(img.rgb, ref.rgb) << wire;
  }
}

TEST(Render3, HiddenFacesAreHidden) {
  // Seen from +z: a big triangle at z = 1 facing the camera (front colour) covers a small one at
  // z = 0 facing away (back colour). The small one must never show, in either triangle order.
  PointSet p;
  p.dim = 3;
  p.coords = {-4, -4, 1, 4, -4, 1, 0, 4, 1, -0.5, -0.5, 0, 0, 0.5, 0, 0.5, -0.5, 0};
  RenderOptions3 o;
  o.width = o.height = 96;
  const View top{0, 90};
  const auto back_pixels = [&](const TriMesh3& m) {
    Image img;
    EXPECT_TRUE(render_mesh3(p, m, {top}, o, img));
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const auto c = img.at(x, y);
        n += c[0] > c[2];  // back colour is red-dominant, front colour blue-dominant
      }
    return n;
  };
  TriMesh3 small_only, small_first, big_first;
  small_only.triangles = {{{3, 4, 5}}};
  small_first.triangles = {{{3, 4, 5}}, {{0, 1, 2}}};
  big_first.triangles = {{{0, 1, 2}}, {{3, 4, 5}}};
  EXPECT_GT(back_pixels(small_only), 50u);  // control: alone it is visible (and red)
  EXPECT_EQ(back_pixels(small_first), 0u);
  EXPECT_EQ(back_pixels(big_first), 0u);
}

TEST(Render3, SameImageOnAnyThreadCountAndSheetLayout) {
  // A finely triangulated closed surface (octahedron subdivided) rendered with 1 and 2 threads.
  PointSet p;
  p.dim = 3;
  TriMesh3 m;
  const int k = 40;
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j) p.coords.insert(p.coords.end(), {i / double(k), j / double(k), 0.3 * std::sin(i * 0.3) * std::cos(j * 0.2)});
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int a = i * (k + 1) + j;
      m.triangles.push_back({{a, a + k + 1, a + 1}});
      m.triangles.push_back({{a + 1, a + k + 1, a + k + 2}});
    }
  RenderOptions3 o;
  o.width = 300;
  o.height = 200;
  o.wireframe = true;
  Image one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    ASSERT_TRUE(render_mesh3(p, m, {View{10, 40}, View{100, 20}, View{190, 60}}, o, one));
  }
  ASSERT_TRUE(render_mesh3(p, m, {View{10, 40}, View{100, 20}, View{190, 60}}, o, two));
  EXPECT_EQ(one.rgb, two.rgb);
  EXPECT_EQ(one.width, 300);
  EXPECT_EQ(one.height, 200);
}

TEST(Render3, RejectsBadInput) {
  Image img;
  RenderOptions3 o;
  TriMesh3 bad;
  bad.triangles = {{{0, 1, 7}}};
  EXPECT_EQ(render_mesh3(tetra_points(), bad, {}, o, img).code(), StatusCode::InvalidArgument);
  o.width = 0;
  EXPECT_EQ(render_mesh3(tetra_points(), tetra_mesh(), {}, o, img).code(), StatusCode::InvalidArgument);
  EXPECT_EQ(render_sheet3(tetra_points(), {}, RenderOptions3{}, img).code(), StatusCode::InvalidArgument);
}

TEST(Render2, SquareGolden) {
  DentedSquare sq;
  ASSERT_NO_FATAL_FAILURE(make_dented_square(sq));
  const PointSet& p = sq.p;
  PolygonSvgLayers& layers = sq.layers;
  RenderOptions2 o;
  o.width = o.height = 64;
  Image img;
  ASSERT_TRUE(render_sheet2(p, {Panel2{{0, 4, 1, 2, 3}, &layers}}, o, img));
  expect_golden(img, "square_64.png");
  // The interior is filled, the outside is white, the dent's notch is outside.
  EXPECT_EQ(img.at(32, 20), (std::array<std::uint8_t, 3>{{234, 241, 249}}));  // 60 % of the fill over white
  EXPECT_EQ(img.at(0, 0), (std::array<std::uint8_t, 3>{{255, 255, 255}}));
  EXPECT_GE(count_colour(img, {{192, 57, 43}}, 10), 5u);  // points (one full pixel each at least)
  EXPECT_GT(count_colour(img, {{31, 78, 140}}, 10), 20u);  // polygon edges
  // A two-panel sheet (e.g. stages) keeps the size and separates the cells.
  o.width = 128;
  ASSERT_TRUE(render_sheet2(p, {Panel2{{0, 1, 2, 3}, nullptr}, Panel2{{0, 4, 1, 2, 3}, &layers}}, o, img));
  EXPECT_EQ(img.at(64, 10), (std::array<std::uint8_t, 3>{{200, 200, 200}}));
}

// A ring set is one even-odd fill: the hole's pixels stay white, an island in the hole is filled
// again, and the ring between them is filled; every ring's edges are drawn.
TEST(Render2, RingsFillEvenOdd) {
  PointSet p;
  p.dim = 2;
  for (const double r : {8.0, 4.0, 2.0})  // shell, hole (clockwise), island
    for (const auto& c : {std::array<double, 2>{{-r, -r}}, {{r, -r}}, {{r, r}}, {{-r, r}}})
      p.coords.insert(p.coords.end(), {c[0], c[1]});
  RenderOptions2 o;
  o.width = o.height = 100;
  Image img;
  Panel2 pan{{0, 1, 2, 3}};
  pan.rings = {{4, 7, 6, 5}, {8, 9, 10, 11}};
  ASSERT_TRUE(render_sheet2(p, {pan}, o, img));
  const std::array<std::uint8_t, 3> fill{{234, 241, 249}}, white{{255, 255, 255}};
  // 16 units over 94 pixels (3 % margins): x = 50 + 5.875 u.
  EXPECT_EQ(img.at(50 + 35, 50), fill);                    // between the shell (8) and the hole (4), u ≈ 6
  EXPECT_EQ(img.at(50 + 18, 50), white);                   // in the hole, outside the island (u ≈ 3)
  EXPECT_EQ(img.at(50 + 4, 50 + 4), fill);                 // the island (u < 1)
  EXPECT_GT(count_colour(img, {{31, 78, 140}}, 10), 60u);  // three rings' edges
  pan.rings.push_back({0, 1, 12});
  EXPECT_EQ(render_sheet2(p, {pan}, o, img).code(), StatusCode::InvalidArgument);  // ring index out of range
}

// Points spanning more than the largest double (±9e307): the frame's span overflowed, the SVG
// held NaN coordinates and the PNG was blank (hostile-argument sweep, 2026-12-07).
TEST(Render2, DataSpanningMoreThanTheLargestDouble) {
  PointSet p;
  p.dim = 2;
  p.coords = {-9e307, -9e307, 9e307, -9e307, 9e307, 9e307, -9e307, 9e307};
  const std::vector<int> square{0, 1, 2, 3};
  RenderOptions2 o;
  o.width = o.height = 64;
  Image img;
  ASSERT_TRUE(render_sheet2(p, {Panel2{square}}, o, img));
  EXPECT_GT(count_colour(img, {{255, 255, 255}}, 0), 0u);
  EXPECT_LT(count_colour(img, {{255, 255, 255}}, 0), static_cast<std::size_t>(64 * 64) / 2);  // filled, not blank
  const std::string svg = tmp("huge_span.svg");
  ASSERT_TRUE(write_polygon2(svg, p, square, PolygonFormat::Svg));
  std::ifstream f(svg);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str().find("nan"), std::string::npos);
  EXPECT_NE(ss.str().find("width=\"800\""), std::string::npos);
  std::filesystem::remove(svg);
}

TEST(Png, RoundTripAndErrors) {
  Image img;
  img.width = 5;
  img.height = 3;
  for (int i = 0; i < 45; ++i) img.rgb.push_back(static_cast<std::uint8_t>(i * 5));
  const std::string path = tmp("rt.png");
  ASSERT_TRUE(write_png(path, img));
  Image back;
  ASSERT_TRUE(read_png(path, back));
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.rgb, img.rgb);
  std::remove(path.c_str());
  EXPECT_EQ(read_png(tmp("missing.png"), back).code(), StatusCode::FileNotFound);
  const std::string txt = tmp("not.png");
  std::ofstream(txt) << "not a png at all";
  EXPECT_EQ(read_png(txt, back).code(), StatusCode::ParseError);
  std::remove(txt.c_str());
  EXPECT_EQ(write_png("/nonexistent-dir/x.png", img).code(), StatusCode::WriteFailed);
}

namespace {

// A minimal XML well-formedness check: one prolog, properly nested and closed elements, quoted
// attributes, no raw '<' or '&' outside entities in text and attribute values.
bool well_formed(const std::string& s, std::string& why) {
  std::vector<std::string> stack;
  std::size_t i = 0, roots = 0;
  const auto entity_ok = [&](std::size_t at) {
    const std::size_t semi = s.find(';', at);
    if (semi == std::string::npos) return false;
    const std::string e = s.substr(at, semi - at + 1);
    return e == "&lt;" || e == "&gt;" || e == "&amp;" || e == "&quot;" || e == "&apos;";
  };
  if (s.rfind("<?xml", 0) == 0) i = s.find("?>") + 2;
  while (i < s.size()) {
    if (s[i] == '&' && !entity_ok(i)) return why = "bad entity at " + std::to_string(i), false;
    if (s[i] != '<') { ++i; continue; }
    const std::size_t end = s.find('>', i);
    if (end == std::string::npos) return why = "unterminated tag", false;
    std::string tag = s.substr(i + 1, end - i - 1);
    if (tag.find('<') != std::string::npos) return why = "'<' inside a tag", false;
    if (!tag.empty() && tag[0] == '/') {
      if (stack.empty() || stack.back() != tag.substr(1)) return why = "mismatched </" + tag.substr(1) + ">", false;
      stack.pop_back();
    } else {
      const bool self = !tag.empty() && tag.back() == '/';
      if (self) tag.pop_back();
      const std::string name = tag.substr(0, tag.find_first_of(" \t\n"));
      if (name.empty()) return why = "empty tag name", false;
      // attributes: name="value" pairs
      std::size_t q = name.size();
      while (q < tag.size()) {
        while (q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
        if (q >= tag.size()) break;
        const std::size_t eq = tag.find('=', q);
        if (eq == std::string::npos || eq + 1 >= tag.size() || tag[eq + 1] != '"') return why = "unquoted attribute in <" + name + ">", false;
        const std::size_t close = tag.find('"', eq + 2);
        if (close == std::string::npos) return why = "unterminated attribute", false;
        for (std::size_t a = eq + 2; a < close; ++a)
          if (tag[a] == '&' && !entity_ok(i + 1 + a)) return why = "bad entity in attribute", false;
        q = close + 1;
      }
      if (stack.empty()) ++roots;
      if (!self) stack.push_back(name);
    }
    i = end + 1;
  }
  if (!stack.empty()) return why = "unclosed <" + stack.back() + ">", false;
  if (roots != 1) return why = "expected one root element", false;
  return true;
}

}  // namespace

TEST(RenderSvg, PolygonSvgIsWellFormedXml) {
  DentedSquare sq;
  ASSERT_NO_FATAL_FAILURE(make_dented_square(sq));
  const PointSet& p = sq.p;
  PolygonSvgLayers& layers = sq.layers;
  layers.title = "a <title> & \"quotes\"";
  const std::string path = tmp("poly.svg");
  ASSERT_TRUE(write_polygon2(path, p, {0, 4, 1, 2, 3}, PolygonFormat::Svg, &layers));
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string why;
  EXPECT_TRUE(well_formed(ss.str(), why)) << why;
  EXPECT_NE(ss.str().find("<svg"), std::string::npos);
  std::remove(path.c_str());
  // The checker itself rejects broken documents.
  EXPECT_FALSE(well_formed("<svg><g></svg>", why));
  EXPECT_FALSE(well_formed("<svg><title>a & b</title></svg>", why));
  EXPECT_FALSE(well_formed("<svg x=1/>", why));
}
