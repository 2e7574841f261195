// SPDX-License-Identifier: GPL-3.0-or-later
// Exact apex magnitude for sliver triangles (cgal/detail/exact_apex3.hpp): the quantities of
// gamma/detail/apex3.hpp's TriangleFrame3 in exact rationals (CGAL::Gmpq), rounded once each.
#include "cgal/detail/exact_apex3.hpp"

#include <CGAL/Gmpq.h>

#include <cmath>

namespace constrict::detail {
namespace {

using Q = CGAL::Gmpq;

struct V3 {
  Q x, y, z;
};
V3 diff(const double* u, const double* v) { return {Q(u[0]) - Q(v[0]), Q(u[1]) - Q(v[1]), Q(u[2]) - Q(v[2])}; }
Q dot(const V3& u, const V3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
V3 cross(const V3& u, const V3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
V3 combine(const Q& s, const V3& u, const Q& t, const V3& v) {
  return {s * u.x - t * v.x, s * u.y - t * v.y, s * u.z - t * v.z};
}
Q abs(const Q& v) { return v < 0 ? -v : v; }

}  // namespace

double exact_apex_magnitude3(const double* a, const double* b, const double* c, const double* p) noexcept {
  const V3 e1 = diff(b, a), e2 = diff(c, a), q = diff(p, a);
  const V3 n = cross(e1, e2);
  const Q nn = dot(n, n);
  const V3 wn = cross(combine(dot(e1, e1), e2, dot(e2, e2), e1), n);  // circumcentre offset · 2|n|²
  const Q d = dot(q, q) * nn - dot(q, wn);                             // ρ |n|²
  const Q qn = dot(q, n);
  const double rho = CGAL::to_double(abs(d) / nn);
  const double h = std::sqrt(CGAL::to_double(qn * qn / nn));
  const double r = std::sqrt(CGAL::to_double(dot(wn, wn) / (Q(4) * nn * nn)));
  const double t = 2 * h * r;
  const double S = std::sqrt(t * t + rho * rho);
  return S > 0 ? std::min(1.0, (rho / S) * (rho / (S + t))) : 0.0;
}

}  // namespace constrict::detail
