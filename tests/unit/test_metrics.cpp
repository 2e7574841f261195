// SPDX-License-Identifier: GPL-3.0-or-later
// Reference (.gt) reading and combinatorial polygon comparison.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "constrict/metrics.hpp"

using namespace constrict;
namespace fs = std::filesystem;

namespace {
std::string write_tmp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("constrict_metrics_" + name);
  std::ofstream(p) << text;
  return p.string();
}
}  // namespace

TEST(Metrics, ReadsClosedAndOpenComponents) {
  Reference2 r;
  const std::string p = write_tmp("ok.gt", "# comment\nc 0 1 2 3\n\no 4 5\n");
  ASSERT_TRUE(read_reference2(p, 6, r).is_ok());
  ASSERT_EQ(r.closed.size(), 1u);
  ASSERT_EQ(r.open.size(), 1u);
  EXPECT_FALSE(r.single_closed_curve());
  EXPECT_EQ(r.edges().size(), 5u);  // 4 closed + 1 open
}

TEST(Metrics, ReferenceErrorsNameTheLine) {
  Reference2 r;
  Status s = read_reference2(write_tmp("range.gt", "c 0 1 7\n"), 5, r);
  EXPECT_EQ(s.code(), StatusCode::ParseError);
  EXPECT_NE(s.message().find(":1: index 7 out of range"), std::string::npos) << s.message();
  s = read_reference2(write_tmp("kind.gt", "# x\nx 0 1 2\n"), 5, r);
  EXPECT_EQ(s.code(), StatusCode::ParseError);
  EXPECT_NE(s.message().find(":2:"), std::string::npos) << s.message();
  s = read_reference2(write_tmp("num.gt", "c 0 1a 2\n"), 5, r);
  EXPECT_EQ(s.code(), StatusCode::ParseError);
  EXPECT_EQ(read_reference2(write_tmp("empty.gt", "# nothing\n"), 5, r).code(), StatusCode::EmptyInput);
  EXPECT_EQ(read_reference2("/nonexistent/x.gt", 5, r).code(), StatusCode::FileNotFound);
}

TEST(Metrics, ExactMatchIgnoresStartAndDirection) {
  Reference2 r;
  r.closed.push_back({0, 1, 2, 3, 4});
  const auto same = compare_polygon2({2, 1, 0, 4, 3}, r);  // reversed, rotated
  EXPECT_TRUE(same.exact_match);
  EXPECT_DOUBLE_EQ(same.edge_recall, 1.0);
  const auto swapped = compare_polygon2({0, 2, 1, 3, 4}, r);  // 1 and 2 swapped
  EXPECT_FALSE(swapped.exact_match);
  EXPECT_EQ(swapped.recovered_edges, 3u);  // (1,2), (3,4), (4,0)
}

// Ring sets against a reference of several closed curves: a ring matches when its point set is a
// reference ring's, whatever its start, direction or vertex order; the edges count over all rings.
TEST(Metrics, RingsMatchByPointSet) {
  Reference2 r;
  r.closed = {{0, 1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  const auto same = compare_rings2({{6, 5, 4}, {2, 3, 0, 1}, {9, 7, 8}}, r);
  EXPECT_TRUE(same.edges.exact_match);
  EXPECT_EQ(same.same_point_sets, 3u);
  EXPECT_EQ(same.result_rings, 3u);
  EXPECT_EQ(same.reference_rings, 3u);
  // The first two rings merged through a slit, and one point moved to the third: one ring right.
  const auto merged = compare_rings2({{0, 1, 2, 4, 5, 6, 3}, {7, 8, 9}}, r);
  EXPECT_FALSE(merged.edges.exact_match);
  EXPECT_EQ(merged.same_point_sets, 1u);
  EXPECT_EQ(merged.edges.recovered_edges, 3u + 2u + 3u);  // (0,1) (1,2) (3,0), (4,5) (5,6), the third ring
  EXPECT_EQ(merged.edges.polygon_edges, 10u);
  const auto swapped = compare_rings2({{0, 2, 1, 3}, {4, 5, 6}, {7, 8, 9}}, r);  // same sets, other order
  EXPECT_EQ(swapped.same_point_sets, 3u);
  EXPECT_FALSE(swapped.edges.exact_match);
  // A single polygon against the same reference: no ring matches.
  EXPECT_EQ(compare_rings2({{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}}, r).same_point_sets, 0u);
}
