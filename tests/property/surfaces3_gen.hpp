// SPDX-License-Identifier: GPL-3.0-or-later
// Generator of 3D point sets with known topology for the auto-topology tests (docs/topology.md
// §"3D"): blue-noise samples (dart throwing at spacing h over dense uniform samples) of spheres,
// tori, hollow spheres, two linked tori and genus-0 controls, then a random rotation, scale and
// offset, and the points shuffled. Deterministic per seed.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <tuple>
#include <vector>

#include "constrict/points.hpp"

namespace constrict::test {

enum class Family3 { Torus, Spheres, Hollow, Links, Sphere, Ellipsoid, Peanut, Window, Block, Plate, Stack, Comb };

struct Sample3 {
  PointSet points;
  int surfaces = 1;  // true number of surfaces
  int genus = 0;     // true total genus
  int inner = 0;     // of them inner (cavity) surfaces
};

namespace detail_gen3 {
using P = std::array<double, 3>;

// Dart throwing: keeps a candidate when no kept point is within h (grid of cell h).
class Darts {
 public:
  explicit Darts(double h) : h_(h) {}
  bool offer(const P& p) {
    const auto c = cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid_.find({std::get<0>(c) + dx, std::get<1>(c) + dy, std::get<2>(c) + dz});
          if (it == grid_.end()) continue;
          for (std::size_t k : it->second) {
            const P& q = kept_[k];
            if ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]) < h_ * h_) return false;
          }
        }
    grid_[c].push_back(kept_.size());
    kept_.push_back(p);
    return true;
  }
  const std::vector<P>& kept() const { return kept_; }

 private:
  std::tuple<long, long, long> cell(const P& p) const {
    return {std::lround(std::floor(p[0] / h_)), std::lround(std::floor(p[1] / h_)), std::lround(std::floor(p[2] / h_))};
  }
  double h_;
  std::map<std::tuple<long, long, long>, std::vector<std::size_t>> grid_;
  std::vector<P> kept_;
};

// Uniform (by area) random point of a sphere / of a torus around the z axis.
inline P on_sphere(std::mt19937_64& rng, const P& c, double r) {
  std::normal_distribution<double> g(0, 1);
  P v{g(rng), g(rng), g(rng)};
  const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {c[0] + r * v[0] / l, c[1] + r * v[1] / l, c[2] + r * v[2] / l};
}
inline P on_torus(std::mt19937_64& rng, double R, double r) {
  std::uniform_real_distribution<double> u(0, 1);
  for (;;) {  // rejection by the area element (R + r cos v)
    const double a = 2 * M_PI * u(rng), v = 2 * M_PI * u(rng);
    if (u(rng) * (R + r) > R + r * std::cos(v)) continue;
    return {(R + r * std::cos(v)) * std::cos(a), (R + r * std::cos(v)) * std::sin(a), r * std::sin(v)};
  }
}
// Uniform (by area) random point of the capsule (tube of radius r around segment ab, round ends).
inline P on_capsule(std::mt19937_64& rng, const P& a, const P& b, double r) {
  std::uniform_real_distribution<double> u(0, 1);
  const P d{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (u(rng) * (len + 2 * r) >= len) {  // the round ends: area 4 pi r^2 against 2 pi r len
    const P q = on_sphere(rng, {0, 0, 0}, r);
    const bool at_b = q[0] * d[0] + q[1] * d[1] + q[2] * d[2] > 0;
    const P& c = at_b ? b : a;
    return {c[0] + q[0], c[1] + q[1], c[2] + q[2]};
  }
  // The tube: a frame (d / len, e, f) around the axis.
  const P t{d[0] / len, d[1] / len, d[2] / len};
  P e = std::fabs(t[0]) < 0.9 ? P{0, -t[2], t[1]} : P{t[2], 0, -t[0]};
  const double le = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  for (double& x : e) x /= le;
  const P f{t[1] * e[2] - t[2] * e[1], t[2] * e[0] - t[0] * e[2], t[0] * e[1] - t[1] * e[0]};
  const double s = u(rng) * len, ph = 2 * M_PI * u(rng);
  P p{};
  for (int k = 0; k < 3; ++k) p[k] = a[k] + s * t[k] + r * (std::cos(ph) * e[k] + std::sin(ph) * f[k]);
  return p;
}
// Uniform (by area) random point of the surface of the box [-a, a] x [-b, b] x [-c, c]: flat faces
// and sharp edges, as machined parts have.
inline P on_box(std::mt19937_64& rng, double a, double b, double c) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double xy = a * b, xz = a * c, yz = b * c;
  const double pick = (u(rng) + 1) / 2 * (xy + xz + yz);
  const double side = u(rng) < 0 ? -1.0 : 1.0;
  if (pick < xy) return {a * u(rng), b * u(rng), side * c};
  if (pick < xy + xz) return {a * u(rng), side * b, c * u(rng)};
  return {side * a, b * u(rng), c * u(rng)};
}
// Distance from p to segment ab.
inline double segment_distance(const P& p, const P& a, const P& b) {
  const P d{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1] + (p[2] - a[2]) * d[2]) / l2;
  t = std::min(1.0, std::max(0.0, t));
  const P q{a[0] + t * d[0] - p[0], a[1] + t * d[1] - p[1], a[2] + t * d[2] - p[2]};
  return std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
}
}  // namespace detail_gen3

