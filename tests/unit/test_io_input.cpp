// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 18 (input): coordinate columns by header name or ReadOptions::columns, more than 3 fields
// refused with a way out, STL and GeoJSON points, LAS/LAZ/E57 refused with a conversion hint,
// --format names, the merged pairs and the file-row views of a merged read, and PLY attributes
// written by write_mesh() and read back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"

namespace constrict {
namespace {

Status read_text(const std::string& text, PointSet& p, const ReadOptions& o = {}, const std::string& name = "t.csv",
                 ReadReport* r = nullptr) {
  return read_points_from_buffer(text, name, PointFormat::Auto, o, p, r);
}

ReadOptions with_columns(const std::string& spec, int dim = 0) {
  ReadOptions o;
  o.dim = dim;
  EXPECT_TRUE(parse_columns(spec, o.columns));
  return o;
}

const std::string kIdXY = "id,x,y\n7,0,0\n8,1,0\n9,0,1\n";

// Large text files are read in parallel blocks after the first data line: the values must be
// those of the text in file order whatever the line formats (signs, exponents, tabs, commas, CRLF,
// comments, blank lines), and a bad line anywhere must give the error of that line (the file is
// then read again in order). 3 x 120 000 lines, about 3-6 MiB, so that there are several blocks.
TEST(IoTextBlocks, LargeFilesKeepValuesAndErrorLines) {
  for (const int variant : {0, 1, 2, 3}) {
    // 2D with a comment and a header, 3D with a header, then both without (dimension from the data).
    const int dim = 2 + variant % 2;
    const bool header = variant < 2;
    std::string text = !header ? "" : dim == 2 ? "# a comment\nx,y\n" : "x y z\n";
    std::vector<double> want;
    std::uint64_t state = 12345 + static_cast<std::uint64_t>(dim);
    const auto next = [&state] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return state >> 11;
    };
    const char* seps[] = {" ", "\t", ",", " , ", ";"};
    std::vector<std::size_t> line_start;  // byte offset of every data line (1-based line numbers below)
    std::size_t line = !header ? 0 : dim == 2 ? 2 : 1;
    std::vector<std::size_t> line_no;
    char buf[64];
    for (int i = 0; i < 120000; ++i) {
      if (next() % 97 == 0) {
        text += next() % 2 ? "\n" : "   # between\n";
        ++line;
      }
      const std::string sep = seps[next() % 5];
      line_start.push_back(text.size());
      line_no.push_back(++line);
      for (int k = 0; k < dim; ++k) {
        const double v =
            (static_cast<double>(next() % 2000001) - 1e6) * std::pow(10.0, static_cast<int>(next() % 9) - 4);
        const unsigned style = next() % 4;
        std::snprintf(buf, sizeof buf,
                      style == 0   ? "%.17g"
                      : style == 1 ? "%+.17e"
                      : style == 2 ? "%.17E"
                                   : "%.17g",
                      v);
        want.push_back(std::stod(buf));
        if (k > 0) text += sep;
        text += buf;
      }
      text += i % 5 == 0 ? "\r\n" : i % 7 == 0 ? " # note\n" : "\n";
    }
    PointSet p;
    const std::string name = dim == 2 ? "big.csv" : "big.xyz";
    ASSERT_TRUE(read_text(text, p, {}, name).is_ok());
    EXPECT_EQ(p.dim, dim);
    ASSERT_EQ(p.coords.size(), want.size());
    EXPECT_TRUE(p.coords == want) << "dim " << dim << " header " << header;

    // A bad line early, in the middle, late and last: its own error and line number.
    for (const std::size_t at :
         {std::size_t{3}, line_start.size() / 2, line_start.size() - 900, line_start.size() - 1}) {
      const std::size_t b = line_start[at];
      const std::size_t e = text.find('\n', b);
      for (const std::string& bad :
           {std::string(dim == 2 ? "1 2 3" : "1 2"), std::string(dim == 2 ? "1 x" : "1 2 x"),
            std::string(dim == 2 ? "nan 1" : "1 inf 2"), std::string(dim == 2 ? "1,,2" : "1,,2,3")}) {
        std::string t = text;
        t.replace(b, e - b, bad);
        PointSet q;
        const Status st = read_text(t, q, {}, name);
        ASSERT_FALSE(st.is_ok()) << bad << " at " << at;
        EXPECT_NE(st.message().find(name + ":" + std::to_string(line_no[at]) + ":"), std::string::npos)
            << st.message() << " (expected line " << line_no[at] << ")";
      }
    }
  }
}

TEST(IoColumns, HeaderNamesChooseTheColumns) {
  // The issue: `id,x,y` with --dim 2 gave a polygon through (id, x).
  for (int dim : {0, 2}) {
    PointSet p;
    ReadOptions o;
    o.dim = dim;
    ASSERT_TRUE(read_text(kIdXY, p, o));
    EXPECT_EQ(p.dim, 2);
    EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
  }
  PointSet p;
  ASSERT_TRUE(read_text("\"Z\";\"Y\";\"X\";label\n3;2;1;a\n6;5;4;b\n0;1;1;c\n1;0;0;d\n", p));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, (std::vector<double>{1, 2, 3, 4, 5, 6, 1, 1, 0, 0, 0, 1}));
}

