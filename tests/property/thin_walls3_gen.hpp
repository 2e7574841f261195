// SPDX-License-Identifier: GPL-3.0-or-later
// Generator of a ball with a thin plate (an ear, a fin) standing out of it, for the tests of
// thin parts the labels miss (docs/reconstruction-3d.md §4.9): the plate is 1-2 sample spacings
// thick, so the circumballs of its tetrahedra reach through both its faces and the labels see no
// inside in it. Blue-noise samples of the union's boundary (dart throwing, minimum distance
// 0.75 h; each point moved by up to 0.02 h), turned by a fixed rotation, and the exact signed
// distance to the true surface. Deterministic per seed (splitmix64).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "constrict/points.hpp"
#include "blue_noise3.hpp"
#include "unit/test_fixtures.hpp"

namespace constrict::test {

struct ThinWallObject {
  double h = 1;          // sample spacing
  double radius = 0;     // the ball's
  std::array<double, 3> half{};  // the plate's half sizes (x out of the ball, y along, z thickness)
  double rot[3][3]{};    // model -> output coordinates
  PointSet points;
};

namespace detail_thin3 {
using P = std::array<double, 3>;
using Rng = Rng01;
// The plate's box: centred on the x axis, its inner end inside the ball.
inline P plate_centre(const ThinWallObject& o) { return {o.radius + o.half[0] - 2 * o.h, 0, 0}; }
inline double box_sdf(const ThinWallObject& o, const P& p) {
  const P c = plate_centre(o);
  double q[3], outside = 0, inside = -HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    q[k] = std::abs(p[k] - c[k]) - o.half[k];
    outside += std::max(q[k], 0.0) * std::max(q[k], 0.0);
    inside = std::max(inside, q[k]);
  }
  return std::sqrt(outside) + std::min(inside, 0.0);
}
inline double ball_sdf(const ThinWallObject& o, const P& p) {
  return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - o.radius;
}
}  // namespace detail_thin3

// Signed distance (model coordinates) to the union's boundary: exact outside, and inside the
// distance to the nearer solid's own boundary (a lower bound).
inline double thin_wall_distance_model(const ThinWallObject& o, const std::array<double, 3>& p) {
  const double a = detail_thin3::ball_sdf(o, p), b = detail_thin3::box_sdf(o, p);
  if (a < 0 || b < 0) return std::max(-a, -b);  // inside: at least as deep as in either solid
  return std::min(a, b);
}
// The same for a point in output coordinates (the rotation undone).
inline double thin_wall_distance(const ThinWallObject& o, const std::array<double, 3>& q) {
  std::array<double, 3> p{};
  for (int i = 0; i < 3; ++i) p[i] = o.rot[0][i] * q[0] + o.rot[1][i] * q[1] + o.rot[2][i] * q[2];
  return thin_wall_distance_model(o, p);
}

// A ball of radius `radius` (in h) and a plate `thickness` h thick, `length` h out of it and
// `width` h wide.
inline ThinWallObject make_thin_wall(double radius, double thickness, double length, double width, std::uint64_t seed) {
  using detail_thin3::P;
  ThinWallObject o;
  o.radius = radius;
  o.half = {(length + 2) / 2, width / 2, thickness / 2};
  detail_thin3::Rng rng{seed * 0x9e3779b97f4a7c15ULL + 3};
  // A fixed rotation (no face of the plate parallel to a coordinate plane).
  const double a = 0.61, b = 0.37, c = 0.23;
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b), cc = std::cos(c), sc = std::sin(c);
  const double R[3][3] = {{cb * cc, -cb * sc, sb}, {sa * sb * cc + ca * sc, -sa * sb * sc + ca * cc, -sa * cb},
                          {-ca * sb * cc + sa * sc, ca * sb * sc + sa * cc, ca * cb}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) o.rot[i][j] = R[i][j];
  std::vector<P> cand;
  const double rad = 0.75 * o.h;
  // The ball.
  const auto n_ball = static_cast<std::size_t>(4 * 4 * M_PI * radius * radius / (rad * rad));
  for (std::size_t k = 0; k < n_ball; ++k) {
    const double z = 2 * rng.next() - 1, th = 2 * M_PI * rng.next(), s = std::sqrt(1 - z * z);
    const P p{radius * s * std::cos(th), radius * s * std::sin(th), radius * z};
    if (detail_thin3::box_sdf(o, p) > 1e-9) cand.push_back(p);
  }
  // The plate's six faces, by area.
  const P ctr = detail_thin3::plate_centre(o);
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const double area = 4 * o.half[u] * o.half[v];
      const auto n = static_cast<std::size_t>(4 * area / (rad * rad)) + 1;
      for (std::size_t k = 0; k < n; ++k) {
        P p = ctr;
        p[axis] += sign * o.half[axis];
        p[u] += (2 * rng.next() - 1) * o.half[u];
        p[v] += (2 * rng.next() - 1) * o.half[v];
        if (detail_thin3::ball_sdf(o, p) > 1e-9) cand.push_back(p);
      }
    }
  std::vector<DartCandidate> darts;
  for (const P& p : cand) darts.push_back({p, rad});
  const std::vector<DartCandidate> kept = dart_throw(std::move(darts), rad, rng);
  o.points.dim = 3;
  for (const DartCandidate& d : kept) {
    P p = d.p;
    for (double& x : p) x += 0.02 * o.h * (2 * rng.next() - 1);
    for (int i = 0; i < 3; ++i) o.points.coords.push_back(R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2]);
  }
  return o;
}

}  // namespace constrict::test
