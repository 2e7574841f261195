// SPDX-License-Identifier: GPL-3.0-or-later
// Apex values, side values and the brute-force oracle (spec §2.1, §4.1).
// Signs come from exact predicates; magnitudes are evaluated in double with cancellation-free
// formulas, so that |γ| is accurate to a few ulps even when the apex is close to the sphere.
#include <algorithm>
#include <cmath>
#include <string>

#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/check_points.hpp"
#include "gamma/detail/apex2.hpp"
#include "gamma/detail/apex3.hpp"
#include "gamma/detail/reconcile.hpp"

namespace constrict {

void GammaFaces::reserve(std::size_t n) {
  vertices.reserve(n * static_cast<std::size_t>(dim));
  gamma_a.reserve(n);
  gamma_b.reserve(n);
  delta.reserve(n);
  flags.reserve(n);
}

void GammaFaces::push_back(const int* ids, double ga, double gb, std::uint8_t flag) {
  vertices.insert(vertices.end(), ids, ids + dim);
  gamma_a.push_back(ga);
  gamma_b.push_back(gb);
  delta.push_back(filtration_value(ga, gb));
  flags.push_back(flag);
}

double filtration_value(double gamma_a, double gamma_b) noexcept {
  return detail::filtration(gamma_a, gamma_b);
}

double apex_gamma2(const double* a, const double* b, const double* p) noexcept {
  int s = 0;
  return detail::apex2(a, b, p, s);
}

double apex_gamma3(const double* a, const double* b, const double* c, const double* p) noexcept {
  return detail::TriangleFrame3(a, b, c).apex(p);
}

void side_values_scan(const PointSet& points, const int* ids, double& gamma_a, double& gamma_b,
                      bool& blocked) {
  gamma_a = 1.0;
  gamma_b = 1.0;
  blocked = false;
  const std::size_t n = points.size();
  std::size_t arg_a = n, arg_b = n;  // apexes realising the side values
  if (points.dim == 2) {
    const double* a = points[static_cast<std::size_t>(ids[0])];
    const double* b = points[static_cast<std::size_t>(ids[1])];
    for (std::size_t i = 0; i < n; ++i) {
      if (static_cast<int>(i) == ids[0] || static_cast<int>(i) == ids[1]) continue;
      const double* p = points[i];
      const int o = orient2(a, b, p);
      if (o == 0) {
        if (diametral_side2(a, b, p) < 0) blocked = true;  // in the open segment
        continue;
      }
      const double g = apex_gamma2(a, b, p);
      if (o > 0 && g < gamma_a) { gamma_a = g; arg_a = i; }
      if (o < 0 && g < gamma_b) { gamma_b = g; arg_b = i; }
    }
    // The sign of γ_a + γ_b is exact: the in-circle test of the two realising apexes.
    if (arg_a < n && arg_b < n)
      detail::reconcile_side_values(gamma_a, gamma_b, in_circle(a, b, points[arg_a], points[arg_b]));
  } else {
    const double* a = points[static_cast<std::size_t>(ids[0])];
    const double* b = points[static_cast<std::size_t>(ids[1])];
    const double* c = points[static_cast<std::size_t>(ids[2])];
    for (std::size_t i = 0; i < n; ++i) {
      const int ii = static_cast<int>(i);
      if (ii == ids[0] || ii == ids[1] || ii == ids[2]) continue;
      const double* p = points[i];
      const int o = orient3(a, b, c, p);
      if (o == 0) {
        if (in_circle_coplanar3(a, b, c, p) > 0) blocked = true;  // in the open circumdisc
        continue;
      }
      const double g = apex_gamma3(a, b, c, p);
      if (o > 0 && g < gamma_a) { gamma_a = g; arg_a = i; }
      if (o < 0 && g < gamma_b) { gamma_b = g; arg_b = i; }
    }
    if (arg_a < n && arg_b < n)
      detail::reconcile_side_values(gamma_a, gamma_b, in_sphere(a, b, c, points[arg_a], points[arg_b]));
  }
}

Status brute_force_gamma_faces(const PointSet& points, GammaFaces& out) {
  if (Status f = detail::check_finite(points, "brute force oracle"); !f) return f;
  const std::size_t n = points.size();
  out.clear();
  out.dim = points.dim;
  auto flag_of = [](double ga, double gb, bool blocked) {
    std::uint8_t f = 0;
    if (blocked) f |= kFaceBlocked;
    else if (ga == 1.0 || gb == 1.0) f |= kFaceHull;
    return f;
  };
  if (points.dim == 2) {
    if (n > 400) return {StatusCode::Unsupported, "brute force oracle: at most 400 points in 2D"};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const int ids[2] = {static_cast<int>(i), static_cast<int>(j)};
        double ga, gb;
        bool blocked;
        side_values_scan(points, ids, ga, gb, blocked);
        out.push_back(ids, ga, gb, flag_of(ga, gb, blocked));
      }
  } else if (points.dim == 3) {
    if (n > 80) return {StatusCode::Unsupported, "brute force oracle: at most 80 points in 3D"};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        for (std::size_t k = j + 1; k < n; ++k) {
          if (collinear3(points[i], points[j], points[k])) continue;
          const int ids[3] = {static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)};
          double ga, gb;
          bool blocked;
          side_values_scan(points, ids, ga, gb, blocked);
          out.push_back(ids, ga, gb, flag_of(ga, gb, blocked));
        }
  } else {
    return {StatusCode::InvalidArgument, "brute force oracle: dimension must be 2 or 3"};
  }
  return Status::ok();
}

}  // namespace constrict
