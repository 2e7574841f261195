// SPDX-License-Identifier: GPL-3.0-or-later
// Point input: text columns (XYZ/CSV/TXT), PLY (ascii and binary), OFF and OBJ vertices.
// The whole file is read into memory once and scanned with raw pointers; numbers are parsed with
// fast_float (exact round-to-nearest, locale independent, several times faster than strtod or
// iostreams). Every defect is reported as a Status naming the file and the 1-based line (or the
// 0-based vertex index for binary PLY, which has no lines).
#include <fast_float/fast_float.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define CONSTRICT_HAVE_MMAP 1
#else
#define CONSTRICT_HAVE_MMAP 0
#endif

#include "constrict/io.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace {

constexpr std::size_t kEmptyField = static_cast<std::size_t>(-1);
constexpr std::size_t kMaxQuoted = 40;  // longest token quoted verbatim in a message

struct Span {
  const char* b = nullptr;
  const char* e = nullptr;
};

// Field separators inside a line. '\r' is whitespace, which makes CRLF files work unchanged.
inline bool is_space(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
inline bool is_delimiter(char c) noexcept { return c == ',' || c == ';'; }

// A token as it appears in a message: quoted, shortened, control bytes escaped (one-line messages).
std::string quote(const char* b, const char* e) {
  std::string s = "'";
  const char* stop = (static_cast<std::size_t>(e - b) > kMaxQuoted) ? b + kMaxQuoted : e;
  for (const char* p = b; p != stop; ++p) {
    const auto u = static_cast<unsigned char>(*p);
    if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(u));
      s += hex;
    } else {
      s += *p;
    }
  }
  if (stop != e) s += "...";
  s += "'";
  return s;
}

Status error_at(StatusCode code, const std::string& name, std::size_t line,
                const std::string& what) {
  return {code, name + ":" + std::to_string(line) + ": " + what};
}

Status error_in(StatusCode code, const std::string& name, const std::string& what) {
  return {code, name + ": " + what};
}

std::string plural(std::uint64_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

// Whole token as a double. fast_float does not take a leading '+', so it is skipped here.
inline bool parse_double(const char* b, const char* e, double& v) noexcept {
  if (e - b > 1 && *b == '+' && b[1] != '+' && b[1] != '-') ++b;
  const auto r = fast_float::from_chars(b, e, v);
  return r.ec == std::errc() && r.ptr == e;
}

inline bool parse_count(const char* b, const char* e, std::uint64_t& v) noexcept {
  const auto r = std::from_chars(b, e, v);
  return r.ec == std::errc() && r.ptr == e;
}

// Parses one coordinate token of a line-based format; the error names file and line.
inline Status parse_coordinate(const Span& tok, const std::string& name, std::size_t line,
                               double& v) {
  if (!parse_double(tok.b, tok.e, v))
    return error_at(StatusCode::ParseError, name, line, "malformed number " + quote(tok.b, tok.e));
  if (!std::isfinite(v))
    return error_at(StatusCode::NonFinite, name, line,
                    "non-finite coordinate " + quote(tok.b, tok.e));
  return Status::ok();
}

// Iterates over the lines of a buffer: [b, e) excludes the '\n' and, if asked, a '#' comment.
class LineReader {
 public:
  explicit LineReader(std::string_view data) : p_(data.data()), end_(data.data() + data.size()) {
    // A UTF-8 byte order mark (written by some spreadsheet exports) is not part of the data.
    if (data.size() >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;
  }

  bool next(const char*& b, const char*& e, bool strip_comment) noexcept {
    if (p_ >= end_) return false;
    ++line_;
    b = p_;
    const void* nl = std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_));
    e = nl != nullptr ? static_cast<const char*>(nl) : end_;
    p_ = e < end_ ? e + 1 : end_;
    if (strip_comment) {
      const void* hash = std::memchr(b, '#', static_cast<std::size_t>(e - b));
      if (hash != nullptr) e = static_cast<const char*>(hash);
    }
    return true;
  }

  std::size_t line() const noexcept { return line_; }   ///< 1-based number of the last line read
  const char* position() const noexcept { return p_; }  ///< start of the next line

 private:
  const char* p_;
  const char* end_;
  std::size_t line_ = 0;
};

// Splits a line into fields separated by whitespace, ',' or ';'. Whitespace around a ',' or ';'
// is allowed; two of them in a row, or one at the start or end of a line, make an empty field,
// which is an error (returns kEmptyField). Otherwise returns the field count; on_field(i, span)
// is called for every field.
template <class OnField>
std::size_t split_fields(const char* p, const char* e, OnField&& on_field) {
  std::size_t count = 0;
  bool need_field = false;  // a ',' or ';' was just consumed
  for (;;) {
    while (p < e && is_space(*p)) ++p;
    if (p == e) return need_field ? kEmptyField : count;
    if (is_delimiter(*p)) {
      if (need_field || count == 0) return kEmptyField;
      need_field = true;
      ++p;
      continue;
    }
    const char* b = p;
    while (p < e && !is_space(*p) && !is_delimiter(*p)) ++p;
    on_field(count, Span{b, p});
    ++count;
    need_field = false;
  }
}

