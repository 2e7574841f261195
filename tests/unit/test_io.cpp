// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of read_points(): every format, the text rules, every error with its code, file name and
// line, duplicates (error and merge) and the %.17g round trip.
#include <gtest/gtest.h>
#include <stdlib.h>  // mkdtemp
#if defined(__unix__) || defined(__APPLE__)
#include <sys/stat.h>  // mkfifo
#endif

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

namespace fs = std::filesystem;

const std::string kDataDir = std::string(CONSTRICT_TEST_DATA_DIR) + "/io/";

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// Fixture with a private temporary directory for files written by the test.
class IoFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "constrict_io_XXXXXX").string();
    ASSERT_NE(mkdtemp(&tmpl[0]), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    EXPECT_TRUE(f.good()) << path;
    return path;
  }

  // Writes `bytes` to `name` and reads it back.
  Status read(const std::string& name, const std::string& bytes, PointSet& out,
              const ReadOptions& options = {}, ReadReport* report = nullptr) const {
    return read_points(write(name, bytes), options, out, report);
  }

  fs::path dir_;
};

class IoText : public IoFixture {};
class IoErrors : public IoFixture {};
class IoPly : public IoFixture {};
class IoOff : public IoFixture {};
class IoObj : public IoFixture {};
class IoFormat : public IoFixture {};
class IoDuplicates : public IoFixture {};
class IoChecks : public IoFixture {};
class IoRoundTrip : public IoFixture {};

const std::string kTetra = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::vector<double> kTetraCoords = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<double> kTetraCoords2 = {0, 0, 1, 0, 0, 1, 0, 0};  // z dropped

// ---- text ------------------------------------------------------------------------------------

