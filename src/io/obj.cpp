// SPDX-License-Identifier: GPL-3.0-or-later
// The OBJ reader shared by read_points() and read_mesh() (contract: io/detail/obj.hpp).
#include "io/detail/obj.hpp"

#include <algorithm>
#include <string_view>

#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {
namespace {

// The vertex indices of an 'f' record [b, e) (after the 'f'), resolved to 0-based.
Status face_ids(const char* p, const char* e, const std::string& name, std::size_t line,
                std::int64_t n_vertices, std::vector<std::int64_t>& ids) {
  ids.clear();
  for (;;) {
    while (p < e && is_space(*p)) ++p;
    if (p == e) return Status::ok();
    const char* b = p;
    while (p < e && !is_space(*p)) ++p;
    const char* slash = b;
    while (slash < p && *slash != '/') ++slash;  // a/b/c: the vertex is a
    std::int64_t v = 0;
    const auto r = std::from_chars(b, slash, v);
    if (r.ec != std::errc() || r.ptr != slash || v == 0)
      return error_at(StatusCode::ParseError, name, line, "malformed vertex index " + quote(b, p));
    ids.push_back(v > 0 ? v - 1 : n_vertices + v);
  }
}

}  // namespace

Status read_obj(std::string_view data, const std::string& name, int dim,
                std::vector<double>& coords, ObjFaceSink* faces) {
  LineReader lines(data);
  ParsedLine f;
  std::vector<std::int64_t> ids;
  const char* b = nullptr;
  const char* e = nullptr;
  while (lines.next(b, e, true)) {
    while (b < e && is_space(*b)) ++b;
    if (b < e && *b == 'v') {
      // Any statement starting with 'v' other than v, vt, vn and vp is a damaged vertex line
      // ("v1 2 3", "v,0,1,0"), whose point would be lost without a word.
      const char* k = b;
      while (k < e && !is_space(*k)) ++k;
      const std::string_view kw(b, static_cast<std::size_t>(k - b));
      if (kw != "v" && kw != "vt" && kw != "vn" && kw != "vp")
        return error_at(StatusCode::ParseError, name, lines.line(),
                        "malformed statement " + quote(b, std::min(e, b + 40)) + " (a vertex is 'v x y z')");
    }
    if (e - b < 2 || !is_space(b[1])) continue;
    const std::size_t line = lines.line();
    if (b[0] == 'f' && faces != nullptr) {
      const auto n = static_cast<std::int64_t>(coords.size() / static_cast<std::size_t>(dim));
      Status st = face_ids(b + 1, e, name, line, n, ids);
      if (st) st = faces->face(line, ids);
      if (!st) return st;
      continue;
    }
    if (b[0] != 'v') continue;
    parse_line(b + 1, e, dim, f);
    if (f.count == kEmptyField) return empty_field_error(name, line);
    if (f.count < 3)
      return error_at(StatusCode::ParseError, name, line,
                      "expected 3 coordinates after 'v', found " + std::to_string(f.count));
    Status st = check_values(f, dim, name, line);
    if (!st) return st;
    coords.insert(coords.end(), f.value, f.value + dim);
  }
  return Status::ok();
}

}  // namespace detail
}  // namespace constrict