Status empty_field_error(const std::string& name, std::size_t line) {
  return error_at(StatusCode::ParseError, name, line,
                  "empty field (a ',' or ';' at the start or end of the line, or two in a row)");
}

// The optional header line: no field of it is a number ("x y z", "X;Y;Z", "east north height").
bool is_header_line(const char* b, const char* e) {
  bool any_number = false;
  split_fields(b, e, [&any_number](std::size_t, const Span& f) {
    double v = 0.0;
    if (parse_double(f.b, f.e, v)) any_number = true;
  });
  return !any_number;
}

// One line split into fields, with the first `want` (at most 3) fields parsed as numbers in the
// same pass: fast_float scans the digits, so the characters of a number are read only once.
struct ParsedLine {
  std::size_t count = 0;     // number of fields, or kEmptyField
  int first_malformed = -1;  // first parsed field that is not a whole number, -1 if none
  Span field[3];
  double value[3] = {0.0, 0.0, 0.0};
  const char* content_end = nullptr;  // where the fields end: '#', '\n' or the end of the data
};

// A character that ends a field.
inline bool ends_field(char c) noexcept {
  return is_space(c) || is_delimiter(c) || c == '\n' || c == '#';
}

inline const char* line_end(const char* p, const char* e) noexcept {
  const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(e - p));
  return nl != nullptr ? static_cast<const char*>(nl) : e;
}

// Parses the line that starts at p and ends at the next '\n' (or e); '#' starts a comment that
// runs to the end of the line. Scanning the line once, without first looking for its end, is
// measurably faster on large files. Returns the position of the '\n' (or e).
inline const char* parse_line(const char* p, const char* e, int want, ParsedLine& out) {
  std::size_t count = 0;
  bool need_field = false;  // a ',' or ';' was just consumed
  out.first_malformed = -1;
  for (;;) {
    while (p < e && is_space(*p)) ++p;
    if (p == e || *p == '\n' || *p == '#') {
      out.content_end = p;
      out.count = need_field ? kEmptyField : count;
      return (p < e && *p == '#') ? line_end(p, e) : p;
    }
    if (is_delimiter(*p)) {
      if (need_field || count == 0) {
        out.content_end = p;
        out.count = kEmptyField;
        return line_end(p, e);
      }
      need_field = true;
      ++p;
      continue;
    }
    const char* b = p;
    if (count < static_cast<std::size_t>(want)) {
      const char* q = p;
      if (e - q > 1 && *q == '+' && q[1] != '+' && q[1] != '-') ++q;  // fast_float rejects '+'
      double v = 0.0;
      const auto r = fast_float::from_chars(q, e, v);
      p = r.ptr;
      if (r.ec != std::errc() || (p < e && !ends_field(*p))) {
        while (p < e && !ends_field(*p)) ++p;
        if (out.first_malformed < 0) out.first_malformed = static_cast<int>(count);
      }
      out.value[count] = v;
      out.field[count] = {b, p};
    } else {
      while (p < e && !ends_field(*p)) ++p;
    }
    ++count;
    need_field = false;
  }
}

// The first `dim` values of a parsed line, checked in field order (malformed, then non-finite).
inline Status check_values(const ParsedLine& f, int dim, const std::string& name,
                           std::size_t line) {
  for (int k = 0; k < dim; ++k) {
    if (k == f.first_malformed)
      return error_at(StatusCode::ParseError, name, line,
                      "malformed number " + quote(f.field[k].b, f.field[k].e));
    if (!std::isfinite(f.value[k]))
      return error_at(StatusCode::NonFinite, name, line,
                      "non-finite coordinate " + quote(f.field[k].b, f.field[k].e));
  }
  return Status::ok();
}

// ---- text columns ----------------------------------------------------------------------------