TEST_F(IoText, Reads3DWhitespace) {
  PointSet p;
  ReadReport report;
  ASSERT_TRUE(read("t.xyz", "0 0 0\n1.5  0\t0\n0 -1e3 0\n 0 0 2.25e-1 \n", p, {}, &report));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 0, 1.5, 0, 0, 0, -1000, 0, 0, 0, 0.225}));
  EXPECT_EQ(report.points_read, 4u);
  EXPECT_EQ(report.merged_duplicates, 0u);
  EXPECT_EQ(report.original_index, (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_TRUE(report.warnings.empty());
}

TEST_F(IoText, Reads2D) {
  PointSet p;
  ASSERT_TRUE(read("t.xy", "0 0\n1 0\n0 1\n", p));
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
}

TEST_F(IoText, Separators) {
  for (const char* text :
       {"0,0,0\n1,0,0\n0,1,0\n0,0,1\n", "0;0;0\n1;0;0\n0;1;0\n0;0;1\n",
        "0\t0\t0\n1\t0\t0\n0\t1\t0\n0\t0\t1\n", "0 , 0 ,0\n1, 0 ,0\n0 ;1; 0\n0\t,0 ,\t1\n"}) {
    PointSet p;
    Status st = read("t.csv", text, p);
    ASSERT_TRUE(st) << st.message() << " for " << text;
    EXPECT_EQ(p.coords, kTetraCoords) << text;
  }
}

TEST_F(IoText, CommentsBlankLinesHeaderAndCrlf) {
  PointSet p;
  Status st = read_points(kDataDir + "header_crlf_semicolon.csv", {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoText, TrailingCommentsAndNoFinalNewline) {
  PointSet p;
  ASSERT_TRUE(read("t.xyz", "# first\n\n0 0 0#a\n1 0 0 # b\n   \n0 1 0\n0 0 1", p));
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoText, HeaderLineIsSkippedOnlyOnce) {
  PointSet p;
  ASSERT_TRUE(read("h.csv", "x,y,z\n" + kTetra, p));
  EXPECT_EQ(p.size(), 4u);
  Status st = read("h2.csv", "x,y,z\nx,y,z\n" + kTetra, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "h2.csv:2: malformed number 'x'"));
  // A header is allowed only before the first point.
  st = read("h3.csv", "0 0 0\nx y z\n1 0 0\n0 1 0\n0 0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "h3.csv:2: malformed number 'x'"));
  // A first line with a number in it is data, not a header.
  st = read("h4.csv", "x1.2,0,0\n" + kTetra, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "h4.csv:1: malformed number 'x1.2'"));
}

TEST_F(IoText, ByteOrderMarkAndLeadingPlus) {
  PointSet p;
  ASSERT_TRUE(read("bom.csv", "\xEF\xBB\xBFx,y,z\n+0,0,0\n+1,0,0\n0,+1,0\n0,0,+1\n", p));
  EXPECT_EQ(p.coords, kTetraCoords);
}

// Found by a hostile-input sweep (2026-12-04): CR-only lines were read as one line of 8 fields
// ("more than x, y, z"), a second byte order mark was printed raw (invisible) in the message, and
// UTF-16 text had its first line taken as a header, then a run of \x00 in the message.
TEST_F(IoText, CrOnlyLinesUtf16AndInvisibleCharacters) {
  PointSet p;
  Status st = read("cr.xyz", "0 0 0\r1 0 0\r0 1 0\r0 0 1\r", p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
  st = read("cr.csv", "x,y,z\r0,0,0\r1,0,0\r0,1,0\r0,0,1", p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);

  st = read("bom2.xy", "\xEF\xBB\xBF\xEF\xBB\xBF" "0 0\n1 0\n0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "bom2.xy:1: malformed number '<U+FEFF byte order mark>0'")) << st.message();
  st = read("nbsp.xy", "0 0\n1\xC2\xA0" "0 0\n0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "<U+00A0 no-break space>")) << st.message();

  std::string utf16 = "\xFF\xFE";
  for (const char c : std::string("0 0\n1 0\n0 1\n")) utf16 += std::string(1, c) + std::string(1, '\0');
  st = read("u16.xy", utf16, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "u16.xy: the file is UTF-16 text")) << st.message();
  st = read("u16nobom.xy", utf16.substr(2), p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "UTF-16 or UTF-32 text or binary")) << st.message();
}

#if defined(__unix__) || defined(__APPLE__)
TEST_F(IoText, ReadsFromPipe) {
  // A FIFO is not a regular file: it cannot be mapped and has no size, so it is read in chunks.
  const std::string path = (dir_ / "pipe.xyz").string();
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  std::string text = "x y z\n";
  for (int i = 0; i < 20000; ++i)  // more than one read chunk
    text += std::to_string(i) + " " + std::to_string(i % 7) + " " + std::to_string(i % 11) + "\n";
  // If the reader stopped early the writer would get SIGPIPE: make that a test failure instead.
  const auto old_handler = std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&path, &text] {
    std::ofstream f(path, std::ios::binary);
    f << text;
  });
  PointSet p;
  Status st = read_points(path, {}, p);
  writer.join();
  std::signal(SIGPIPE, old_handler);
  ASSERT_TRUE(st) << st.message();
  ASSERT_EQ(p.size(), 20000u);
  EXPECT_EQ(p[19999][0], 19999.0);
  EXPECT_EQ(p[19999][1], 19999 % 7);
  EXPECT_EQ(p[19999][2], 19999 % 11);
}
#endif

TEST_F(IoText, ForcedDim2DropsZ) {
  PointSet p;
  ReadOptions o;
  o.dim = 2;
  ASSERT_TRUE(read("t.xyz", "0 0 5\n1 0 6\n0 1 7\n", p, o));
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
}

// Issue 18: wider lines used to give their first `dim` fields silently (`id x y` -> (id, x)); now
// the columns must be chosen (ReadOptions::columns or a header naming x, y, z).
TEST_F(IoText, ForcedDimOnWiderLinesNeedsChosenColumns) {
  PointSet p;
  ReadOptions o;
  o.dim = 3;
  const std::string text = "0 0 0 red 1\n1 0 0 blue 2\n0 1 0 x 3\n0 0 1 y 4\n";
  Status st = read("t.txt", text, p, o);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "t.txt:1: 5 fields per line, more than x, y, z: choose the coordinate columns"));
  ASSERT_TRUE(parse_columns("1,2,3", o.columns));
  ASSERT_TRUE(read("t.txt", text, p, o));
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kTetraCoords);
  ASSERT_TRUE(read("h.txt", "x y z name id\n" + text, p, ReadOptions{}));
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoText, ForcedDim3WithTwoFieldsIsParseError) {
  PointSet p;
  ReadOptions o;
  o.dim = 3;
  Status st = read("two.xy", "\n0 0\n1 0\n0 1\n", p, o);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "two.xy:2: expected at least 3 fields"));
  EXPECT_TRUE(Contains(st.message(), "found 2"));
}

