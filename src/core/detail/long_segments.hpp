// SPDX-License-Identifier: GPL-3.0-or-later
// The long segments of a segment grid (sparse_segments.hpp, dense_segments.hpp): those whose strip
// would cross many of the grid's cells. They go to levels of cells kGrowth times wider each: a
// segment to the first level where it is at most kGrowth cells long (along either axis), where it
// is registered with its bounding box in the cells that box meets (at most 3 x 3); the last level
// has one cell and takes every longer segment. A query reads the cells of its own box in each
// level and reports a segment there once, from the cell of the lower corner of the two boxes'
// intersection, and only when the boxes meet and the query's ends are not strictly on one side of
// the segment's line (exact orientations on the segment's ends, which are two opposite corners of
// its box: no memory read; such a segment cannot meet the query). So it reports every registered
// segment that can meet the query segment (closed), each once: exact candidate sets for exact
// tests.
//
// Why: a single polygon through two concentric circles zigzags between them (27 000 edges of half
// the figure at 10^5 points). They were in one list that every query read, box first, and the
// query's caller then read each box hit's coordinates (docs/benchmarks.md, "Inputs of several
// rings").
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/detail/cell_table.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/semi_static.hpp"

namespace constrict::detail {

template <class Id> class LongSegments {
 public:
  /// A level's cells are this many times wider than the previous level's (2 rather than 4: a cell
  /// holds fewer segments that merely pass by; concentric circles at 10^5, refinement 3.84 s with
  /// 4, 3.42 s with 2).
  static constexpr double kGrowth = 2;

  /// A segment longer than this many of its grid's cells (along either axis) is long.
  static constexpr double kLongCells = 32;

  /// Empty, for the long segments of a grid of cells of half edge grid_half_cell over the box
  /// from (lo_x, lo_y) with half spans hw, hh and largest coordinate magnitude mag. The first
  /// level's cells are kLongCells grid cells wide: the shortest long segments are 1 to kGrowth
  /// cells long there.
  void reset(double lo_x, double lo_y, double hw, double hh, double mag, double grid_half_cell) {
    levels_.clear();
    count_ = 0;
    limit_ = kLongCells * (2 * grid_half_cell);
    for (double h = grid_half_cell * kLongCells;; h *= kGrowth) {
      Level l;
      l.frame = GridFrame{lo_x, lo_y, mag, h, cell_count(hw, h, kMaxCells), cell_count(hh, h, kMaxCells)};
      levels_.push_back(std::move(l));
      // (A cell edge of 0, from a subnormal box, would never grow: that level is the last.)
      if ((levels_.back().frame.nx == 1 && levels_.back().frame.ny == 1) || !(h > 0) || !std::isfinite(h * kGrowth))
        break;
    }
    Level& top = levels_.back();  // one cell, whatever the span: takes every segment
    top.frame.half_cell = HUGE_VAL;
    top.frame.nx = top.frame.ny = 1;
  }
  /// Segments registered.
  std::size_t size() const { return count_; }
  /// Is segment ab long (registered here rather than in its grid's cells)?
  bool takes(const double* a, const double* b) const { return !(extent(a, b) <= limit_); }

  void add(const double* a, const double* b, Id id) {
    Level& l = levels_[level_of(a, b)];
    const double x0 = std::min(a[0], b[0]), y0 = std::min(a[1], b[1]);
    const bool rising = (a[0] < b[0]) == (a[1] < b[1]);  // (either when axis-parallel)
    const Entry e{id, rising, {{l.frame.cx(x0), l.frame.cy(y0)}}, {{x0, y0, std::max(a[0], b[0]), std::max(a[1], b[1])}}};
    if (!l.used) {
      l.table.clear();
      l.used = true;
    }
    l.box_cells(e.box[0], e.box[1], e.box[2], e.box[3], [&](int i, int j) {
      const std::size_t slot = static_cast<std::size_t>(l.table.insert(i, j));
      if (slot >= l.lists.size()) {
        l.lists.resize(slot + 1);
        l.cells.push_back({{i, j}});
      }
      l.lists[slot].push_back(e);
      ++l.count;
    });
    ++count_;
  }
  /// Removes id (added with the same a, b); nothing if it is not there.
  void remove(const double* a, const double* b, Id id) {
    Level& l = levels_[level_of(a, b)];
    if (!l.used) return;
    bool found = false;
    l.box_cells(std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[0], b[0]), std::max(a[1], b[1]), [&](int i, int j) {
      const int c = l.table.find(i, j);
      if (c < 0) return;
      std::vector<Entry>& list = l.lists[static_cast<std::size_t>(c)];
      const auto it = std::find_if(list.begin(), list.end(), [&](const Entry& e) { return e.id == id; });
      if (it == list.end()) return;
      *it = list.back();
      list.pop_back();
      --l.count;
      found = true;
    });
    if (found) --count_;
  }
  /// Calls f(id) for the registered segments that can meet segment ab, each once, until f returns
  /// true; true if it did. Read-only.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    if (count_ == 0) return false;
    const double lo[2] = {std::min(a[0], b[0]), std::min(a[1], b[1])}, hi[2] = {std::max(a[0], b[0]), std::max(a[1], b[1])};
    for (const Level& l : levels_) {
      if (l.count == 0) continue;
      // The cell of the intersection's lower corner: cell_of is monotone, so its column is the
      // larger of the query's and the segment's first columns; likewise its row.
      const int qi = l.frame.cx(lo[0]), qj = l.frame.cy(lo[1]);
      const auto cell = [&](std::size_t slot, int i, int j) {
        for (const Entry& e : l.lists[slot]) {
          if (e.box[2] < lo[0] || e.box[0] > hi[0] || e.box[3] < lo[1] || e.box[1] > hi[1]) continue;
          if (std::max(qi, e.first[0]) != i || std::max(qj, e.first[1]) != j) continue;
          const double p[2] = {e.box[0], e.rising ? e.box[1] : e.box[3]};
          const double q[2] = {e.box[2], e.rising ? e.box[3] : e.box[1]};
          if (orient2_fast(p, q, a) * orient2_fast(p, q, b) > 0) continue;
          if (f(e.id)) return true;
        }
        return false;
      };
      const double cells = (static_cast<double>(l.frame.cx(hi[0])) - qi + 1) * (static_cast<double>(l.frame.cy(hi[1])) - qj + 1);
      bool done = false;
      // A query whose box has more cells than the level has entries reads every entry instead
      // (either way at most about as many steps as the level has entries).
      if (cells > static_cast<double>(l.count)) {
        for (std::size_t c = 0; c < l.cells.size() && !done; ++c) done = cell(c, l.cells[c][0], l.cells[c][1]);
      } else {
        l.box_cells(lo[0], lo[1], hi[0], hi[1], [&](int i, int j) {
          if (done) return;
          const int c = l.table.find(i, j);
          if (c >= 0) done = cell(static_cast<std::size_t>(c), i, j);
        });
      }
      if (done) return true;
    }
    return false;
  }

 private:
  static constexpr int kMaxCells = 1 << 28;  // per axis
  struct Entry {
    Id id;
    bool rising;               // the segment runs from (min x, min y) to (max x, max y), else from (min x, max y)
    std::array<int, 2> first;  // the cell of the box's lower corner, in the segment's level
    std::array<double, 4> box;  // min x, min y, max x, max y
  };
  struct Level {
    GridFrame frame{0, 0, 0, 1, 1, 1};
    CellTable table;                        // cell -> slot (cleared when first used)
    std::vector<std::vector<Entry>> lists;  // by slot
    std::vector<std::array<int, 2>> cells;  // slot -> cell
    std::size_t count = 0;                  // registrations
    bool used = false;
    // Calls f(i, j) for the cells of the box [x0, x1] x [y0, y1].
    template <class F> void box_cells(double x0, double y0, double x1, double y1, F&& f) const {
      const int i0 = frame.cx(x0), i1 = frame.cx(x1), j1 = frame.cy(y1);
      for (int j = frame.cy(y0); j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(i, j);
    }
  };
  // The larger of the segment's extents along the axes.
  static double extent(const double* a, const double* b) {
    return std::max(std::fabs(a[0] - b[0]), std::fabs(a[1] - b[1]));
  }
  // The first level where the segment is at most kGrowth cells long; the last one otherwise.
  std::size_t level_of(const double* a, const double* b) const {
    const double e = extent(a, b);
    std::size_t k = 0;
    while (k + 1 < levels_.size() && !(e <= kGrowth * 2 * levels_[k].frame.half_cell)) ++k;
    return k;
  }
  std::vector<Level> levels_;
  std::size_t count_ = 0;
  double limit_ = HUGE_VAL;  // longer segments are long (kLongCells grid cells)
};

}  // namespace constrict::detail