Status parse_text(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  const char* p = data.data();
  const char* const end = data.data() + data.size();
  // A UTF-8 byte order mark (written by some spreadsheet exports) is not part of the data.
  if (data.size() >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3;
  int dim = forced_dim;
  std::size_t expected_fields = 0;  // set by the first data line
  bool seen_content = false;
  ParsedLine f;
  std::vector<double>& coords = out.coords;
  coords.reserve(data.size() / 16);

  for (std::size_t line = 1; p < end; ++line) {
    const char* const begin = p;
    const char* const next = parse_line(p, end, dim == 0 ? 3 : dim, f);
    p = next < end ? next + 1 : end;
    const std::size_t count = f.count;
    if (count == 0) continue;  // blank or comment-only line
    if (count == kEmptyField) return empty_field_error(name, line);
    if (!seen_content) {
      seen_content = true;
      if (f.first_malformed >= 0 && is_header_line(begin, f.content_end)) continue;
    }
    if (expected_fields == 0) {
      if (dim == 0) {
        if (count != 2 && count != 3)
          return error_at(StatusCode::ParseError, name, line,
                          "expected 2 or 3 fields (x y [z]), found " + std::to_string(count));
        dim = static_cast<int>(count);
      } else if (count < static_cast<std::size_t>(dim)) {
        return error_at(StatusCode::ParseError, name, line,
                        "expected at least " + std::to_string(dim) + " fields for dimension " +
                            std::to_string(dim) + ", found " + std::to_string(count));
      }
      expected_fields = count;
    } else if (count != expected_fields) {
      return error_at(StatusCode::ParseError, name, line,
                      "expected " + std::to_string(expected_fields) + " fields, found " +
                          std::to_string(count));
    }
    Status st = check_values(f, dim, name, line);
    if (!st) return st;
    coords.insert(coords.end(), f.value, f.value + dim);
  }
  out.dim = dim == 0 ? 2 : dim;
  return Status::ok();
}

// ---- OBJ -------------------------------------------------------------------------------------

Status parse_obj(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  LineReader lines(data);
  const int dim = forced_dim == 0 ? 3 : forced_dim;
  ParsedLine f;
  const char* b = nullptr;
  const char* e = nullptr;
  while (lines.next(b, e, true)) {
    while (b < e && is_space(*b)) ++b;
    // Only "v x y z [w]" lines are points; vt, vn, f, o, g, usemtl ... are ignored.
    if (e - b < 2 || b[0] != 'v' || !is_space(b[1])) continue;
    parse_line(b + 1, e, dim, f);
    const std::size_t line = lines.line();
    if (f.count == kEmptyField) return empty_field_error(name, line);
    if (f.count < 3)
      return error_at(StatusCode::ParseError, name, line,
                      "expected 3 coordinates after 'v', found " + std::to_string(f.count));
    Status st = check_values(f, dim, name, line);
    if (!st) return st;
    out.coords.insert(out.coords.end(), f.value, f.value + dim);
  }
  out.dim = dim;
  return Status::ok();
}

// ---- OFF -------------------------------------------------------------------------------------

// OFF, COFF, NOFF, CNOFF, STOFF, STCNOFF...: the optional prefixes only add per-vertex fields
// after x y z, which are skipped. 4OFF / nOFF (other dimensions) are not supported.
bool is_off_keyword(std::string_view w) {
  if (w.size() < 3 || w.substr(w.size() - 3) != "OFF") return false;
  w.remove_suffix(3);
  if (w.substr(0, 2) == "ST") w.remove_prefix(2);
  if (!w.empty() && w.front() == 'C') w.remove_prefix(1);
  if (!w.empty() && w.front() == 'N') w.remove_prefix(1);
  return w.empty();
}

Status parse_off(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  LineReader lines(data);
  const int dim = forced_dim == 0 ? 3 : forced_dim;
  std::vector<Span> fields;
  const auto collect = [&fields](std::size_t, const Span& f) { fields.push_back(f); };
  const char* b = nullptr;
  const char* e = nullptr;

  // Keyword line, possibly followed by the counts on the same line.
  std::size_t count = 0;
  do {
    if (!lines.next(b, e, true)) return Status::ok();  // nothing but comments: no points
    fields.clear();
    count = split_fields(b, e, collect);
  } while (count == 0);
  if (count == kEmptyField) return empty_field_error(name, lines.line());
  const std::string_view keyword(fields[0].b, static_cast<std::size_t>(fields[0].e - fields[0].b));
  if (!is_off_keyword(keyword))
    return error_at(StatusCode::ParseError, name, lines.line(),
                    "not an OFF file: expected 'OFF' (or COFF, NOFF...), found " +
                        quote(fields[0].b, fields[0].e));
  fields.erase(fields.begin());

  if (fields.empty()) {
    do {
      if (!lines.next(b, e, true))
        return error_in(StatusCode::ParseError, name, "OFF file ends before the counts line");
      fields.clear();
      count = split_fields(b, e, collect);
    } while (count == 0);
    if (count == kEmptyField) return empty_field_error(name, lines.line());
  }
  std::uint64_t n_vertices = 0;
  if (fields[0].e - fields[0].b == 6 && std::memcmp(fields[0].b, "BINARY", 6) == 0)
    return error_at(StatusCode::ParseError, name, lines.line(), "binary OFF is not supported");
  if (!parse_count(fields[0].b, fields[0].e, n_vertices))
    return error_at(StatusCode::ParseError, name, lines.line(),
                    "malformed OFF vertex count " + quote(fields[0].b, fields[0].e));

  // Never trust a count for an allocation: each vertex takes at least 6 bytes ("0 0 0\n").
  out.coords.reserve(
      static_cast<std::size_t>(std::min<std::uint64_t>(n_vertices, data.size() / 6)) *
      static_cast<std::size_t>(dim));
  ParsedLine f;
  for (std::uint64_t i = 0; i < n_vertices;) {
    if (!lines.next(b, e, true))
      return error_at(
          StatusCode::ParseError, name, lines.line(),
          "OFF file ends after " + std::to_string(i) + " of " + plural(n_vertices, "vertex line"));
    parse_line(b, e, dim, f);
    if (f.count == 0) continue;
    const std::size_t line = lines.line();
    if (f.count == kEmptyField) return empty_field_error(name, line);
    if (f.count < 3)
      return error_at(StatusCode::ParseError, name, line,
                      "expected 3 coordinates, found " + std::to_string(f.count));
    Status st = check_values(f, dim, name, line);
    if (!st) return st;
    out.coords.insert(out.coords.end(), f.value, f.value + dim);
    ++i;
  }
  out.dim = dim;
  return Status::ok();
}

// ---- PLY -------------------------------------------------------------------------------------

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  bool has_list = false;
  std::size_t fixed_size = 0;  // bytes per instance when !has_list
};