TEST(IoColumns, HeaderWithoutXYKeepsTheFirstFields) {
  PointSet p;
  ASSERT_TRUE(read_text("east,north\n0,0\n1,0\n0,1\n", p));
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
}

TEST(IoColumns, MoreThanThreeFieldsSaysHowToChoose) {
  PointSet p;
  Status st = read_text("1 2 3 4 5 6 7\n1 2 3 4 5 6 8\n", p, {}, "seven.txt");
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("seven.txt:1: 7 fields per line"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("--columns"), std::string::npos);
  ReadOptions o;
  o.dim = 3;  // a forced dim used to take the first 3 of them silently
  EXPECT_EQ(read_text("1 2 3 4\n1 2 3 5\n", p, o).code(), StatusCode::ParseError);
  st = read_text("id,a,b,c\n1,0,0,0\n", p, {}, "h.csv");
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("h.csv:1: the header names 4 columns, none of them x and y"), std::string::npos)
      << st.message();
}

TEST(IoColumns, NumbersAndNames) {
  PointSet p;
  ASSERT_TRUE(read_text("a b c d\n9 0 0 5\n9 1 0 5\n9 0 1 5\n", p, with_columns("2,3")));
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
  ASSERT_TRUE(read_text("9 0 0 5 1\n9 1 0 5 1\n9 0 1 5 1\n9 0 0 5 0\n", p, with_columns("3,2,5")));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 1, 1, 1, 0, 1, 0, 0, 0}));
  ASSERT_TRUE(read_text("lon,lat,h\n0,0,9\n1,0,9\n0,1,9\n", p, with_columns("LON,lat")));
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
  // Forced dim 2 with three columns drops the third; dim 3 with two is refused.
  ASSERT_TRUE(read_text("0 0 0\n1 0 0\n0 1 0\n", p, with_columns("1,2,3", 2)));
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(read_text("0 0 0\n1 0 0\n0 1 0\n", p, with_columns("1,2", 3)).code(), StatusCode::InvalidArgument);
  // A column past the end of the line, a name not in the header, names without a header.
  Status st = read_text("0 0\n1 0\n0 1\n", p, with_columns("1,4"), "c.xy");
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("c.xy:1: column 4"), std::string::npos) << st.message();
  EXPECT_EQ(read_text(kIdXY, p, with_columns("x,q")).code(), StatusCode::InvalidArgument);
  EXPECT_EQ(read_text("0 0\n1 0\n0 1\n", p, with_columns("x,y")).code(), StatusCode::InvalidArgument);
  // Selected columns are checked like any coordinate.
  st = read_text("a b c\n0 0 0\n1 nan 0\n", p, with_columns("2,3"), "n.txt");
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_NE(st.message().find("n.txt:3:"), std::string::npos) << st.message();
  // Only text input has columns.
  EXPECT_EQ(read_points_from_buffer("OFF\n4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "m.off", PointFormat::Auto,
                                    with_columns("1,2,3"), p)
                .code(),
            StatusCode::InvalidArgument);
}

