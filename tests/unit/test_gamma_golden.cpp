// SPDX-License-Identifier: GPL-3.0-or-later
// Golden values of the γ-neighborhood graph (spec ../shared/spec/gamma-graph.md §5.1, §5.2, §5.3,
// §6.2). The tables were computed from exact closed forms; decimals are compared with 1e-6, the
// exact zeros and ones of the tables exactly. "left" = orient2(x_i, x_j, p) > 0 for i < j, which is
// gamma_a of the face (i, j) (include/constrict/gamma_graph.hpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/points.hpp"
#include "constrict/predicates.hpp"

namespace constrict {
namespace {

constexpr double kTol = 1e-6;

using Edge = std::array<int, 2>;
using Tri = std::array<int, 3>;
using EdgeSet = std::set<Edge>;

PointSet make_points(int dim, std::initializer_list<double> coords) {
  PointSet p;
  p.dim = dim;
  p.coords.assign(coords.begin(), coords.end());
  return p;
}

// Example A (spec §5.1): rectangle plus one point.
PointSet example_a() { return make_points(2, {0, 0, 8, 0, 8, 6, 0, 6, 3, 2}); }
// Example B (spec §5.2).
PointSet example_b() { return make_points(2, {-8, 13, 12, 13, 20, -3, 15, 20, 8, 6, 9, 11, 4, 17}); }
// Example N9 (spec §6.2).
PointSet example_n9() {
  return make_points(2, {12, 2, 0, 0, -1, 12, -14, -3, 0, -14, 1, 2, 12, 15, -20, 4, 8, -19});
}

// Index of the face with the given ascending ids, or -1.
long find_face(const GammaFaces& g, const int* ids) {
  for (std::size_t f = 0; f < g.size(); ++f) {
    bool same = true;
    for (int j = 0; j < g.dim; ++j) same = same && g.vertex(f, j) == ids[j];
    if (same) return static_cast<long>(f);
  }
  return -1;
}

EdgeSet edge_set(const GammaFaces& g) {
  EdgeSet s;
  for (std::size_t f = 0; f < g.size(); ++f) s.insert({g.vertex(f, 0), g.vertex(f, 1)});
  return s;
}

std::string edges_str(const EdgeSet& s) {
  std::ostringstream o;
  for (const Edge& e : s) o << " P" << e[0] << "P" << e[1];
  return s.empty() ? std::string(" (none)") : o.str();
}

EdgeSet edges_from_pairs(std::initializer_list<Edge> pairs) { return EdgeSet(pairs.begin(), pairs.end()); }

EdgeSet all_pairs(int n) {
  EdgeSet s;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) s.insert({i, j});
  return s;
}

EdgeSet edges_of_triangles(std::initializer_list<Tri> tris) {
  EdgeSet s;
  for (const Tri& t : tris)
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = a + 1; b < 3; ++b) s.insert({std::min(t[a], t[b]), std::max(t[a], t[b])});
  return s;
}

// One row of a 2D golden table.
struct Row2 {
  int i, j;
  double left, right, delta;
};

// Expects that the face (i, j) of @p g has the side values of @p row within kTol; values that
// are exactly 0 or 1 in the table must be exactly 0 or 1.
void expect_row(const GammaFaces& g, const Row2& row, const char* source) {
  SCOPED_TRACE(std::string(source) + " pair " + std::to_string(row.i) + " " + std::to_string(row.j));
  const int ids[2] = {row.i, row.j};
  const long f = find_face(g, ids);
  ASSERT_GE(f, 0) << "face missing";
  const auto k = static_cast<std::size_t>(f);
  EXPECT_NEAR(g.gamma_a[k], row.left, kTol) << "gamma_left (orient > 0 side)";
  EXPECT_NEAR(g.gamma_b[k], row.right, kTol) << "gamma_right (orient < 0 side)";
  EXPECT_NEAR(g.delta[k], row.delta, kTol) << "filtration value";
  if (row.left == 0.0 || row.left == 1.0) {
    EXPECT_EQ(g.gamma_a[k], row.left) << "exact value expected";
  }
  if (row.right == 0.0 || row.right == 1.0) {
    EXPECT_EQ(g.gamma_b[k], row.right) << "exact value expected";
  }
  if (row.delta == 1.0) {
    EXPECT_EQ(g.delta[k], 1.0);
  }
  EXPECT_EQ(g.delta[k], filtration_value(g.gamma_a[k], g.gamma_b[k]));
  EXPECT_EQ((g.flags[k] & kFaceBlocked) != 0, false);
}

GammaFaces graph_of(const PointSet& p, const GraphSpec& spec) {
  GammaFaces out;
  const Status s = build_gamma_graph(p, spec, out);
  EXPECT_TRUE(s.is_ok()) << spec.describe() << ": " << s.message();
  return out;
}

