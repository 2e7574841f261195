// SPDX-License-Identifier: GPL-3.0-or-later
// Exact predicates on plain doubles: thin wrappers around CGAL's filtered Epick predicates
// (static + dynamic interval filters, exact fallback), so that no other module includes CGAL.
#include "constrict/predicates.hpp"
#include "core/detail/semi_static.hpp"
#include "core/detail/volume_filter.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mpzf.h>

#include <cmath>


namespace constrict {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;
using P3 = K::Point_3;
inline P2 p2(const double* a) { return P2(a[0], a[1]); }
inline P3 p3(const double* a) { return P3(a[0], a[1], a[2]); }

}  // namespace

int orient2(const double* a, const double* b, const double* c) noexcept {
  return static_cast<int>(CGAL::orientation(p2(a), p2(b), p2(c)));
}

int orient3(const double* a, const double* b, const double* c, const double* d) noexcept {
  return static_cast<int>(CGAL::orientation(p3(a), p3(b), p3(c), p3(d)));
}

int diametral_side2(const double* a, const double* b, const double* p) noexcept {
  bool ok = false;
  const int s = detail::diametral2_filtered(a, b, p, ok);
  if (ok) return s;
  // CGAL: ON_BOUNDED_SIDE = +1 (inside). We return +1 outside.
  return -static_cast<int>(CGAL::side_of_bounded_circle(p2(a), p2(b), p2(p)));
}

int diametral_side3(const double* a, const double* b, const double* c, const double* p) noexcept {
  bool ok = false;
  const int s = detail::diametral3_filtered(a, b, c, p, ok);
  if (ok) return s;
  // Sphere through a, b, c with centre in their plane (the smallest sphere through them).
  return -static_cast<int>(K().side_of_bounded_sphere_3_object()(p3(a), p3(b), p3(c), p3(p)));
}

// The oriented in-circle/in-sphere predicates have CGAL's static filters; the unoriented ones
// do not, so we orient first (orientation is statically filtered too).
int in_circle(const double* a, const double* b, const double* c, const double* d) noexcept {
  const int o = orient2(a, b, c);
  return o * static_cast<int>(CGAL::side_of_oriented_circle(p2(a), p2(b), p2(c), p2(d)));
}

int in_circle_ccw(const double* a, const double* b, const double* c, const double* d) noexcept {
  return static_cast<int>(CGAL::side_of_oriented_circle(p2(a), p2(b), p2(c), p2(d)));
}

int in_sphere(const double* a, const double* b, const double* c, const double* d,
              const double* e) noexcept {
  const int o = orient3(a, b, c, d);
  return o * static_cast<int>(CGAL::side_of_oriented_sphere(p3(a), p3(b), p3(c), p3(d), p3(e)));
}

int in_sphere_positive(const double* a, const double* b, const double* c, const double* d,
                       const double* e) noexcept {
  return static_cast<int>(CGAL::side_of_oriented_sphere(p3(a), p3(b), p3(c), p3(d), p3(e)));
}

bool collinear3(const double* a, const double* b, const double* c) noexcept {
  return CGAL::collinear(p3(a), p3(b), p3(c));
}

int in_circle_coplanar3(const double* a, const double* b, const double* c,
                        const double* p) noexcept {
  // For p in the plane of abc, inside the smallest sphere of abc <=> inside its circumcircle.
  return static_cast<int>(K().side_of_bounded_sphere_3_object()(p3(a), p3(b), p3(c), p3(p)));
}

namespace {
// 6 x the signed volume, exactly: Mpzf sums and products of doubles are exact (unbounded exponent
// range). Each triangle's determinant about o, the first point of the first triangle.
CGAL::Mpzf exact_volume6(const double* xyz, const int* tris, std::size_t n_tris) {
  const double* o = xyz + 3 * static_cast<std::size_t>(tris[0]);
  const auto pt = [&](std::size_t t, int k) {
    return xyz + 3 * static_cast<std::size_t>(tris[3 * t + static_cast<std::size_t>(k)]);
  };
  CGAL::Mpzf total(0);
  for (std::size_t t = 0; t < n_tris; ++t) {
    CGAL::Mpzf u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = CGAL::Mpzf(pt(t, 0)[k]) - CGAL::Mpzf(o[k]);
      v[k] = CGAL::Mpzf(pt(t, 1)[k]) - CGAL::Mpzf(o[k]);
      w[k] = CGAL::Mpzf(pt(t, 2)[k]) - CGAL::Mpzf(o[k]);
    }
    total = total + (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                     u[2] * (v[0] * w[1] - v[1] * w[0]));
  }
  return total;
}

}  // namespace

