// SPDX-License-Identifier: GPL-3.0-or-later
// Fetching what a pass over rows (tetrahedra, triangles) will read at random, a few rows ahead.
#pragma once

#include <cstddef>

namespace constrict::detail {

/// How many rows ahead the passes over tetrahedra and faces fetch what they read of other arrays
/// (neighbours' records, points, per-vertex entries): enough lead for the misses of several rows
/// to overlap (docs/benchmarks.md, thirty-third 2026-12-07 session).
inline constexpr std::size_t kFetchAhead = 16;

/// fetch(x) for each entry x of rows[i + kFetchAhead], when that row is before `end`. Always
/// inlined, and so must be every helper that only prefetches: GCC 12 finds a function whose only
/// effect is __builtin_prefetch free of side effects and deletes its calls (check a new use with
/// `objdump -d ... | grep -c prefetch`).
template <class Rows, class Fetch>
[[gnu::always_inline]] inline void fetch_ahead(const Rows& rows, std::size_t i, std::size_t end, const Fetch& fetch) {
  if (i + kFetchAhead < end)
    for (const auto x : rows[i + kFetchAhead]) fetch(x);
}

}  // namespace constrict::detail