bool ply_type_from_name(std::string_view s, PlyType& t) {
  static const struct {
    const char* name;
    PlyType type;
  } kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& k : kTypes) {
    if (s == k.name) {
      t = k.type;
      return true;
    }
  }
  return false;
}

std::size_t ply_size(PlyType t) noexcept {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

bool ply_is_integer(PlyType t) noexcept { return t != PlyType::Float32 && t != PlyType::Float64; }

bool host_is_little_endian() noexcept {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

template <typename T>
T load(const unsigned char* p, bool swap) noexcept {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return v;
}

double load_double(const unsigned char* p, PlyType t, bool swap) noexcept {
  switch (t) {
    case PlyType::Int8:
      return load<std::int8_t>(p, swap);
    case PlyType::UInt8:
      return load<std::uint8_t>(p, swap);
    case PlyType::Int16:
      return load<std::int16_t>(p, swap);
    case PlyType::UInt16:
      return load<std::uint16_t>(p, swap);
    case PlyType::Int32:
      return load<std::int32_t>(p, swap);
    case PlyType::UInt32:
      return load<std::uint32_t>(p, swap);
    case PlyType::Float32:
      return static_cast<double>(load<float>(p, swap));
    case PlyType::Float64:
      return load<double>(p, swap);
  }
  return 0.0;
}

// List length; false if negative. @pre t is an integer type (checked in the header).
bool load_count(const unsigned char* p, PlyType t, bool swap, std::uint64_t& n) noexcept {
  std::int64_t v = 0;
  switch (t) {
    case PlyType::Int8:
      v = load<std::int8_t>(p, swap);
      break;
    case PlyType::UInt8:
      v = load<std::uint8_t>(p, swap);
      break;
    case PlyType::Int16:
      v = load<std::int16_t>(p, swap);
      break;
    case PlyType::UInt16:
      v = load<std::uint16_t>(p, swap);
      break;
    case PlyType::Int32:
      v = load<std::int32_t>(p, swap);
      break;
    case PlyType::UInt32:
      v = load<std::uint32_t>(p, swap);
      break;
    case PlyType::Float32:
    case PlyType::Float64:
      return false;
  }
  if (v < 0) return false;
  n = static_cast<std::uint64_t>(v);
  return true;
}

std::vector<std::string_view> split_words(const char* b, const char* e) {
  std::vector<std::string_view> words;
  const char* p = b;
  while (p < e) {
    while (p < e && is_space(*p)) ++p;
    const char* w = p;
    while (p < e && !is_space(*p)) ++p;
    if (p > w) words.emplace_back(w, static_cast<std::size_t>(p - w));
  }
  return words;
}

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  // byte offset of the first byte after "end_header\n"
  std::size_t body_line = 0;    // 1-based line number of the body's first line (ascii)
};

Status parse_ply_header(std::string_view data, const std::string& name, PlyHeader& h) {
  LineReader lines(data);
  const char* b = nullptr;
  const char* e = nullptr;
  if (!lines.next(b, e, false) || split_words(b, e) != std::vector<std::string_view>{"ply"})
    return error_at(StatusCode::ParseError, name, 1, "not a PLY file (first line must be 'ply')");
  bool have_format = false;
  for (;;) {
    if (!lines.next(b, e, false))
      return error_in(StatusCode::ParseError, name, "PLY header has no 'end_header' line");
    const std::size_t line = lines.line();
    const std::vector<std::string_view> w = split_words(b, e);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    const auto bad = [&](const std::string& what) {
      return error_at(StatusCode::ParseError, name, line, what);
    };
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() < 2) return bad("PLY 'format' line without a format");
      if (w[1] == "ascii") {
        h.encoding = PlyEncoding::Ascii;
      } else if (w[1] == "binary_little_endian") {
        h.encoding = PlyEncoding::BinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        h.encoding = PlyEncoding::BinaryBigEndian;
      } else {
        return bad("unknown PLY format " + quote(w[1].data(), w[1].data() + w[1].size()));
      }
      have_format = true;
    } else if (w[0] == "element") {
      PlyElement el;
      if (w.size() != 3 || !parse_count(w[2].data(), w[2].data() + w[2].size(), el.count))
        return bad("malformed PLY element line (expected 'element NAME COUNT')");
      el.name = std::string(w[1]);
      h.elements.push_back(std::move(el));
    } else if (w[0] == "property") {
      if (h.elements.empty()) return bad("PLY property before any element");
      PlyElement& el = h.elements.back();
      PlyProperty prop;
      if (w.size() == 5 && w[1] == "list") {
        prop.is_list = true;
        if (!ply_type_from_name(w[2], prop.count_type) || !ply_is_integer(prop.count_type))
          return bad("PLY list count type must be an integer type, found " +
                     quote(w[2].data(), w[2].data() + w[2].size()));
        if (!ply_type_from_name(w[3], prop.type))
          return bad("unknown PLY type " + quote(w[3].data(), w[3].data() + w[3].size()));
        prop.name = std::string(w[4]);
        el.has_list = true;
      } else if (w.size() == 3) {
        if (!ply_type_from_name(w[1], prop.type))
          return bad("unknown PLY type " + quote(w[1].data(), w[1].data() + w[1].size()));
        prop.name = std::string(w[2]);
        el.fixed_size += ply_size(prop.type);
      } else {
        return bad("malformed PLY property line");
      }
      el.properties.push_back(std::move(prop));
    } else {
      return bad("unknown PLY header keyword " + quote(w[0].data(), w[0].data() + w[0].size()));
    }
  }
  if (!have_format)
    return error_in(StatusCode::ParseError, name, "PLY header has no 'format' line");
  h.body_offset = static_cast<std::size_t>(lines.position() - data.data());
  h.body_line = lines.line() + 1;
  return Status::ok();
}