TEST(IoColumns, ParseColumns) {
  ColumnSelection c;
  ASSERT_TRUE(parse_columns("2, 3,4", c));
  EXPECT_EQ(c.numbers, (std::vector<std::size_t>{2, 3, 4}));
  ASSERT_TRUE(parse_columns("x,y", c));
  EXPECT_EQ(c.names, (std::vector<std::string>{"x", "y"}));
  for (const char* bad : {"", "1", "1,2,3,4", "0,1", "1,x", "1,1", "x,,y"})
    EXPECT_EQ(parse_columns(bad, c).code(), StatusCode::InvalidArgument) << bad;
}

TEST(IoFormats, Names) {
  PointFormat f = PointFormat::Auto;
  for (const char* n : {"auto", "text", "ply", "off", "obj", "stl", "geojson"}) {
    ASSERT_TRUE(point_format_from_name(n, f)) << n;
    EXPECT_STREQ(to_string(f), n);
  }
  EXPECT_EQ(point_format_from_name("las", f).code(), StatusCode::InvalidArgument);
}

// A unit tetrahedron as ASCII STL: 4 facets, 12 corners, 4 distinct vertices.
const std::string kTetraStl =
    "solid t\n"
    "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "endsolid t\n";

TEST(IoFormats, StlVerticesOnceEach) {
  PointSet p;
  ReadReport r;
  ASSERT_TRUE(read_points_from_buffer(kTetraStl, "t.stl", PointFormat::Auto, {}, p, &r));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1}));
  EXPECT_EQ(r.points_read, 4u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("12 facet corners read, 4 distinct points kept"), std::string::npos) << r.warnings[0];
  // Binary STL, named otherwise and read with an explicit format.
  PointSet q;
  TriMesh3 m;
  ASSERT_TRUE(read_mesh_from_buffer(kTetraStl, "t.stl", q, m));
  const std::string path = (std::filesystem::temp_directory_path() / "constrict_test_tetra_bin.stl").string();
  ASSERT_TRUE(write_mesh(path, q, m));
  std::ifstream f(path, std::ios::binary);
  const std::string bin((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  PointSet b;
  ASSERT_TRUE(read_points_from_buffer(bin, "t.dat", PointFormat::Stl, {}, b));
  EXPECT_EQ(b.size(), 4u);
  ReadOptions two;
  two.dim = 2;
  EXPECT_EQ(read_points_from_buffer(kTetraStl, "t.stl", PointFormat::Auto, two, p).code(), StatusCode::Duplicate);
}

TEST(IoFormats, GeoJsonPoints) {
  const std::string fc =
      R"({"type": "FeatureCollection", "features": [
          {"type": "Feature", "properties": {"n": 1}, "geometry": {"type": "Point", "coordinates": [0, 0]}},
          {"type": "Feature", "properties": null, "geometry": null},
          {"type": "Feature", "geometry": {"type": "MultiPoint", "coordinates": [[1, 0], [0, 1.5]]}}]})";
  PointSet p;
  ASSERT_TRUE(read_points_from_buffer(fc, "p.geojson", PointFormat::Auto, {}, p));
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1.5}));
  ASSERT_TRUE(read_points_from_buffer(R"({"type": "MultiPoint", "coordinates": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]]})",
                                      "m.json", PointFormat::Auto, {}, p));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.size(), 4u);
  const auto code = [&p](const std::string& text) {
    Status st = read_points_from_buffer(text, "e.geojson", PointFormat::Auto, {}, p);
    EXPECT_EQ(st.message().find('\n'), std::string::npos) << st.message();
    return st.code();
  };
  EXPECT_EQ(code(R"({"type": "Polygon", "coordinates": [[[0,0],[1,0],[0,1],[0,0]]]})"), StatusCode::ParseError);
  EXPECT_EQ(code(R"({"type": "MultiPoint", "coordinates": [[0,0],[1,0,0]]})"), StatusCode::ParseError);
  EXPECT_EQ(code(R"({"type": "Point", "coordinates": [0]})"), StatusCode::ParseError);
  EXPECT_EQ(code(R"({"type": "Point", "coordinates": [0, 1e400]})"), StatusCode::NonFinite);
  EXPECT_EQ(code("{\"type\": \"Point\",\n \"coordinates\": [0, x]}"), StatusCode::ParseError);
  EXPECT_EQ(code(R"({"type": "FeatureCollection", "features": []})"), StatusCode::EmptyInput);
  // A type with an escaped line break is quoted in the message (found by fuzz_geojson).
  EXPECT_EQ(code(R"({"type": "Poly\ngon"})"), StatusCode::ParseError);
  EXPECT_EQ(code(R"({"type": "Poly\ngon", "coordinates": []})"), StatusCode::ParseError);
  Status st = read_points_from_buffer(
      R"({"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "LineString", "coordinates": []}}]})",
      "l.geojson", PointFormat::Auto, {}, p);
  EXPECT_NE(st.message().find("l.geojson: /features/0/geometry: geometry type 'LineString'"), std::string::npos)
      << st.message();
}

