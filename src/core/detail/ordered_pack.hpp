// SPDX-License-Identifier: GPL-3.0-or-later
// An order-preserving parallel gather: the engines collect millions of surface faces, body
// tetrahedra or flip candidates from per-simplex arrays, and the result must be the sequential
// one (same items, same order) at any thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace constrict::detail {

/// Appends to `out` what emit(i, push) pushes (push(item) appends one) for each i in [0, n), in
/// the order of i. One parallel pass over fixed blocks, each into its own list, then each list
/// copied to its offset in `out` (in parallel, straight into the caller's storage): the blocks and
/// the result do not depend on the scheduling. Below two blocks one sequential pass.
template <class T, class Emit>
void ordered_pack_append(std::vector<T>& out, std::size_t n, const Emit& emit, std::size_t block = std::size_t{1} << 15) {
  if (n < 2 * block) {
    const auto push = [&](const T& item) { out.push_back(item); };
    for (std::size_t i = 0; i < n; ++i) emit(i, push);
    return;
  }
  const std::size_t nb = (n + block - 1) / block;
  std::vector<std::vector<T>> part(nb);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      std::vector<T>& mine = part[b];
      const auto push = [&](const T& item) { mine.push_back(item); };
      for (std::size_t i = b * block, e = std::min(n, i + block); i < e; ++i) emit(i, push);
    }
  });
  std::vector<std::size_t> off(nb + 1, out.size());
  for (std::size_t b = 0; b < nb; ++b) off[b + 1] = off[b] + part[b].size();
  out.resize(off[nb]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      std::copy(part[b].begin(), part[b].end(), out.begin() + static_cast<std::ptrdiff_t>(off[b]));
      std::vector<T>().swap(part[b]);
    }
  });
}

/// The same into a new vector.
template <class T, class Emit>
std::vector<T> ordered_pack(std::size_t n, const Emit& emit, std::size_t block = std::size_t{1} << 15) {
  std::vector<T> out;
  ordered_pack_append(out, n, emit, block);
  return out;
}

}  // namespace constrict::detail