std::string lens_note(const GraphSpec& spec) {
  return spec.delaunay_subgraph() ? std::string()
                                  : std::string(" [non-Delaunay graph: built by detail::lens_faces]");
}

// ---- spec §5.1 Example A -----------------------------------------------------------------------

struct RowA {
  int i, j;
  double left, right, delta;
  bool gabriel, dt, hull;
};

std::vector<RowA> table_a() {
  const double s13 = std::sqrt(13.0), s29 = std::sqrt(29.0), s41 = std::sqrt(41.0);
  return {
      {0, 1, 16 / std::sqrt(377.0) - 1, 1, 1, false, true, true},
      {0, 2, 0, 2 / std::sqrt(533.0) - 1, 2 / std::sqrt(533.0) - 1, false, false, false},
      {0, 3, 1, 1 - 18 * s13 / 65, 1, true, true, true},
      {0, 4, 0.4, 1 - 2 / s29, 1 - 2 / s29, true, true, false},
      {1, 2, 1 - 30 / std::sqrt(1189.0), 1, 1, true, true, true},
      {1, 3, 14 / (5 * s29) - 1, 0, 14 / (5 * s29) - 1, false, false, false},
      {1, 4, 1 - 2 / s13, 1 - 5 / s41, 1 - 2 / s13, true, true, false},
      {2, 3, 1 - 32 / (5 * s41), 1, 1, true, true, true},
      {2, 4, 1 - 5 / s29, 0.2, 0.2, true, true, false},
      {3, 4, 1 - 4 / s41, 1 - 3 / s13, 1 - 4 / s41, true, true, false},
  };
}

TEST(GammaGoldenExampleA, ClosedFormsMatchTableDecimals) {
  // Guards the transcription of the closed forms against the decimals printed in the spec.
  const std::vector<RowA> t = table_a();
  const double dec_left[] = {-0.175958, 0, 1, 0.4, 0.129978, -0.480053, 0.445300, 0.000488, 0.071523, 0.375305};
  const double dec_right[] = {1, -0.913370, 0.001540, 0.628609, 1, 0, 0.219131, 1, 0.2, 0.167950};
  for (std::size_t r = 0; r < t.size(); ++r) {
    EXPECT_NEAR(t[r].left, dec_left[r], 5e-7) << "row " << r;
    EXPECT_NEAR(t[r].right, dec_right[r], 5e-7) << "row " << r;
    EXPECT_EQ(t[r].delta, filtration_value(t[r].left, t[r].right)) << "row " << r;
  }
}

TEST(GammaGoldenExampleA, BruteForceSideValuesAndMemberships) {
  const PointSet p = example_a();
  GammaFaces bf;
  ASSERT_TRUE(brute_force_gamma_faces(p, bf).is_ok());
  ASSERT_EQ(bf.dim, 2);
  ASSERT_EQ(bf.size(), 10u);
  const GraphSpec gabriel = GraphSpec::fixed(0, 0);
  const GraphSpec delaunay = GraphSpec::interval(-1, 1, 0, 1);
  const GraphSpec hull = GraphSpec::fixed(-1, 1);
  for (const RowA& r : table_a()) {
    expect_row(bf, {r.i, r.j, r.left, r.right, r.delta}, "brute force");
    const int ids[2] = {r.i, r.j};
    const long f = find_face(bf, ids);
    if (f < 0) continue;
    const auto k = static_cast<std::size_t>(f);
    SCOPED_TRACE("pair P" + std::to_string(r.i) + "P" + std::to_string(r.j));
    EXPECT_EQ(in_graph(gabriel, bf.gamma_a[k], bf.gamma_b[k], false), r.gabriel) << "Gabriel γ(0,0)";
    EXPECT_EQ(in_graph(delaunay, bf.gamma_a[k], bf.gamma_b[k], false), r.dt) << "DT γ([-1,1],[0,1])";
    EXPECT_EQ(in_graph(hull, bf.gamma_a[k], bf.gamma_b[k], false), r.hull) << "hull γ(-1,1)";
    EXPECT_EQ((bf.flags[k] & kFaceHull) != 0, r.hull) << "kFaceHull flag of the brute force";
  }
}

