// SPDX-License-Identifier: GPL-3.0-or-later
// The STL reader shared by read_points() and read_mesh() (contract: io/detail/stl.hpp).
#include "io/detail/stl.hpp"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace constrict {
namespace detail {
namespace {

Status at(StatusCode c, const std::string& name, std::size_t line, const std::string& what) {
  return {c, name + ":" + std::to_string(line) + ": " + what};
}

bool to_double(std::string_view t, double& v) {
  const auto r = fast_float::from_chars(t.data(), t.data() + t.size(), v);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char buf[sizeof(T)];
  std::memcpy(buf, p, sizeof(T));
  if (swap) std::reverse(buf, buf + sizeof(T));
  T v;
  std::memcpy(&v, buf, sizeof(T));
  return v;
}

// Splits a text buffer into lines (without '\n', '\r' stripped).
struct Lines {
  std::string_view data;
  std::size_t pos = 0, line = 0;
  bool next(std::string_view& out) {
    if (pos >= data.size()) return false;
    std::size_t e = data.find('\n', pos);
    if (e == std::string_view::npos) e = data.size();
    out = data.substr(pos, e - pos);
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    pos = e + 1;
    ++line;
    return true;
  }
};

void words(std::string_view s, std::vector<std::string_view>& w) {
  w.clear();
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    if (i >= s.size() || s[i] == '#') break;
    std::size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    w.push_back(s.substr(i, j - i));
    i = j;
  }
}

// Identical corner coordinates are one vertex (first occurrence order).
class Corners {
 public:
  explicit Corners(std::vector<double>& coords) : coords_(coords), first_(coords.size() / 3) {}
  std::int64_t id(const std::array<double, 3>& p) {
    ++count_;
    auto [it, fresh] = ids_.emplace(p, static_cast<std::int64_t>(coords_.size() / 3 - first_));
    if (fresh) coords_.insert(coords_.end(), p.begin(), p.end());
    return it->second;
  }
  std::size_t count() const noexcept { return count_; }

 private:
  std::vector<double>& coords_;
  std::size_t first_;
  std::size_t count_ = 0;
  std::map<std::array<double, 3>, std::int64_t> ids_;
};

Status read_binary(const unsigned char* base, std::uint32_t n, bool swap, const std::string& name,
                   Corners& corners, StlFacetSink* facets) {
  std::vector<std::int64_t> tri;
  for (std::uint32_t f = 0; f < n; ++f) {
    tri.clear();
    for (int v = 0; v < 3; ++v) {
      std::array<double, 3> p{};
      for (int k = 0; k < 3; ++k)
        p[static_cast<std::size_t>(k)] =
            static_cast<double>(load<float>(base + 84 + 50ull * f + 12 + 12 * v + 4 * k, swap));
      for (double c : p)
        if (!std::isfinite(c))
          return {StatusCode::NonFinite, name + ": STL triangle " + std::to_string(f) + ": non-finite coordinate"};
      tri.push_back(corners.id(p));
    }
    if (facets != nullptr) facets->facet(tri);
  }
  return Status::ok();
}

Status read_ascii(std::string_view data, const std::string& name, Corners& corners, StlFacetSink* facets) {
  Lines L{data};
  std::string_view s;
  std::vector<std::string_view> w;
  std::vector<std::int64_t> tri;
  bool solid = false;
  while (L.next(s)) {
    words(s, w);
    if (w.empty()) continue;
    if (!solid) {
      if (w[0] != "solid")
        return at(StatusCode::ParseError, name, L.line, "not a binary STL (size mismatch) and not ASCII STL ('solid')");
      solid = true;
    } else if (w[0] == "vertex") {
      std::array<double, 3> p{};
      if (w.size() != 4) return at(StatusCode::ParseError, name, L.line, "a vertex needs 3 coordinates");
      for (int k = 0; k < 3; ++k)
        if (!to_double(w[static_cast<std::size_t>(k + 1)], p[static_cast<std::size_t>(k)]))
          return at(StatusCode::ParseError, name, L.line, "malformed number");
      for (double c : p)
        if (!std::isfinite(c)) return at(StatusCode::NonFinite, name, L.line, "non-finite vertex coordinate");
      tri.push_back(corners.id(p));
    } else if (w[0] == "endloop") {
      if (tri.size() < 3) return at(StatusCode::ParseError, name, L.line, "a facet needs at least 3 vertices");
      if (facets != nullptr) facets->facet(tri);
      tri.clear();
    }
  }
  return Status::ok();
}

}  // namespace

Status read_stl(std::string_view data, const std::string& name, std::vector<double>& coords,
                StlFacetSink* facets, std::size_t& corners) {
  Corners ids(coords);
  const auto* base = reinterpret_cast<const unsigned char*>(data.data());
  const bool little_host = [] {
    const std::uint16_t x = 1;
    unsigned char c;
    std::memcpy(&c, &x, 1);
    return c == 1;
  }();
  Status st;
  bool binary = false;
  if (data.size() >= 84) {
    const auto n = load<std::uint32_t>(base + 80, !little_host);
    if (84 + 50ull * n == data.size()) {
      binary = true;
      st = read_binary(base, n, !little_host, name, ids, facets);
    }
  }
  // Binary data whose size does not match its facet count (truncated, or bytes appended): its
  // header often starts with "solid" too, and the ASCII reader found no vertex in it ("no
  // points"). ASCII STL holds no NUL byte.
  if (!binary && data.size() >= 84 &&
      std::memchr(data.data(), 0, std::min<std::size_t>(data.size(), 4096)) != nullptr) {
    const auto n = load<std::uint32_t>(base + 80, !little_host);
    corners = 0;
    return {StatusCode::ParseError, name + ": a binary STL of " + std::to_string(data.size()) + " bytes, but its " +
                                        std::to_string(n) + " facets need 84 + 50 x " + std::to_string(n) + " = " +
                                        std::to_string(84 + 50ull * n) + ": the file is truncated or damaged"};
  }
  if (!binary) st = read_ascii(data, name, ids, facets);
  corners = ids.count();
  return st;
}

}  // namespace detail
}  // namespace constrict
