// SPDX-License-Identifier: GPL-3.0-or-later
// Canonical point order (core/detail/canonical_order.hpp).
#include "core/detail/canonical_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/detail/big_vector.hpp"
#include "core/detail/bucket_sort.hpp"

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

}  // namespace

std::vector<int> canonical_order(const PointSet& p) {
  const std::size_t n = p.size(), d = static_cast<std::size_t>(p.dim);
  const int bits = p.dim == 3 ? kBits3 : kBits2;
  // The box: min and max are exact, so the split into blocks does not change them.
  using Box = std::array<double, 6>;  // lo x y z, hi x y z
  Box box{0, 0, 0, 0, 0, 0};
  if (n > 0) {
    for (std::size_t k = 0; k < d; ++k) box[k] = box[3 + k] = p[0][k];
    box = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 16384), box,
        [&](const tbb::blocked_range<std::size_t>& r, Box b) {
          for (std::size_t i = r.begin(); i != r.end(); ++i)
            for (std::size_t k = 0; k < d; ++k) {
              b[k] = std::min(b[k], p[i][k]);
              b[3 + k] = std::max(b[3 + k], p[i][k]);
            }
          return b;
        },
        [&](Box a, const Box& b) {
          for (std::size_t k = 0; k < 3; ++k) {
            a[k] = std::min(a[k], b[k]);
            a[3 + k] = std::max(a[3 + k], b[3 + k]);
          }
          return a;
        });
  }
  const double* lo = box.data();
  const double* hi = box.data() + 3;
  const double cells = std::ldexp(1.0, bits);
  // Cell of coordinate x on axis k, in [0, 2^bits): the same double operations for the same x.
  const auto cell = [&](double x, std::size_t k) -> std::uint64_t {
    const double w = hi[k] - lo[k];
    if (!(w > 0) || !std::isfinite(w)) return 0;
    const double t = (x - lo[k]) / w * cells;
    if (!(t > 0)) return 0;
    return t >= cells - 1 ? static_cast<std::uint64_t>(cells - 1) : static_cast<std::uint64_t>(t);
  };
  struct Key {
    std::uint64_t code;
    int index;
  };
  BigArray<Key> key;  // (written whole below: not zero-filled)
  key.allocate(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint64_t m = 0;
      for (std::size_t k = 0; k < d; ++k) m |= (p.dim == 3 ? spread3(cell(p[i][k], k)) : spread2(cell(p[i][k], k))) << k;
      key[i] = {m, static_cast<int>(i)};
    }
  });
  // The order: by code, equal codes (points in one cell) by the exact lexicographic order of the
  // coordinates, a strict total order on distinct points (equal points, an error found later, by
  // index): the result is that order whatever the sort does (bucket_sort, on both cores).
  bucket_sort(
      key, [](const Key& a) { return a.code; },
      [&](const Key& a, const Key& b) {
        if (a.code != b.code) return a.code < b.code;
        const double* pa = p[static_cast<std::size_t>(a.index)];
        const double* pb = p[static_cast<std::size_t>(b.index)];
        if (std::lexicographical_compare(pa, pa + d, pb, pb + d)) return true;
        if (std::lexicographical_compare(pb, pb + d, pa, pa + d)) return false;
        return a.index < b.index;
      });
  std::vector<int> order(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 65536), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) order[i] = key[i].index;
  });
  return order;
}

bool has_adjacent_duplicate(const PointSet& q) {
  const std::size_t n = q.size(), d = static_cast<std::size_t>(q.dim);
  if (n < 2) return false;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(1, n, 65536), false,
      [&](const tbb::blocked_range<std::size_t>& r, bool found) {
        for (std::size_t i = r.begin(); i != r.end() && !found; ++i) found = std::equal(q[i - 1], q[i - 1] + d, q[i]);
        return found;
      },
      [](bool a, bool b) { return a || b; });
}

PointSet permuted(const PointSet& p, const std::vector<int>& order) {
  PointSet q;
  q.dim = p.dim;
  const std::size_t d = static_cast<std::size_t>(p.dim);
  q.coords.resize(p.coords.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      std::copy(p[static_cast<std::size_t>(order[k])], p[static_cast<std::size_t>(order[k])] + d, q[k]);
  });
  return q;
}

}  // namespace constrict::detail
