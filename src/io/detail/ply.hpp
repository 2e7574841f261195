// SPDX-License-Identifier: GPL-3.0-or-later
// The one PLY reader (ascii, binary_little_endian, binary_big_endian), used by read_points() and
// read_mesh(). The header is parsed once into plain element/property tables; the body is then
// read element by element through PlyBody, which keeps only the properties a caller asks for.
//
// Contract (PLY spec, "PLY - Polygon File Format", Greg Turk 1994):
// - A count in the header is never trusted for a loop or an allocation: before an element is
//   read, check_room() refuses a count that the rest of the file cannot hold (binary: count x
//   smallest record size > bytes left; ascii: count x properties > bytes left, each value being at
//   least one character; an element without properties holds nothing, so its count may not exceed
//   the bytes left either). Reading is then bounded by the file size.
// - List lengths and kept list items are integers: a list length type must be an integer type
//   (header), and kept items (face indices) must be integral, in range, whatever their type.
// - Errors are one line: "file:LINE: ..." where a line exists (header, ascii body), else
//   "file: PLY ELEMENT I: ..." (binary body).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/status.hpp"
#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  ///< item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  bool has_list = false;
  std::size_t fixed_size = 0;   ///< bytes of the scalar properties (the whole record when !has_list)
  std::size_t min_size = 0;     ///< smallest binary record: scalars plus every list's length field
  std::size_t header_line = 0;  ///< line of the 'element' line

  /// Index of the first property called @p n, or -1.
  int find(std::string_view n) const noexcept;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  ///< byte offset of the first byte after "end_header\n"
  std::size_t body_line = 0;    ///< 1-based line number of the body's first line (ascii)
};

std::size_t ply_size(PlyType t) noexcept;
bool ply_is_integer(PlyType t) noexcept;

/// Parses the header. @return Ok or ParseError ("file:LINE: ...", or "file: ..." when missing).
Status parse_ply_header(std::string_view data, const std::string& name, PlyHeader& h);

/// What to keep of each record of one element.
struct PlyRecordSpec {
  /// slot[k] >= 0: the value of scalar property k goes to values[slot[k]]; -1: skipped.
  std::vector<int> slot;
  /// values[0, n_finite) are coordinates: a non-finite one is a NonFinite error.
  int n_finite = 0;
  /// The one list property whose items are kept (as integers, e.g. face indices), or -1.
  int list = -1;
};

/// Reads the body of a PLY file, element after element, in header order.
class PlyBody {
 public:
  PlyBody(std::string_view data, const std::string& name, const PlyHeader& header);

  /// Refuses an element whose count the rest of the file cannot hold (see the contract above).
  /// Call before reading or skipping @p el. @return Ok or ParseError naming the header line.
  Status check_room(const PlyElement& el) const;

  /// Skips every record of @p el (still checking lists and, for ascii, the tokens' presence).
  Status skip(const PlyElement& el);

  /// Reads every record of @p el: spec.slot's values appended to @p table, n_slots per record
  /// (row-major). Binary records of fixed size are read with a stride.
  /// @pre spec.list == -1, check_room(el) passed
  Status read_table(const PlyElement& el, const PlyRecordSpec& spec, int n_slots,
                    std::vector<double>& table);

  /// Reads record @p i of @p el: scalars to values[slot], the kept list to @p list.
  Status read_record(const PlyElement& el, std::uint64_t i, const PlyRecordSpec& spec,
                     double* values, std::vector<std::int64_t>* list);

  /// After @p last, the file's last element: ParseError when data is left that no element
  /// announced (a count smaller than the data; its records would be lost without a word).
  /// Binary files may end with a few padding bytes, fewer than one record of @p last.
  Status check_end(const PlyElement& last);

  bool ascii() const noexcept { return ascii_; }
  /// Line of the last token read (ascii); 0 for binary files.
  std::size_t line() const noexcept { return line_; }

 private:
  // The next whitespace-separated token (ascii), counting lines; false at the end of the data.
  // Defined here so that it inlines into the per-value loops.
  bool next_token(const char*& b, const char*& e) noexcept {
    while (p_ < end_ && (is_space(*p_) || *p_ == '\n')) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    if (p_ == end_) return false;
    b = p_;
    while (p_ < end_ && !is_space(*p_) && *p_ != '\n') ++p_;
    e = p_;
    return true;
  }
  std::uint64_t bytes_left() const noexcept { return static_cast<std::uint64_t>(end_ - p_); }
  Status truncated(const PlyElement& el, std::uint64_t i) const;
  Status read_record_ascii(const PlyElement& el, std::uint64_t i, const PlyRecordSpec& spec,
                           double* values, std::vector<std::int64_t>* list);
  Status read_record_binary(const PlyElement& el, std::uint64_t i, const PlyRecordSpec& spec,
                            double* values, std::vector<std::int64_t>* list);
  Status read_fixed_binary(const PlyElement& el, const PlyRecordSpec& spec, int n_slots,
                           std::vector<double>& table);

  const std::string& name_;
  const char* p_;
  const char* end_;
  bool ascii_;
  bool swap_;
  std::size_t line_ = 0;
};

}  // namespace detail
}  // namespace constrict
