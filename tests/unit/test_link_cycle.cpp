// SPDX-License-Identifier: GPL-3.0-or-later
// detail::link_is_one_cycle (the region passes' and the body repair's link test) against its
// definition: every link vertex of degree 2 and the link connected (union-find), on random links
// of 3-300 edges (seeds printed): one cycle, two cycles, a cycle with a chord, with a repeated
// edge, with a dangling edge; each in a shuffled order with shuffled ends. Links of more than 32
// edges take the sorted path, shorter ones the scan: both are checked on the same kinds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "core/detail/link_cycle.hpp"

namespace constrict {
namespace {

bool by_definition(const std::vector<std::array<int, 2>>& link) {
  if (link.size() < 3) return false;
  std::map<int, int> degree, parent;
  for (const auto& e : link)
    for (int v : e) {
      ++degree[v];
      parent.emplace(v, v);
    }
  for (const auto& d : degree)
    if (d.second != 2) return false;
  const auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& e : link) parent[find(e[0])] = find(e[1]);
  const int root = find(link[0][0]);
  for (const auto& d : degree)
    if (find(d.first) != root) return false;
  return true;
}

std::vector<std::array<int, 2>> cycle(const std::vector<int>& v) {
  std::vector<std::array<int, 2>> e;
  for (std::size_t i = 0; i < v.size(); ++i) e.push_back({v[i], v[(i + 1) % v.size()]});
  return e;
}

TEST(LinkCycle, MatchesTheDefinitionOnRandomLinks) {
  int agree = 0, ones = 0;
  for (unsigned seed = 1; seed <= 400; ++seed) {
    std::mt19937 rng(seed);
    const int L = 3 + static_cast<int>(rng() % 298);
    std::vector<int> ids(static_cast<std::size_t>(L) + 3);
    std::iota(ids.begin(), ids.end(), 1000);
    std::shuffle(ids.begin(), ids.end(), rng);
    std::vector<std::array<int, 2>> link;
    const int kind = static_cast<int>(seed % 6);
    const std::vector<int> first(ids.begin(), ids.begin() + L);
    if (kind == 1 && L >= 6) {  // two cycles
      link = cycle(std::vector<int>(first.begin(), first.begin() + L / 2));
      const auto b = cycle(std::vector<int>(first.begin() + L / 2, first.end()));
      link.insert(link.end(), b.begin(), b.end());
    } else {
      link = cycle(first);
      if (kind == 2) link.push_back({first[0], first[static_cast<std::size_t>(L / 2)]});  // a chord
      if (kind == 3) link.push_back(link[static_cast<std::size_t>(L) / 3]);               // an edge twice
      if (kind == 4) link.push_back({first[0], ids[static_cast<std::size_t>(L)]});        // a dangling edge
      if (kind == 5) link.pop_back();                                                     // a path
    }
    std::shuffle(link.begin(), link.end(), rng);
    for (auto& e : link)
      if (rng() % 2) std::swap(e[0], e[1]);
    const bool want = by_definition(link);
    const bool got = detail::link_is_one_cycle(link);
    EXPECT_EQ(got, want) << "seed " << seed << ", kind " << kind << ", " << link.size() << " edges";
    agree += got == want;
    ones += want;
  }
  std::printf("[link] 400 random links: %d agree with the definition, %d of them one cycle\n", agree, ones);
  EXPECT_GT(ones, 50);
}

}  // namespace
}  // namespace constrict
