// SPDX-License-Identifier: GPL-3.0-or-later
// Generator of genus-0 objects whose parts nearly touch, for the bridge tests (issue 17,
// docs/reconstruction-3d.md §4.9): unions of capsules (a segment and a radius) — two parallel
// fingers on a base, two legs that come together at the feet, an ear hanging beside a ball, a
// hook whose end runs along a body — with a gap of g sample spacings between the close parts; and
// two separate parts (an arm beside a body, not joined to it).
// Blue-noise samples of the union's boundary (dart throwing, minimum distance 0.75 h per part, so
// a part can be sampled more sparsely than the rest; each point moved by up to 0.02 h), and the exact distance to the
// true surface outside the union (a lower bound inside). Deterministic per seed (splitmix64).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "constrict/points.hpp"
#include "blue_noise3.hpp"
#include "unit/test_fixtures.hpp"

namespace constrict::test {

enum class GapShape { Fingers, Legs, Ear, Hook, Apart };

inline const char* gap_shape_name(GapShape s) {
  switch (s) {
    case GapShape::Fingers: return "fingers";
    case GapShape::Legs: return "legs";
    case GapShape::Ear: return "ear";
    case GapShape::Hook: return "hook";
    case GapShape::Apart: return "apart";
  }
  return "?";
}

struct Capsule {
  std::array<double, 3> a, b;
  double r;
  double sparse = 1;  // sample spacing of this part, in units of h
};

struct GapObject {
  std::vector<Capsule> parts;
  PointSet points;
  double h = 1;     // sample spacing of the dense parts
  double diag = 0;  // bounding-box diagonal of the points
};

namespace detail_gaps3 {
using P = std::array<double, 3>;

inline double capsule_sdf(const Capsule& c, const P& p) {
  const double ab[3] = {c.b[0] - c.a[0], c.b[1] - c.a[1], c.b[2] - c.a[2]};
  const double ap[3] = {p[0] - c.a[0], p[1] - c.a[1], p[2] - c.a[2]};
  const double l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  double t = l2 > 0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2 : 0;
  t = std::max(0.0, std::min(1.0, t));
  const double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - c.r;
}

using Rng = Rng01;

// A uniform point on the capsule's boundary.
inline P on_capsule(const Capsule& c, Rng& rng) {
  const double ab[3] = {c.b[0] - c.a[0], c.b[1] - c.a[1], c.b[2] - c.a[2]};
  const double L = std::sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
  const double ax[3] = {ab[0] / L, ab[1] / L, ab[2] / L};
  const double pick[3] = {std::abs(ax[0]) < 0.9 ? 1.0 : 0.0, std::abs(ax[0]) < 0.9 ? 0.0 : 1.0, 0};
  double u[3] = {ax[1] * pick[2] - ax[2] * pick[1], ax[2] * pick[0] - ax[0] * pick[2], ax[0] * pick[1] - ax[1] * pick[0]};
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& x : u) x /= lu;
  const double w[3] = {ax[1] * u[2] - ax[2] * u[1], ax[2] * u[0] - ax[0] * u[2], ax[0] * u[1] - ax[1] * u[0]};
  const double cyl = 2 * M_PI * c.r * L, sph = 4 * M_PI * c.r * c.r;
  if (rng.next() * (cyl + sph) < cyl) {
    const double th = 2 * M_PI * rng.next(), z = L * rng.next();
    P p;
    for (std::size_t k = 0; k < 3; ++k) p[k] = c.a[k] + z * ax[k] + c.r * (std::cos(th) * u[k] + std::sin(th) * w[k]);
    return p;
  }
  const double zz = 2 * rng.next() - 1, th = 2 * M_PI * rng.next(), s = std::sqrt(1 - zz * zz);
  const double v[3] = {s * std::cos(th), s * std::sin(th), zz};
  const bool top = v[0] * ax[0] + v[1] * ax[1] + v[2] * ax[2] > 0;
  P p;
  for (std::size_t k = 0; k < 3; ++k) p[k] = (top ? c.b[k] : c.a[k]) + c.r * v[k];
  return p;
}

// Points exactly on a sphere or a cylinder are cospherical by the hundred (a degenerate Delaunay
// tetrahedralization real data does not have): every point moves by up to 0.02 h.
inline P jitter(P p, Rng& rng) {
  for (double& x : p) x += 0.02 * (2 * rng.next() - 1);
  return p;
}

inline std::vector<Capsule> shape(GapShape s, double g, double r, double sparse) {
  using A = std::array<double, 3>;
  switch (s) {
    case GapShape::Fingers: {  // base + two parallel fingers; gap g between the fingers
      const double x = r + g / 2;
      return {{A{-x, 0, 0}, A{x, 0, 0}, r}, {A{-x, 0, r / 2}, A{-x, 0, 10 * r}, r, sparse},
              {A{x, 0, r / 2}, A{x, 0, 10 * r}, r, sparse}};
    }
    case GapShape::Legs: {  // a body and two legs closest at the feet (gap g there)
      const double x = r + g / 2;
      return {{A{-3 * r, 0, 0}, A{3 * r, 0, 0}, 2 * r}, {A{-2.5 * r, 0, 0}, A{-x, 0, -10 * r}, r, sparse},
              {A{2.5 * r, 0, 0}, A{x, 0, -10 * r}, r, sparse}};
    }
    case GapShape::Ear: {  // a ball and an ear hanging beside it (gap g), joined at the top
      const double R = 4 * r, x = R + r + g;
      return {{A{0, 0, 0}, A{0, 0, 1e-3 * r}, R}, {A{x, 0, R + 2 * r}, A{x, 0, -R / 2}, r, sparse},
              {A{0, 0, R - r}, A{x, 0, R + r}, r, sparse}};
    }
    case GapShape::Hook: {  // a body; an arm leaves its top and comes back down along it (gap g)
      const double x = 2 * r + r + g;
      return {{A{0, 0, 0}, A{0, 0, 10 * r}, 2 * r}, {A{0, 0, 10 * r}, A{x, 0, 12 * r}, r, sparse},
              {A{x, 0, 11.5 * r}, A{x, 0, 3 * r}, r, sparse}};
    }
    case GapShape::Apart: {  // two parts: a body and an arm beside it along most of its length (gap g)
      const double x = 2 * r + r + g;
      return {{A{0, 0, 0}, A{0, 0, 10 * r}, 2 * r}, {A{x, 0, 11.5 * r}, A{x, 0, 3 * r}, r, sparse}};
    }
  }
  return {};
}
}  // namespace detail_gaps3