// Where x, y, z sit in the vertex element and what dimension is read.
struct VertexLayout {
  int prop[3] = {-1, -1, -1};  // property index of x, y, z (-1: absent)
  int dim = 3;
};

Status vertex_layout(const PlyElement& vertex, const std::string& name, int forced_dim,
                     VertexLayout& layout) {
  static const char* const kAxes[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (layout.prop[k] < 0 && vertex.properties[i].name == kAxes[k]) {
        if (vertex.properties[i].is_list)
          return error_in(StatusCode::ParseError, name,
                          std::string("PLY vertex property '") + kAxes[k] + "' is a list");
        layout.prop[k] = static_cast<int>(i);
      }
    }
  }
  if (layout.prop[0] < 0 || layout.prop[1] < 0)
    return error_in(StatusCode::ParseError, name, "PLY vertex element has no x and y properties");
  const bool has_z = layout.prop[2] >= 0;
  if (forced_dim == 3 && !has_z)
    return error_in(StatusCode::ParseError, name,
                    "PLY vertex element has no z property, but dimension 3 was requested");
  layout.dim = forced_dim != 0 ? forced_dim : (has_z ? 3 : 2);
  return Status::ok();
}

Status ply_truncated(const std::string& name, const PlyElement& el, std::uint64_t instance) {
  return error_in(StatusCode::ParseError, name,
                  "PLY data ends inside element '" + el.name + "' (" + el.name + " " +
                      std::to_string(instance) + " of " + std::to_string(el.count) + ")");
}

Status ply_nonfinite(const std::string& name, std::uint64_t vertex, double v) {
  return error_in(StatusCode::NonFinite, name,
                  "PLY vertex " + std::to_string(vertex) + ": non-finite coordinate (" +
                      (std::isnan(v) ? "nan"
                       : v > 0       ? "inf"
                                     : "-inf") +
                      ")");
}

enum class Walk { Ok, Truncated, NegativeLength };

Status ply_walk_error(Walk w, const std::string& name, const PlyElement& el,
                      std::uint64_t instance) {
  if (w == Walk::NegativeLength)
    return error_in(StatusCode::ParseError, name,
                    "PLY list with a negative length in element '" + el.name + "' (" + el.name +
                        " " + std::to_string(instance) + ")");
  return ply_truncated(name, el, instance);
}

