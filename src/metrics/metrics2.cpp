// SPDX-License-Identifier: GPL-3.0-or-later
// 2D reference files (.gt) and combinatorial comparison of a polygon with a reference.
#include <algorithm>
#include <charconv>
#include <fstream>
#include <string>

#include "constrict/metrics.hpp"

namespace constrict {
namespace {

std::array<int, 2> edge(int u, int v) { return u < v ? std::array<int, 2>{{u, v}} : std::array<int, 2>{{v, u}}; }

void add_path(std::vector<std::array<int, 2>>& out, const std::vector<int>& p, bool closed) {
  if (p.size() < 2) return;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) out.push_back(edge(p[i], p[i + 1]));
  if (closed && p.size() > 2) out.push_back(edge(p.back(), p.front()));
}

}  // namespace

std::vector<std::array<int, 2>> Reference2::edges() const {
  std::vector<std::array<int, 2>> e;
  for (const auto& c : closed) add_path(e, c, true);
  for (const auto& o : open) add_path(e, o, false);
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

Status read_reference2(const std::string& path, std::size_t n_points, Reference2& out) {
  std::ifstream f(path);
  if (!f) return {StatusCode::FileNotFound, path + ": cannot open reference file"};
  Reference2 r;
  std::string line;
  std::size_t lineno = 0;
  while (std::getline(f, line)) {
    ++lineno;
    std::size_t pos = line.find_first_not_of(" \t\r");
    if (pos == std::string::npos || line[pos] == '#') continue;
    const char kind = line[pos];
    if ((kind == 'c' || kind == 'o') && line.find_first_not_of(" \t\r", pos + 1) == std::string::npos)
      return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": a component without indices ('" +
                                          std::string(1, kind) + "' alone)"};
    if ((kind != 'c' && kind != 'o') || pos + 1 >= line.size() || (line[pos + 1] != ' ' && line[pos + 1] != '\t'))
      return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": a component line starts with 'c' or 'o'"};
    std::vector<int> ids;
    const char* p = line.data() + pos + 1;
    const char* end = line.data() + line.size();
    while (true) {
      while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
      if (p >= end) break;
      long long v = 0;
      auto [q, ec] = std::from_chars(p, end, v);
      if (ec != std::errc() || (q < end && *q != ' ' && *q != '\t' && *q != '\r'))
        return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": malformed index"};
      if (v < 0 || static_cast<unsigned long long>(v) >= n_points)
        return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": index " + std::to_string(v) +
                                            " out of range (" + std::to_string(n_points) + " points)"};
      ids.push_back(static_cast<int>(v));
      p = q;
    }
    if (ids.empty()) return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": empty component"};
    (kind == 'c' ? r.closed : r.open).push_back(std::move(ids));
  }
  if (r.closed.empty() && r.open.empty()) return {StatusCode::EmptyInput, path + ": no component in reference file"};
  out = std::move(r);
  return Status::ok();
}

RingsComparison compare_rings2(const std::vector<std::vector<int>>& rings, const Reference2& reference) {
  RingsComparison c;
  std::vector<std::array<int, 2>> pe;
  for (const auto& r : rings) add_path(pe, r, true);
  std::sort(pe.begin(), pe.end());
  pe.erase(std::unique(pe.begin(), pe.end()), pe.end());
  const std::vector<std::array<int, 2>> re = reference.edges();
  std::vector<std::array<int, 2>> common;
  std::set_intersection(pe.begin(), pe.end(), re.begin(), re.end(), std::back_inserter(common));
  PolygonComparison& e = c.edges;
  e.reference_edges = re.size();
  e.polygon_edges = pe.size();
  e.recovered_edges = common.size();
  e.edge_recall = re.empty() ? 1.0 : static_cast<double>(common.size()) / static_cast<double>(re.size());
  e.edge_precision = pe.empty() ? 0.0 : static_cast<double>(common.size()) / static_cast<double>(pe.size());
  e.exact_match = reference.open.empty() && !reference.closed.empty() && pe == re;
  const auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<std::vector<int>> sets;
  for (const auto& r : rings) sets.push_back(sorted(r));
  std::sort(sets.begin(), sets.end());
  c.result_rings = rings.size();
  c.reference_rings = reference.closed.size();
  for (const auto& g : reference.closed)
    if (std::binary_search(sets.begin(), sets.end(), sorted(g))) ++c.same_point_sets;
  return c;
}

// One polygon is a ring set of one ring: a single cycle's edges equal the reference's only when
// the reference is that one closed curve.
PolygonComparison compare_polygon2(const std::vector<int>& polygon, const Reference2& reference) {
  return compare_rings2({polygon}, reference).edges;
}

}  // namespace constrict
