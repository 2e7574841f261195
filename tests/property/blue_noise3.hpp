// SPDX-License-Identifier: GPL-3.0-or-later
// Blue-noise sampling shared by the 3D test generators (gaps3_gen.hpp, thin_walls3_gen.hpp):
// a uniform double stream from splitmix64, and dart throwing over shuffled candidates.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "unit/test_fixtures.hpp"

namespace constrict::test {

// Uniform doubles in [0, 1) from splitmix64 (the same on every platform).
struct Rng01 {
  std::uint64_t s;
  double next() { return static_cast<double>(splitmix64(s) >> 11) * 0x1.0p-53; }
};

struct DartCandidate {
  std::array<double, 3> p;
  double rad;  // its minimum distance to the others
};

// Shuffles the candidates (Fisher-Yates, from rng) and keeps, in that order, each one farther than
// the larger radius of the two from every candidate kept before it. cell: at least every radius.
inline std::vector<DartCandidate> dart_throw(std::vector<DartCandidate> cand, double cell, Rng01& rng) {
  for (std::size_t k = cand.size(); k > 1; --k) std::swap(cand[k - 1], cand[static_cast<std::size_t>(rng.next() * double(k))]);
  std::map<std::tuple<long, long, long>, std::vector<std::size_t>> grid;
  std::vector<DartCandidate> kept;
  for (const DartCandidate& c : cand) {
    const long cx = std::lround(std::floor(c.p[0] / cell)), cy = std::lround(std::floor(c.p[1] / cell)),
               cz = std::lround(std::floor(c.p[2] / cell));
    bool ok = true;
    for (long dx = -1; dx <= 1 && ok; ++dx)
      for (long dy = -1; dy <= 1 && ok; ++dy)
        for (long dz = -1; dz <= 1 && ok; ++dz) {
          const auto it = grid.find({cx + dx, cy + dy, cz + dz});
          if (it == grid.end()) continue;
          for (std::size_t k : it->second) {
            const DartCandidate& q = kept[k];
            const double rr = std::max(c.rad, q.rad);
            const double d2 = (c.p[0] - q.p[0]) * (c.p[0] - q.p[0]) + (c.p[1] - q.p[1]) * (c.p[1] - q.p[1]) +
                              (c.p[2] - q.p[2]) * (c.p[2] - q.p[2]);
            if (d2 < rr * rr) {
              ok = false;
              break;
            }
          }
        }
    if (!ok) continue;
    grid[{cx, cy, cz}].push_back(kept.size());
    kept.push_back(c);
  }
  return kept;
}

}  // namespace constrict::test