// Found by a hostile-input sweep (2026-12-05): 20 000 nested GeometryCollections overflowed the
// stack (each level also built a longer error location: 2 GB); a Feature as another's geometry
// was read. Both are refused now, in one line.
TEST(IoFormats, GeoJsonNestingIsBounded) {
  PointSet p;
  const auto nested = [](int depth, const char* open, const char* close) {
    std::string s;
    for (int i = 0; i < depth; ++i) s += open;
    s += R"({"type": "MultiPoint", "coordinates": [[0,0],[1,0],[0,1]]})";
    for (int i = 0; i < depth; ++i) s += close;
    return s;
  };
  const char* gc_open = R"({"type": "GeometryCollection", "geometries": [)";
  ASSERT_TRUE(read_points_from_buffer(nested(10, gc_open, "]}"), "ok.geojson", PointFormat::Auto, {}, p));
  EXPECT_EQ(p.size(), 3u);
  for (int depth : {65, 20000}) {
    const Status st = read_points_from_buffer(nested(depth, gc_open, "]}"), "deep.geojson", PointFormat::Auto, {}, p);
    EXPECT_EQ(st.code(), StatusCode::ParseError) << depth;
    EXPECT_NE(st.message().find("nested deeper than 64 levels"), std::string::npos) << st.message();
    EXPECT_LT(st.message().size(), 300u);
  }
  const Status st = read_points_from_buffer(
      nested(1, R"({"type": "Feature", "geometry": {"type": "Feature", "geometry": )", "}}"), "f.geojson", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("/geometry: a Feature where RFC 7946 allows a geometry only"), std::string::npos) << st.message();
}