Status parse_ply_binary(std::string_view data, const std::string& name, const PlyHeader& h,
                        int forced_dim, PointSet& out) {
  const bool swap = (h.encoding == PlyEncoding::BinaryLittleEndian) != host_is_little_endian();
  const auto* p = reinterpret_cast<const unsigned char*>(data.data()) + h.body_offset;
  const auto* const end = reinterpret_cast<const unsigned char*>(data.data()) + data.size();
  const auto left = [&p, end]() { return static_cast<std::uint64_t>(end - p); };

  // Walks one instance of an element with list properties; values of scalar properties are
  // handed to on_scalar(property index, pointer).
  const auto walk = [&](const PlyElement& el, auto&& on_scalar) {
    for (std::size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& prop = el.properties[k];
      const std::size_t size = ply_size(prop.type);
      if (!prop.is_list) {
        if (left() < size) return Walk::Truncated;
        on_scalar(k, p);
        p += size;
        continue;
      }
      const std::size_t count_size = ply_size(prop.count_type);
      std::uint64_t n = 0;
      if (left() < count_size) return Walk::Truncated;
      if (!load_count(p, prop.count_type, swap, n)) return Walk::NegativeLength;
      p += count_size;
      if (n > left() / size) return Walk::Truncated;
      p += n * size;
    }
    return Walk::Ok;
  };

  for (const PlyElement& el : h.elements) {
    if (el.name != "vertex") {
      // Elements before the vertices are skipped; elements after them are never read.
      if (!el.has_list) {
        if (el.fixed_size != 0 && el.count > left() / el.fixed_size)
          return ply_truncated(name, el, left() / el.fixed_size);
        p += el.count * el.fixed_size;
      } else {
        for (std::uint64_t i = 0; i < el.count; ++i) {
          const Walk w = walk(el, [](std::size_t, const unsigned char*) {});
          if (w != Walk::Ok) return ply_walk_error(w, name, el, i);
        }
      }
      continue;
    }

    VertexLayout layout;
    Status st = vertex_layout(el, name, forced_dim, layout);
    if (!st) return st;
    const int dim = layout.dim;
    out.dim = dim;
    if (!el.has_list) {
      // Fixed record size: check the whole block once, then read with a stride.
      const std::size_t stride = el.fixed_size;
      if (el.count > left() / stride) return ply_truncated(name, el, left() / stride);
      std::size_t offset[3] = {0, 0, 0};
      PlyType type[3] = {PlyType::Float32, PlyType::Float32, PlyType::Float32};
      for (int k = 0; k < dim; ++k) {
        const auto pk = static_cast<std::size_t>(layout.prop[k]);
        for (std::size_t j = 0; j < pk; ++j) offset[k] += ply_size(el.properties[j].type);
        type[k] = el.properties[pk].type;
      }
      out.coords.resize(static_cast<std::size_t>(el.count) * static_cast<std::size_t>(dim));
      double* dst = out.coords.data();
      for (std::uint64_t i = 0; i < el.count; ++i, p += stride) {
        for (int k = 0; k < dim; ++k) {
          const double v = load_double(p + offset[k], type[k], swap);
          if (!std::isfinite(v)) return ply_nonfinite(name, i, v);
          *dst++ = v;
        }
      }
    } else {
      out.coords.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(el.count, left())) *
                         static_cast<std::size_t>(dim));
      double xyz[3] = {0.0, 0.0, 0.0};
      for (std::uint64_t i = 0; i < el.count; ++i) {
        const Walk w = walk(el, [&](std::size_t k, const unsigned char* q) {
          for (int a = 0; a < 3; ++a)
            if (layout.prop[a] == static_cast<int>(k))
              xyz[a] = load_double(q, el.properties[k].type, swap);
        });
        if (w != Walk::Ok) return ply_walk_error(w, name, el, i);
        for (int k = 0; k < dim; ++k) {
          if (!std::isfinite(xyz[k])) return ply_nonfinite(name, i, xyz[k]);
          out.coords.push_back(xyz[k]);
        }
      }
    }
    return Status::ok();
  }
  return error_in(StatusCode::ParseError, name, "PLY file has no 'vertex' element");
}

// Whitespace-separated tokens across lines (ascii PLY is a token stream), tracking line numbers.
class TokenReader {
 public:
  TokenReader(const char* p, const char* end, std::size_t line) : p_(p), end_(end), line_(line) {}

  bool next(Span& tok) noexcept {
    while (p_ < end_ && (is_space(*p_) || *p_ == '\n')) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    if (p_ == end_) return false;
    tok.b = p_;
    while (p_ < end_ && !is_space(*p_) && *p_ != '\n') ++p_;
    tok.e = p_;
    return true;
  }
  std::size_t line() const noexcept { return line_; }  ///< line of the last token read