TEST_F(IoText, FourColumnsWithoutDimIsParseError) {
  PointSet p;
  Status st = read("four.txt", "# c\n0 0 0 1\n1 0 0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "four.txt:2: 4 fields per line, more than x, y, z: choose the coordinate columns with --columns"));
  st = read("one.txt", "5\n6\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "one.txt:1: expected 2 or 3 fields (x y [z]), found 1"));
}

// ---- errors ----------------------------------------------------------------------------------

TEST_F(IoErrors, MalformedNumberNamesFileLineAndToken) {
  PointSet p;
  Status st = read_points(kDataDir + "bad_number.csv", {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "bad_number.csv:7: malformed number 'x1.2'"));
  EXPECT_EQ(st.message().find('\n'), std::string::npos);
}

TEST_F(IoErrors, TrailingGarbageAndBadExponent) {
  PointSet p;
  Status st = read("g.xyz", kTetra + "1.5x 2 3\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "g.xyz:5: malformed number '1.5x'"));
  st = read("e.xyz", "1 2 3\n1e 2 3\n", p);
  EXPECT_TRUE(Contains(st.message(), "e.xyz:2: malformed number '1e'"));
  st = read("pm.xyz", "1 2 3\n+-1 2 3\n", p);
  EXPECT_TRUE(Contains(st.message(), "pm.xyz:2: malformed number '+-1'"));
}

TEST_F(IoErrors, ControlBytesAreEscapedInMessages) {
  PointSet p;
  Status st = read("c.xyz", std::string("1 2 3\n1 \x01z 3\n", 13), p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "c.xyz:2: malformed number '\\x01z'"));
}

TEST_F(IoErrors, WrongFieldCount) {
  PointSet p;
  Status st = read_points(kDataDir + "field_count_line4.xyz", {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "field_count_line4.xyz:4: expected 3 fields, found 2"));
  st = read("w.xy", "0 0\n1 0\n\n# x\n0 1 2\n", p);
  EXPECT_TRUE(Contains(st.message(), "w.xy:5: expected 2 fields, found 3"));
}

TEST_F(IoErrors, EmptyField) {
  PointSet p;
  for (const char* text : {"0,0,0\n1,,0\n", "0,0,0\n1,0,0,\n", "0,0,0\n,1,0,0\n"}) {
    Status st = read("ef.csv", text, p);
    EXPECT_EQ(st.code(), StatusCode::ParseError) << text;
    EXPECT_TRUE(Contains(st.message(), "ef.csv:2: empty field")) << text;
  }
}

TEST_F(IoErrors, NonFiniteInText) {
  PointSet p;
  Status st = read_points(kDataDir + "nan_line3.xyz", {}, p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "nan_line3.xyz:3: non-finite coordinate 'nan'"));
  st = read("inf.csv", "0,0\n1,-inf\n", p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "inf.csv:2: non-finite coordinate '-inf'"));
  // Overflow to infinity is non-finite too.
  st = read("big.csv", "0,0\n1,0\n1e400,1\n", p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "big.csv:3: non-finite coordinate '1e400'"));
}

