// SPDX-License-Identifier: GPL-3.0-or-later
// Exact power-of-two rescaling of a point set (points.hpp). Multiplying by 2^k is exact for every
// double that stays normal (or zero) and for every scaling up without overflow, so it commutes
// with every predicate and with every IEEE operation on the result that does not overflow or
// underflow: the engines can work on magnitudes near 1 whatever the input's scale.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "constrict/points.hpp"

namespace constrict {
namespace {

std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

namespace {
int exponent_of(double largest) noexcept {
  int e = 0;
  if (largest > 0) std::frexp(largest, &e);
  return e;
}
}  // namespace

int max_coordinate_exponent(const PointSet& points) noexcept {
  double m = 0;
  for (double c : points.coords) m = std::max(m, std::fabs(c));
  return exponent_of(m);
}

int max_coordinate_exponent(const PointSet& points, const std::vector<char>& used) noexcept {
  const std::size_t dim = points.dim > 0 ? static_cast<std::size_t>(points.dim) : 1;
  double m = 0;
  for (std::size_t i = 0; i < used.size() && i < points.size(); ++i)
    if (used[i])
      for (std::size_t k = 0; k < dim; ++k) m = std::max(m, std::fabs(points.coords[i * dim + k]));
  return exponent_of(m);
}

PointSet scaled_by_power_of_two(const PointSet& points, int e) {
  PointSet s;
  s.dim = points.dim;
  s.coords.resize(points.coords.size());
  std::transform(points.coords.begin(), points.coords.end(), s.coords.begin(),
                 [e](double x) { return std::ldexp(x, e); });
  return s;
}

Status exact_power_of_two_scale(const PointSet& in, PointSet& out, int& exponent) {
  exponent = 0;
  out = PointSet{};
  out.dim = in.dim;
  double smallest = 0, largest = 0;  // smallest nonzero and largest magnitude
  for (std::size_t i = 0; i < in.coords.size(); ++i) {
    const double x = in.coords[i];
    if (!std::isfinite(x)) {
      const std::size_t dim = in.dim > 0 ? static_cast<std::size_t>(in.dim) : 1;
      return {StatusCode::NonFinite, "point " + std::to_string(i / dim) + " has a non-finite coordinate"};
    }
    const double a = std::fabs(x);
    largest = std::max(largest, a);
    if (a > 0 && (smallest == 0 || a < smallest)) smallest = a;
  }
  const int e = max_coordinate_exponent(in);
  // Only a scaling down can lose bits, and the smallest nonzero magnitude loses them first if any
  // coordinate does (a coordinate keeps its bits iff its lowest set bit stays representable); the
  // round trip of every coordinate is checked anyway, which also names the first one that fails.
  for (std::size_t i = 0; e > 0 && i < in.coords.size(); ++i) {
    const double x = in.coords[i];
    if (std::ldexp(std::ldexp(x, -e), e) != x) {
      const std::size_t dim = in.dim > 0 ? static_cast<std::size_t>(in.dim) : 1;
      return {StatusCode::Unsupported, "coordinates span too many orders of magnitude to rescale exactly (|x| from " +
                                           short_number(smallest) + " to " + short_number(largest) + "; point " +
                                           std::to_string(i / dim) +
                                           " would lose bits); round the coordinates that are tiny beside the "
                                           "largest to 0, or move the data nearer the origin's scale"};
    }
  }
  out = scaled_by_power_of_two(in, -e);
  exponent = e;
  return Status::ok();
}

}  // namespace constrict
