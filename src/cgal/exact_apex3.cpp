// SPDX-License-Identifier: GPL-3.0-or-later
// Exact apex magnitude for sliver triangles (cgal/detail/exact_apex3.hpp): the quantities of
// gamma/detail/apex3.hpp's TriangleFrame3 as exact polynomials in the coordinates (CGAL::Mpzf:
// sums and products of doubles, exact, no allocation for small sizes), each converted to double
// once. Only when a conversion leaves the normal double range (inputs far from unit scale) are
// the three ratios formed in exact rationals (CGAL::Gmpq) instead, which is slower.
#include "cgal/detail/exact_apex3.hpp"

#include <CGAL/Gmpq.h>
#include <CGAL/Mpzf.h>

#include <cmath>
#include <algorithm>

namespace constrict::detail {
namespace {

using Z = CGAL::Mpzf;

struct V3 {
  Z x, y, z;
};
V3 diff(const double* u, const double* v) { return {Z(u[0]) - Z(v[0]), Z(u[1]) - Z(v[1]), Z(u[2]) - Z(v[2])}; }
Z dot(const V3& u, const V3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
V3 cross(const V3& u, const V3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
V3 combine(const Z& s, const V3& u, const Z& t, const V3& v) {
  return {s * u.x - t * v.x, s * u.y - t * v.y, s * u.z - t * v.z};
}
Z abs(const Z& v) { return CGAL::sign(v) == CGAL::NEGATIVE ? -v : v; }

bool normal(double v) { return v == 0 || std::isnormal(v); }

// num / den in double: two roundings, or one through exact rationals out of range.
double ratio(const Z& num, const Z& den) {
  const double n = num.to_double(), d = den.to_double(), q = n / d;
  if (normal(n) && normal(d) && normal(q) && d != 0) return q;
  return CGAL::to_double(CGAL::Gmpq(num) / CGAL::Gmpq(den));
}

}  // namespace

double exact_apex_magnitude3(const double* a, const double* b, const double* c, const double* p) noexcept {
  const V3 e1 = diff(b, a), e2 = diff(c, a), q = diff(p, a);
  const V3 n = cross(e1, e2);
  const Z nn = dot(n, n);
  const V3 wn = cross(combine(dot(e1, e1), e2, dot(e2, e2), e1), n);  // circumcentre offset · 2|n|²
  const Z d = dot(q, q) * nn - dot(q, wn);                             // ρ |n|²
  const Z qn = dot(q, n);
  const double rho = ratio(abs(d), nn);
  const double h = std::sqrt(ratio(qn * qn, nn));
  const double r = std::sqrt(ratio(dot(wn, wn), Z(4.0) * nn * nn));
  const double t = 2 * h * r;
  const double S = std::sqrt(t * t + rho * rho);
  return S > 0 ? std::min(1.0, (rho / S) * (rho / (S + t))) : 0.0;
}

}  // namespace constrict::detail