// Signed distance to the union of the parts: exact outside (> 0), a lower bound of the distance
// to the boundary inside (the nearest part's own boundary).
inline double gap_object_distance(const GapObject& o, const std::array<double, 3>& p) {
  double out = HUGE_VAL, in = HUGE_VAL;
  bool inside = false;
  for (const Capsule& c : o.parts) {
    const double d = detail_gaps3::capsule_sdf(c, p);
    out = std::min(out, d);
    in = std::min(in, std::abs(d));
    inside = inside || d < 0;
  }
  return inside ? in : out;
}

// The object with gap g (in units of h = 1), part radius r (in h), the close parts sampled at
// `sparse` times the spacing of the rest.
inline GapObject make_gap_object(GapShape s, double g, double r, double sparse, std::uint64_t seed) {
  using detail_gaps3::P;
  GapObject o;
  o.parts = detail_gaps3::shape(s, g, r, sparse);
  detail_gaps3::Rng rng{seed * 0x2545f4914f6cdd1dULL + 17};
  // Candidates: 4 per (0.75 h·sparse)² of each part's area, kept outside every other part.
  std::vector<DartCandidate> cand;
  for (std::size_t i = 0; i < o.parts.size(); ++i) {
    const Capsule& c = o.parts[i];
    const double L = std::sqrt((c.b[0] - c.a[0]) * (c.b[0] - c.a[0]) + (c.b[1] - c.a[1]) * (c.b[1] - c.a[1]) +
                               (c.b[2] - c.a[2]) * (c.b[2] - c.a[2]));
    const double rad = 0.75 * c.sparse;
    const double area = 2 * M_PI * c.r * L + 4 * M_PI * c.r * c.r;
    const auto n = static_cast<std::size_t>(4 * area / (rad * rad));
    for (std::size_t k = 0; k < n; ++k) {
      const P p = detail_gaps3::on_capsule(c, rng);
      bool keep = true;
      for (std::size_t j = 0; j < o.parts.size() && keep; ++j)
        keep = j == i || detail_gaps3::capsule_sdf(o.parts[j], p) > 1e-6;
      if (keep) cand.push_back({detail_gaps3::jitter(p, rng), rad});
    }
  }
  // Shuffled, then dart throwing with the larger radius of the two points.
  double cell = 0;
  for (const Capsule& c : o.parts) cell = std::max(cell, 0.75 * c.sparse);
  const std::vector<DartCandidate> kept = dart_throw(std::move(cand), cell, rng);
  o.points.dim = 3;
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const DartCandidate& c : kept) {
    o.points.coords.insert(o.points.coords.end(), c.p.begin(), c.p.end());
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c.p[k]);
      hi[k] = std::max(hi[k], c.p[k]);
    }
  }
  o.diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return o;
}

// A random subset of the object's points, each kept with probability `keep` (as in the random
// halves and quarters of bench/close_parts.sh): clumps and holes instead of blue noise. The gap and
// radius of make_gap_object are then best given in units of the subset's spacing, sparse / √keep.
// std::mt19937_64 is the same on every platform; its draw d is taken as d · 2^-64 (what libstdc++'s
// uniform_real_distribution gives, written out so that the subset does not depend on the library).
inline GapObject random_subset(const GapObject& o, double keep, std::uint64_t seed) {
  GapObject s = o;
  s.points.coords.clear();
  std::mt19937_64 rng(seed * 7919 + 13);
  for (std::size_t i = 0; i < o.points.size(); ++i)
    if (static_cast<double>(rng()) * 0x1.0p-64 < keep)
      s.points.coords.insert(s.points.coords.end(), o.points[i], o.points[i] + 3);
  return s;
}

}  // namespace constrict::test
