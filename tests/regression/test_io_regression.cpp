// SPDX-License-Identifier: GPL-3.0-or-later
// Reader defects found by review and by the fuzz targets (fuzz/), one named file each in
// tests/data/regression/: both readers (read_points, read_mesh) must refuse them with a
// ParseError that names the defect, quickly and without allocating from a lying count.
#include <gtest/gtest.h>

#include <string>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"

namespace constrict {
namespace {

const std::string kRegression = std::string(CONSTRICT_TEST_DATA_DIR) + "/regression/";

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

Status points_of(const std::string& file) {
  PointSet p;
  return read_points(kRegression + file, {}, p);
}

Status mesh_of(const std::string& file) {
  PointSet p;
  TriMesh3 m;
  return read_mesh(kRegression + file, p, m);
}

// `element junk 10000000000000000` without properties used to make the point reader walk 10^16
// empty records (`constrict reconstruct` never returned).
TEST(IoRegression, PlyEmptyElementWithHugeCountIsRefused) {
  const std::string f = "ply_empty_element_1e16_records_hang.ply";
  for (const Status& st : {points_of(f), mesh_of(f)}) {
    EXPECT_EQ(st.code(), StatusCode::ParseError);
    EXPECT_TRUE(Contains(st.message(), f + ":3: PLY element 'junk' announces 10000000000000000 "
                                           "records and has no properties"));
  }
}

// A float list count (`property list float int vertex_indices`) was cast to an integer: UB for
// 3e30. A list count type must be an integer type.
TEST(IoRegression, PlyFloatListCountIsRefusedInTheHeader) {
  const std::string f = "ply_binary_float_list_count_ub.ply";
  const Status st = mesh_of(f);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), f + ":8: PLY list count type must be an integer type"));
}

// Face indices of type double were cast to long long: UB for 1e300.
TEST(IoRegression, PlyDoubleIndexOutOfRangeIsParseError) {
  const std::string f = "ply_binary_double_index_1e300_ub.ply";
  const Status st = mesh_of(f);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(
      Contains(st.message(), f + ": PLY face 0: list 'vertex_indices' item 1 is not an integer index"));
}

// A fractional index was truncated silently (1.5 -> 1).
TEST(IoRegression, PlyFractionalIndexIsParseError) {
  const std::string f = "ply_ascii_fractional_index_1.5.ply";
  const Status st = mesh_of(f);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), f + ":13: PLY list 'vertex_indices': '1.5' is not an integer index"));
}

// 3e18 vertices: the mesh reader reserved 3e18 x 3 doubles ("internal error: vector::reserve").
TEST(IoRegression, Off3e18VerticesIsRefusedBeforeReserving) {
  const std::string f = "off_3e18_vertices_reserve.off";
  for (const Status& st : {points_of(f), mesh_of(f)}) {
    EXPECT_EQ(st.code(), StatusCode::ParseError);
    EXPECT_TRUE(Contains(st.message(), f + ":2: OFF counts announce 3000000000000000000 vertices"));
    EXPECT_TRUE(Contains(st.message(), "correct the counts"));
  }
}

// 7e9 vertices in a 25-byte file: the mesh reader reserved 168 GB.
TEST(IoRegression, Off7e9VerticesIsRefusedBeforeReserving) {
  const std::string f = "off_7e9_vertices_23_bytes.off";
  for (const Status& st : {points_of(f), mesh_of(f)}) {
    EXPECT_EQ(st.code(), StatusCode::ParseError);
    EXPECT_TRUE(Contains(st.message(), f + ":2: OFF counts announce 7000000000 vertices"));
  }
}

}  // namespace
}  // namespace constrict
