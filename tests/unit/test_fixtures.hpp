// SPDX-License-Identifier: GPL-3.0-or-later
// Small fixture helpers shared by the unit tests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/points.hpp"

namespace constrict::test {

#ifdef CONSTRICT_TEST_DATA_DIR
/// A 3D point file of tests/data/regression, by its name.
inline Status read_regression3(const std::string& name, PointSet& p) {
  ReadOptions ro;
  ro.dim = 3;
  return read_points(std::string(CONSTRICT_TEST_DATA_DIR) + "/regression/" + name, ro, p);
}
#endif

/// splitmix64: the next value of the sequence of state s (the same numbers on every platform).
inline std::uint64_t splitmix64(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// A 2D PointSet from coordinate pairs.
inline PointSet make2(const std::vector<std::array<double, 2>>& xy) {
  PointSet p;
  p.dim = 2;
  for (const auto& q : xy) {
    p.coords.push_back(q[0]);
    p.coords.push_back(q[1]);
  }
  return p;
}

/// n points at uniformly random positions along a five-petal closed curve (r = 1 + 0.3 cos 5t,
/// about 7.3 long), with normal noise of standard deviation h per coordinate (default 7/n, about
/// one spacing): large enough, it splits into arcs, and the 2D constriction locks inside the band.
inline PointSet noisy_petal_curve(std::size_t n, unsigned seed, double h = -1) {
  if (h < 0) h = 7.0 / static_cast<double>(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> along(0, 2 * M_PI);
  std::normal_distribution<double> noise(0, 1);
  PointSet p;
  p.dim = 2;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = along(rng), r = 1 + 0.3 * std::cos(5 * t);
    p.coords.push_back(r * std::cos(t) + h * noise(rng));
    p.coords.push_back(r * std::sin(t) + h * noise(rng));
  }
  return p;
}

/// A 3D PointSet from coordinate triples.
inline PointSet make3(const std::vector<std::array<double, 3>>& xyz) {
  PointSet p;
  p.dim = 3;
  for (const auto& q : xyz) p.coords.insert(p.coords.end(), q.begin(), q.end());
  return p;
}

// Signed volume of a set of tetrahedra over the points (double arithmetic).
inline double tets_volume(const PointSet& p, const std::vector<std::array<int, 4>>& tets) {
  double v = 0;
  for (const auto& t : tets) {
    const double* a = p[static_cast<std::size_t>(t[0])];
    double m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = p[static_cast<std::size_t>(t[static_cast<std::size_t>(r + 1)])][c] - a[c];
    v += (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) / 6;
  }
  return v;
}

}  // namespace constrict::test
