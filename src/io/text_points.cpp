// SPDX-License-Identifier: GPL-3.0-or-later
// Text columns (XYZ/CSV/TXT): one point per line, scanned once per line with fast_float.
// The coordinate columns are, in this order: ReadOptions::columns, the header's x, y[, z], or the
// first fields (the fast path, also taken when a selection is the first fields). A line with more
// than 3 fields and no selection is refused: taking "the first two" of `id,x,y` used to give a
// polygon through (id, x) without a word (issue 18).
#include "io/detail/text_points.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <vector>

#include "core/detail/ordered_pack.hpp"
#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {
namespace {

constexpr int kMaxDim = 3;

// The optional header line: its 1-based line number (0: none) and its fields.
struct Header {
  std::size_t line = 0;
  std::vector<std::string> names;
};

// A header field as compared: surrounding quotes (CSV exports write "x") dropped, lower case.
std::string header_key(const char* b, const char* e) {
  if (e - b >= 2 && (*b == '"' || *b == '\'') && e[-1] == *b) {
    ++b;
    --e;
  }
  std::string s(b, e);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The header, if the first non-blank, non-comment line is one (no field of it is a number).
Header find_header(std::string_view data) {
  LineReader lines(data);
  const char* b = nullptr;
  const char* e = nullptr;
  while (lines.next(b, e, true)) {
    const std::size_t count = split_fields(b, e, [](std::size_t, const Span&) {});
    if (count == 0) continue;
    Header h;
    if (count == kEmptyField || !is_header_line(b, e)) return h;
    h.line = lines.line();
    split_fields(b, e, [&h](std::size_t, const Span& f) { h.names.push_back(header_key(f.b, f.e)); });
    return h;
  }
  return {};
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

Status too_many_fields(const std::string& name, std::size_t line, std::size_t count) {
  return error_at(StatusCode::ParseError, name, line,
                  std::to_string(count) + " fields per line, more than x, y, z: " + kChooseColumnsAdvice);
}

// A coordinate's header name must name one column: "x,x,y" would pick one of two silently.
Status unique_name(const Header& h, std::vector<std::string>::const_iterator it, const std::string& name) {
  const auto again = std::find(it + 1, h.names.cend(), *it);
  if (again == h.names.cend()) return Status::ok();
  return error_at(StatusCode::ParseError, name, h.line,
                  "the header names '" + *it + "' twice (columns " + std::to_string(it - h.names.cbegin() + 1) + " and " +
                      std::to_string(again - h.names.cbegin() + 1) + "); rename one or choose the columns with --columns (e.g. 1,3)");
}

// 0-based field index of each coordinate; empty: the first fields (no selection made).
Status select_columns(const Header& h, const ColumnSelection& c, int forced_dim,
                      const std::string& name, std::vector<std::size_t>& index) {
  index.clear();
  if (!c.numbers.empty()) {
    for (std::size_t n : c.numbers) index.push_back(n - 1);
  } else if (!c.names.empty()) {
    if (h.line == 0)
      return error_in(StatusCode::InvalidArgument, name,
                      "columns chosen by header name, but the file has no header line; give "
                      "1-based column numbers (e.g. --columns 2,3,4)");
    for (const std::string& want : c.names) {
      const auto it = std::find(h.names.begin(), h.names.end(), header_key(want.data(), want.data() + want.size()));
      if (it == h.names.end())
        return error_at(StatusCode::InvalidArgument, name, h.line,
                        "no column named '" + want + "' in the header (" + joined(h.names) + ")");
      if (Status u = unique_name(h, it, name); !u) return u;
      index.push_back(static_cast<std::size_t>(it - h.names.begin()));
    }
  } else if (h.line != 0) {
    static const char* const kAxes[kMaxDim] = {"x", "y", "z"};
    for (const char* axis : kAxes) {
      const auto it = std::find(h.names.begin(), h.names.end(), axis);
      if (it == h.names.end()) break;
      if (Status u = unique_name(h, it, name); !u) return u;
      index.push_back(static_cast<std::size_t>(it - h.names.begin()));
    }
    if (index.size() < 2) {
      index.clear();
      if (h.names.size() > static_cast<std::size_t>(kMaxDim))
        return error_at(StatusCode::ParseError, name, h.line,
                        "the header names " + std::to_string(h.names.size()) +
                            " columns, none of them x and y: " + kChooseColumnsAdvice);
      return Status::ok();  // "east,north,height": the first fields, as without a header
    }
    if (forced_dim == 3 && index.size() == 2)
      return error_at(StatusCode::ParseError, name, h.line,
                      "the header names x and y but no z column, and dimension 3 was requested; "
                      "choose the columns with --columns");
  }
  if (index.empty()) return Status::ok();
  if (forced_dim != 0 && index.size() > static_cast<std::size_t>(forced_dim))
    index.resize(static_cast<std::size_t>(forced_dim));  // a forced dim 2 drops z
  if (forced_dim != 0 && index.size() < static_cast<std::size_t>(forced_dim))
    return error_in(StatusCode::InvalidArgument, name,
                    std::to_string(index.size()) + " coordinate columns chosen, but dimension " +
                        std::to_string(forced_dim) + " was requested");
  return Status::ok();
}

// The lines of [p, end) once the first data line has fixed the layout: each must have
// `expected_fields` fields with `dim` valid numbers first (blank and comment lines skipped). Pushes
// the values; false at the first line that breaks the rule (the caller then reads the file again
// in order, for the error and its line number).
template <class Push>
bool read_layout_lines(const char* p, const char* end, int dim, std::size_t expected_fields, const Push& push) {
  ParsedLine f;
  while (p < end) {
    const char* const next = parse_line(p, end, dim, f);
    p = next < end ? next + 1 : end;
    if (f.count == 0) continue;
    if (f.count != expected_fields || (f.first_malformed >= 0 && f.first_malformed < dim)) return false;
    for (int k = 0; k < dim; ++k)
      if (!std::isfinite(f.value[k])) return false;
    for (int k = 0; k < dim; ++k) push(f.value[k]);
  }
  return true;
}

// Large files: the lines after the first data line are read in blocks of about kBlockBytes on
// every core, each block from the line after a '\n' to the '\n' that ends its last line, and the
// blocks' values joined in file order (ordered_pack), so the points are the ones of the sequential
// scan. False when a block holds a line the layout does not allow (nothing is appended then).
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
bool read_layout_blocks(const char* p, const char* end, int dim, std::size_t expected_fields,
                        std::vector<double>& coords) {
  std::vector<const char*> cut{p};
  while (static_cast<std::size_t>(end - cut.back()) > kBlockBytes) {
    const char* nl = line_end(cut.back() + kBlockBytes, end);
    if (nl == end) break;
    cut.push_back(nl + 1);
  }
  cut.push_back(end);
  std::atomic<bool> ok{true};
  const std::size_t before = coords.size();
  ordered_pack_append<double>(
      coords, cut.size() - 1,
      [&](std::size_t k, const auto& push) {
        if (ok.load(std::memory_order_relaxed) && !read_layout_lines(cut[k], cut[k + 1], dim, expected_fields, push))
          ok = false;
      },
      1);
  if (!ok) {
    coords.resize(before);
    return false;
  }
  return true;
}

// A data line with another field count than the first one; a carriage return inside it (a file
// that mixes line ends: CR alone ends no line here) is named.
Status field_count_error(const std::string& name, std::size_t line, std::size_t expected, std::size_t count,
                         const char* b, const char* e) {
  std::string msg = "expected " + std::to_string(expected) + " fields, found " + std::to_string(count);
  for (const char* c = b; c < e; ++c)
    if (*c == '\r' && c + 1 < e && c[1] != '\n') {
      msg += "; the line holds a carriage return (CR) inside: the file mixes line ends, convert them to LF";
      break;
    }
  return error_at(StatusCode::ParseError, name, line, msg);
}

// The fast path: the first `dim` fields of each line (dim 0: 2 or 3, from the first data line).
// `chosen`: the columns were selected (by the header), so more fields than 3 are fine.
// `in_blocks`: the lines after the first data line may be read in parallel blocks (a file that
// breaks its layout there is read again with this false, for the error of its first bad line).
Status read_first_fields(std::string_view data, const std::string& name, int dim, bool chosen, PointSet& out,
                         bool in_blocks = true) {
  const char* p = data.data();
  const char* const end = data.data() + data.size();
  // A UTF-8 byte order mark (written by some spreadsheet exports) is not part of the data.
  if (data.size() >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3;
  std::size_t expected_fields = 0;  // set by the first data line
  bool seen_content = false;
  std::size_t header_line = 0, header_fields = 0;  // a header line that names no columns
  ParsedLine f;
  std::vector<double>& coords = out.coords;
  const std::size_t coords_before = coords.size();
  const int dim_asked = dim;  // (dim 0 becomes the first data line's field count below)

  for (std::size_t line = 1; p < end; ++line) {
    if (in_blocks && expected_fields != 0 && static_cast<std::size_t>(end - p) > 2 * kBlockBytes) {
      if (read_layout_blocks(p, end, dim, expected_fields, coords)) break;
      coords.resize(coords_before);
      return read_first_fields(data, name, dim_asked, chosen, out, false);
    }
    if (line == 1) coords.reserve(data.size() / 16);
    const char* const begin = p;
    const char* const next = parse_line(p, end, dim == 0 ? kMaxDim : dim, f);
    p = next < end ? next + 1 : end;
    const std::size_t count = f.count;
    if (count == 0) continue;  // blank or comment-only line
    if (count == kEmptyField) return empty_field_error(name, line);
    if (!seen_content) {
      seen_content = true;
      if (f.first_malformed >= 0 && is_header_line(begin, f.content_end)) {
        header_line = line;
        header_fields = count;
        continue;
      }
    }
    if (expected_fields == 0) {
      // A header that names no x and y column is taken on trust only if it names as many columns
      // as the data have: "OFF" above an OFF file's counts and vertices was dropped as a header.
      if (header_line != 0 && !chosen && header_fields != count)
        return error_at(StatusCode::ParseError, name, header_line,
                        "this first line looks like a header, but it has " + plural(header_fields, "field") +
                            " and the data lines have " + std::to_string(count) +
                            ": remove it or make it name every column (an OFF, PLY or OBJ file needs its own "
                            "extension or --format)");
      if (count > static_cast<std::size_t>(kMaxDim) && !chosen) return too_many_fields(name, line, count);
      if (dim == 0) {
        if (count != 2 && count != 3)
          return error_at(
              StatusCode::ParseError, name, line,
              "expected 2 or 3 fields (x y [z]), found " + std::to_string(count) +
                  (count == 1 && f.first_malformed < 0 && f.value[0] >= 0 && f.value[0] == std::floor(f.value[0])
                       ? "; if this line is a point count (as .pts files start), remove it"
                       : ""));
        dim = static_cast<int>(count);
      } else if (count < static_cast<std::size_t>(dim)) {
        return error_at(StatusCode::ParseError, name, line,
                        "expected at least " + std::to_string(dim) + " fields for dimension " +
                            std::to_string(dim) + ", found " + std::to_string(count));
      }
      expected_fields = count;
    } else if (count != expected_fields) {
      return field_count_error(name, line, expected_fields, count, begin, next);
    }
    Status st = check_values(f, dim, name, line);
    if (!st) return st;
    coords.insert(coords.end(), f.value, f.value + dim);
  }
  // The reserve guessed 16 bytes of text per number; short numbers leave room over, which the
  // points would carry through the whole run.
  if (coords.capacity() - coords.size() > coords.size() / 16) coords.shrink_to_fit();
  out.dim = dim == 0 ? 2 : dim;
  return Status::ok();
}

// Any columns: the fields of each line are split first, then the chosen ones parsed.
Status read_columns(std::string_view data, const std::string& name, std::size_t header_line,
                    const std::vector<std::size_t>& index, PointSet& out) {
  const std::size_t dim = index.size();
  const std::size_t needed = *std::max_element(index.begin(), index.end()) + 1;
  LineReader lines(data);
  const char* b = nullptr;
  const char* e = nullptr;
  std::size_t expected_fields = 0;
  Span field[kMaxDim];
  while (lines.next(b, e, true)) {
    const std::size_t count = split_fields(b, e, [&](std::size_t i, const Span& s) {
      for (std::size_t k = 0; k < dim; ++k)
        if (index[k] == i) field[k] = s;
    });
    const std::size_t line = lines.line();
    if (count == 0 || line == header_line) continue;
    if (count == kEmptyField) return empty_field_error(name, line);
    if (expected_fields == 0) {
      if (count < needed)
        return error_at(StatusCode::ParseError, name, line,
                        "column " + std::to_string(needed) + " is a coordinate, but the line has " +
                            plural(count, "field"));
      expected_fields = count;
    } else if (count != expected_fields) {
      return field_count_error(name, line, expected_fields, count, b, e);
    }
    for (std::size_t k = 0; k < dim; ++k) {
      double v = 0.0;
      Status st = parse_coordinate(field[k], name, line, v);
      if (!st) return st;
      out.coords.push_back(v);
    }
  }
  out.dim = static_cast<int>(dim);
  return Status::ok();
}

}  // namespace

Status read_text_points(std::string_view data, const std::string& name, int forced_dim,
                        const ColumnSelection& columns, PointSet& out) {
  // UTF-16 text (a byte order mark, or a NUL in every other byte of the start: Windows tools
  // save "Unicode" text so) is not read as ASCII: one line saying what the file is.
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(data[i]); };
  std::size_t nuls = 0;
  const std::size_t head = std::min<std::size_t>(data.size(), 64);
  for (std::size_t i = 0; i < head; ++i) nuls += byte(i) == 0 ? 1 : 0;
  if (data.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF)))
    return error_in(StatusCode::ParseError, name,
                    "the file is UTF-16 text (it starts with a UTF-16 byte order mark): save it as UTF-8 or "
                    "plain text (e.g. iconv -f UTF-16 -t UTF-8 IN > OUT)");
  if (head >= 8 && 4 * nuls >= head)
    return error_in(StatusCode::ParseError, name,
                    "a quarter or more of the first bytes are NUL: the file is UTF-16 or UTF-32 text or binary "
                    "data, not ASCII or UTF-8 text; save it as UTF-8 or plain text");
  // Lines ended by CR alone (classic Mac OS): read as if they ended by LF.
  if (data.find('\n') == std::string_view::npos && data.find('\r') != std::string_view::npos) {
    std::string lf(data);
    std::replace(lf.begin(), lf.end(), '\r', '\n');
    return read_text_points(lf, name, forced_dim, columns, out);
  }
  const Header header = find_header(data);
  std::vector<std::size_t> index;
  Status st = select_columns(header, columns, forced_dim, name, index);
  if (!st) return st;
  if (index.empty()) return read_first_fields(data, name, forced_dim, false, out);
  bool leading = true;  // the first fields in order: the fast path reads them
  for (std::size_t k = 0; k < index.size(); ++k) leading = leading && index[k] == k;
  if (leading) return read_first_fields(data, name, static_cast<int>(index.size()), true, out);
  return read_columns(data, name, header.line, index, out);
}

}  // namespace detail
}  // namespace constrict