TEST(GammaGoldenExampleA, DelaunayGammaFacesAreTheEightDtEdges) {
  const PointSet p = example_a();
  DelaunayGamma2 dg;
  ASSERT_TRUE(delaunay_gamma2(p, dg).is_ok());
  EXPECT_EQ(dg.dt.triangles.size(), 4u);
  EdgeSet expected;
  for (const RowA& r : table_a())
    if (r.dt) expected.insert({r.i, r.j});
  EXPECT_EQ(edge_set(dg.faces), expected) << "got" << edges_str(edge_set(dg.faces)) << "\nexpected"
                                          << edges_str(expected);
  for (const RowA& r : table_a()) {
    if (!r.dt) continue;
    expect_row(dg.faces, {r.i, r.j, r.left, r.right, r.delta}, "delaunay_gamma2");
    const int ids[2] = {r.i, r.j};
    const long f = find_face(dg.faces, ids);
    if (f < 0) continue;
    const std::uint8_t fl = dg.faces.flags[static_cast<std::size_t>(f)];
    EXPECT_NE(fl & kFaceDelaunay, 0) << "P" << r.i << "P" << r.j;
    EXPECT_EQ(fl & kFaceCospherical, 0) << "P" << r.i << "P" << r.j;
    EXPECT_EQ((fl & kFaceHull) != 0, r.hull) << "P" << r.i << "P" << r.j;
  }
  // simplex_face[t][i] is the face opposite vertex i of triangle t.
  ASSERT_EQ(dg.simplex_face.size(), dg.dt.triangles.size());
  for (std::size_t t = 0; t < dg.dt.triangles.size(); ++t)
    for (std::size_t i = 0; i < 3; ++i) {
      const int f = dg.simplex_face[t][i];
      ASSERT_GE(f, 0);
      const int u = dg.dt.triangles[t][(i + 1) % 3], v = dg.dt.triangles[t][(i + 2) % 3];
      EXPECT_EQ(dg.faces.vertex(static_cast<std::size_t>(f), 0), std::min(u, v));
      EXPECT_EQ(dg.faces.vertex(static_cast<std::size_t>(f), 1), std::max(u, v));
    }
}

