// SPDX-License-Identifier: GPL-3.0-or-later
// Inline 2D apex value (the hot loop of delaunay_gamma2) and the inline filtration value.
// apex_gamma2 and filtration_value (gamma_values.cpp) are these functions.
#pragma once
#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "constrict/predicates.hpp"
#include "core/detail/semi_static.hpp"

namespace constrict::detail {

/// γ(ab; p) (spec §2.1) and its exact sign @p s (+1: angle apb acute, 0: right, -1: obtuse).
inline double apex2(const double* a, const double* b, const double* p, int& s) noexcept {
  const double ux = a[0] - p[0], uy = a[1] - p[1];
  const double vx = b[0] - p[0], vy = b[1] - p[1];
  const double dot = ux * vx + uy * vy;
  const double mdot = std::fabs(ux * vx) + std::fabs(uy * vy);
  if (safe_range(mdot) && std::fabs(dot) > 6 * kU * mdot) s = dot > 0 ? 1 : -1;
  else s = diametral_side2(a, b, p);
  if (s == 0) return 0.0;
  const double uu = ux * ux + uy * uy, vv = vx * vx + vy * vy;
  const double cross = std::fabs(ux * vy - uy * vx);
  const double nn = std::sqrt(uu * vv);
  // 1 - sin φ = cos²φ / (1 + sin φ): no cancellation near φ = 90°.
  const double sin_phi = std::min(1.0, cross / nn);
  const double cos2 = std::min(1.0, (dot / nn) * (dot / nn));
  const double mag = std::min(1.0, cos2 / (1.0 + sin_phi));
  return s > 0 ? mag : -mag;
}

/// apex2(a, b, p) and apex2(a, b, q) together: the same IEEE operations in the same order, one
/// SSE2 lane per apex (bit-identical to two scalar calls; halves the division/sqrt latency).
inline void apex2_pair(const double* a, const double* b, const double* p, const double* q, double& gp, int& sp,
                       double& gq, int& sq) noexcept {
#if defined(__SSE2__)
  const __m128d ux = _mm_sub_pd(_mm_set1_pd(a[0]), _mm_set_pd(q[0], p[0]));
  const __m128d uy = _mm_sub_pd(_mm_set1_pd(a[1]), _mm_set_pd(q[1], p[1]));
  const __m128d vx = _mm_sub_pd(_mm_set1_pd(b[0]), _mm_set_pd(q[0], p[0]));
  const __m128d vy = _mm_sub_pd(_mm_set1_pd(b[1]), _mm_set_pd(q[1], p[1]));
  const __m128d absmask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  const __m128d uxvx = _mm_mul_pd(ux, vx), uyvy = _mm_mul_pd(uy, vy);
  const __m128d dot = _mm_add_pd(uxvx, uyvy);
  const __m128d mdot = _mm_add_pd(_mm_and_pd(uxvx, absmask), _mm_and_pd(uyvy, absmask));
  alignas(16) double d2[2], m2[2];
  _mm_store_pd(d2, dot);
  _mm_store_pd(m2, mdot);
  const double* pts[2] = {p, q};
  int s2[2];
  for (int k = 0; k < 2; ++k) {
    if (safe_range(m2[k]) && std::fabs(d2[k]) > 6 * kU * m2[k]) s2[k] = d2[k] > 0 ? 1 : -1;
    else s2[k] = diametral_side2(a, b, pts[k]);
  }
  const __m128d one = _mm_set1_pd(1.0);
  const __m128d uu = _mm_add_pd(_mm_mul_pd(ux, ux), _mm_mul_pd(uy, uy));
  const __m128d vv = _mm_add_pd(_mm_mul_pd(vx, vx), _mm_mul_pd(vy, vy));
  const __m128d cross = _mm_and_pd(_mm_sub_pd(_mm_mul_pd(ux, vy), _mm_mul_pd(uy, vx)), absmask);
  const __m128d nn = _mm_sqrt_pd(_mm_mul_pd(uu, vv));
  const __m128d sin_phi = _mm_min_pd(_mm_div_pd(cross, nn), one);  // = std::min(1.0, x)
  const __m128d c = _mm_div_pd(dot, nn);
  const __m128d cos2 = _mm_min_pd(_mm_mul_pd(c, c), one);
  const __m128d mag = _mm_min_pd(_mm_div_pd(cos2, _mm_add_pd(one, sin_phi)), one);
  alignas(16) double g2[2];
  _mm_store_pd(g2, mag);
  sp = s2[0];
  sq = s2[1];
  gp = sp == 0 ? 0.0 : (sp > 0 ? g2[0] : -g2[0]);
  gq = sq == 0 ? 0.0 : (sq > 0 ? g2[1] : -g2[1]);
#else
  gp = apex2(a, b, p, sp);
  gq = apex2(a, b, q, sq);
#endif
}

/// Δ (spec §2.2): the larger-magnitude side value, ties -> the max.
inline double filtration(double gamma_a, double gamma_b) noexcept {
  const double ma = std::fabs(gamma_a), mb = std::fabs(gamma_b);
  if (ma > mb) return gamma_a;
  if (mb > ma) return gamma_b;
  return std::max(gamma_a, gamma_b);
}

}  // namespace constrict::detail
