// SPDX-License-Identifier: GPL-3.0-or-later
// The tetrahedra of a Delaunay tetrahedralization in a spatial order (core/detail/tet_order.hpp).
#include "core/detail/tet_order.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/detail/big_vector.hpp"
#include "core/detail/owned_ranges.hpp"

namespace constrict::detail {
namespace {

constexpr std::size_t kGrain = 1 << 14;

// The rows of @p v moved to their new positions (at[t]: where row t goes), remapped by @p f, in
// v's own storage (a copy of the rows is read).
template <class Row, class F>
void scatter(std::vector<Row>& v, const OsArray<int>& at, const F& f) {
  OsArray<Row> rows(v.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, v.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::copy(v.begin() + static_cast<std::ptrdiff_t>(r.begin()),
                                v.begin() + static_cast<std::ptrdiff_t>(r.end()), rows.data() + r.begin());
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, v.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t t = r.begin(); t != r.end(); ++t)
                        v[static_cast<std::size_t>(at[t])] = f(rows[t]);
                    });
}

}  // namespace

void order_tets_by_vertex(Delaunay3& dt, std::vector<std::array<int, 4>>* also) {
  const std::size_t T = dt.tets.size(), n = dt.n_vertices;
  if (T < 2 || n == 0) return;
  // (The temporaries come from the system and go back to it: core/detail/big_vector.hpp, OsArray.)
  OsArray<int> at(T);  // each tetrahedron's new position
  {
    OsArray<int> key(T);  // its smallest vertex
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t)
        key[t] = *std::min_element(dt.tets[t].begin(), dt.tets[t].end());
    });
    // A counting sort by key whose tasks each own a range of keys (core/detail/owned_ranges.hpp):
    // the positions within a key in container order (stable).
    OsArray<int> next(n + 1);  // (positions are below T, an int)
    const auto mine = [&](std::size_t t, std::size_t lo, std::size_t hi) {
      return static_cast<std::size_t>(key[t]) >= lo && static_cast<std::size_t>(key[t]) < hi;
    };
    for_owned_ranges(n, T, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t t = 0; t < T; ++t)
        if (mine(t, lo, hi)) ++next[static_cast<std::size_t>(key[t]) + 1];
    });
    for (std::size_t v = 0; v < n; ++v) next[v + 1] += next[v];
    for_owned_ranges(n, T, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t t = 0; t < T; ++t)
        if (mine(t, lo, hi)) at[t] = next[static_cast<std::size_t>(key[t])]++;
    });
  }
  const auto same = [](const std::array<int, 4>& row) { return row; };
  scatter(dt.tets, at, same);
  scatter(dt.neighbors, at, [&](std::array<int, 4> row) {
    for (int& x : row)
      if (x >= 0) x = at[static_cast<std::size_t>(x)];
    return row;
  });
  if (also) scatter(*also, at, same);
}

}  // namespace constrict::detail