TEST(GammaGoldenExampleA, FixedParameterGraphs) {
  const PointSet p = example_a();
  const EdgeSet dt = edges_from_pairs({{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}});
  const EdgeSet gab = edges_from_pairs({{0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}});
  EdgeSet all_but_02 = all_pairs(5);
  all_but_02.erase({0, 2});
  struct Case {
    double g0, g1;
    EdgeSet edges;
  };
  const std::vector<Case> cases = {
      {0, 0, gab},
      {0.2, 0.2, edges_from_pairs({{0, 4}, {1, 4}})},
      {-0.2, -0.2, dt},
      {0, 0.5, edges_from_pairs({{0, 3}, {0, 4}, {1, 2}, {2, 3}})},
      {-0.5, 0.5, edges_from_pairs({{0, 1}, {0, 3}, {0, 4}, {1, 2}, {2, 3}})},
      {0.3, -0.6, edges_from_pairs({{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {3, 4}})},
      {-0.9, -0.9, all_but_02},
      {-0.1, 0.15, gab},
  };
  const std::vector<RowA> table = table_a();
  for (const Case& c : cases) {
    for (const bool swapped : {false, true}) {
      const GraphSpec spec = swapped ? GraphSpec::fixed(c.g1, c.g0) : GraphSpec::fixed(c.g0, c.g1);
      SCOPED_TRACE(spec.describe() + lens_note(spec));
      const GammaFaces g = graph_of(p, spec);
      const EdgeSet got = edge_set(g);
      EXPECT_EQ(got, c.edges) << "got" << edges_str(got) << "\nexpected" << edges_str(c.edges);
      EXPECT_EQ(got.size(), g.size()) << "duplicate faces in the output";
      // The member faces carry their exact side values.
      for (const RowA& r : table) {
        const int ids[2] = {r.i, r.j};
        if (find_face(g, ids) >= 0) expect_row(g, {r.i, r.j, r.left, r.right, r.delta}, "build_gamma_graph");
      }
    }
  }
}

TEST(GammaGoldenExampleA, IntervalGraphWithNegativeLowerBoundIsTheDt) {
  // γ([−1,1],[−0.2,1]) = the 8 DT edges: the diagonals have Δ < −0.2.
  const PointSet p = example_a();
  const GraphSpec spec = GraphSpec::interval(-1, 1, -0.2, 1);
  SCOPED_TRACE(spec.describe() + lens_note(spec));
  const GammaFaces g = graph_of(p, spec);
  const EdgeSet dt = edges_from_pairs({{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}});
  EXPECT_EQ(edge_set(g), dt) << "got" << edges_str(edge_set(g)) << "\nexpected" << edges_str(dt);
  // And the plain Delaunay interval graph is the same set.
  const GammaFaces d = graph_of(p, GraphSpec::interval(-1, 1, 0, 1));
  EXPECT_EQ(edge_set(d), dt) << "got" << edges_str(edge_set(d));
  // γ([−1,1],[−1,0]) = complement of the DT plus the faces with Δ = 0 (none here).
  const GammaFaces c = graph_of(p, GraphSpec::interval(-1, 1, -1, 0));
  EXPECT_EQ(edge_set(c), edges_from_pairs({{0, 2}, {1, 3}})) << "γ([-1,1],[-1,0]) got" << edges_str(edge_set(c))
                                                             << lens_note(GraphSpec::interval(-1, 1, -1, 0));
}

// ---- spec §5.2 Example B -----------------------------------------------------------------------

std::vector<Row2> table_b() {
  return {
      {0, 1, -0.292893, -0.351881, -0.351881}, {0, 2, -0.770961, 1, 1},
      {0, 3, -0.944530, -0.108837, -0.944530}, {0, 4, -0.000365, 0.875965, 0.875965},
      {0, 5, -0.068757, 0.023027, -0.068757},  {0, 6, 1, 0.275978, 1},
      {1, 2, 0.419818, -0.007722, 0.419818},   {1, 3, 0.333205, 0.752996, 0.752996},
      {1, 4, 0.552786, -0.292893, 0.552786},   {1, 5, 0.683772, 0.599181, 0.683772},
      {1, 6, -0.005691, 0.216889, 0.216889},   {2, 3, -0.236614, 1, 1},
      {2, 4, 0.893467, 0.167950, 0.893467},    {2, 5, -0.097866, 0.007722, -0.097866},
      {2, 6, -0.453211, -0.971235, -0.971235}, {3, 4, -0.885994, -0.619250, -0.885994},
      {3, 5, -0.453732, 0.090404, -0.453732},  {3, 6, 0.001726, 1, 1},
      {4, 5, 0.660893, 0.552786, 0.660893},    {4, 6, 0.330035, -0.221587, 0.330035},
      {5, 6, 0.480585, 0.131757, 0.480585},
  };
}

// Checks a 2D golden table against the brute force, delaunay_gamma2 and the graph builder.
void check_table_2d(const PointSet& p, const std::vector<Row2>& table, const EdgeSet& dt_edges,
                    const EdgeSet& hull_edges) {
  const std::size_t n = p.size();
  ASSERT_EQ(table.size(), n * (n - 1) / 2);
  GammaFaces bf;
  ASSERT_TRUE(brute_force_gamma_faces(p, bf).is_ok());
  ASSERT_EQ(bf.size(), table.size());
  for (const Row2& r : table) expect_row(bf, r, "brute force");

  // Δ >= 0 exactly on the DT edges (no co-circular empty circles in these examples).
  EdgeSet nonneg;
  for (const Row2& r : table)
    if (r.delta >= 0) nonneg.insert({r.i, r.j});
  EXPECT_EQ(nonneg, dt_edges) << "table: Δ >= 0 must be the DT edges";

  DelaunayGamma2 dg;
  ASSERT_TRUE(delaunay_gamma2(p, dg).is_ok());
  EXPECT_EQ(edge_set(dg.faces), dt_edges) << "delaunay_gamma2 got" << edges_str(edge_set(dg.faces));
  for (const Row2& r : table)
    if (dt_edges.count({r.i, r.j})) expect_row(dg.faces, r, "delaunay_gamma2");
  EdgeSet hull_flagged;
  for (std::size_t f = 0; f < dg.faces.size(); ++f)
    if (dg.faces.flags[f] & kFaceHull) hull_flagged.insert({dg.faces.vertex(f, 0), dg.faces.vertex(f, 1)});
  EXPECT_EQ(hull_flagged, hull_edges) << "kFaceHull flags";

  const GammaFaces hull = graph_of(p, GraphSpec::fixed(-1, 1));
  EXPECT_EQ(edge_set(hull), hull_edges) << "hull preset got" << edges_str(edge_set(hull));
  const GammaFaces del = graph_of(p, GraphSpec::interval(-1, 1, 0, 1));
  EXPECT_EQ(edge_set(del), dt_edges) << "delaunay preset got" << edges_str(edge_set(del));
  for (const Row2& r : table)
    if (dt_edges.count({r.i, r.j})) expect_row(del, r, "build_gamma_graph(delaunay)");

  // Every interval graph γ([−1,1],[β,1]) is {Δ >= β}; β < 0 needs the non-Delaunay path.
  for (const double beta : {0.5, 0.3, -0.05, -0.1, -0.3, -0.9}) {
    const GraphSpec spec = GraphSpec::interval(-1, 1, beta, 1);
    SCOPED_TRACE(spec.describe() + lens_note(spec));
    EdgeSet expected;
    for (const Row2& r : table)
      if (r.delta >= beta) expected.insert({r.i, r.j});
    const GammaFaces g = graph_of(p, spec);
    EXPECT_EQ(edge_set(g), expected) << "got" << edges_str(edge_set(g)) << "\nexpected" << edges_str(expected);
    for (const Row2& r : table)
      if (expected.count({r.i, r.j})) expect_row(g, r, "build_gamma_graph(interval)");
  }
}

TEST(GammaGoldenExampleB, SideValuesTable) {
  const EdgeSet dt = edges_of_triangles(
      {{0, 2, 4}, {0, 4, 6}, {1, 2, 3}, {1, 2, 4}, {1, 3, 6}, {1, 4, 5}, {1, 5, 6}, {4, 5, 6}});
  ASSERT_EQ(dt.size(), 14u);
  check_table_2d(example_b(), table_b(), dt, edges_from_pairs({{0, 2}, {2, 3}, {3, 6}, {0, 6}}));
}

TEST(GammaGoldenExampleB, NewEdgesAtNegativeGamma0) {
  // spec §5.2: at γ0 = −0.05 no new edge; at γ0 = −0.1 the edges (0,5) and (2,5) enter.
  const PointSet p = example_b();
  const EdgeSet dt = edges_of_triangles(
      {{0, 2, 4}, {0, 4, 6}, {1, 2, 3}, {1, 2, 4}, {1, 3, 6}, {1, 4, 5}, {1, 5, 6}, {4, 5, 6}});
  const GraphSpec s05 = GraphSpec::interval(-1, 1, -0.05, 1);
  const GraphSpec s10 = GraphSpec::interval(-1, 1, -0.1, 1);
  SCOPED_TRACE(lens_note(s10));
  EXPECT_EQ(edge_set(graph_of(p, s05)), dt);
  EdgeSet plus = dt;
  plus.insert({0, 5});
  plus.insert({2, 5});
  EXPECT_EQ(edge_set(graph_of(p, s10)), plus);
}

// ---- spec §6.2 Example N9 ----------------------------------------------------------------------

std::vector<Row2> table_n9() {
  return {
      {0, 1, 0.400000, -0.105573, 0.400000},  {0, 2, -0.019419, 0.025609, 0.025609},
      {0, 3, 0.000252, -0.954072, -0.954072}, {0, 4, 0.067809, -0.013606, 0.067809},
      {0, 5, 0.191264, 0.342342, 0.342342},   {0, 6, 0.227674, 1, 1},
      {0, 7, -0.905191, -0.130486, -0.905191}, {0, 8, 1, 0.003602, 1},
      {1, 2, 0.398312, -0.386059, 0.398312},  {1, 3, 0.213682, 0.284575, 0.284575},
      {1, 4, 0.309524, 0.231136, 0.309524},   {1, 5, 0.885994, 0.835601, 0.885994},
      {1, 6, -0.763648, -0.013606, -0.763648}, {1, 7, -0.121237, 0.049322, -0.121237},
      {1, 8, 0.061788, -0.152002, -0.152002}, {2, 3, -0.008175, 0.047698, 0.047698},
      {2, 4, -0.916955, 0.001158, -0.916955}, {2, 5, 0.390289, 0.480053, 0.480053},
      {2, 6, 1, 0.207376, 1},                  {2, 7, 0.010944, 1, 1},
      {2, 8, -0.107291, -0.875965, -0.875965}, {3, 4, 0.022198, 1, 1},
      {3, 5, 0.209585, -0.219131, -0.219131}, {3, 6, -0.410931, -0.480053, -0.480053},
      {3, 7, 1, 0.557681, 1},                  {3, 8, -0.017513, -0.892836, -0.892836},
      {4, 5, -0.552786, 0.200000, -0.552786}, {4, 6, -0.402934, -0.400000, -0.402934},
      {4, 7, -0.805056, -0.019419, -0.805056}, {4, 8, 0.560287, 1, 1},
      {5, 6, -0.000432, 0, -0.000432},         {5, 7, -0.073908, 0.020158, -0.073908},
      {5, 8, 0.017661, -0.240743, -0.240743}, {6, 7, -0.178811, -0.829119, -0.829119},
      {6, 8, -0.812888, -0.145801, -0.812888}, {7, 8, -0.172366, -0.826664, -0.826664},
  };
}

TEST(GammaGoldenExampleN9, SideValuesTable) {
  const EdgeSet dt = edges_of_triangles(
      {{0, 1, 4}, {0, 1, 5}, {0, 2, 5}, {0, 2, 6}, {0, 4, 8}, {1, 2, 3}, {1, 2, 5}, {1, 3, 4}, {2, 3, 7}});
  ASSERT_EQ(dt.size(), 17u);
  // Hull 7 3 4 8 0 6 2.
  const EdgeSet hull = edges_from_pairs({{3, 7}, {3, 4}, {4, 8}, {0, 8}, {0, 6}, {2, 6}, {2, 7}});
  check_table_2d(example_n9(), table_n9(), dt, hull);
}

TEST(GammaGoldenExampleN9, ExactZeroOnTheDiameterCircle) {
  // Point 0 = (12,2) lies exactly on the diameter circle of (5,6) = (1,2)-(12,15): γ_right = 0
  // exactly (decided by the exact sign predicate, not by rounding).
  const PointSet p = example_n9();
  EXPECT_EQ(apex_gamma2(p[5], p[6], p[0]), 0.0);
  double ga = 0, gb = 0;
  bool blocked = true;
  const int ids[2] = {5, 6};
  side_values_scan(p, ids, ga, gb, blocked);
  EXPECT_FALSE(blocked);
  EXPECT_EQ(gb, 0.0);
  EXPECT_NEAR(ga, -0.000432, kTol);
  EXPECT_LT(ga, 0.0);
  EXPECT_EQ(filtration_value(ga, gb), ga) << "Δ is the larger-magnitude value";
  // Edge (5,6) enters γ([−1,1],[γ0,1]) exactly from γ0 = Δ(5,6) = −0.000432 on.
  const GraphSpec before = GraphSpec::interval(-1, 1, -0.0004, 1);
  const GraphSpec after = GraphSpec::interval(-1, 1, -0.00044, 1);
  SCOPED_TRACE(lens_note(after));
  EXPECT_EQ(edge_set(graph_of(p, before)).count({5, 6}), 0u);
  EXPECT_EQ(edge_set(graph_of(p, after)).count({5, 6}), 1u);
}

TEST(GammaGoldenExampleA, ExactZerosOnTheDiameterCircle) {
  // P3 lies on the diameter circle of P0P2 and P2 on that of P1P3 (rectangle corners).
  const PointSet p = example_a();
  EXPECT_EQ(apex_gamma2(p[0], p[2], p[3]), 0.0);
  EXPECT_EQ(apex_gamma2(p[1], p[3], p[2]), 0.0);
  EXPECT_EQ(apex_gamma2(p[1], p[3], p[0]), 0.0);
  double ga = 0, gb = 0;
  bool blocked = true;
  const int ids02[2] = {0, 2};
  side_values_scan(p, ids02, ga, gb, blocked);
  EXPECT_EQ(ga, 0.0);
  EXPECT_FALSE(blocked);
  const int ids13[2] = {1, 3};
  side_values_scan(p, ids13, ga, gb, blocked);
  EXPECT_EQ(gb, 0.0);
  EXPECT_NEAR(ga, 14 / (5 * std::sqrt(29.0)) - 1, 1e-12);
}

// ---- apex values in 2D -------------------------------------------------------------------------

TEST(GammaGoldenApex2, SignAndMagnitudeFromTheApexAngle) {
  // γ = sign(cos φ)(1 − sin φ), φ = ∠apb.
  const double a[2] = {0, 0}, b[2] = {2, 0};
  const double right[2] = {1, 1};        // φ = 90°
  const double acute[2] = {1, 1e3};      // φ small
  const double equi[2] = {1, std::sqrt(3.0)};  // φ ≈ 60°
  const double obtuse[2] = {1, 0.5};     // φ = 2 atan 2
  EXPECT_EQ(apex_gamma2(a, b, right), 0.0);
  EXPECT_NEAR(apex_gamma2(a, b, equi), 1 - std::sqrt(3.0) / 2, 1e-12);
  const double phi = 2 * std::atan(2.0);
  EXPECT_NEAR(apex_gamma2(a, b, obtuse), -(1 - std::sin(phi)), 1e-12);
  EXPECT_NEAR(apex_gamma2(a, b, acute), 1 - std::sin(2 * std::atan(1e-3)), 1e-12);
  // Symmetric in a and b, and the same on both sides of the line.
  const double below[2] = {1, -0.5};
  EXPECT_EQ(apex_gamma2(b, a, obtuse), apex_gamma2(a, b, obtuse));
  EXPECT_EQ(apex_gamma2(a, b, below), apex_gamma2(a, b, obtuse));
  EXPECT_DOUBLE_EQ(filtration_value(0.3, -0.3), 0.3);
  EXPECT_DOUBLE_EQ(filtration_value(-0.3, 0.2), -0.3);
  EXPECT_DOUBLE_EQ(filtration_value(1, -0.5), 1);
}

// ---- spec §5.3 3D ------------------------------------------------------------------------------

struct Row3 {
  Tri ids;
  double ga, gb;  // positive / negative side (orient3 of the ascending ids)
};

void expect_row3(const GammaFaces& g, const Row3& r, const char* source, double tol = 1e-9) {
  SCOPED_TRACE(std::string(source) + " face (" + std::to_string(r.ids[0]) + "," + std::to_string(r.ids[1]) +
               "," + std::to_string(r.ids[2]) + ")");
  const long f = find_face(g, r.ids.data());
  ASSERT_GE(f, 0) << "face missing";
  const auto k = static_cast<std::size_t>(f);
  EXPECT_NEAR(g.gamma_a[k], r.ga, tol);
  EXPECT_NEAR(g.gamma_b[k], r.gb, tol);
  if (r.ga == 1.0) {
    EXPECT_EQ(g.gamma_a[k], 1.0);
  }
  if (r.gb == 1.0) {
    EXPECT_EQ(g.gamma_b[k], 1.0);
  }
  EXPECT_EQ(g.delta[k], filtration_value(g.gamma_a[k], g.gamma_b[k]));
}

TEST(GammaGolden3D, UnitTetrahedronFaces) {
  const PointSet p = make_points(3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
  const double axis = 1 - std::sqrt(6.0) / 3;         // 0.183503
  const double slanted = 2 * std::sqrt(2.0) / 3 - 1;  // −0.057191
  EXPECT_NEAR(axis, 0.183503, 5e-7);
  EXPECT_NEAR(slanted, -0.057191, 5e-7);
  // The side of the apex: orient3 of the ascending face ids and the apex (a positively oriented
  // unit tetrahedron puts 3 on the positive side of (0,1,2), etc.).
  ASSERT_EQ(orient3(p[0], p[1], p[2], p[3]), 1);
  ASSERT_EQ(orient3(p[0], p[1], p[3], p[2]), -1);
  ASSERT_EQ(orient3(p[0], p[2], p[3], p[1]), 1);
  ASSERT_EQ(orient3(p[1], p[2], p[3], p[0]), -1);
  const std::vector<Row3> rows = {
      {{0, 1, 2}, axis, 1}, {{0, 1, 3}, 1, axis}, {{0, 2, 3}, axis, 1}, {{1, 2, 3}, 1, slanted}};

  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[2], p[3]), axis, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[3], p[2]), axis, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[2], p[3], p[1]), axis, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[1], p[2], p[3], p[0]), slanted, 1e-12);
  // Independent of the order of the face vertices.
  EXPECT_NEAR(apex_gamma3(p[3], p[1], p[2], p[0]), slanted, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[2], p[3], p[1], p[0]), slanted, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[1], p[0], p[2], p[3]), axis, 1e-12);

  GammaFaces bf;
  ASSERT_TRUE(brute_force_gamma_faces(p, bf).is_ok());
  ASSERT_EQ(bf.dim, 3);
  ASSERT_EQ(bf.size(), 4u);
  for (const Row3& r : rows) expect_row3(bf, r, "brute force");

  DelaunayGamma3 dg;
  ASSERT_TRUE(delaunay_gamma3(p, dg).is_ok());
  ASSERT_EQ(dg.dt.tets.size(), 1u);
  ASSERT_EQ(dg.faces.size(), 4u);
  for (const Row3& r : rows) expect_row3(dg.faces, r, "delaunay_gamma3");
  for (std::size_t f = 0; f < 4; ++f) {
    EXPECT_NE(dg.faces.flags[f] & kFaceHull, 0);
    EXPECT_NE(dg.faces.flags[f] & kFaceDelaunay, 0);
  }
  // simplex_face[0][i] is the face opposite tets[0][i].
  for (std::size_t i = 0; i < 4; ++i) {
    const int f = dg.simplex_face[0][i];
    ASSERT_GE(f, 0);
    for (int j = 0; j < 3; ++j) EXPECT_NE(dg.faces.vertex(static_cast<std::size_t>(f), j), dg.dt.tets[0][i]);
  }
  // Scaled by 6 and translated: the same values.
  const PointSet q = make_points(3, {5, -3, 1, 11, -3, 1, 5, 3, 1, 5, -3, 7});
  EXPECT_NEAR(apex_gamma3(q[0], q[1], q[2], q[3]), axis, 1e-12);
  EXPECT_NEAR(apex_gamma3(q[1], q[2], q[3], q[0]), slanted, 1e-12);
}

