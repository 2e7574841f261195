// SPDX-License-Identifier: GPL-3.0-or-later
// A sparse uniform grid of segments with cells sized for the spacing where the data are (the 2D
// refinement's polygon edges, the fallback's boundary edges), for inputs whose points lie on a
// curve: an area-sized grid would hold O(√N) segments per cell there, and every local test would
// read them all (docs/benchmarks.md, the noisy curve). Only non-empty cells are stored: a
// CellTable (cell_table.hpp) in front of one id list per cell. A segment is registered in
// the cells its strip crosses (for_cells_of_hull, grid_cells.hpp); a segment longer than
// LongSegments::kLongCells cells goes to coarser levels instead (a strip of thousands of fine cells each;
// long_segments.hpp). A query visits every cell where a point of the query segment can lie, so
// it reports every registered segment that can meet it (exact candidate sets for exact tests),
// possibly more than once.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/detail/cell_lists.hpp"
#include "core/detail/cell_table.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/long_segments.hpp"

namespace constrict::detail {

template <class Id> class SparseSegments {
 public:
  /// The smallest half cell edge for a box of half spans hw, hh and largest coordinate magnitude
  /// mag: the strips stay narrow (for_cells_of_hull) and the cell counts fit an int.
  static double min_half_cell(double hw, double hh, double mag) {
    return std::max({std::ldexp(mag, -28), hw / kMaxCells, hh / kMaxCells});
  }
  /// The half cell edge of a sparse grid for items about median_edge long (largest coordinate
  /// difference) in a box of half spans hw, hh and magnitude mag, or 0 when area-sized cells of
  /// half edge area_half_cell serve as well (the sparse cells would not be under a quarter of
  /// them). Used by the refinement's edge grid and the fallback's fine layer (constrict/detail/grid2.hpp):
  /// every cell a query reads is a table lookup that mostly misses the cache, so the cells are
  /// wider than one edge: 16 median edges. Noisy 10⁶ curve, half-widths of 1 to 32 median edges,
  /// 3 runs each: refinement 3.95 s (1), 3.0 (2), 2.6-3.8 (4), 2.6 (8), 2.6-3.7 (16), 4.9 (32);
  /// fallback 2.2 s (1), 1.9 (4), 1.8 (8), 2.1-2.6 (16).
  static double sparse_half_cell(double median_edge, double hw, double hh, double mag, double area_half_cell) {
    const double half = std::max(kEdgesPerHalfCell * median_edge, min_half_cell(hw, hh, mag));
    return std::isfinite(half) && half > 0 && half <= 0.25 * area_half_cell ? half : 0;
  }
  /// An empty grid over the box [lo_x, hi_x] x [lo_y, hi_y], cells of edge 2 * half_cell
  /// (>= min_half_cell).
  void reset(double lo_x, double lo_y, double hi_x, double hi_y, double half_cell) {
    frame_ = GridFrame{lo_x, lo_y, box_magnitude(lo_x, lo_y, hi_x, hi_y), half_cell, cell_count(half_span(lo_x, hi_x), half_cell, kMaxCells),
                       cell_count(half_span(lo_y, hi_y), half_cell, kMaxCells)};
    lists_.clear();
    table_.clear();
    blocks_.clear();
    long_.reset(lo_x, lo_y, half_span(lo_x, hi_x), half_span(lo_y, hi_y), frame_.magnitude, half_cell);
  }
  double cell_size() const { return 2 * frame_.half_cell; }
  void add(const double* a, const double* b, Id id) {
    if (long_.takes(a, b)) return long_.add(a, b, id);
    const double* seg[2] = {a, b};
    for_cells_of_hull(frame_, seg, 2, [&](int i, int j) {
      const std::size_t cells = table_.size();
      const std::size_t slot = static_cast<std::size_t>(table_.insert(i, j));
      if (table_.size() != cells) blocks_.insert(i >> kBlockShift, j >> kBlockShift);
      lists_.grow(slot + 1);
      lists_.add(slot, id);
    });
  }
  /// Registers count segments on an empty grid (after reset()), seg(k, a, b, id) giving the k-th
  /// (the same each call): what count calls of add() would do, in one counting sort instead of a
  /// list growth per cell.
  template <class Seg> void add_all(std::size_t count, Seg&& seg) {
    const auto each = [&](auto&& f) { for_each_segment<Id>(count, seg, f); };
    if (lists_.size() != 0 || long_.size() != 0)
      return each([&](const double* a, const double* b, Id id) { add(a, b, id); });
    each([&](const double* a, const double* b, Id id) {
      if (long_.takes(a, b)) long_.add(a, b, id);
    });
    // Both passes insert (the second finds every cell the first added).
    lists_.build(0, [&](auto&& emit) {
      each([&](const double* a, const double* b, Id id) {
        if (long_.takes(a, b)) return;
        const double* s[2] = {a, b};
        for_cells_of_hull(frame_, s, 2, [&](int i, int j) { emit(static_cast<std::size_t>(table_.insert(i, j)), id); });
      });
    });
    table_.for_each([&](int i, int j) { blocks_.insert(i >> kBlockShift, j >> kBlockShift); });
  }
  /// Removes one registration of id (added with the same a, b).
  void remove(const double* a, const double* b, Id id) {
    if (long_.takes(a, b)) return long_.remove(a, b, id);
    stored_cells(a, b, [&](std::size_t c) {
      lists_.remove(c, id);
      return false;
    });
  }
  /// Calls f(id) for the registered segments that can meet segment ab until f returns true; true
  /// if it did. Read-only: concurrent queries are safe while nothing is added or removed.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    if (stored_cells(a, b, [&](std::size_t c) { return lists_.any(c, f); })) return true;
    return long_.any(a, b, f);
  }

