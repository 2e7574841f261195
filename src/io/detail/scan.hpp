// SPDX-License-Identifier: GPL-3.0-or-later
// Scanning helpers shared by the text readers (text columns, OFF, OBJ, ascii PLY): lines, fields,
// numbers (fast_float: exact round-to-nearest, locale independent, no iostreams) and the
// one-line "file:LINE: ..." messages. Everything is inline: these loops are the readers' hot path.
#pragma once

#include <fast_float/fast_float.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>

#include "constrict/status.hpp"

namespace constrict {
namespace detail {

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

// A token as it appears in a message: quoted, shortened, control bytes escaped (one-line
// messages), and the two invisible characters spreadsheets leave in numbers named (a byte order
// mark U+FEFF, a no-break space U+00A0).
inline std::string quote(const char* b, const char* e) {
  std::string s = "'";
  const char* stop = (static_cast<std::size_t>(e - b) > kMaxQuoted) ? b + kMaxQuoted : e;
  for (const char* p = b; p != stop; ++p) {
    const auto u = static_cast<unsigned char>(*p);
    if (u == 0xEF && stop - p >= 3 && static_cast<unsigned char>(p[1]) == 0xBB &&
        static_cast<unsigned char>(p[2]) == 0xBF) {
      s += "<U+FEFF byte order mark>";
      p += 2;
    } else if (u == 0xC2 && stop - p >= 2 && static_cast<unsigned char>(p[1]) == 0xA0) {
      s += "<U+00A0 no-break space>";
      p += 1;
    } else if (u < 0x20 || u == 0x7f) {
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

inline Status error_at(StatusCode code, const std::string& name, std::size_t line,
                const std::string& what) {
  return {code, name + ":" + std::to_string(line) + ": " + what};
}

inline Status error_in(StatusCode code, const std::string& name, const std::string& what) {
  return {code, name + ": " + what};
}

inline std::string plural(std::uint64_t n, const char* word) {
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
inline std::size_t split_fields(const char* p, const char* e, OnField&& on_field) {
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

inline Status empty_field_error(const std::string& name, std::size_t line) {
  return error_at(StatusCode::ParseError, name, line,
                  "empty field (a ',' or ';' at the start or end of the line, or two in a row)");
}

// The optional header line: no field of it is a number, its first field starts like a name (a
// letter or '_', after an optional quote: "x y z", "X;Y;Z", "east north height", "Höhe"), and no
// field holds a control character. Anything else is data, read (and refused) as such: a first
// line of hex numbers ("0x10"), quoted numbers ("5"), '-' or numbers joined by a no-break space
// was taken for a header and dropped, a point silently lost.
inline bool is_header_line(const char* b, const char* e) {
  bool header = true;
  split_fields(b, e, [&header](std::size_t i, const Span& f) {
    double v = 0.0;
    if (parse_double(f.b, f.e, v)) header = false;
    for (const char* p = f.b; p < f.e; ++p)
      if (static_cast<unsigned char>(*p) < 0x20 || *p == 0x7f) header = false;
    if (i != 0) return;
    const char* c = f.b;
    if (c < f.e && (*c == '"' || *c == '\'')) ++c;
    const auto u = c < f.e ? static_cast<unsigned char>(*c) : 0u;
    const bool nbsp = u == 0xC2 && c + 1 < f.e && static_cast<unsigned char>(c[1]) == 0xA0;
    if (!((u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || u == '_' || (u >= 0x80 && !nbsp))) header = false;
  });
  return header;
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

}  // namespace detail
}  // namespace constrict