VolumeEstimate signed_volume_estimate(const double* xyz, const int* tris, std::size_t n_tris) noexcept {
  if (n_tris == 0) return {};
  const auto pt = [&](std::size_t t, int k) { return xyz + 3 * static_cast<std::size_t>(tris[3 * t + static_cast<std::size_t>(k)]); };
  detail::VolumeFilterSum filter(pt(0, 0));
  for (std::size_t t = 0; t < n_tris; ++t) filter.add(pt(t, 0), pt(t, 1), pt(t, 2));
  return filter.estimate(n_tris);
}

int signed_volume_sign(const double* xyz, const int* tris, std::size_t n_tris,
                       const VolumeEstimate* estimate) noexcept {
  if (n_tris == 0) return 0;
  const VolumeEstimate e = estimate ? *estimate : signed_volume_estimate(xyz, tris, n_tris);
  if (e.valid && std::abs(e.sum6) > e.bound6) return e.sum6 > 0 ? 1 : -1;
  return static_cast<int>(CGAL::sign(exact_volume6(xyz, tris, n_tris)));
}

double signed_volume_checked(const double* xyz, const int* tris, std::size_t n_tris, double approx, bool* exact,
                             const VolumeEstimate* estimate) {
  if (exact) *exact = false;
  if (n_tris == 0) return approx;
  const VolumeEstimate e = estimate ? *estimate : signed_volume_estimate(xyz, tris, n_tris);
  // Known to about 2^-10 relatively (the bound is far from tight: the error is usually ~sqrt(n)
  // eps of the permanents), and approx on the same side of 0: approx.
  if (e.valid && std::abs(e.sum6) > std::ldexp(e.bound6, 10) && (e.sum6 > 0 ? approx > 0 : approx < 0)) return approx;
  if (exact) *exact = true;
  // The exact sum converted (within about an ulp: Mpzf's to_double), then divided by 6; what
  // overflows the double range is ±inf, what underflows it 0 or a subnormal of the right sign.
  return CGAL::to_double(exact_volume6(xyz, tris, n_tris)) / 6.0;
}

namespace {
// sign(k·|pq|^2 - t^2·Σ|a_i b_i|^2) in D dimensions: the semi-static filter
// (core/detail/semi_static.hpp, gap_filtered), then exact Mpzf arithmetic.
template <int D>
int compare_gap(const double* p, const double* q, const double* const* a, const double* const* b, int k, double t) {
  const auto sq = [](const double* u, const double* v) {
    double s = 0;
    for (int c = 0; c < D; ++c) s += (u[c] - v[c]) * (u[c] - v[c]);
    return s;
  };
  double sum = 0;
  for (int i = 0; i < k; ++i) sum += sq(a[i], b[i]);
  bool ok = false;
  const int sign = detail::gap_filtered(static_cast<double>(k) * sq(p, q), sum, t, k, D, ok);
  if (ok) return sign;
  using Z = CGAL::Mpzf;
  const auto zsq = [](const double* u, const double* v) {
    Z s(0);
    for (int c = 0; c < D; ++c) {
      const Z dc = Z(u[c]) - Z(v[c]);
      s = s + dc * dc;
    }
    return s;
  };
  Z zsum(0);
  for (int i = 0; i < k; ++i) zsum = zsum + zsq(a[i], b[i]);
  const Z diff = Z(static_cast<double>(k)) * zsq(p, q) - Z(t) * Z(t) * zsum;
  return static_cast<int>(CGAL::sign(diff));
}
}  // namespace

int compare_ring_fatness2(const double* xy, const int* ring, std::size_t m, double c) noexcept {
  if (m < 3) return c > 0 ? -1 : 0;  // (no area; Σ|e|^2 >= 0)
  const auto pt = [&](std::size_t i) { return xy + 2 * static_cast<std::size_t>(ring[i % m]); };
  const double* o = pt(0);
  // Filter. Translated coordinates carry a relative error <= eps, a cross product <= 3 eps of
  // its permanent on top, an edge's squared length <= 3 eps, the sums <= m eps of the sums of
  // magnitudes: generous bounds (m + 16)·2^-52 times those sums, without overflow and underflow.
  double area = 0, area_perm = 0, edges = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double* a = pt(i);
    const double* b = pt(i + 1);
    const double ux = a[0] - o[0], uy = a[1] - o[1], vx = b[0] - o[0], vy = b[1] - o[1];
    area += ux * vy - uy * vx;
    area_perm += std::abs(ux * vy) + std::abs(uy * vx);
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    edges += dx * dx + dy * dy;
  }
  const double eps = (static_cast<double>(m) + 16.0) * std::ldexp(1.0, -52);
  const double value = std::abs(area) - c * edges;
  const double bound = eps * (area_perm + 2 * c * edges);
  if (std::isfinite(value) && std::isfinite(bound) && (area_perm > 1e-280 || edges > 1e-280) && std::abs(value) > bound)
    return value > 0 ? 1 : -1;
  CGAL::Mpzf a2(0), e2(0);
  for (std::size_t i = 0; i < m; ++i) {
    const double* a = pt(i);
    const double* b = pt(i + 1);
    const CGAL::Mpzf ux = CGAL::Mpzf(a[0]) - CGAL::Mpzf(o[0]), uy = CGAL::Mpzf(a[1]) - CGAL::Mpzf(o[1]);
    const CGAL::Mpzf vx = CGAL::Mpzf(b[0]) - CGAL::Mpzf(o[0]), vy = CGAL::Mpzf(b[1]) - CGAL::Mpzf(o[1]);
    a2 = a2 + (ux * vy - uy * vx);
    const CGAL::Mpzf dx = CGAL::Mpzf(b[0]) - CGAL::Mpzf(a[0]), dy = CGAL::Mpzf(b[1]) - CGAL::Mpzf(a[1]);
    e2 = e2 + (dx * dx + dy * dy);
  }
  if (CGAL::sign(a2) < 0) a2 = -a2;
  return static_cast<int>(CGAL::sign(a2 - CGAL::Mpzf(c) * e2));
}