TEST(GammaGolden3D, TetrahedronPlusInteriorPoint) {
  const PointSet p = make_points(3, {0, 0, 0, 6, 0, 0, 0, 6, 0, 0, 0, 6, 1, 2, 1});
  const double v012 = std::sqrt(3.0) / 3 - 1;          // −0.422650
  const double v013 = 2 * std::sqrt(2.0) / 3 - 1;      // −0.057191
  const double v123 = 4 * std::sqrt(34.0) / 51 - 1;    // −0.542670
  EXPECT_NEAR(v012, -0.422650, 5e-7);
  EXPECT_NEAR(v123, -0.542670, 5e-7);
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[2], p[4]), v012, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[3], p[4]), v013, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[2], p[3], p[4]), v012, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[1], p[2], p[3], p[4]), v123, 1e-12);
  EXPECT_NEAR(1 - apex_gamma3(p[1], p[2], p[3], p[4]), 1.542670, 5e-7);

  // Inner side values of the hull faces: P4 is the apex of the adjacent Delaunay tetrahedron.
  const std::vector<Row3> rows = {
      {{0, 1, 2}, v012, 1}, {{0, 1, 3}, 1, v013}, {{0, 2, 3}, v012, 1}, {{1, 2, 3}, 1, v123}};
  GammaFaces bf;
  ASSERT_TRUE(brute_force_gamma_faces(p, bf).is_ok());
  EXPECT_EQ(bf.size(), 10u);
  for (const Row3& r : rows) expect_row3(bf, r, "brute force");

  DelaunayGamma3 dg;
  ASSERT_TRUE(delaunay_gamma3(p, dg).is_ok());
  EXPECT_EQ(dg.dt.tets.size(), 4u);
  for (const auto& t : dg.dt.tets) EXPECT_TRUE(t[0] == 4 || t[1] == 4 || t[2] == 4 || t[3] == 4);
  EXPECT_EQ(dg.faces.size(), 10u) << "4 hull faces + 6 interior faces (i,j,4)";
  for (const Row3& r : rows) expect_row3(dg.faces, r, "delaunay_gamma3");
  for (std::size_t f = 0; f < dg.faces.size(); ++f) {
    const bool hull = dg.faces.vertex(f, 2) != 4;
    EXPECT_EQ((dg.faces.flags[f] & kFaceHull) != 0, hull) << "face " << f;
    EXPECT_GE(dg.faces.delta[f], 0.0);
  }
  // The hull preset on this input is the 4 outer faces.
  const GammaFaces h = graph_of(p, GraphSpec::fixed(-1, 1));
  ASSERT_EQ(h.size(), 4u);
  for (const Row3& r : rows) expect_row3(h, r, "build_gamma_graph(hull)");
}