// A header count smaller than the data dropped the points beyond it without a word (hostile-input
// sweep, 2026-12-05); a repeated coordinate name picked one of the two columns.
TEST(IoFormats, MoreDataThanAnnouncedIsAnError) {
  PointSet p;
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n";
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
  Status st = read_points_from_buffer(ply + verts, "short.ply", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("PLY data goes on after its last element"), std::string::npos) << st.message();
  ASSERT_TRUE(read_points_from_buffer(ply + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n\n  \n", "ok.ply", PointFormat::Auto, {}, p));
  EXPECT_EQ(p.size(), 4u);
  // With a face element after the vertices, its first record must read as one.
  const std::string ply_faces = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                                "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(read_points_from_buffer(ply_faces + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0.5 0.5\n3 0 1 2\n", "shortf.ply", PointFormat::Auto, {}, p).code(),
            StatusCode::ParseError);
  ASSERT_TRUE(read_points_from_buffer(ply_faces + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n", "okf.ply", PointFormat::Auto, {}, p));
  st = read_points_from_buffer("OFF\n4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0.5 0.5\n", "short.off", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("short.off:7: more lines than the header announces (4 vertices and 0 faces)"),
            std::string::npos)
      << st.message();
  ASSERT_TRUE(read_points_from_buffer("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n", "ok.off", PointFormat::Auto, {}, p));
  st = read_points_from_buffer("OFF\r4 0 0\r0 0 0\r1 0 0\r0 1 0\r0 0 1\r", "cr.off", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("CR only"), std::string::npos) << st.message();
  st = read_points_from_buffer("x,x,y\n0,1,2\n1,2,3\n4,5,7\n", "xxy.csv", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("xxy.csv:1: the header names 'x' twice (columns 1 and 2)"), std::string::npos) << st.message();
  st = read_points_from_buffer("ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double x\nproperty double y\n"
                               "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n",
                               "xx.ply", PointFormat::Auto, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_NE(st.message().find("two properties 'x'"), std::string::npos) << st.message();
}

// Damaged files whose damage looked like something harmless lost points without a word (an
// adversarial sweep of the readers): each is refused now, and its undamaged sibling still reads.
TEST(IoFormats, DamagedLinesAreRefusedNotDropped) {
  PointSet p;
  const auto code = [&p](const std::string& data, const std::string& name) {
    return read_points_from_buffer(data, name, PointFormat::Auto, {}, p).code();
  };
  const std::string tetra = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  // OFF: a fifth vertex line taken for a face line, a face line more than announced.
  EXPECT_EQ(code("OFF\n4 0 0\n" + tetra + "1 1 1\n", "a.off"), StatusCode::ParseError);
  EXPECT_EQ(code("OFF\n4 1 0\n" + tetra + "1 1 1\n3 0 1 2\n", "b.off"), StatusCode::ParseError);
  EXPECT_EQ(code("OFF\n4 1 0\n" + tetra + "3 0 1 2\n3 0 1 3\n", "c.off"), StatusCode::ParseError);
  EXPECT_EQ(code("OFF\n4 1 0\n" + tetra + "3 0 1 7\n", "d.off"), StatusCode::ParseError);
  EXPECT_EQ(code("OFF\n4 2 0\n" + tetra + "3 0 1 2\n3 0 1 3\n# end\n", "ok.off"), StatusCode::Ok);
  EXPECT_EQ(p.size(), 4u);
  EXPECT_EQ(code("OFF\n4 2 0\n" + tetra + "3 0 1 2\n", "cut.off"), StatusCode::Ok);  // (no point lost)
  EXPECT_EQ(p.size(), 4u);
  // Text: a first line that is no header of the data was dropped as one.
  for (const char* first : {"OFF\n", "0x10 0x10 0x10\n", "\"5\",\"5\",\"5\"\n", "- - -\n",
                            "0\xc2\xa0"
                            "0 0\n"})
    EXPECT_EQ(code(first + tetra, "t.xyz"), StatusCode::ParseError) << first;
  for (const char* first : {"x y z\n", "east north height\n", "H\xc3\xb6he b c\n", "\"x\",\"y\",\"z\"\n"}) {
    EXPECT_EQ(code(first + tetra, "h.xyz"), StatusCode::Ok) << first;
    EXPECT_EQ(p.size(), 4u) << first;
  }
  // OBJ: a damaged vertex statement.
  EXPECT_EQ(code("v 0 0 0\nv1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n", "a.obj"), StatusCode::ParseError);
  EXPECT_EQ(code("v,0,1,0\nv 0 0 0\nv 1 0 0\nv 0 0 1\n", "b.obj"), StatusCode::ParseError);
  EXPECT_EQ(code("v 0 0 0\nvn 0 0 1\nvt 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvp 0.5\n", "ok.obj"), StatusCode::Ok);
  EXPECT_EQ(p.size(), 4u);
  // Binary STL whose size does not match its facet count, with a header starting "solid" (as many
  // exporters write): read as ASCII, it gave "no points".
  std::string stl = "solid exported";
  stl.resize(80, '\0');
  const std::uint32_t facets = 1;
  stl.append(reinterpret_cast<const char*>(&facets), 4);  // (little-endian hosts: the test machines)
  const float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  stl.append(reinterpret_cast<const char*>(tri), sizeof tri);
  stl.append(2, '\0');
  EXPECT_NE(code(stl, "ok.stl"), StatusCode::ParseError);  // (read: its corners are then too few)
  EXPECT_EQ(code(stl.substr(0, stl.size() - 1), "short.stl"), StatusCode::ParseError);
  EXPECT_EQ(code(stl + '\0', "long.stl"), StatusCode::ParseError);
  // Meshes: faces beyond the announced count.
  PointSet v;
  TriMesh3 m;
  EXPECT_EQ(read_mesh_from_buffer("OFF\n4 1 0\n" + tetra + "3 0 1 2\n3 0 1 3\n", "m.off", v, m).code(),
            StatusCode::ParseError);
  EXPECT_TRUE(read_mesh_from_buffer("OFF\n4 2 0\n" + tetra + "3 0 1 2\n3 0 1 3\n", "m.off", v, m));
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
      tetra;
  EXPECT_EQ(read_mesh_from_buffer(ply + "3 0 1 2\n3 0 1 3\n", "m.ply", v, m).code(), StatusCode::ParseError);
  EXPECT_TRUE(read_mesh_from_buffer(ply + "3 0 1 2\n", "m.ply", v, m));
  // ASCII PLY: a kept value that its declared integer type cannot hold (a fraction, out of range)
  // was taken as written; floats take any finite value, integers written as 1e2 or 7.0 are fine.
  const std::string ints = "ply\nformat ascii 1.0\nelement vertex 4\nproperty int x\nproperty int y\nproperty int z\n"
                           "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  EXPECT_EQ(code(ints + "0 0 0 1 2 3\n1 0 0 1 2 3\n0 1.5 0 1 2 3\n0 0 1 1 2 3\n", "frac.ply"), StatusCode::ParseError);
  EXPECT_EQ(code(ints + "0 0 0 1 2 3\n1 0 0 1 2 3\n0 3000000000 0 1 2 3\n0 0 1 1 2 3\n", "range.ply"), StatusCode::ParseError);
  EXPECT_EQ(code(ints + "0 0 0 1 2 3\n1e2 0 0 1 2 3\n0 7.0 0 1 2 3\n0 0 1 -0 2 255\n", "ok.ply"), StatusCode::Ok);
  EXPECT_EQ(code("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                 "0.12345678901234567 0 0\n1 0 0\n0 1 0\n0 0 1\n",
                 "f.ply"),
            StatusCode::Ok);
}

TEST(IoFormats, ScannerFormatsRefusedWithAHint) {
  PointSet p;
  std::string las = "LASF";
  las.append(300, '\0');
  for (const auto& [data, name] : std::vector<std::pair<std::string, std::string>>{
           {las, "scan.xyz"}, {"0 0\n1 0\n0 1\n", "scan.las"}, {las, "scan.laz"}, {"ASTM-E57xxxx", "scan.bin"},
           {"", "scan.e57"}}) {
    Status st = read_points_from_buffer(data, name, PointFormat::Auto, {}, p);
    EXPECT_EQ(st.code(), StatusCode::Unsupported) << name;
    EXPECT_NE(st.message().find(name + ": "), std::string::npos);
    EXPECT_NE(st.message().find("pdal translate"), std::string::npos) << st.message();
  }
  // Magic bytes win over an explicit format; an extension does not.
  EXPECT_EQ(read_points_from_buffer(las, "s.txt", PointFormat::Text, {}, p).code(), StatusCode::Unsupported);
  EXPECT_TRUE(read_points_from_buffer("0 0\n1 0\n0 1\n", "s.las", PointFormat::Text, {}, p));
}

TEST(IoMerge, PairsAndFileRows) {
  ReadOptions o;
  o.merge_duplicates = true;
  PointSet p;
  ReadReport r;
  // rows: 0 (0,0), 1 (1,0), 2 = row 0, 3 (0,1), 4 = row 1, 5 = row 0
  ASSERT_TRUE(read_text("0 0\n1 0\n0 0\n0 1\n1 0\n-0 0\n", p, o, "m.xy", &r));
  EXPECT_EQ(p.size(), 3u);
  EXPECT_EQ(r.original_index, (std::vector<std::size_t>{0, 1, 3}));
  using Pair = std::array<std::size_t, 2>;
  EXPECT_EQ(r.merged, (std::vector<Pair>{{0, 2}, {1, 4}, {0, 5}}));
  const PointSet rows = file_row_points(p, r);
  EXPECT_EQ(rows.coords, (std::vector<double>{0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0}));
  // Nothing merged: no pairs, the same points.
  ASSERT_TRUE(read_text("0 0\n1 0\n0 1\n", p, o, "n.xy", &r));
  EXPECT_TRUE(r.merged.empty());
  EXPECT_EQ(file_row_points(p, r).coords, p.coords);
}

TEST(IoAttributesOut, ColouredPlyRoundTrip) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\nend_header\n"
      "0 0 0 0 0 -1 255 0 0 255\n1 0 0 1 0 0 0 255 0 128\n0 1 0 0 1 0 0 0 255 0\n"
      "0 0 1 0.25 0.5 0.75 10 20 30 40\n0 0 0 9 9 9 1 2 3 4\n";
  ReadOptions o;
  o.merge_duplicates = true;  // row 4 repeats row 0
  PointSet p;
  ReadReport r;
  ASSERT_TRUE(read_points_from_buffer(ply, "c.ply", PointFormat::Auto, o, p, &r));
  ASSERT_EQ(p.size(), 4u);
  TriMesh3 m;
  m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
  const PointSet rows = file_row_points(p, r);
  const PointAttributes attributes = file_row_attributes(r);
  const auto dir = std::filesystem::temp_directory_path();
  for (bool ascii : {false, true}) {
    MeshWriteOptions w;
    w.ply_ascii = ascii;
    w.attributes = &attributes;
    const std::string path = (dir / (ascii ? "constrict_rt_ascii.ply" : "constrict_rt_bin.ply")).string();
    ASSERT_TRUE(write_mesh(path, rows, m, w));
    PointSet back;
    ReadReport rb;
    ASSERT_TRUE(read_points(path, o, back, &rb));
    std::filesystem::remove(path);
    EXPECT_EQ(back.coords, p.coords);
    EXPECT_EQ(rb.attributes.normals, r.attributes.normals) << ascii;
    EXPECT_EQ(rb.attributes.color_channels, 4);
    EXPECT_EQ(rb.attributes.colors, r.attributes.colors) << ascii;
  }
  // Arrays that do not match the points are refused.
  PointAttributes bad = attributes;
  bad.normals.pop_back();
  MeshWriteOptions w;
  w.attributes = &bad;
  EXPECT_EQ(write_mesh((dir / "constrict_rt_bad.ply").string(), rows, m, w).code(), StatusCode::InvalidArgument);
}

}  // namespace
}  // namespace constrict
