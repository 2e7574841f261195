// SPDX-License-Identifier: GPL-3.0-or-later
// A dense uniform grid of segments: every cell an array slot, for segments about as long as the
// cells (the area-sized layer of the 2D fallback's boundary grid and of the refinement's edge
// grid; sparse_segments.hpp is the counterpart for cells far below the area's). A segment is
// registered in the cells where a point of it can lie, and a query reads those of the query
// segment (both for_cells_of_hull, grid_cells.hpp), so it reports every registered segment that
// can meet it (exact candidate sets for exact tests), possibly more than once. A segment longer
// than LongSegments::kLongCells cells goes to coarser levels instead (long_segments.hpp): a single polygon
// through two concentric circles of 10^6 points registered its 270 000 edges across the annulus
// in about 10^8 cells of the fallback's area-sized layer (1.2 GB), and a query read hundreds.
#pragma once
#include <algorithm>
#include <cstddef>

#include "core/detail/cell_lists.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/long_segments.hpp"

namespace constrict::detail {

template <class Id> class DenseSegments {
 public:
  /// An empty grid of frame's cells.
  void reset(const GridFrame& frame) {
    frame_ = frame;
    lists_.clear();
    lists_.grow(static_cast<std::size_t>(frame.nx) * static_cast<std::size_t>(frame.ny));
    long_.reset(frame.lo_x, frame.lo_y, frame.half_cell * frame.nx, frame.half_cell * frame.ny, frame.magnitude,
                frame.half_cell);
  }
  void add(const double* a, const double* b, Id id) {
    if (long_.takes(a, b)) return long_.add(a, b, id);
    strip_cells(a, b, [&](std::size_t c) { lists_.add(c, id); });
  }
  /// Removes one registration of id (added with the same a, b).
  void remove(const double* a, const double* b, Id id) {
    if (long_.takes(a, b)) return long_.remove(a, b, id);
    strip_cells(a, b, [&](std::size_t c) { lists_.remove(c, id); });
  }
  /// Registers count segments on an empty grid (after reset()), seg(k, a, b, id) giving the k-th
  /// (the same each call): what count calls of add() would do, in one counting sort.
  template <class Seg> void add_all(std::size_t count, Seg&& seg) {
    // (In two ranges side by side for long inputs, CellLists::build_in_blocks: seg must allow
    // concurrent calls.)
    lists_.build_in_blocks(lists_.size(), count, [&](std::size_t k0, std::size_t k1, auto&& emit) {
      for_each_segment<Id>(k0, k1, seg, [&](const double* a, const double* b, Id id) {
        if (!long_.takes(a, b)) strip_cells(a, b, [&](std::size_t c) { emit(c, id); });
      });
    });
    for_each_segment<Id>(count, seg, [&](const double* a, const double* b, Id id) {
      if (long_.takes(a, b)) long_.add(a, b, id);
    });
  }
  /// Calls f(id) for the registered segments that can meet segment ab until f returns true; true
  /// if it did.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    bool done = false;
    strip_cells(a, b, [&](std::size_t c) {
      if (!done) done = lists_.any(c, f);
    });
    return done || long_.any(a, b, f);
  }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(frame_.nx) + static_cast<std::size_t>(i);
  }
  // The cells where a point of segment ab can lie: its strip, for registrations and queries alike
  // (a long diagonal's bounding box would be quadratically many cells: the fallback's edges across
  // an empty interior registered millions on a noisy 10^6 curve).
  template <class F> void strip_cells(const double* a, const double* b, F&& f) const {
    const double* seg[2] = {a, b};
    for_cells_of_hull(frame_, seg, 2, [&](int i, int j) { f(index(i, j)); });
  }
  GridFrame frame_{0, 0, 0, 1, 1, 1};
  CellLists<Id> lists_;
  LongSegments<Id> long_;  // the segments longer than LongSegments::kLongCells cells
};

}  // namespace constrict::detail
