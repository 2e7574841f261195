// SPDX-License-Identifier: GPL-3.0-or-later
// Text columns (XYZ/CSV/TXT): one point per line, scanned once per line with fast_float.
#include "io/detail/text_points.hpp"

#include <vector>

#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {

Status read_text_points(std::string_view data, const std::string& name, int forced_dim,
                        PointSet& out) {
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

}  // namespace detail
}  // namespace constrict
