// SPDX-License-Identifier: GPL-3.0-or-later
// The double sum behind signed_volume_sign()'s filter (VolumeEstimate), one triangle at a time:
// shared by signed_volume_estimate() (src/cgal/predicates.cpp) and the mesh check's one pass that
// also sums mesh_volume() (the same terms in the same order: the same bits).
#pragma once
#include <cmath>
#include <cstddef>

#include "constrict/predicates.hpp"

namespace constrict::detail {

// The translated determinants about o (the first point of the first triangle) in double: their
// sum S and a bound on |S - exact|. Each translated coordinate has relative error <= eps, each
// determinant <= 5 eps of its permanent on top, the sum n eps of the permanents: |S - exact| <=
// (n + 16) * 2^-52 * P (generous), valid without overflow and underflow.
class VolumeFilterSum {
 public:
  explicit VolumeFilterSum(const double* o) : o_(o) {}
  void add(const double* a, const double* b, const double* c) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = a[k] - o_[k];
      v[k] = b[k] - o_[k];
      w[k] = c[k] - o_[k];
    }
    const double d = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                     u[2] * (v[0] * w[1] - v[1] * w[0]);
    const double p = std::abs(u[0]) * (std::abs(v[1] * w[2]) + std::abs(v[2] * w[1])) +
                     std::abs(u[1]) * (std::abs(v[0] * w[2]) + std::abs(v[2] * w[0])) +
                     std::abs(u[2]) * (std::abs(v[0] * w[1]) + std::abs(v[1] * w[0]));
    sum_ += d;
    perm_ += p;
  }
  // valid false: the bound does not hold (overflow, underflow).
  VolumeEstimate estimate(std::size_t n_tris) const {
    VolumeEstimate e;
    e.sum6 = sum_;
    e.bound6 = (static_cast<double>(n_tris) + 16.0) * std::ldexp(1.0, -52) * perm_;
    e.valid = n_tris > 0 && std::isfinite(e.sum6) && std::isfinite(e.bound6) && perm_ > 1e-280;
    return e;
  }

 private:
  const double* o_;
  double sum_ = 0, perm_ = 0;
};

}  // namespace constrict::detail
