// SPDX-License-Identifier: GPL-3.0-or-later
// The OFF reader shared by read_points() and read_mesh() (contract: io/detail/off.hpp).
#include "io/detail/off.hpp"

#include <algorithm>

namespace constrict {
namespace detail {
namespace {

// A vertex line is at least "0 0 0\n": reservations assume no fewer bytes per vertex.
constexpr std::uint64_t kMinVertexLineBytes = 6;
// A header count is refused when even two bytes per line (a value and '\n') would not fit.
constexpr std::uint64_t kMinRecordBytes = 2;

}  // namespace

bool is_off_keyword(std::string_view w) {
  if (w.size() < 3 || w.substr(w.size() - 3) != "OFF") return false;
  w.remove_suffix(3);
  if (w.substr(0, 2) == "ST") w.remove_prefix(2);
  if (!w.empty() && w.front() == 'C') w.remove_prefix(1);
  if (!w.empty() && w.front() == 'N') w.remove_prefix(1);
  return w.empty();
}

OffReader::OffReader(std::string_view data, const std::string& name)
    : data_(data), name_(name), lines_(data) {}

Status OffReader::header(bool with_faces) {
  std::vector<Span> fields;
  const auto collect = [&fields](std::size_t, const Span& f) { fields.push_back(f); };
  const char* b = nullptr;
  const char* e = nullptr;

  // Keyword line, possibly followed by the counts on the same line.
  std::size_t count = 0;
  do {
    if (!lines_.next(b, e, true)) {
      empty_ = true;  // nothing but comments
      return Status::ok();
    }
    fields.clear();
    count = split_fields(b, e, collect);
  } while (count == 0);
  if (count == kEmptyField) return empty_field_error(name_, lines_.line());
  const std::string_view keyword(fields[0].b, static_cast<std::size_t>(fields[0].e - fields[0].b));
  if (!is_off_keyword(keyword))
    return error_at(StatusCode::ParseError, name_, lines_.line(),
                    "not an OFF file: expected 'OFF' (or COFF, NOFF...), found " +
                        quote(fields[0].b, fields[0].e));
  fields.erase(fields.begin());

  if (fields.empty()) {
    do {
      if (!lines_.next(b, e, true))
        return error_in(StatusCode::ParseError, name_, "OFF file ends before the counts line");
      fields.clear();
      count = split_fields(b, e, collect);
    } while (count == 0);
    if (count == kEmptyField) return empty_field_error(name_, lines_.line());
  }
  return counts(fields, with_faces);
}

Status OffReader::counts(std::vector<Span>& fields, bool with_faces) {
  const std::size_t line = lines_.line();
  if (fields[0].e - fields[0].b == 6 && std::memcmp(fields[0].b, "BINARY", 6) == 0)
    return error_at(StatusCode::ParseError, name_, line, "binary OFF is not supported");
  if (!parse_count(fields[0].b, fields[0].e, n_vertices_))
    return error_at(StatusCode::ParseError, name_, line,
                    "malformed OFF vertex count " + quote(fields[0].b, fields[0].e));
  if (with_faces) {
    if (fields.size() < 2 || !parse_count(fields[1].b, fields[1].e, n_faces_))
      return error_at(StatusCode::ParseError, name_, line,
                      "malformed OFF face count (expected 'vertices faces edges')");
    faces_known_ = true;
  } else {
    faces_known_ = fields.size() >= 2 && parse_count(fields[1].b, fields[1].e, n_faces_);
    if (!faces_known_) n_faces_ = 0;
  }
  const auto left = static_cast<std::uint64_t>(data_.data() + data_.size() - lines_.position());
  const std::uint64_t room = left / kMinRecordBytes + 1;  // the last line may lack its '\n'
  if (n_vertices_ > room || n_faces_ > room - n_vertices_)
    return error_at(StatusCode::ParseError, name_, line,
                    "OFF counts announce " + std::to_string(n_vertices_) +
                        (n_vertices_ == 1 ? " vertex" : " vertices") +
                        (with_faces ? " and " + plural(n_faces_, "face") : std::string()) +
                        ", more lines than the " + std::to_string(left) +
                        " bytes left in the file can hold; correct the counts");
  return Status::ok();
}

Status OffReader::vertices(int dim, std::vector<double>& coords) {
  const std::size_t left = data_.size() - static_cast<std::size_t>(lines_.position() - data_.data());
  coords.reserve(coords.size() + static_cast<std::size_t>(std::min<std::uint64_t>(
                                     n_vertices_, left / kMinVertexLineBytes + 1)) *
                                     static_cast<std::size_t>(dim));
  const char* b = nullptr;
  const char* e = nullptr;
  ParsedLine f;
  for (std::uint64_t i = 0; i < n_vertices_;) {
    if (!lines_.next(b, e, true))
      return error_at(
          StatusCode::ParseError, name_, lines_.line(),
          "OFF file ends after " + std::to_string(i) + " of " + plural(n_vertices_, "vertex line"));
    parse_line(b, e, dim, f);
    if (f.count == 0) continue;
    const std::size_t line = lines_.line();
    if (f.count == kEmptyField) return empty_field_error(name_, line);
    if (f.count < 3)
      return error_at(StatusCode::ParseError, name_, line,
                      "expected 3 coordinates, found " + std::to_string(f.count));
    Status st = check_values(f, dim, name_, line);
    if (!st) return st;
    coords.insert(coords.end(), f.value, f.value + dim);
    ++i;
  }
  return Status::ok();
}

std::size_t OffReader::next_fields(const char*& b, const char*& e, std::vector<Span>& fields) {
  std::size_t count = 0;
  do {
    if (!lines_.next(b, e, true)) return 0;
    fields.clear();
    count = split_fields(b, e, [&fields](std::size_t, const Span& s) { fields.push_back(s); });
  } while (count == 0);
  return count;
}

Status OffReader::after_vertices() {
  if (faces_known_) {
    // (A file that ends inside its faces lost no point: read as it is. A vertex line read as a
    // face line has fewer than 3 indices or fractional ones.)
    std::vector<std::int64_t> ids;
    for (std::uint64_t f = 0; f < n_faces_; ++f) {
      if (Status st = face(f, ids); !st) return ended_ ? Status::ok() : st;
      if (ids.size() < 3)
        return error_at(StatusCode::ParseError, name_, lines_.line(),
                        "a face has at least 3 vertices; if this line is a point, correct the vertex count");
      for (std::int64_t v : ids)
        if (v < 0 || static_cast<std::uint64_t>(v) >= n_vertices_)
          return error_at(StatusCode::ParseError, name_, lines_.line(),
                          "vertex index " + std::to_string(v) + " out of range (" + std::to_string(n_vertices_) +
                              (n_vertices_ == 1 ? " vertex" : " vertices") + "): correct the counts or the face");
    }
    return end();
  }
  const char* b = nullptr;
  const char* e = nullptr;
  std::vector<Span> fields;
  const std::size_t count = next_fields(b, e, fields);
  if (count == 0) return Status::ok();
  std::uint64_t k = 0;
  if (count != kEmptyField && parse_count(fields[0].b, fields[0].e, k) && k <= fields.size() - 1) return Status::ok();
  return error_at(StatusCode::ParseError, name_, lines_.line(),
                  "the header announces " + std::to_string(n_vertices_) + (n_vertices_ == 1 ? " vertex" : " vertices") + ", but the line after them, " +
                      quote(b, std::min(e, b + 40)) + ", is not a face line; correct the vertex count");
}

Status OffReader::end() {
  const char* b = nullptr;
  const char* e = nullptr;
  std::vector<Span> fields;
  if (next_fields(b, e, fields) != 0)
    return error_at(StatusCode::ParseError, name_, lines_.line(),
                    "more lines than the header announces (" + std::to_string(n_vertices_) +
                        (n_vertices_ == 1 ? " vertex" : " vertices") + " and " + plural(n_faces_, "face") + "), from " +
                        quote(b, std::min(e, b + 40)) + " on: correct the counts");
  return Status::ok();
}

Status OffReader::face(std::uint64_t f, std::vector<std::int64_t>& ids) {
  const char* b = nullptr;
  const char* e = nullptr;
  std::vector<Span> fields;
  const std::size_t count = next_fields(b, e, fields);
  if (count == 0) {
    ended_ = true;
    return error_at(StatusCode::ParseError, name_, lines_.line(),
                    "OFF file ends after " + std::to_string(f) + " of " + plural(n_faces_, "face line"));
  }
  const std::size_t line = lines_.line();
  if (count == kEmptyField) return empty_field_error(name_, line);
  std::uint64_t k = 0;
  if (!parse_count(fields[0].b, fields[0].e, k) || k > fields.size() - 1)
    return error_at(StatusCode::ParseError, name_, line,
                    "malformed face (count, then that many indices)");
  ids.assign(static_cast<std::size_t>(k), 0);
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const Span& s = fields[j + 1];
    const auto r = std::from_chars(s.b, s.e, ids[j]);
    if (r.ec != std::errc() || r.ptr != s.e)
      return error_at(StatusCode::ParseError, name_, line,
                      "malformed vertex index " + quote(s.b, s.e));
  }
  return Status::ok();
}

}  // namespace detail
}  // namespace constrict
