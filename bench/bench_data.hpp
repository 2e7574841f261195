// SPDX-License-Identifier: GPL-3.0-or-later
// Deterministic point generators for the benchmarks (fixed seeds).
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

#include "constrict/points.hpp"

namespace constrict::bench {

enum class Dist { Uniform = 0, Surface = 1 };
inline const char* dist_name(Dist d) { return d == Dist::Uniform ? "uniform" : "surface"; }

/// 2D: uniform in the unit square, or on a closed five-petal curve with tiny noise.
inline PointSet points2(std::size_t n, Dist d, std::uint64_t seed = 42) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointSet p;
  p.dim = 2;
  p.coords.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (d == Dist::Uniform) {
      p.coords[2 * i] = u(rng);
      p.coords[2 * i + 1] = u(rng);
    } else {
      const double t = 2 * M_PI * u(rng);
      const double r = (1 + 0.3 * std::cos(5 * t)) * (1 + 1e-4 * (u(rng) - 0.5));
      p.coords[2 * i] = r * std::cos(t);
      p.coords[2 * i + 1] = r * std::sin(t);
    }
  }
  return p;
}

/// 2D: n points exactly on the closed five-petal curve r(t) = 1 + 0.3 cos(5t), t uniform at
/// random: "sampled on a closed curve" up to double rounding, no noise band (so no lock).
inline PointSet curve_points2(std::size_t n, std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 2 * M_PI);
  PointSet p;
  p.dim = 2;
  p.coords.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = u(rng), r = 1 + 0.3 * std::cos(5 * t);
    p.coords[2 * i] = r * std::cos(t);
    p.coords[2 * i + 1] = r * std::sin(t);
  }
  return p;
}

/// 3D: uniform in the unit cube, or on an ellipsoid surface with tiny noise.
inline PointSet points3(std::size_t n, Dist d, std::uint64_t seed = 42) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  PointSet p;
  p.dim = 3;
  p.coords.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (d == Dist::Uniform) {
      for (int k = 0; k < 3; ++k) p.coords[3 * i + static_cast<std::size_t>(k)] = u(rng);
    } else {
      double v[3] = {g(rng), g(rng), g(rng)};
      const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / (1 + 1e-4 * (u(rng) - 0.5));
      p.coords[3 * i] = 2.0 * v[0] / len;
      p.coords[3 * i + 1] = 1.2 * v[1] / len;
      p.coords[3 * i + 2] = 0.8 * v[2] / len;
    }
  }
  return p;
}

}  // namespace constrict::bench