TEST(GammaGolden3D, BipyramidApexValues) {
  // B0=(3,0,0) B1=(−1,2,0) B2=(−1,−2,0) B3=(0,0,2) B4=(0,0,−2).
  const PointSet p = make_points(3, {3, 0, 0, -1, 2, 0, -1, -2, 0, 0, 0, 2, 0, 0, -2});
  const double g01 = 1 - 9 * std::sqrt(13949.0) / 1073;  // 0.009364
  const double g12 = 1 - 9 * std::sqrt(85.0) / 85;
  EXPECT_NEAR(g01, 0.009364, 5e-7);
  // Two-face tetrahedra: both hull faces use the other tip as apex.
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[3], p[4]), g01, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[4], p[3]), g01, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[2], p[3], p[4]), g01, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[0], p[2], p[4], p[3]), g01, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[1], p[2], p[3], p[4]), g12, 1e-12);
  EXPECT_NEAR(apex_gamma3(p[1], p[2], p[4], p[3]), g12, 1e-12);
  EXPECT_NEAR(2 * (1 - apex_gamma3(p[0], p[1], p[3], p[4])), 1.981273, 5e-7);
  EXPECT_NEAR(2 * (1 - apex_gamma3(p[1], p[2], p[3], p[4])), 1.952374, 5e-7);
  // Mirror symmetry y -> −y: the two crit values tie exactly in the spec; here within rounding.
  EXPECT_NEAR(apex_gamma3(p[0], p[1], p[3], p[4]), apex_gamma3(p[0], p[2], p[3], p[4]), 1e-15);

  DelaunayGamma3 dg;
  ASSERT_TRUE(delaunay_gamma3(p, dg).is_ok());
  ASSERT_EQ(dg.dt.tets.size(), 3u);
  for (const auto& t : dg.dt.tets) {
    int tips = 0;
    for (const int v : t) tips += (v == 3 || v == 4) ? 1 : 0;
    EXPECT_EQ(tips, 2) << "every DT tetrahedron contains the edge B3B4";
  }
  // Each hull face: the inner side value is the apex value of the other tip.
  const std::vector<std::pair<Tri, double>> hull_faces = {
      {{0, 1, 3}, g01}, {{0, 1, 4}, g01}, {{0, 2, 3}, g01}, {{0, 2, 4}, g01}, {{1, 2, 3}, g12}, {{1, 2, 4}, g12}};
  for (const auto& [ids, g] : hull_faces) {
    SCOPED_TRACE("face (" + std::to_string(ids[0]) + "," + std::to_string(ids[1]) + "," + std::to_string(ids[2]) + ")");
    const long f = find_face(dg.faces, ids.data());
    ASSERT_GE(f, 0);
    const auto k = static_cast<std::size_t>(f);
    EXPECT_NE(dg.faces.flags[k] & kFaceHull, 0);
    const double inner = dg.faces.gamma_a[k] == 1.0 ? dg.faces.gamma_b[k] : dg.faces.gamma_a[k];
    EXPECT_TRUE(dg.faces.gamma_a[k] == 1.0 || dg.faces.gamma_b[k] == 1.0);
    EXPECT_NEAR(inner, g, 1e-12);
  }
}

}  // namespace
}  // namespace constrict
