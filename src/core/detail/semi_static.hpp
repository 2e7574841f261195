// SPDX-License-Identifier: GPL-3.0-or-later
// Semi-static floating-point filters shared by the predicates and the γ-value code (no CGAL).
#pragma once
#include <cmath>
#include <limits>

#include "constrict/predicates.hpp"

namespace constrict::detail {

// Semi-static filters. For an expression tree of +, -, * of depth d over exact double leaves,
// the computed value f~ satisfies |f~ - f| <= γ_d · f_abs (Higham, Accuracy and Stability of
// Numerical Algorithms, §3.1), where f_abs is the same tree over |leaves| with every - turned
// into +. Evaluating f_abs in double loses at most a factor (1-u)^d, u = 2^-53. So when
// |f~| > (d+3)·u·f_abs~ the sign of f~ is the exact sign. Outside a safe exponent range
// (underflow breaks the error model) we fall back to CGAL's exact predicate.
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
inline bool safe_range(double m) { return m > 1e-250 && m < 1e250; }

// sign(k·|pq|^2 - t^2·Σ|a_i b_i|^2) from lhs = k·|pq|^2 and sum = Σ|a_i b_i|^2, each squared
// length summed coordinate by coordinate in D dimensions and the sum in any order (compare_gap2/3):
// depth <= D + 1 + (k - 1) + D + 1 + 2, the bound uses 2k + 2D + 4.
// The factors t^2 and sum must not be subnormal (nor within a factor 2^53 of it): a subnormal one
// has a large relative error, which the product carries into the safe range (t = 1e-160 against a
// sum of 1e100 gave the wrong sign); m's range alone does not see it.
constexpr double kMinGapFactor = std::numeric_limits<double>::min() / kU;  // 2^-969
inline int gap_filtered(double lhs, double sum, double t, int k, int dim, bool& ok) {
  const double tt = t * t, rhs = tt * sum, d = lhs - rhs,
               m = lhs + rhs;  // every leaf product is a square: m is the |tree|
  ok = std::isfinite(m) && safe_range(m) && (tt == 0 || tt >= kMinGapFactor) && (sum == 0 || sum >= kMinGapFactor) &&
       std::fabs(d) > (2.0 * k + 2 * dim + 4) * kU * m;
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

// sign((b-a) x (c-a)); depth 3.
inline int orient2_filtered(const double* a, const double* b, const double* c, bool& ok) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
  const double d = ux * vy - uy * vx;
  const double m = std::fabs(ux * vy) + std::fabs(uy * vx);
  ok = safe_range(m) && std::fabs(d) > 6 * kU * m;
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

// orient2 (exact) with its semi-static filter inline: the hot loops of the 2D fallback (segment
// and side tests) and the long segments' side test call it hundreds of millions of times, and
// most signs are clear at once.
inline int orient2_fast(const double* a, const double* b, const double* c) {
  bool ok = false;
  const int s = orient2_filtered(a, b, c, ok);
  return ok ? s : orient2(a, b, c);
}

// sign((a-p).(b-p)); depth 3.
inline int diametral2_filtered(const double* a, const double* b, const double* p, bool& ok) {
  const double ux = a[0] - p[0], uy = a[1] - p[1], vx = b[0] - p[0], vy = b[1] - p[1];
  const double d = ux * vx + uy * vy;
  const double m = std::fabs(ux * vx) + std::fabs(uy * vy);
  ok = safe_range(m) && std::fabs(d) > 6 * kU * m;
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

// sign(|p-c|^2 - r^2), c/r = circumcentre/-radius of abc, times |n|^2 > 0:
// D = |q|^2 |n|^2 - q.(w x n), q = p-a, e1 = b-a, e2 = c-a, n = e1 x e2,
// w = |e1|^2 e2 - |e2|^2 e1. Depth 12.
inline int diametral3_filtered(const double* a, const double* b, const double* c, const double* p, bool& ok) {
  double e1[3], e2[3], q[3], ae1[3], ae2[3], aq[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = b[i] - a[i];
    e2[i] = c[i] - a[i];
    q[i] = p[i] - a[i];
    ae1[i] = std::fabs(e1[i]);
    ae2[i] = std::fabs(e2[i]);
    aq[i] = std::fabs(q[i]);
  }
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double an[3] = {ae1[1] * ae2[2] + ae1[2] * ae2[1], ae1[2] * ae2[0] + ae1[0] * ae2[2],
                        ae1[0] * ae2[1] + ae1[1] * ae2[0]};
  const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  const double w[3] = {l1 * e2[0] - l2 * e1[0], l1 * e2[1] - l2 * e1[1], l1 * e2[2] - l2 * e1[2]};
  const double aw[3] = {l1 * ae2[0] + l2 * ae1[0], l1 * ae2[1] + l2 * ae1[1], l1 * ae2[2] + l2 * ae1[2]};
  const double wn[3] = {w[1] * n[2] - w[2] * n[1], w[2] * n[0] - w[0] * n[2], w[0] * n[1] - w[1] * n[0]};
  const double awn[3] = {aw[1] * an[2] + aw[2] * an[1], aw[2] * an[0] + aw[0] * an[2], aw[0] * an[1] + aw[1] * an[0]};
  const double qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const double ann = an[0] * an[0] + an[1] * an[1] + an[2] * an[2];
  const double d = qq * nn - (q[0] * wn[0] + q[1] * wn[1] + q[2] * wn[2]);
  const double m = qq * ann + (aq[0] * awn[0] + aq[1] * awn[1] + aq[2] * awn[2]);
  ok = safe_range(m) && std::fabs(d) > 16 * kU * m;
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

}  // namespace constrict::detail
