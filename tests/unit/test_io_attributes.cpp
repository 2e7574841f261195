// SPDX-License-Identifier: GPL-3.0-or-later
// PLY vertex attributes (normals, colours) kept by read_points(), and the buffer twin of
// read_mesh() agreeing with the file reader.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"

namespace constrict {
namespace {

const std::string kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";

TEST(IoAttributes, AsciiNormalsAndUcharColours) {
  const std::string text = kAsciiHeader +
                           "0 0 0 0 0 1 255 0 0\n1 0 0 0 1 0 0 255 0\n"
                           "0 1 0 1 0 0 0 0 51\n0 0 1 0 0 -1 0 0 0\n";
  PointSet p;
  ReadReport r;
  ASSERT_TRUE(read_points_from_buffer(text, "a.ply", PointFormat::Auto, {}, p, &r));
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_EQ(r.attributes.normals, (std::vector<double>{0, 0, 1, 0, 1, 0, 1, 0, 0, 0, 0, -1}));
  EXPECT_EQ(r.attributes.color_channels, 3);
  ASSERT_EQ(r.attributes.colors.size(), 12u);
  EXPECT_EQ(r.attributes.colors[0], 1.0);
  EXPECT_EQ(r.attributes.colors[4], 1.0);
  EXPECT_DOUBLE_EQ(r.attributes.colors[8], 0.2);
  // Without a report nothing extra is parsed, and the points are the same.
  PointSet q;
  ASSERT_TRUE(read_points_from_buffer(text, "a.ply", PointFormat::Auto, {}, q));
  EXPECT_EQ(q.coords, p.coords);
}

TEST(IoAttributes, BinaryFloatRgbaAndMergedDuplicates) {
  std::string body;
  const auto put = [&body](float v) {
    char b[4];
    std::memcpy(b, &v, 4);
    body.append(b, 4);  // little-endian host assumed by this test's data
  };
  const float rows[5][7] = {{0, 0, 0, 0.5f, 0.25f, 0, 1},
                            {1, 0, 0, 0, 0, 0, 1},
                            {0, 0, 0, 1, 1, 1, 1},  // duplicate of point 0: dropped
                            {0, 1, 0, 0, 0, 0, 0.5f},
                            {0, 0, 1, 0, 0, 0, 0}};
  for (const auto& row : rows)
    for (float v : row) put(v);
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  if (first != 1) GTEST_SKIP() << "big-endian host";
  const std::string data =
      "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nproperty float red\nproperty float green\n"
      "property float blue\nproperty float alpha\nend_header\n" +
      body;
  PointSet p;
  ReadReport r;
  ReadOptions o;
  o.merge_duplicates = true;
  ASSERT_TRUE(read_points_from_buffer(data, "b.ply", PointFormat::Ply, o, p, &r));
  EXPECT_EQ(p.size(), 4u);
  EXPECT_TRUE(r.attributes.normals.empty());
  EXPECT_EQ(r.attributes.color_channels, 4);
  EXPECT_EQ(r.attributes.colors, (std::vector<double>{0.5, 0.25, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.5,
                                                      0, 0, 0, 0}));
}

TEST(IoAttributes, NoAttributesLeavesThemEmpty) {
  PointSet p;
  ReadReport r;
  ASSERT_TRUE(read_points_from_buffer("0 0\n1 0\n0 1\n", "t.xy", PointFormat::Auto, {}, p, &r));
  EXPECT_TRUE(r.attributes.normals.empty());
  EXPECT_TRUE(r.attributes.colors.empty());
  EXPECT_EQ(r.attributes.color_channels, 0);
}

TEST(IoAttributes, MeshFromBufferMatchesTheFileReader) {
  const std::string path = std::string(CONSTRICT_TEST_DATA_DIR) + "/io/tetra_faces_ascii.ply";
  PointSet a, b;
  TriMesh3 ma, mb;
  ASSERT_TRUE(read_mesh(path, a, ma));
  std::string data;
  {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t got = 0;
    while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, got);
    std::fclose(f);
  }
  ASSERT_TRUE(read_mesh_from_buffer(data, "tetra.ply", b, mb));
  EXPECT_EQ(a.coords, b.coords);
  EXPECT_EQ(ma.triangles, mb.triangles);
  const Status st = read_mesh_from_buffer("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1.5\n", "x.off", b, mb);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("x.off:6: malformed vertex index '1.5'"), std::string::npos)
      << st.message();
}

}  // namespace
}  // namespace constrict