void RegionFatness2Filter::add_triangle(const double* a, const double* b, const double* d) noexcept {
  // Each triangle's determinant from its own first vertex; the error analysis of
  // compare_ring_fatness2's filter, with one term per triangle and per wall.
  const double ux = b[0] - a[0], uy = b[1] - a[1], vx = d[0] - a[0], vy = d[1] - a[1];
  area_ += ux * vy - uy * vx;
  area_perm_ += std::abs(ux * vy) + std::abs(uy * vx);
  ++terms_;
}

void RegionFatness2Filter::add_wall(const double* a, const double* b) noexcept {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  edges_ += dx * dx + dy * dy;
  ++terms_;
}

int RegionFatness2Filter::sign(double c) const noexcept {
  const double eps = (static_cast<double>(terms_) + 16.0) * std::ldexp(1.0, -52);
  const double value = area_ - c * edges_;
  const double bound = eps * (area_perm_ + 2 * c * edges_);
  if (std::isfinite(value) && std::isfinite(bound) && (area_perm_ > 1e-280 || edges_ > 1e-280) && std::abs(value) > bound)
    return value > 0 ? 1 : -1;
  return 0;
}

int compare_region_fatness2(const double* xy, const int* tris, std::size_t n_tris, const int* walls, std::size_t n_walls,
                            double c) noexcept {
  const auto pt = [&](int i) { return xy + 2 * static_cast<std::size_t>(i); };
  RegionFatness2Filter filter;
  for (std::size_t t = 0; t < n_tris; ++t) filter.add_triangle(pt(tris[3 * t]), pt(tris[3 * t + 1]), pt(tris[3 * t + 2]));
  for (std::size_t w = 0; w < n_walls; ++w) filter.add_wall(pt(walls[2 * w]), pt(walls[2 * w + 1]));
  if (const int s = filter.sign(c)) return s;
  using Z = CGAL::Mpzf;
  Z a2(0), e2(0);
  for (std::size_t t = 0; t < n_tris; ++t) {
    const double* a = pt(tris[3 * t]);
    const double* b = pt(tris[3 * t + 1]);
    const double* d = pt(tris[3 * t + 2]);
    const Z ux = Z(b[0]) - Z(a[0]), uy = Z(b[1]) - Z(a[1]), vx = Z(d[0]) - Z(a[0]), vy = Z(d[1]) - Z(a[1]);
    a2 = a2 + (ux * vy - uy * vx);
  }
  for (std::size_t w = 0; w < n_walls; ++w) {
    const double* a = pt(walls[2 * w]);
    const double* b = pt(walls[2 * w + 1]);
    const Z dx = Z(b[0]) - Z(a[0]), dy = Z(b[1]) - Z(a[1]);
    e2 = e2 + (dx * dx + dy * dy);
  }
  return static_cast<int>(CGAL::sign(a2 - Z(c) * e2));
}

int compare_gap2(const double* p, const double* q, const double* const* a, const double* const* b, int k,
                 double t) noexcept {
  return compare_gap<2>(p, q, a, b, k, t);
}

int compare_gap3(const double* p, const double* q, const double* const* a, const double* const* b, int k,
                 double t) noexcept {
  return compare_gap<3>(p, q, a, b, k, t);
}


int compare_distance2(const double* p, const double* q, const double* r) noexcept {
  // sign(|pq|^2 - |pr|^2): compare_gap's semi-static filter first (CGAL's filtered predicate
  // alone was 10 % of a 10^6-point topology inference), then its exact Mpzf arithmetic.
  const double* a[1] = {p};
  const double* b[1] = {r};
  return compare_gap<2>(p, q, a, b, 1, 1.0);
}

int compare_distance3(const double* p, const double* q, const double* r) noexcept {
  const double* a[1] = {p};
  const double* b[1] = {r};
  return compare_gap<3>(p, q, a, b, 1, 1.0);
}

}  // namespace constrict
