// SPDX-License-Identifier: GPL-3.0-or-later
// Is a vertex's link one cycle? The link is given as its edges (the surface faces at the vertex,
// each with the vertex left out): every link vertex has degree 2 and one walk passes every edge.
// Shared by the 3D engine's region passes (carve3.cpp) and the auto topology's body repair
// (repair3.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace constrict::detail {

// (Equivalently: every link vertex has degree 2 and the link is connected.) Short links (the
// usual case: 4-8 edges) by scanning; long ones (a point on the axis of a sampled circle has
// thousands of tetrahedra around it) in O(L log L) — the scan was O(L^2) per link test and took
// a fill pass 77 s on 4 000 points.
inline bool link_is_one_cycle(const std::vector<std::array<int, 2>>& link) {
  if (link.size() < 3) return false;
  constexpr std::size_t kScanMax = 32;
  if (link.size() > kScanMax) {
    // Each end (vertex, edge) once; sorted, a vertex's two edges are next to each other.
    std::vector<std::pair<int, std::size_t>> ends;
    ends.reserve(2 * link.size());
    for (std::size_t j = 0; j < link.size(); ++j) {
      ends.emplace_back(link[j][0], j);
      ends.emplace_back(link[j][1], j);
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t k = 0; k < ends.size(); k += 2)  // every vertex exactly twice
      if (ends[k + 1].first != ends[k].first || (k + 2 < ends.size() && ends[k + 2].first == ends[k].first))
        return false;
    std::size_t steps = 0, cur_e = 0;
    int cur = link[0][1];
    do {
      const auto it = std::lower_bound(ends.begin(), ends.end(), std::make_pair(cur, std::size_t{0}));
      const std::size_t next_e = it->second == cur_e ? (it + 1)->second : it->second;
      cur = link[next_e][0] == cur ? link[next_e][1] : link[next_e][0];
      cur_e = next_e;
      ++steps;
    } while (cur_e != 0 && steps <= link.size());
    return steps == link.size();
  }
  std::size_t steps = 0, cur_e = 0;
  int cur = link[0][1];
  for (;;) {
    std::size_t next_e = SIZE_MAX;
    int deg = 0;
    for (std::size_t j = 0; j < link.size(); ++j)
      if (link[j][0] == cur || link[j][1] == cur) {
        ++deg;
        if (j != cur_e) next_e = j;
      }
    if (deg != 2) return false;
    ++steps;
    cur = link[next_e][0] == cur ? link[next_e][1] : link[next_e][0];
    cur_e = next_e;
    if (cur_e == 0) break;
    if (steps > link.size()) return false;
  }
  return steps == link.size();
}

}  // namespace constrict::detail