 private:
  const char* p_;
  const char* end_;
  std::size_t line_;
};

Status parse_ply_ascii(std::string_view data, const std::string& name, const PlyHeader& h,
                       int forced_dim, PointSet& out) {
  TokenReader tokens(data.data() + h.body_offset, data.data() + data.size(), h.body_line);
  Span tok;
  // Reads one instance; scalar tokens go to on_scalar(property index, token). Lists are skipped.
  const auto walk = [&](const PlyElement& el, std::uint64_t instance, auto&& on_scalar) -> Status {
    for (std::size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& prop = el.properties[k];
      if (!tokens.next(tok)) return ply_truncated(name, el, instance);
      if (!prop.is_list) {
        Status st = on_scalar(k, tok);
        if (!st) return st;
        continue;
      }
      std::uint64_t n = 0;
      if (!parse_count(tok.b, tok.e, n))
        return error_at(StatusCode::ParseError, name, tokens.line(),
                        "malformed PLY list length " + quote(tok.b, tok.e));
      for (std::uint64_t j = 0; j < n; ++j)
        if (!tokens.next(tok)) return ply_truncated(name, el, instance);
    }
    return Status::ok();
  };

  for (const PlyElement& el : h.elements) {
    if (el.name != "vertex") {
      for (std::uint64_t i = 0; i < el.count; ++i) {
        Status st = walk(el, i, [](std::size_t, const Span&) { return Status::ok(); });
        if (!st) return st;
      }
      continue;
    }
    VertexLayout layout;
    Status st = vertex_layout(el, name, forced_dim, layout);
    if (!st) return st;
    const int dim = layout.dim;
    out.dim = dim;
    const std::size_t body = data.size() - h.body_offset;
    out.coords.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(el.count, body / 4)) *
                       static_cast<std::size_t>(dim));
    double xyz[3] = {0.0, 0.0, 0.0};
    for (std::uint64_t i = 0; i < el.count; ++i) {
      st = walk(el, i, [&](std::size_t k, const Span& t) {
        for (int a = 0; a < dim; ++a) {
          if (layout.prop[a] != static_cast<int>(k)) continue;
          Status cs = parse_coordinate(t, name, tokens.line(), xyz[a]);
          if (!cs) {
            if (cs.code() == StatusCode::NonFinite)
              return Status(cs.code(), cs.message() + " (vertex " + std::to_string(i) + ")");
            return cs;
          }
        }
        return Status::ok();
      });
      if (!st) return st;
      out.coords.insert(out.coords.end(), xyz, xyz + dim);
    }
    return Status::ok();
  }
  return error_in(StatusCode::ParseError, name, "PLY file has no 'vertex' element");
}

Status parse_ply(std::string_view data, const std::string& name, int forced_dim, PointSet& out) {
  PlyHeader header;
  Status st = parse_ply_header(data, name, header);
  if (!st) return st;
  if (header.encoding == PlyEncoding::Ascii)
    return parse_ply_ascii(data, name, header, forced_dim, out);
  return parse_ply_binary(data, name, header, forced_dim, out);
}

// ---- common ----------------------------------------------------------------------------------

PointFormat format_from_name(const std::string& name) {
  const std::size_t slash = name.find_last_of("/\\");
  const std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return PointFormat::Text;
  std::string ext = name.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "ply") return PointFormat::Ply;
  if (ext == "off") return PointFormat::Off;
  if (ext == "obj") return PointFormat::Obj;
  return PointFormat::Text;
}

bool is_blank(std::string_view data) {
  return std::all_of(data.begin(), data.end(), [](char c) { return is_space(c) || c == '\n'; });
}

Status cannot_read(const std::string& path, int err) {
  return {StatusCode::FileNotFound,
          path + ": cannot read: " + std::generic_category().message(err)};
}

// The bytes of a file. A regular file is memory-mapped where the platform allows it: for large
// inputs copying the file into a buffer (and faulting that buffer in) costs as much as parsing it.
// Other files (pipes, /proc) and other platforms are read into a string.
class FileContents {
 public:
  FileContents() = default;
  FileContents(const FileContents&) = delete;
  FileContents& operator=(const FileContents&) = delete;
  ~FileContents() {
#if CONSTRICT_HAVE_MMAP
    if (map_ != nullptr) ::munmap(map_, map_size_);
#endif
  }

  std::string_view view() const noexcept {
    if (map_ != nullptr) return {static_cast<const char*>(map_), map_size_};
    return buffer_;
  }