TEST_F(IoErrors, EmptyFileAndNoPoints) {
  PointSet p;
  Status st = read("empty.xyz", "", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  EXPECT_TRUE(Contains(st.message(), "empty.xyz: empty file"));
  st = read("blank.xyz", "\n  \r\n\n", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  st = read("comments.xyz", "# only\n# comments\n", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  EXPECT_TRUE(Contains(st.message(), "comments.xyz: no points"));
  st = read("header_only.csv", "x,y,z\n", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  st = read("empty.ply",
            "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
            "property float y\nend_header\n",
            p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  st = read("empty.off", "OFF\n0 0 0\n", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
  st = read("empty.obj", "# nothing\nf 1 2 3\n", p);
  EXPECT_EQ(st.code(), StatusCode::EmptyInput);
}

TEST_F(IoErrors, MissingFile) {
  PointSet p;
  const std::string path = (dir_ / "does_not_exist.xyz").string();
  Status st = read_points(path, {}, p);
  EXPECT_EQ(st.code(), StatusCode::FileNotFound);
  EXPECT_TRUE(Contains(st.message(), path));
  EXPECT_TRUE(Contains(st.message(), std::strerror(ENOENT)));
}

TEST_F(IoErrors, DirectoryIsNotAFile) {
  PointSet p;
  Status st = read_points(dir_.string(), {}, p);
  EXPECT_EQ(st.code(), StatusCode::FileNotFound);
  EXPECT_TRUE(Contains(st.message(), dir_.string()));
}

TEST_F(IoErrors, InvalidDimOption) {
  PointSet p;
  ReadOptions o;
  o.dim = 4;
  Status st = read("t.xyz", kTetra, p, o);
  EXPECT_EQ(st.code(), StatusCode::InvalidArgument);
  EXPECT_TRUE(Contains(st.message(), "t.xyz"));
}

TEST_F(IoErrors, OutputUntouchedOnError) {
  PointSet p;
  p.dim = 2;
  p.coords = {7, 8};
  Status st = read("bad.xyz", "0 0 0\n1 x 0\n", p);
  EXPECT_FALSE(st);
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{7, 8}));
}

TEST_F(IoErrors, BufferNameUsedInMessages) {
  PointSet p;
  Status st = read_points_from_buffer("0 0\n1 0\n0 q\n", "<stdin>", PointFormat::Text, {}, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "<stdin>:3: malformed number 'q'"));
  ASSERT_TRUE(read_points_from_buffer("0 0\n1 0\n0 1", "mem", PointFormat::Text, {}, p));
  EXPECT_EQ(p.size(), 3u);
}

// ---- PLY -------------------------------------------------------------------------------------

// Builds binary PLY bodies with a given byte order, independent of the host's.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_(big_endian) {}
  template <typename T>
  Bytes& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    const std::uint16_t one = 1;
    unsigned char host_first = 0;
    std::memcpy(&host_first, &one, 1);
    const bool host_little = host_first == 1;
    if (host_little == big_) std::reverse(b, b + sizeof(T));
    s_.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  const std::string& str() const { return s_; }

 private:
  bool big_;
  std::string s_;
};

// A PLY with an element (with a list) before the vertices, extra vertex properties of all sizes
// (one of them a list) and faces after the vertices.
std::string binary_ply(bool big_endian, float nan_at_vertex2 = 0.0f, bool use_nan = false) {
  std::string header = std::string("ply\nformat ") +
                       (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\ncomment made by test_io\n"
                       "element camera 2\nproperty list uint8 int16 tags\nproperty double f\n"
                       "element vertex 4\n"
                       "property uchar red\nproperty float32 x\nproperty short s\n"
                       "property double y\nproperty list ushort uint32 neighbours\n"
                       "property int z\nproperty ushort u\n"
                       "element face 1\nproperty list uchar int vertex_indices\n"
                       "end_header\n";
  Bytes b(big_endian);
  // cameras: 2 tags + double, 0 tags + double
  b.put<std::uint8_t>(2).put<std::int16_t>(-5).put<std::int16_t>(7).put<double>(1.25);
  b.put<std::uint8_t>(0).put<double>(-3.0);
  const float xs[4] = {0.0f, 1.5f, 0.0f, 0.0f};
  const double ys[4] = {0.0, 0.0, -2.25, 0.0};
  const std::int32_t zs[4] = {0, 0, 0, 70000};
  for (int i = 0; i < 4; ++i) {
    b.put<std::uint8_t>(200);
    b.put<float>(i == 2 && use_nan ? nan_at_vertex2 : xs[i]);
    b.put<std::int16_t>(-1);
    b.put<double>(ys[i]);
    b.put<std::uint16_t>(static_cast<std::uint16_t>(i));  // list of i uint32
    for (int k = 0; k < i; ++k) b.put<std::uint32_t>(0xdeadbeefu);
    b.put<std::int32_t>(zs[i]);
    b.put<std::uint16_t>(9);
  }
  b.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2);
  return header + b.str();
}

const std::vector<double> kPlyCoords = {0, 0, 0, 1.5, 0, 0, 0, -2.25, 0, 0, 0, 70000};

TEST_F(IoPly, BinaryLittleEndian) {
  PointSet p;
  Status st = read("le.ply", binary_ply(false), p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kPlyCoords);
}

TEST_F(IoPly, BinaryBigEndian) {
  PointSet p;
  Status st = read("be.ply", binary_ply(true), p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kPlyCoords);
}

// Vertices of fixed size (no list property), read through the strided fast path; properties of
// sizes 1, 4 and 8 before and between x, y, z.
std::string fixed_size_ply(bool big, const std::vector<double>& xyz) {
  Bytes b(big);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    b.put<std::uint8_t>(1).put<float>(static_cast<float>(xyz[i])).put<double>(xyz[i + 1]);
    b.put<float>(static_cast<float>(xyz[i + 2])).put<std::uint8_t>(2);
  }
  return std::string("ply\r\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
         " 1.0\r\nelement vertex " + std::to_string(xyz.size() / 3) +
         "\r\nproperty uint8 r\r\nproperty float x\r\nproperty float64 y\r\n"
         "property float32 z\r\nproperty uchar g\r\nend_header\r\n" +
         b.str();
}

TEST_F(IoPly, BinaryFixedSizeVertices) {
  for (bool big : {false, true}) {
    const std::vector<double> want = {0, 0, 0, 1, 0, 0, 0, 1.0 / 3.0, 0, 0, 0, 1};
    PointSet p;
    Status st = read("fixed.ply", fixed_size_ply(big, want), p);
    ASSERT_TRUE(st) << st.message();
    EXPECT_EQ(p.coords, want) << (big ? "big endian" : "little endian");
  }
}

TEST_F(IoPly, BinaryFixedSizeNaNNamesVertex) {
  for (bool big : {false, true}) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PointSet p;
    ReadOptions o;
    o.check = false;  // the reader itself must catch it, not check_points()
    Status st =
        read("fixed_nan.ply", fixed_size_ply(big, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, nan}), p, o);
    EXPECT_EQ(st.code(), StatusCode::NonFinite);
    EXPECT_TRUE(Contains(st.message(), "fixed_nan.ply: PLY vertex 3: non-finite coordinate (nan)"));
  }
}

TEST_F(IoPly, BinaryNaNNamesVertex) {
  for (bool big : {false, true}) {
    PointSet p;
    Status st = read("nan.ply", binary_ply(big, std::numeric_limits<float>::quiet_NaN(), true), p);
    EXPECT_EQ(st.code(), StatusCode::NonFinite);
    EXPECT_TRUE(Contains(st.message(), "nan.ply: PLY vertex 2: non-finite coordinate (nan)"));
    st = read("inf.ply", binary_ply(big, -std::numeric_limits<float>::infinity(), true), p);
    EXPECT_EQ(st.code(), StatusCode::NonFinite);
    EXPECT_TRUE(Contains(st.message(), "PLY vertex 2: non-finite coordinate (-inf)"));
  }
}