 private:
  static constexpr int kMaxCells = 1 << 28;  // per axis
  static constexpr double kEdgesPerHalfCell = 8;
  // Calls f(cell list) for the stored cells of segment ab's strip until f returns true; true if
  // it did. A query whose strip would cross more cells than are stored (a long one on a fine
  // grid: up to 2^28 rows) reads every stored cell instead.
  template <class F> bool stored_cells(const double* a, const double* b, F&& f) const {
    const double rows = std::fabs(static_cast<double>(frame_.cy(a[1])) - frame_.cy(b[1])) + 1;
    const double cols = std::fabs(static_cast<double>(frame_.cx(a[0])) - frame_.cx(b[0])) + 1;
    if (3 * (rows + cols) > static_cast<double>(lists_.size())) {
      for (std::size_t c = 0; c < lists_.size(); ++c)
        if (f(c)) return true;
      return false;
    }
    const double* seg[2] = {a, b};
    bool done = false;
    if (rows + cols <= 4 * kBlock) {
      for_cells_of_hull(frame_, seg, 2, [&](int i, int j) {
        if (done) return;
        const int c = table_.find(i, j);
        if (c >= 0) done = f(static_cast<std::size_t>(c));
      });
      return done;
    }
    // A long strip: the same cells, but a block of kBlock x kBlock cells where no cell was ever
    // stored is passed over at once (a query across the empty middle of a figure).
    for_rows_of_hull(frame_, seg, 2, [&](int j, int lo, int hi) {
      for (int i = lo; i <= hi && !done;) {
        const int next = std::min(hi + 1, ((i >> kBlockShift) + 1) << kBlockShift);
        if (blocks_.find(i >> kBlockShift, j >> kBlockShift) < 0) {
          i = next;
          continue;
        }
        for (; i < next && !done; ++i) {
          const int c = table_.find(i, j);
          if (c >= 0) done = f(static_cast<std::size_t>(c));
        }
      }
    });
    return done;
  }
  static constexpr int kBlockShift = 5;  // blocks of 32 x 32 cells
  static constexpr int kBlock = 1 << kBlockShift;
  GridFrame frame_{0, 0, 0, 1, 1, 1};
  CellLists<Id> lists_;                   // by slot
  CellTable table_;                       // cell -> slot
  CellTable blocks_;                      // the blocks of kBlock x kBlock cells with a stored cell
  LongSegments<Id> long_;                 // the segments longer than LongSegments::kLongCells cells
};

}  // namespace constrict::detail