  Status open(const std::string& path) {
#if CONSTRICT_HAVE_MMAP
    int flags = O_RDONLY;
#ifdef O_CLOEXEC
    flags |= O_CLOEXEC;
#endif
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) return cannot_read(path, errno);
    Status st = read_fd(path, fd);
    ::close(fd);
    return st;
#else
    // fopen() succeeds on a directory on some systems (reading then fails), so catch it first.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return cannot_read(path, EISDIR);
    errno = 0;
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return cannot_read(path, errno != 0 ? errno : ENOENT);
    char chunk[1 << 16];
    for (;;) {
      const std::size_t got = std::fread(chunk, 1, sizeof chunk, file);
      buffer_.append(chunk, got);
      if (got < sizeof chunk) break;
    }
    const bool failed = std::ferror(file) != 0;
    const int err = errno;
    std::fclose(file);
    if (failed) return cannot_read(path, err != 0 ? err : EIO);
    return Status::ok();
#endif
  }

 private:
#if CONSTRICT_HAVE_MMAP
  Status read_fd(const std::string& path, int fd) {
    struct stat info {};
    if (::fstat(fd, &info) != 0) return cannot_read(path, errno);
    if (S_ISDIR(info.st_mode)) return cannot_read(path, EISDIR);
    if (S_ISREG(info.st_mode) && info.st_size > 0) {
      int map_flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
      map_flags |= MAP_POPULATE;  // fault the pages in at once, not one by one while parsing
#endif
      const auto size = static_cast<std::size_t>(info.st_size);
      void* m = ::mmap(nullptr, size, PROT_READ, map_flags, fd, 0);
      if (m != MAP_FAILED) {
        map_ = m;
        map_size_ = size;
        return Status::ok();
      }
      buffer_.reserve(size);  // mapping refused (some file systems): read it instead
    }
    char chunk[1 << 16];
    for (;;) {
      const ssize_t got = ::read(fd, chunk, sizeof chunk);
      if (got < 0) {
        if (errno == EINTR) continue;
        return cannot_read(path, errno);
      }
      if (got == 0) break;
      buffer_.append(chunk, static_cast<std::size_t>(got));
    }
    return Status::ok();
  }
#endif

  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::string buffer_;
};

}  // namespace

Status read_points_from_buffer(std::string_view data, const std::string& name, PointFormat format,
                               const ReadOptions& options, PointSet& out, ReadReport* report) {
  if (report != nullptr) *report = ReadReport{};
  if (options.dim != 0 && options.dim != 2 && options.dim != 3)
    return error_in(
        StatusCode::InvalidArgument, name,
        "dimension must be 0 (from the data), 2 or 3, got " + std::to_string(options.dim));
  if (format == PointFormat::Auto) format = options.format;
  if (format == PointFormat::Auto) format = format_from_name(name);
  if (is_blank(data)) return error_in(StatusCode::EmptyInput, name, "empty file");

  PointSet points;
  points.dim = options.dim == 0 ? 3 : options.dim;
  Status st;
  switch (format) {
    case PointFormat::Auto:
    case PointFormat::Text:
      st = parse_text(data, name, options.dim, points);
      break;
    case PointFormat::Ply:
      st = parse_ply(data, name, options.dim, points);
      break;
    case PointFormat::Off:
      st = parse_off(data, name, options.dim, points);
      break;
    case PointFormat::Obj:
      st = parse_obj(data, name, options.dim, points);
      break;
  }
  if (!st) return st;
  const std::size_t n_read = points.size();
  if (report != nullptr) report->points_read = n_read;
  if (n_read == 0) return error_in(StatusCode::EmptyInput, name, "no points");

  std::vector<std::size_t> kept;
  if (options.merge_duplicates) {
    PointSet merged = merge_duplicates(points, &kept);
    if (merged.size() == n_read) {
      kept.clear();
    } else {
      points = std::move(merged);
    }
  }
  const std::size_t n_merged = n_read - points.size();

  if (options.check) {
    st = check_points(points);
    if (!st) return error_in(st.code(), name, st.message());
  }

  if (report != nullptr) {
    report->merged_duplicates = n_merged;
    if (n_merged > 0) {
      report->original_index = std::move(kept);
      report->warnings.push_back(name + ": merged " + plural(n_merged, "duplicate point") +
                                 " (kept the first occurrence of each)");
    } else {
      report->original_index.resize(n_read);
      std::iota(report->original_index.begin(), report->original_index.end(), std::size_t{0});
    }
  }
  out = std::move(points);
  return Status::ok();
}

Status read_points(const std::string& path, const ReadOptions& options, PointSet& out,
                   ReadReport* report) {
  if (report != nullptr) *report = ReadReport{};
  FileContents contents;
  Status st = contents.open(path);
  if (!st) return st;
  const PointFormat format =
      options.format == PointFormat::Auto ? format_from_name(path) : options.format;
  return read_points_from_buffer(contents.view(), path, format, options, out, report);
}

}  // namespace constrict