TEST_F(IoPly, BinaryTruncated) {
  const std::string full = binary_ply(false);
  PointSet p;
  // Cut inside the third vertex: the faces are never needed, the vertices are.
  Status st = read("cut.ply", full.substr(0, full.size() - 60), p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "cut.ply: PLY data ends inside element 'vertex'"));
  // Faces after the vertices are not read, so a cut there does not matter.
  st = read("cutfaces.ply", full.substr(0, full.size() - 5), p);
  EXPECT_TRUE(st) << st.message();
}

TEST_F(IoPly, BinaryNegativeListLength) {
  Bytes b(false);
  b.put<std::int8_t>(-1);  // list length of the single "tag" instance
  for (int i = 0; i < 4; ++i) b.put<float>(0.0f).put<float>(static_cast<float>(i));
  PointSet p;
  Status st = read("neg.ply",
                   "ply\nformat binary_little_endian 1.0\nelement tag 1\n"
                   "property list char int ids\nelement vertex 4\nproperty float x\n"
                   "property float y\nend_header\n" +
                       b.str(),
                   p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "neg.ply: PLY list with a negative length in element 'tag'"));
}

TEST_F(IoPly, AsciiWithListsAndFaces) {
  PointSet p;
  Status st = read_points(kDataDir + "tetra_faces_ascii.ply", {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoPly, AsciiErrorsNameLine) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  PointSet p;
  Status st = read("a.ply", head + "0 0 0\n1 0 0\n0 nan 0\n0 0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "a.ply:10: non-finite coordinate 'nan' (vertex 2)"));
  st = read("b.ply", head + "0 0 0\n1 0 0\n0 1 0\n0 0 1e\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "b.ply:11: malformed number '1e'"));
  st = read("c.ply", head + "0 0 0\n1 0 0\n0 1 0\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "PLY data ends inside element 'vertex' (vertex 3 of 4)"));
}

TEST_F(IoPly, TwoDimensionalWithoutZ) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\n"
      "property int y\nend_header\n0 0\n1 0\n0 1\n";
  PointSet p;
  ASSERT_TRUE(read("flat.ply", text, p));
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1}));
  ReadOptions o;
  o.dim = 3;
  Status st = read("flat.ply", text, p, o);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "flat.ply: PLY vertex element has no z property"));
}

TEST_F(IoPly, ForcedDim2DropsZ) {
  PointSet p;
  ReadOptions o;
  o.dim = 2;
  o.check = false;
  Status st = read("le.ply", binary_ply(false), p, o);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1.5, 0, 0, -2.25, 0, 0}));
}

TEST_F(IoPly, HeaderErrors) {
  PointSet p;
  Status st = read("x.ply", "plx\nformat ascii 1.0\nend_header\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "x.ply:1: not a PLY file"));
  st = read("f.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", p);
  EXPECT_TRUE(Contains(st.message(), "f.ply:2: unknown PLY format 'binary_middle_endian'"));
  st =
      read("t.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n1\n", p);
  EXPECT_TRUE(Contains(st.message(), "t.ply:4: unknown PLY type 'real'"));
  st = read("e.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", p);
  EXPECT_TRUE(Contains(st.message(), "e.ply: PLY header has no 'end_header' line"));
  st = read("n.ply",
            "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\n"
            "end_header\n3 0 1 2\n",
            p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "n.ply: PLY file has no 'vertex' element"));
  st = read("y.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
            "property float z\nend_header\n1 2\n",
            p);
  EXPECT_TRUE(Contains(st.message(), "y.ply: PLY vertex element has no x and y properties"));
  st = read("c.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n"
            "end_header\n1 2\n",
            p);
  EXPECT_TRUE(Contains(st.message(), "c.ply:4: PLY list count type must be an integer type"));
}

TEST_F(IoPly, HugeCountDoesNotAllocate) {
  PointSet p;
  Status st = read("huge.ply",
                   "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\n"
                   "property double x\nproperty double y\nend_header\n" +
                       std::string(32, '\0'),
                   p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "(vertex 2 of 4000000000000)"));
}

// ---- OFF / OBJ -------------------------------------------------------------------------------

