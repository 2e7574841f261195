// SPDX-License-Identifier: GPL-3.0-or-later
// The first index with a property, found in parallel: the validators scan millions of faces or
// tetrahedra and must report the same first fault as a sequential scan would, at any thread count.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace constrict::detail {

/// The smallest i in [0, n) with bad(i), or n. Each chunk stops at its first hit or at a smaller
/// hit already known to it; the result does not depend on the scheduling.
template <class Bad>
std::size_t first_index(std::size_t n, const Bad& bad, std::size_t grain = std::size_t{1} << 14) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, grain), n,
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t found) {
        for (std::size_t i = r.begin(); i != r.end() && i < found; ++i)
          if (bad(i)) return i;
        return found;
      },
      [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

}  // namespace constrict::detail
