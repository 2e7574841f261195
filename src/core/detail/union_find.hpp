// SPDX-License-Identifier: GPL-3.0-or-later
// Union-find over 0..n-1 with path halving; the root of a set is always its smallest member, so
// the sets and their roots depend only on the joins made, not on their order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace constrict::detail {

struct UnionFind {
  std::vector<int> up;
  explicit UnionFind(std::size_t n) : up(n) { std::iota(up.begin(), up.end(), 0); }
  int find(int x) {
    while (up[static_cast<std::size_t>(x)] != x)
      x = up[static_cast<std::size_t>(x)] = up[static_cast<std::size_t>(up[static_cast<std::size_t>(x)])];
    return x;
  }
  // false when a and b were in one set already.
  bool join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    up[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    return true;
  }
};

}  // namespace constrict::detail