/// @param gap distance between neighbouring surfaces in spacings (Spheres, Hollow, Stack)
/// @param h the spacing (before the random scale)
inline Sample3 make_surfaces3(Family3 f, double gap, unsigned seed, double h = 0.12) {
  using detail_gen3::P;
  if (f == Family3::Links) h *= 0.6;  // (thin tubes: about 20 points around)
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  detail_gen3::Darts darts(h);
  Sample3 s;
  // Candidates: dense uniform samples, about 30 per spacing disk.
  const auto throw_on = [&](double area, const std::function<P()>& draw, const std::function<bool(const P&)>& keep) {
    const long n = std::lround(30 * area / (M_PI * h * h / 4));
    for (long i = 0; i < n; ++i) {
      const P p = draw();
      if (keep(p)) darts.offer(p);
    }
  };
  const auto all = [](const P&) { return true; };
  switch (f) {
    case Family3::Torus:
      s.genus = 1;
      throw_on(4 * M_PI * M_PI * 0.35, [&] { return detail_gen3::on_torus(rng, 1.0, 0.35); }, all);
      break;
    case Family3::Spheres: {
      s.surfaces = 2;
      const double d = 2 + gap * h;
      throw_on(4 * M_PI, [&] { return detail_gen3::on_sphere(rng, {0, 0, 0}, 1); }, all);
      throw_on(4 * M_PI, [&] { return detail_gen3::on_sphere(rng, {d, 0, 0}, 1); }, all);
      break;
    }
    case Family3::Hollow: {
      s.surfaces = 2;
      s.inner = 1;
      const double ri = 1.2 - gap * h;
      throw_on(4 * M_PI * 1.44, [&] { return detail_gen3::on_sphere(rng, {0, 0, 0}, 1.2); }, all);
      throw_on(4 * M_PI * ri * ri, [&] { return detail_gen3::on_sphere(rng, {0, 0, 0}, ri); }, all);
      break;
    }
    case Family3::Links: {  // two tori, each through the other's hole
      s.surfaces = 2;
      s.genus = 2;
      const double r = 0.25;
      throw_on(4 * M_PI * M_PI * r, [&] { return detail_gen3::on_torus(rng, 1.0, r); }, all);
      throw_on(4 * M_PI * M_PI * r, [&] {
        const P q = detail_gen3::on_torus(rng, 1.0, r);
        return P{1.0 + q[0], q[2], q[1]};  // in the xz plane, centred at (1, 0, 0)
      }, all);
      break;
    }
    case Family3::Sphere:
      throw_on(4 * M_PI, [&] { return detail_gen3::on_sphere(rng, {0, 0, 0}, 1); }, all);
      break;
    case Family3::Ellipsoid:
      throw_on(4 * M_PI * 0.6, [&] {
        const P q = detail_gen3::on_sphere(rng, {0, 0, 0}, 1);
        return P{1.4 * q[0], 0.8 * q[1], 0.6 * q[2]};  // (dart throwing evens the density out)
      }, all);
      break;
    case Family3::Peanut:  // two overlapping spheres: the boundary of their union, genus 0
      throw_on(4 * M_PI, [&] { return detail_gen3::on_sphere(rng, {0, 0, 0}, 1); },
               [](const P& p) { return (p[0] - 1.4) * (p[0] - 1.4) + p[1] * p[1] + p[2] * p[2] > 1; });
      throw_on(4 * M_PI, [&] { return detail_gen3::on_sphere(rng, {1.4, 0, 0}, 1); },
               [](const P& p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1; });
      break;
    case Family3::Window: {  // a frame of two square windows: tubes of radius 5 h, genus 2
      s.genus = 2;
      const double r = 5 * h;
      const std::vector<std::array<P, 2>> bars = {{P{0, 0, 0}, P{2, 0, 0}}, {P{0, 1, 0}, P{2, 1, 0}},
                                                  {P{0, 0, 0}, P{0, 1, 0}}, {P{1, 0, 0}, P{1, 1, 0}},
                                                  {P{2, 0, 0}, P{2, 1, 0}}};
      for (std::size_t i = 0; i < bars.size(); ++i) {
        const P& a = bars[i][0];
        const P& b = bars[i][1];
        const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
        throw_on(2 * M_PI * r * len + 4 * M_PI * r * r, [&] { return detail_gen3::on_capsule(rng, a, b, r); },
                 [&](const P& p) {  // the boundary of the union: outside every other tube
                   for (std::size_t j = 0; j < bars.size(); ++j)
                     if (j != i && detail_gen3::segment_distance(p, bars[j][0], bars[j][1]) < r) return false;
                   return true;
                 });
      }
      break;
    }
    case Family3::Block:  // a box: flat faces and sharp edges, genus 0
      throw_on(8 * (2 * 1 + 2 * 0.3 + 1 * 0.3), [&] { return detail_gen3::on_box(rng, 2, 1, 0.3); }, all);
      break;
    case Family3::Plate: {  // the box with a round hole of radius 0.4 through it: genus 1
      s.genus = 1;
      const double r = 0.4;
      throw_on(8 * (2 * 1 + 2 * 0.3 + 1 * 0.3), [&] { return detail_gen3::on_box(rng, 2, 1, 0.3); },
               [&](const P& p) { return p[0] * p[0] + p[1] * p[1] >= r * r; });
      throw_on(2 * M_PI * r * 0.6, [&] {
        const double ph = 2 * M_PI * u(rng);
        return P{r * std::cos(ph), r * std::sin(ph), 0.6 * u(rng) - 0.3};
      }, all);
      break;
    }
    case Family3::Stack: {  // two boxes, one on the other, their large faces gap spacings apart
      s.surfaces = 2;
      const double dz = 0.6 + gap * h;
      const double area = 8 * (2 * 1 + 2 * 0.3 + 1 * 0.3);
      throw_on(area, [&] { return detail_gen3::on_box(rng, 2, 1, 0.3); }, all);
      throw_on(area, [&] {
        const P q = detail_gen3::on_box(rng, 2, 1, 0.3);
        return P{q[0], q[1], q[2] + dz};
      }, all);
      break;
    }
    case Family3::Comb: {  // a box with five fingers on it, gap spacings apart: genus 0
      // Boxes as (centre, half sides); a candidate of one is kept outside all the others.
      const double a = 0.25, g = gap * h;  // the fingers' half width, the slots' width
      std::vector<std::array<P, 2>> boxes;
      const double w = 5 * 2 * a + 4 * g;
      boxes.push_back({P{w / 2, 0.5, 0.3}, P{w / 2, 0.5, 0.3}});
      for (int i = 0; i < 5; ++i) boxes.push_back({P{a + i * (2 * a + g), 0.5, 1.65}, P{a, 0.5, 1.35}});
      const auto inside = [](const P& p, const std::array<P, 2>& bx) {
        for (int k = 0; k < 3; ++k)
          if (!(std::fabs(p[k] - bx[0][k]) < bx[1][k])) return false;
        return true;
      };
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        const P c = boxes[i][0], e = boxes[i][1];
        throw_on(8 * (e[0] * e[1] + e[0] * e[2] + e[1] * e[2]), [&] {
          const P q = detail_gen3::on_box(rng, e[0], e[1], e[2]);
          return P{q[0] + c[0], q[1] + c[1], q[2] + c[2]};
        }, [&](const P& p) {
          for (std::size_t j = 0; j < boxes.size(); ++j)
            if (j != i && inside(p, boxes[j])) return false;
          return true;
        });
      }
      break;
    }
  }
  // A random rotation (three angles), scale and offset; then shuffled. (In double precision: the
  // points of a flat face end up coplanar up to rounding only, as in a rotated CAD model.)
  const double a = 2 * M_PI * u(rng), b = 2 * M_PI * u(rng), c = 2 * M_PI * u(rng);
  const double scale = std::exp(4 * u(rng) - 2), ox = 20 * u(rng) - 10, oy = 20 * u(rng) - 10, oz = 20 * u(rng) - 10;
  std::vector<P> pts = darts.kept();
  std::shuffle(pts.begin(), pts.end(), rng);
  s.points.dim = 3;
  for (const P& p : pts) {
    const double x1 = std::cos(a) * p[0] - std::sin(a) * p[1], y1 = std::sin(a) * p[0] + std::cos(a) * p[1], z1 = p[2];
    const double y2 = std::cos(b) * y1 - std::sin(b) * z1, z2 = std::sin(b) * y1 + std::cos(b) * z1;
    const double x3 = std::cos(c) * x1 + std::sin(c) * z2, z3 = -std::sin(c) * x1 + std::cos(c) * z2;
    s.points.coords.insert(s.points.coords.end(), {scale * x3 + ox, scale * y2 + oy, scale * z3 + oz});
  }
  return s;
}

}  // namespace constrict::test
