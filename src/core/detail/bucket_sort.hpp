// SPDX-License-Identifier: GPL-3.0-or-later
// A parallel sort for millions of items whose order is led by a 64-bit key: one bucket pass on the
// key's leading bits, then each bucket sorted on its own. The engines rank millions of simplices by
// a static key; a comparison sort of them on two cores (tbb::parallel_sort) took longer than the
// loop that used the ranks.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/detail/big_vector.hpp"

namespace constrict::detail {

namespace bucket_sort_detail {

// Ranges of at most kDirect items are sorted by comparisons; larger ones are first bucketed on
// their keys' next leading bits (256 buckets a level), so that keys crowding into a few leading
// values (points along a curve: their Morton codes) do not leave a few large comparison sorts.
constexpr std::size_t kDirect = 64;

template <class T, class Key, class Less>
void sort_range(T* b, T* e, const Key& key, const Less& less, std::vector<T>& tmp) {
  const std::size_t n = static_cast<std::size_t>(e - b);
  if (n <= kDirect) {
    std::sort(b, e, less);
    return;
  }
  std::uint64_t lo = key(*b), hi = lo;
  for (T* x = b; x != e; ++x) {
    lo = std::min(lo, key(*x));
    hi = std::max(hi, key(*x));
  }
  if (lo == hi) {  // (one key: the comparator decides)
    std::sort(b, e, less);
    return;
  }
  int shift = 0;
  while (((hi - lo) >> shift) >= 256) ++shift;
  std::size_t start[257] = {};
  for (T* x = b; x != e; ++x) ++start[((key(*x) - lo) >> shift) + 1];
  for (int k = 0; k < 256; ++k) start[k + 1] += start[k];
  tmp.resize(n);
  std::size_t at[256];
  std::copy(start, start + 256, at);
  for (T* x = b; x != e; ++x) tmp[at[(key(*x) - lo) >> shift]++] = *x;
  std::copy(tmp.begin(), tmp.begin() + static_cast<std::ptrdiff_t>(n), b);
  for (int k = 0; k < 256; ++k)
    if (start[k + 1] - start[k] > 1) sort_range(b + start[k], b + start[k + 1], key, less, tmp);
}

}  // namespace bucket_sort_detail

/// Sorts @p v by @p less, a strict total order on its items that the key leads: key(a) < key(b)
/// implies less(a, b) (key(item) is a std::uint64_t). The result is that order, whatever the
/// thread count: the items go to buckets of equal leading key bits in a fixed number of blocks,
/// each bucket is then sorted by @p less (in parallel over the buckets; a large one bucketed again
/// on the next bits first).
template <class T, class Key, class Less>
void bucket_sort(BigArray<T>& v, const Key& key, const Less& less) {
  const std::size_t n = v.size();
  constexpr std::size_t kSmall = std::size_t{1} << 16;
  if (n < kSmall) {
    std::sort(v.data(), v.data() + n, less);
    return;
  }
  using Range = std::pair<std::uint64_t, std::uint64_t>;
  const Range mm = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kSmall), Range{~std::uint64_t{0}, 0},
      [&](const tbb::blocked_range<std::size_t>& r, Range m) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint64_t k = key(v[i]);
          m.first = std::min(m.first, k);
          m.second = std::max(m.second, k);
        }
        return m;
      },
      [](const Range& a, const Range& b) { return Range{std::min(a.first, b.first), std::max(a.second, b.second)}; });
  // Buckets: the key minus the smallest, shifted to at most kBuckets values (about n / kBuckets
  // items each when the keys spread).
  constexpr std::uint64_t kBuckets = std::uint64_t{1} << 18;
  const std::uint64_t span = mm.second - mm.first;
  int shift = 0;
  while ((span >> shift) >= kBuckets) ++shift;
  const std::size_t nb = static_cast<std::size_t>(span >> shift) + 1;
  const auto bucket = [&](const T& x) { return static_cast<std::size_t>((key(x) - mm.first) >> shift); };
  // Fixed blocks (not the scheduler's ranges), each with its own counts: the positions do not
  // depend on the thread count.
  constexpr std::size_t kBlocks = 4;
  const std::size_t per = (n + kBlocks - 1) / kBlocks;
  std::vector<std::uint32_t> count(kBlocks * nb, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kBlocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      std::uint32_t* c = count.data() + b * nb;
      for (std::size_t i = b * per, e = std::min(n, i + per); i < e; ++i) ++c[bucket(v[i])];
    }
  });
  // Offsets, bucket-major then block: a bucket's items in block order.
  std::vector<std::size_t> start(nb + 1, 0);
  std::size_t at = 0;
  for (std::size_t k = 0; k < nb; ++k) {
    start[k] = at;
    for (std::size_t b = 0; b < kBlocks; ++b) {
      const std::uint32_t c = count[b * nb + k];
      count[b * nb + k] = static_cast<std::uint32_t>(at - start[k]);
      at += c;
    }
  }
  start[nb] = n;
  BigArray<T> out;  // (every element written once below: not zero-filled)
  out.allocate(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kBlocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      std::uint32_t* c = count.data() + b * nb;
      for (std::size_t i = b * per, e = std::min(n, i + per); i < e; ++i) {
        const std::size_t k = bucket(v[i]);
        out[start[k] + c[k]++] = v[i];
      }
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<T> tmp;
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      if (start[k + 1] - start[k] > 1)
        bucket_sort_detail::sort_range(out.data() + start[k], out.data() + start[k + 1], key, less, tmp);
  });
  v.swap(out);
}

}  // namespace constrict::detail
