// SPDX-License-Identifier: GPL-3.0-or-later
// Is a vertex's link one cycle? The link is given as its edges (the surface faces at the vertex,
// each with the vertex left out): every link vertex has degree 2 and one walk passes every edge.
// Shared by the 3D engine's region passes (carve3.cpp) and the auto topology's body repair
// (surfaces3.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace constrict::detail {

inline bool link_is_one_cycle(const std::vector<std::array<int, 2>>& link) {
  if (link.size() < 3) return false;
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
