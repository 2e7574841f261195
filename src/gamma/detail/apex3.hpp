// SPDX-License-Identifier: GPL-3.0-or-later
// Apex values of several points against one triangle, sharing the triangle's circumcentre
// (the hot loop of delaunay_gamma3). Same results as apex_gamma3.
#pragma once
#include <algorithm>
#include <cmath>

#include "cgal/detail/exact_apex3.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/semi_static.hpp"

namespace constrict::detail {

// A sliver: sin² of the angle at a below this, the double cross product e1 x e2 has a relative
// error above ~2^-32 (a few ulps / sin) and the magnitudes are evaluated exactly instead.
constexpr double kExactMagnitudeSin2 = 0x1p-40;  // (~1e-12: extra_faces.cpp's kSliverSin2)

class TriangleFrame3 {
 public:
  TriangleFrame3(const double* a, const double* b, const double* c) : a_(a), b_(b), c_(c) {
    for (int i = 0; i < 3; ++i) {
      e1_[i] = b[i] - a[i];
      e2_[i] = c[i] - a[i];
    }
    n_[0] = e1_[1] * e2_[2] - e1_[2] * e2_[1];
    n_[1] = e1_[2] * e2_[0] - e1_[0] * e2_[2];
    n_[2] = e1_[0] * e2_[1] - e1_[1] * e2_[0];
    const double ae1[3] = {std::fabs(e1_[0]), std::fabs(e1_[1]), std::fabs(e1_[2])};
    const double ae2[3] = {std::fabs(e2_[0]), std::fabs(e2_[1]), std::fabs(e2_[2])};
    const double an[3] = {ae1[1] * ae2[2] + ae1[2] * ae2[1], ae1[2] * ae2[0] + ae1[0] * ae2[2],
                          ae1[0] * ae2[1] + ae1[1] * ae2[0]};
    const double l1 = e1_[0] * e1_[0] + e1_[1] * e1_[1] + e1_[2] * e1_[2];
    const double l2 = e2_[0] * e2_[0] + e2_[1] * e2_[1] + e2_[2] * e2_[2];
    double w[3], aw[3];
    for (int i = 0; i < 3; ++i) {
      w[i] = l1 * e2_[i] - l2 * e1_[i];
      aw[i] = l1 * ae2[i] + l2 * ae1[i];
    }
    wn_[0] = w[1] * n_[2] - w[2] * n_[1];
    wn_[1] = w[2] * n_[0] - w[0] * n_[2];
    wn_[2] = w[0] * n_[1] - w[1] * n_[0];
    awn_[0] = aw[1] * an[2] + aw[2] * an[1];
    awn_[1] = aw[2] * an[0] + aw[0] * an[2];
    awn_[2] = aw[0] * an[1] + aw[1] * an[0];
    nn_ = n_[0] * n_[0] + n_[1] * n_[1] + n_[2] * n_[2];
    ann_ = an[0] * an[0] + an[1] * an[1] + an[2] * an[2];
    // circumcentre offset o = (w x n) / (2|n|^2), radius r = |o|
    const double ox = wn_[0] / (2 * nn_), oy = wn_[1] / (2 * nn_), oz = wn_[2] / (2 * nn_);
    r_ = std::sqrt(ox * ox + oy * oy + oz * oz);
    inv_norm_n_ = 1.0 / std::sqrt(nn_);
    sliver_ = !(nn_ >= kExactMagnitudeSin2 * l1 * l2);  // (NaN from over- or underflow: exact too)
  }

  /// γ(abc; p), sign exact (semi-static filter, exact predicate when undecided).
  double apex(const double* p) const noexcept {
    int s = 0;
    return apex(p, s);
  }
  /// Same, and the exact sign @p s of |p-c|^2 - r^2 (c, r: circumcentre and -radius of abc).
  double apex(const double* p, int& s) const noexcept {
    const double q[3] = {p[0] - a_[0], p[1] - a_[1], p[2] - a_[2]};
    const double qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    const double qwn = q[0] * wn_[0] + q[1] * wn_[1] + q[2] * wn_[2];
    const double d = qq * nn_ - qwn;  // = ρ |n|^2
    const double m = qq * ann_ + (std::fabs(q[0]) * awn_[0] + std::fabs(q[1]) * awn_[1] + std::fabs(q[2]) * awn_[2]);
    if (safe_range(m) && std::fabs(d) > 16 * kU * m) s = d > 0 ? 1 : -1;
    else s = diametral_side3(a_, b_, c_, p);
    if (s == 0) return 0.0;
    if (sliver_) {
      const double mag = exact_apex_magnitude3(a_, b_, c_, p);
      return s > 0 ? mag : -mag;
    }
    const double rho = std::fabs(d) / nn_;
    const double h = std::fabs(q[0] * n_[0] + q[1] * n_[1] + q[2] * n_[2]) * inv_norm_n_;
    const double t = 2 * h * r_;
    const double S = std::sqrt(t * t + rho * rho);
    const double mag = S > 0 ? std::min(1.0, (rho / S) * (rho / (S + t))) : 0.0;
    return s > 0 ? mag : -mag;
  }

 private:
  const double *a_, *b_, *c_;
  double e1_[3], e2_[3], n_[3], wn_[3], awn_[3];
  double nn_ = 0, ann_ = 0, r_ = 0, inv_norm_n_ = 0;
  bool sliver_ = false;
};

}  // namespace constrict::detail
