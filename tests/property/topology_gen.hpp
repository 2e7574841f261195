// SPDX-License-Identifier: GPL-3.0-or-later
// Generator of 2D ring sets with known topology for the topology tests (docs/topology.md
// §"Generator"): annuli, shells with holes, separate parts, island in a lake in an island, curves
// sampled at about one spacing h (jittered along the arc, or at random angles with normal noise),
// every two curves gap·h apart, then a
// random rotation, scale and offset, and the points shuffled. Deterministic per seed.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "constrict/points.hpp"

namespace constrict::test {

enum class TopoFamily { Annulus, Holes, Parts, Nested };

/// One true ring: its points (input indices, any order), role and parent.
struct TrueRing {
  bool shell = true;
  int parent = -1;
  std::vector<int> points;
};

struct TopoSample {
  PointSet points;
  std::vector<TrueRing> rings;
  double spacing = 0;  ///< the sampling step after the random scale
};

namespace detail_gen {
struct Circle {
  double cx, cy, r;
  bool shell;
  int parent;
};
}  // namespace detail_gen

/// @param gap distance between neighbouring curves in spacings (>= 1)
/// @param h the spacing (before the random scale)
/// @param noise < 0: the points jittered along the arc by up to 0.3 h; >= 0: the points at
///   uniformly random angles (the mean spacing h, gaps up to about ln(n) h), then moved by normal
///   noise of noise·h per coordinate (a scan's samples)
inline TopoSample make_topology(TopoFamily f, double gap, unsigned seed, double h = 1.0, double noise = -1) {
  using detail_gen::Circle;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double g = gap * h;
  std::vector<Circle> c;
  const double R = 20 * h + 10 * h * u(rng);
  switch (f) {
    case TopoFamily::Annulus:
      c = {{0, 0, R, true, -1}, {0, 0, R - g, false, 0}};
      break;
    case TopoFamily::Holes: {  // three holes of radius R/5 along a diameter
      const double r = R / 5;
      c = {{0, 0, R, true, -1}};
      for (int k = -1; k <= 1; ++k) c.push_back({k * (2 * r + g), 0, r, false, 0});
      break;
    }
    case TopoFamily::Parts: {  // three separate discs in a row, gap between neighbours
      const double r = R / 3;
      for (int k = 0; k < 3; ++k) c.push_back({k * (2 * r + g), 0, r, true, -1});
      break;
    }
    case TopoFamily::Nested:  // shell ⊃ hole ⊃ island ⊃ lake
      c = {{0, 0, R, true, -1}, {0, 0, R - g, false, 0}, {0, 0, R - 2 * g - 2 * h, true, 1}, {0, 0, R - 3 * g - 2 * h, false, 2}};
      break;
  }
  const double angle = 2 * M_PI * u(rng), scale = std::exp(6 * u(rng) - 3), ox = 200 * u(rng) - 100, oy = 200 * u(rng) - 100;
  TopoSample s;
  s.points.dim = 2;
  s.spacing = scale * h;
  for (std::size_t k = 0; k < c.size(); ++k) {
    TrueRing tr;
    tr.shell = c[k].shell;
    tr.parent = c[k].parent;
    const int n = std::max(8, static_cast<int>(std::lround(2 * M_PI * c[k].r / h)));
    const double phase = 2 * M_PI * u(rng);
    std::normal_distribution<double> normal(0, 1);
    for (int i = 0; i < n; ++i) {
      const double t = noise < 0 ? phase + 2 * M_PI * (i + 0.3 * (2 * u(rng) - 1)) / n : 2 * M_PI * u(rng);
      double x = c[k].cx + c[k].r * std::cos(t), y = c[k].cy + c[k].r * std::sin(t);
      if (noise >= 0) {
        x += noise * h * normal(rng);
        y += noise * h * normal(rng);
      }
      const double xr = std::cos(angle) * x - std::sin(angle) * y, yr = std::sin(angle) * x + std::cos(angle) * y;
      tr.points.push_back(static_cast<int>(s.points.size()));
      s.points.coords.push_back(ox + scale * xr);
      s.points.coords.push_back(oy + scale * yr);
    }
    s.rings.push_back(std::move(tr));
  }
  // Shuffle the point order, and the ring point ids with it.
  const std::size_t n = s.points.size();
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);  // new index of old point i = perm[i]
  std::vector<double> xy(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    xy[2 * static_cast<std::size_t>(perm[i])] = s.points.coords[2 * i];
    xy[2 * static_cast<std::size_t>(perm[i]) + 1] = s.points.coords[2 * i + 1];
  }
  s.points.coords = xy;
  for (auto& r : s.rings)
    for (int& v : r.points) v = perm[static_cast<std::size_t>(v)];
  return s;
}

}  // namespace constrict::test
