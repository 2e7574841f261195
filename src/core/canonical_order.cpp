// SPDX-License-Identifier: GPL-3.0-or-later
// Canonical point order (core/detail/canonical_order.hpp).
#include "core/detail/canonical_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace constrict::detail {
namespace {

// Bits per axis of the Morton code: 3 x 21 = 63 (3D), 2 x 31 = 62 (2D).
constexpr int kBits3 = 21, kBits2 = 31;

// Spreads the low 32 bits of x to the even bits (2D Morton code).
std::uint64_t spread2(std::uint64_t x) {
  x &= 0xffffffffULL;
  x = (x | (x << 16)) & 0x0000ffff0000ffffULL;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffULL;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | (x << 2)) & 0x3333333333333333ULL;
  x = (x | (x << 1)) & 0x5555555555555555ULL;
  return x;
}
// Spreads the low 21 bits of x to every third bit (3D Morton code).
std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffffULL;
  x = (x | (x << 32)) & 0x1f00000000ffffULL;
  x = (x | (x << 16)) & 0x1f0000ff0000ffULL;
  x = (x | (x << 8)) & 0x100f00f00f00f00fULL;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3ULL;
  x = (x | (x << 2)) & 0x1249249249249249ULL;
  return x;
}

// Sorts (key, index) pairs by key: least-significant-digit radix sort, 16-bit digits (stable).
void radix_sort(std::vector<std::pair<std::uint64_t, int>>& a) {
  constexpr int kDigit = 16;
  constexpr std::size_t kRadix = std::size_t(1) << kDigit;
  std::vector<std::pair<std::uint64_t, int>> tmp(a.size());
  std::vector<std::size_t> count(kRadix);
  for (int shift = 0; shift < 64; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0);
    for (const auto& e : a) ++count[(e.first >> shift) & (kRadix - 1)];
    if (a.empty() || count[(a[0].first >> shift) & (kRadix - 1)] == a.size()) continue;  // one digit value
    std::size_t sum = 0;
    for (auto& c : count) {
      const std::size_t k = c;
      c = sum;
      sum += k;
    }
    for (const auto& e : a) tmp[count[(e.first >> shift) & (kRadix - 1)]++] = e;
    a.swap(tmp);
  }
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
  std::vector<std::pair<std::uint64_t, int>> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t m = 0;
    for (std::size_t k = 0; k < d; ++k) m |= (p.dim == 3 ? spread3(cell(p[i][k], k)) : spread2(cell(p[i][k], k))) << k;
    key[i] = {m, static_cast<int>(i)};
  }
  radix_sort(key);
  // Equal codes (points in one cell): the exact lexicographic order of the coordinates.
  const auto lex = [&](const std::pair<std::uint64_t, int>& a, const std::pair<std::uint64_t, int>& b) {
    const double* pa = p[static_cast<std::size_t>(a.second)];
    const double* pb = p[static_cast<std::size_t>(b.second)];
    return std::lexicographical_compare(pa, pa + d, pb, pb + d);
  };
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && key[j].first == key[i].first) ++j;
    if (j - i > 1) std::sort(key.begin() + static_cast<std::ptrdiff_t>(i), key.begin() + static_cast<std::ptrdiff_t>(j), lex);
    i = j;
  }
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = key[i].second;
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
