// SPDX-License-Identifier: GPL-3.0-or-later
// Selection criteria of the constriction (seed paper §2.6, §4, §6; docs/comparison-methods.md).
#include "constrict/criterion.hpp"

#include <cmath>
#include <cstring>

#include "constrict/gamma_graph.hpp"

namespace constrict {

const char* criterion_name(Criterion c) noexcept {
  switch (c) {
    case Criterion::Gamma: return "gamma";
    case Criterion::MinAreaChange: return "min-area-change";
    case Criterion::Boissonnat: return "boissonnat";
  }
  return "gamma";
}

bool criterion_from_name(const std::string& name, Criterion& out) noexcept {
  for (Criterion c : {Criterion::Gamma, Criterion::MinAreaChange, Criterion::Boissonnat})
    if (name == criterion_name(c)) {
      out = c;
      return true;
    }
  return false;
}

double area_change_ratio2(const double* a, const double* b, const double* y) noexcept {
  const double ay = std::hypot(y[0] - a[0], y[1] - a[1]);
  const double yb = std::hypot(b[0] - y[0], b[1] - y[1]);
  const double ab = std::hypot(b[0] - a[0], b[1] - a[1]);
  return (ay + yb - ab) / (ay + yb + ab);
}

double area_change_ratio3(const double areas[4], const bool on_boundary[4]) noexcept {
  double in = 0, bd = 0;
  for (int i = 0; i < 4; ++i) (on_boundary[i] ? bd : in) += areas[i];
  return (in - bd) / (in + bd);
}

double triangle_area3(const double* a, const double* b, const double* c) noexcept {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

double criterion_key2(Criterion c, const double* a, const double* b, const double* y) noexcept {
  // Boissonnat's 84a criterion equals γ for one boundary segment (seed paper §6): in 2D always.
  if (c == Criterion::MinAreaChange) return -area_change_ratio2(a, b, y);
  return 1.0 - apex_gamma2(a, b, y);
}

}  // namespace constrict
