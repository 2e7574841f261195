// SPDX-License-Identifier: GPL-3.0-or-later
// Canonical point order (core/detail/canonical_order.hpp).
#include "core/detail/canonical_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace constrict::detail {
namespace {

// Bits per axis of the Morton code: 3 x 21 = 63 (3D), 2 x 31 = 62 (2D).
constexpr int kBits3 = 21, kBits2 = 31;

// Spreads the low `bits` bits of x to every `stride`-th bit.
std::uint64_t spread(std::uint64_t x, int bits, int stride) {
  std::uint64_t r = 0;
  for (int b = 0; b < bits; ++b) r |= ((x >> b) & 1u) << (b * stride);
  return r;
}

}  // namespace

std::vector<int> canonical_order(const PointSet& p) {
  const std::size_t n = p.size(), d = static_cast<std::size_t>(p.dim);
  const int bits = p.dim == 3 ? kBits3 : kBits2;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t k = 0; k < d && n > 0; ++k) lo[k] = hi[k] = p[0][k];
  for (std::size_t i = 1; i < n; ++i)
    for (std::size_t k = 0; k < d; ++k) {
      lo[k] = std::min(lo[k], p[i][k]);
      hi[k] = std::max(hi[k], p[i][k]);
    }
  const double cells = std::ldexp(1.0, bits);
  // Cell of coordinate x on axis k, in [0, 2^bits): the same double operations for the same x.
  const auto cell = [&](double x, std::size_t k) -> std::uint64_t {
    const double w = hi[k] - lo[k];
    if (!(w > 0) || !std::isfinite(w)) return 0;
    const double t = (x - lo[k]) / w * cells;
    if (!(t > 0)) return 0;
    return t >= cells - 1 ? static_cast<std::uint64_t>(cells - 1) : static_cast<std::uint64_t>(t);
  };
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t m = 0;
    for (std::size_t k = 0; k < d; ++k) m |= spread(cell(p[i][k], k), bits, p.dim) << k;
    key[i] = m;
  }
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const std::size_t ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
    if (key[ia] != key[ib]) return key[ia] < key[ib];
    return std::lexicographical_compare(p[ia], p[ia] + d, p[ib], p[ib] + d);
  });
  return order;
}

PointSet permuted(const PointSet& p, const std::vector<int>& order) {
  PointSet q;
  q.dim = p.dim;
  const std::size_t d = static_cast<std::size_t>(p.dim);
  q.coords.resize(p.coords.size());
  for (std::size_t k = 0; k < order.size(); ++k) std::copy(p[static_cast<std::size_t>(order[k])], p[static_cast<std::size_t>(order[k])] + d, q[k]);
  return q;
}

}  // namespace constrict::detail
