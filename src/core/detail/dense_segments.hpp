// SPDX-License-Identifier: GPL-3.0-or-later
// A dense uniform grid of segments: every cell an array slot, for segments about as long as the
// cells (the area-sized layer of the 2D fallback's boundary grid and of the refinement's edge
// grid; sparse_segments.hpp is the counterpart for cells far below the area's). A segment is
// registered in the cells of its bounding box; a query reads the cells where a point of the
// query segment can lie (for_cells_of_hull, grid_cells.hpp), so it reports every registered
// segment that can meet it (exact candidate sets for exact tests), possibly more than once.
#pragma once
#include <algorithm>
#include <cstddef>

#include "core/detail/cell_lists.hpp"
#include "core/detail/grid_cells.hpp"

namespace constrict::detail {

template <class Id> class DenseSegments {
 public:
  /// An empty grid of frame's cells.
  void reset(const GridFrame& frame) {
    frame_ = frame;
    lists_.clear();
    lists_.grow(static_cast<std::size_t>(frame.nx) * static_cast<std::size_t>(frame.ny));
  }
  void add(const double* a, const double* b, Id id) {
    box_cells(a, b, [&](std::size_t c) { lists_.add(c, id); });
  }
  /// Removes one registration of id (added with the same a, b).
  void remove(const double* a, const double* b, Id id) {
    box_cells(a, b, [&](std::size_t c) { lists_.remove(c, id); });
  }
  /// Registers count segments on an empty grid (after reset()), seg(k, a, b, id) giving the k-th
  /// (the same each call): what count calls of add() would do, in one counting sort.
  template <class Seg> void add_all(std::size_t count, Seg&& seg) {
    lists_.build(lists_.size(), [&](auto&& emit) {
      for_each_segment<Id>(count, seg, [&](const double* a, const double* b, Id id) {
        box_cells(a, b, [&](std::size_t c) { emit(c, id); });
      });
    });
  }
  /// Calls f(id) for the registered segments that can meet segment ab until f returns true; true
  /// if it did.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    const double* seg[2] = {a, b};
    bool done = false;
    for_cells_of_hull(frame_, seg, 2, [&](int i, int j) {
      if (!done) done = lists_.any(index(i, j), f);
    });
    return done;
  }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(frame_.nx) + static_cast<std::size_t>(i);
  }
  template <class F> void box_cells(const double* a, const double* b, F&& f) const {
    const int i0 = frame_.cx(std::min(a[0], b[0])), i1 = frame_.cx(std::max(a[0], b[0]));
    const int j0 = frame_.cy(std::min(a[1], b[1])), j1 = frame_.cy(std::max(a[1], b[1]));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(index(i, j));
  }
  GridFrame frame_{0, 0, 0, 1, 1, 1};
  CellLists<Id> lists_;
};

}  // namespace constrict::detail
