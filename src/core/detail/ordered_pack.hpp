// SPDX-License-Identifier: GPL-3.0-or-later
// An order-preserving parallel gather: the engines collect millions of surface faces or body
// tetrahedra from per-simplex arrays, and the result must be the sequential one (same items, same
// order) at any thread count.
#pragma once

#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace constrict::detail {

/// What emit(i, out) writes for each i in [0, n), in the order of i. count(i) says how many items
/// emit(i, out) writes. Two passes over fixed blocks (the counts, then each block's items at its
/// prefix offset), so the blocks and the result do not depend on the scheduling; below two blocks
/// one sequential pass.
template <class T, class Count, class Emit>
std::vector<T> ordered_pack(std::size_t n, const Count& count, const Emit& emit,
                            std::size_t block = std::size_t{1} << 15) {
  std::vector<T> out;
  if (n < 2 * block) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t c = count(i);
      if (c == 0) continue;
      out.resize(out.size() + c);
      emit(i, out.data() + out.size() - c);
    }
    return out;
  }
  const std::size_t nb = (n + block - 1) / block;
  std::vector<std::size_t> off(nb + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      std::size_t c = 0;
      for (std::size_t i = b * block, e = std::min(n, i + block); i < e; ++i) c += count(i);
      off[b + 1] = c;
    }
  });
  for (std::size_t b = 0; b < nb; ++b) off[b + 1] += off[b];
  out.resize(off[nb]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      T* o = out.data() + off[b];
      for (std::size_t i = b * block, e = std::min(n, i + block); i < e; ++i) o += emit(i, o);
    }
  });
  return out;
}

}  // namespace constrict::detail