TEST_F(IoOff, CommentsAndFaces) {
  PointSet p;
  Status st = read_points(kDataDir + "tetra_comments.off", {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoOff, NoffAndCoffHeaders) {
  PointSet p;
  Status st = read_points(kDataDir + "noff_normals.off", {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
  st = read("c.off",
            "COFF\n4 0 0\n0 0 0 255 0 0 255\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n"
            "0 0 1 1 1 1 1\n",
            p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoOff, CountsOnKeywordLineAndForcedDim2) {
  PointSet p;
  ReadOptions o;
  o.dim = 2;
  Status st = read("k.off", "OFF 4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", p, o);
  EXPECT_EQ(st.code(), StatusCode::Duplicate);  // (0,0) twice once z is dropped
  o.check = false;
  st = read("k.off", "OFF 4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", p, o);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 2);
  EXPECT_EQ(p.coords, kTetraCoords2);
}

TEST_F(IoOff, Errors) {
  PointSet p;
  Status st = read("short.off", "OFF\n5 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "short.off:6: OFF file ends after 4 of 5 vertex lines"));
  st = read("kw.off", "# c\nOBJ\n4 0 0\n", p);
  EXPECT_TRUE(Contains(st.message(), "kw.off:2: not an OFF file"));
  st = read("two.off", "OFF\n4 0 0\n0 0 0\n1 0\n", p);
  EXPECT_TRUE(Contains(st.message(), "two.off:4: expected 3 coordinates, found 2"));
  st = read("num.off", "OFF\n4 0 0\n0 0 0\n1 0 zz\n", p);
  EXPECT_TRUE(Contains(st.message(), "num.off:4: malformed number 'zz'"));
  st = read("cnt.off", "OFF\nfour 0 0\n", p);
  EXPECT_TRUE(Contains(st.message(), "cnt.off:2: malformed OFF vertex count 'four'"));
  st = read("nan.off", "OFF\n4 0 0\n0 0 0\n1 0 inf\n", p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "nan.off:4: non-finite coordinate 'inf'"));
}

TEST_F(IoObj, VerticesOnly) {
  PointSet p;
  Status st = read_points(kDataDir + "tetra_with_normals.obj", {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.dim, 3);
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoObj, Errors) {
  PointSet p;
  Status st = read("a.obj", "v 0 0 0\nvn 1 2\nv 1 0\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "a.obj:3: expected 3 coordinates after 'v', found 2"));
  st = read("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\n", p);
  EXPECT_EQ(st.code(), StatusCode::NonFinite);
  EXPECT_TRUE(Contains(st.message(), "b.obj:4: non-finite coordinate 'nan'"));
  st = read("c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1.0.0\n", p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "c.obj:4: malformed number '1.0.0'"));
}

// ---- format selection ------------------------------------------------------------------------

TEST_F(IoFormat, ExtensionIsCaseInsensitive) {
  PointSet p;
  Status st = read("UPPER.OFF", "OFF\n4 0 0\n" + kTetra, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
  st = read("UPPER.PLY", binary_ply(true), p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kPlyCoords);
}

TEST_F(IoFormat, OptionOverridesExtension) {
  PointSet p;
  // Read as text, this OFF file fails: its keyword line is no header of the data.
  Status st = read("mesh.txt", "OFF\n4 1\n" + kTetra, p);
  EXPECT_EQ(st.code(), StatusCode::ParseError);
  EXPECT_TRUE(Contains(st.message(), "mesh.txt:1: this first line looks like a header, but it has 1 field"))
      << st.message();
  ReadOptions o;
  o.format = PointFormat::Off;
  st = read("mesh.txt", "OFF\n4 1\n" + kTetra, p, o);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
  o.format = PointFormat::Text;
  st = read("pts.obj", kTetra, p, o);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
}

TEST_F(IoFormat, DotInDirectoryNameIsNoExtension) {
  fs::create_directory(dir_ / "d.ply");
  PointSet p;
  const std::string path = write("d.ply/points", kTetra);
  Status st = read_points(path, {}, p);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, kTetraCoords);
}

// ---- duplicates and checks -------------------------------------------------------------------

TEST_F(IoDuplicates, ErrorListsIndexPairs) {
  // Points 0 and 4 are identical, 1 and 5 and 6.
  PointSet p;
  Status st = read("dup.xy", "0 0\n1 0\n0 1\n1 1\n0 0\n1 0\n1 0\n", p);
  EXPECT_EQ(st.code(), StatusCode::Duplicate);
  EXPECT_TRUE(Contains(st.message(),
                       "dup.xy: points 0 and 4 are identical; 1 and 5; 1 and 6 "
                       "(3 duplicate points in all; use --merge-duplicates"));
}

TEST_F(IoDuplicates, ErrorListsAtMostFivePairs) {
  std::string text;
  for (int copy = 0; copy < 2; ++copy)
    for (int i = 0; i < 8; ++i) text += std::to_string(i) + " " + std::to_string(i * i) + "\n";
  PointSet p;
  Status st = read("many.xy", text, p);
  EXPECT_EQ(st.code(), StatusCode::Duplicate);
  EXPECT_TRUE(Contains(st.message(),
                       "points 0 and 8 are identical; 1 and 9; 2 and 10; 3 and 11; "
                       "4 and 12; ... (8 duplicate points in all"));
}

TEST_F(IoDuplicates, MergeKeepsFirstOccurrence) {
  PointSet p;
  ReadOptions o;
  o.merge_duplicates = true;
  ReadReport report;
  Status st = read("dup.xy", "0 0\n1 0\n0 0\n0 1\n1 0\n1 1\n0 0\n", p, o, &report);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(p.coords, (std::vector<double>{0, 0, 1, 0, 0, 1, 1, 1}));
  EXPECT_EQ(report.points_read, 7u);
  EXPECT_EQ(report.merged_duplicates, 3u);
  EXPECT_EQ(report.original_index, (std::vector<std::size_t>{0, 1, 3, 5}));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_TRUE(Contains(report.warnings[0], "dup.xy: merged 3 duplicate points"));
}

TEST_F(IoDuplicates, MergeWithoutDuplicatesIsIdentity) {
  PointSet p;
  ReadOptions o;
  o.merge_duplicates = true;
  ReadReport report;
  ASSERT_TRUE(read("t.xyz", kTetra, p, o, &report));
  EXPECT_EQ(report.merged_duplicates, 0u);
  EXPECT_EQ(report.original_index, (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_TRUE(report.warnings.empty());
}

TEST_F(IoDuplicates, MergeThenTooFew) {
  PointSet p;
  ReadOptions o;
  o.merge_duplicates = true;
  Status st = read("t.xy", "1 2\n1 2\n3 4\n1 2\n", p, o);
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_TRUE(Contains(st.message(), "t.xy: only 2 points; at least 3"));
}

TEST_F(IoDuplicates, NegativeZeroEqualsZero) {
  PointSet p;
  Status st = read("z.xy", "0 0\n1 0\n-0 0\n0 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::Duplicate);
  EXPECT_TRUE(Contains(st.message(), "points 0 and 2 are identical"));
}

TEST_F(IoChecks, TooFewCollinearCoplanar) {
  PointSet p;
  Status st = read("two.xy", "0 0\n1 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_TRUE(Contains(st.message(), "two.xy: only 2 points; at least 3 are needed in 2D"));
  st = read("three.xyz", "0 0 0\n1 0 0\n0 1 0\n", p);
  EXPECT_EQ(st.code(), StatusCode::TooFewPoints);
  EXPECT_TRUE(Contains(st.message(), "only 3 points; at least 4 are needed in 3D"));
  st = read("line.xy", "0 0\n1 1\n2 2\n-5 -5\n0.5 0.5\n", p);
  EXPECT_EQ(st.code(), StatusCode::Collinear);
  EXPECT_TRUE(Contains(st.message(), "line.xy: all 5 points are collinear"));
  st = read("plane.xyz", "0 0 1\n1 0 1\n0 1 1\n5 7 1\n", p);
  EXPECT_EQ(st.code(), StatusCode::Coplanar);
  EXPECT_TRUE(Contains(st.message(), "plane.xyz: all 4 points are coplanar: every z is the same"));
  st = read("line.xyz", "0 0 0\n1 1 1\n2 2 2\n3 3 3\n", p);
  EXPECT_EQ(st.code(), StatusCode::Coplanar);
  EXPECT_TRUE(Contains(st.message(), "line.xyz: all 4 points are collinear (3D)"));
}

TEST_F(IoChecks, CheckFalseSkipsPointChecks) {
  PointSet p;
  ReadOptions o;
  o.check = false;
  ASSERT_TRUE(read("two.xy", "0 0\n0 0\n", p, o));
  EXPECT_EQ(p.size(), 2u);
  // Parse-level defects are still errors.
  EXPECT_EQ(read("nan.xy", "0 nan\n", p, o).code(), StatusCode::NonFinite);
}

// ---- robustness ------------------------------------------------------------------------------

TEST(IoRobustness, CorruptedInputsGiveAStatus) {
  // Byte flips, insertions and truncations of valid files of every format: the reader must return
  // a status (never crash, hang or read out of bounds: run under ASan in CI), and an Ok result
  // must be a well-formed point set.
  const std::vector<std::pair<std::string, PointFormat>> seeds = {
      {"x,y,z\n0,0,0\n1,0,0 # c\n0,1,0\n0,0,1\n", PointFormat::Text},
      {"OFF\n4 1 0\n" + kTetra + "3 0 1 2\n", PointFormat::Off},
      {"v 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", PointFormat::Obj},
      {"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
       "property float z\nproperty list uchar int l\nelement face 1\n"
       "property list uchar int v\nend_header\n0 0 0 0\n1 0 0 1 5\n0 1 0 0\n0 0 1 0\n3 0 1 2\n",
       PointFormat::Ply},
      {binary_ply(false), PointFormat::Ply},
      {binary_ply(true), PointFormat::Ply}};
  const std::uint64_t seed = 4242;
  std::mt19937_64 rng(seed);
  const char alphabet[] = "0123456789 \n\r\t,;#.-+eEnaif\xff\x00vOFply";
  for (int round = 0; round < 3000; ++round) {
    const auto& [text, format] = seeds[static_cast<std::size_t>(round) % seeds.size()];
    std::string data = text;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits && !data.empty(); ++k) {
      const std::size_t at = rng() % data.size();
      const char c = alphabet[rng() % (sizeof alphabet - 1)];
      switch (rng() % 4) {
        case 0:
          data[at] = c;
          break;
        case 1:
          data.insert(at, 1, c);
          break;
        case 2:
          data.erase(at, 1 + rng() % 8);
          break;
        default:
          data.resize(at);
          break;
      }
    }
    PointSet p;
    ReadOptions o;
    o.check = (round % 2) == 0;
    o.dim = (round % 3) == 0 ? 2 : 0;
    const Status st = read_points_from_buffer(data, "fuzz", format, o, p);
    if (st) {
      ASSERT_TRUE(p.dim == 2 || p.dim == 3) << "seed " << seed << " round " << round;
      ASSERT_EQ(p.coords.size() % static_cast<std::size_t>(p.dim), 0u) << "round " << round;
      for (double v : p.coords) ASSERT_TRUE(std::isfinite(v)) << "round " << round;
    } else {
      ASSERT_FALSE(st.message().empty());
      ASSERT_EQ(st.message().find('\n'), std::string::npos) << st.message();
      ASSERT_EQ(st.message().rfind("fuzz", 0), 0u) << st.message();
    }
  }
}

// ---- round trip ------------------------------------------------------------------------------

TEST_F(IoRoundTrip, PercentDot17gIsBitIdentical) {
  const std::uint64_t seed = 20240611;
  std::mt19937_64 rng(seed);
  for (int dim : {2, 3}) {
    std::vector<double> values;
    std::string text;
    char buf[64];
    const int n = 20000;
    for (int i = 0; i < n * dim; ++i) {
      double v = 0.0;
      if (i % 3 == 0) {
        // Any finite bit pattern: subnormals, huge and tiny exponents, negative zero.
        std::uint64_t bits = rng();
        std::memcpy(&v, &bits, sizeof v);
        if (!std::isfinite(v)) v = -0.0;
      } else {
        v = std::uniform_real_distribution<double>(-1e3, 1e3)(rng);
      }
      values.push_back(v);
      std::snprintf(buf, sizeof buf, "%.17g", v);
      text += buf;
      text += ((i + 1) % dim == 0) ? "\n" : (i % 2 == 0 ? " " : ",");
    }
    PointSet p;
    ReadOptions o;
    o.check = false;
    Status st = read("rt.txt", text, p, o);
    ASSERT_TRUE(st) << st.message() << " seed " << seed;
    ASSERT_EQ(p.dim, dim);
    ASSERT_EQ(p.coords.size(), values.size());
    EXPECT_EQ(std::memcmp(p.coords.data(), values.data(), values.size() * sizeof(double)), 0)
        << "seed " << seed;
  }
}

}  // namespace
}  // namespace constrict

namespace constrict {
namespace {

// A polygon's .idx is one index per line in polygon order; a large one is formatted in blocks on
// all cores (write_polygon.cpp) and must be the same text, across block ends too.
TEST_F(IoRoundTrip, LargeIndexPolygonIsOneIndexPerLine) {
  for (const std::size_t n : {std::size_t{5}, std::size_t{300001}}) {
    PointSet p;
    p.dim = 2;
    p.coords.assign(2 * n, 0.0);
    std::vector<int> ids(n);
    for (std::size_t k = 0; k < n; ++k) ids[k] = static_cast<int>((k * 7919) % n);  // (a permutation: n prime to 7919)
    std::string want;
    for (int v : ids) want += std::to_string(v) + "\n";
    const std::string path = (dir_ / "large.idx").string();
    ASSERT_TRUE(write_polygon2(path, p, ids, PolygonFormat::Idx).is_ok());
    std::ifstream f(path, std::ios::binary);
    const std::string got((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(got.size(), want.size()) << n;
    EXPECT_TRUE(got == want) << n << " indices";
  }
}

}  // namespace
// SVG titles carry the input's file name: a control character or a byte that is not UTF-8 made
// the picture malformed XML (an adversarial sweep of the command line).
TEST(XmlEscape, KeepsTheDocumentWellFormed) {
  using detail::xml_escape;
  EXPECT_EQ(xml_escape("a<b>&\"c"), "a&lt;b&gt;&amp;&quot;c");
  EXPECT_EQ(xml_escape("H\xc3\xb6he \xe2\x82\xac \xf0\x9f\x99\x82"),
            "H\xc3\xb6he \xe2\x82\xac \xf0\x9f\x99\x82");  // UTF-8 kept
  const std::string r = "\xef\xbf\xbd";                    // U+FFFD
  EXPECT_EQ(xml_escape("b\xff.xy"), "b" + r + ".xy");
  EXPECT_EQ(xml_escape(std::string("x\x01y\x00z", 5)), "x" + r + "y" + r + "z");
  EXPECT_EQ(xml_escape("\xc3"), r);                  // cut short
  EXPECT_EQ(xml_escape("\xc0\xaf"), r + r);          // overlong
  EXPECT_EQ(xml_escape("\xed\xa0\x80"), r + r + r);  // a surrogate
  EXPECT_EQ(xml_escape("tab\tnl\n"), "tab\tnl\n");
}

}  // namespace constrict
