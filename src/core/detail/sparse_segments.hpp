// SPDX-License-Identifier: GPL-3.0-or-later
// A sparse uniform grid of segments with cells sized for the spacing where the data are (the 2D
// refinement's polygon edges, the fallback's boundary edges), for inputs whose points lie on a
// curve: an area-sized grid would hold O(√N) segments per cell there, and every local test would
// read them all (docs/benchmarks.md, the noisy curve). Only non-empty cells are stored: a
// CellTable (cell_table.hpp) in front of one id list per cell. A segment is registered in
// the cells its strip crosses (for_cells_of_hull, grid_cells.hpp); a segment longer than
// kLongCells cells goes to a coarser level instead (a strip of thousands of fine cells each):
// levels of cells kLevelGrowth times wider each, a segment in the first level where it is at most
// kLevelGrowth cells long, registered with its bounding box in the cells that box meets. A query
// visits every cell where a point of the query segment can lie (fine cells: its strip; levels:
// its box), so it reports every registered segment that can meet it (exact candidate sets for
// exact tests), possibly more than once from the fine cells; from a level, once (in the cell of
// the lower corner of the two boxes' intersection), and only when the boxes meet and the query's
// ends are not strictly on one side of the segment's line (exact orientations: such segments
// cannot meet it).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "constrict/predicates.hpp"
#include "core/detail/cell_lists.hpp"
#include "core/detail/cell_table.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/semi_static.hpp"

namespace constrict::detail {

template <class Id> class SparseSegments {
 public:
  static constexpr double kLongCells = 32;  ///< longer segments (in cells, either axis): the list

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
    levels_.clear();
    long_count_ = 0;
    // The levels: cells of kLongCells / kLevelGrowth fine cells, then kLevelGrowth times wider
    // each, up to one cell over the box (which takes every longer segment).
    const double hw = half_span(lo_x, hi_x), hh = half_span(lo_y, hi_y);
    for (double h = half_cell * (kLongCells / kLevelGrowth);; h *= kLevelGrowth) {
      Level l;
      l.frame = GridFrame{lo_x, lo_y, frame_.magnitude, h, cell_count(hw, h, kMaxCells), cell_count(hh, h, kMaxCells)};
      levels_.push_back(std::move(l));
      if ((levels_.back().frame.nx == 1 && levels_.back().frame.ny == 1) || !std::isfinite(h * kLevelGrowth)) break;
    }
    levels_.back().frame.half_cell = HUGE_VAL;  // (one cell, whatever the span: takes every segment)
    levels_.back().frame.nx = levels_.back().frame.ny = 1;
  }
  double cell_size() const { return 2 * frame_.half_cell; }
  /// Does segment ab go to the long list (longer than kLongCells cells along an axis)?
  bool is_long(const double* a, const double* b) const {
    return !(std::max(std::fabs(a[0] - b[0]), std::fabs(a[1] - b[1])) <= kLongCells * cell_size());
  }
  void add(const double* a, const double* b, Id id) {
    if (is_long(a, b)) return add_long(a, b, id);
    const double* seg[2] = {a, b};
    for_cells_of_hull(frame_, seg, 2, [&](int i, int j) {
      const std::size_t slot = static_cast<std::size_t>(table_.insert(i, j));
      lists_.grow(slot + 1);
      lists_.add(slot, id);
    });
  }
  /// Registers count segments on an empty grid (after reset()), seg(k, a, b, id) giving the k-th
  /// (the same each call): what count calls of add() would do, in one counting sort instead of a
  /// list growth per cell.
  template <class Seg> void add_all(std::size_t count, Seg&& seg) {
    const auto each = [&](auto&& f) { for_each_segment<Id>(count, seg, f); };
    if (lists_.size() != 0 || long_count_ != 0)
      return each([&](const double* a, const double* b, Id id) { add(a, b, id); });
    each([&](const double* a, const double* b, Id id) {
      if (is_long(a, b)) add_long(a, b, id);
    });
    // Both passes insert (the second finds every cell the first added).
    lists_.build(0, [&](auto&& emit) {
      each([&](const double* a, const double* b, Id id) {
        if (is_long(a, b)) return;
        const double* s[2] = {a, b};
        for_cells_of_hull(frame_, s, 2, [&](int i, int j) { emit(static_cast<std::size_t>(table_.insert(i, j)), id); });
      });
    });
  }
  /// Removes one registration of id (added with the same a, b).
  void remove(const double* a, const double* b, Id id) {
    if (is_long(a, b)) {
      Level& l = levels_[level_of(a, b)];
      if (!l.used) return;
      bool found = false;
      l.box_cells(std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[0], b[0]), std::max(a[1], b[1]),
                  [&](int i, int j) {
                    const int c = l.table.find(i, j);
                    if (c < 0) return;
                    std::vector<Long>& list = l.lists[static_cast<std::size_t>(c)];
                    const auto it = std::find_if(list.begin(), list.end(), [&](const Long& e) { return e.id == id; });
                    if (it == list.end()) return;
                    *it = list.back();
                    list.pop_back();
                    --l.count;
                    found = true;
                  });
      if (found) --long_count_;
      return;
    }
    stored_cells(a, b, [&](std::size_t c) {
      lists_.remove(c, id);
      return false;
    });
  }
  /// Calls f(id) for the registered segments that can meet segment ab until f returns true; true
  /// if it did. Read-only: concurrent queries are safe while nothing is added or removed.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    if (stored_cells(a, b, [&](std::size_t c) { return lists_.any(c, f); })) return true;
    if (long_count_ == 0) return false;
    const double lo[2] = {std::min(a[0], b[0]), std::min(a[1], b[1])}, hi[2] = {std::max(a[0], b[0]), std::max(a[1], b[1])};
    for (const Level& l : levels_) {
      if (l.count == 0) continue;
      // The cell's segments whose boxes meet the query's, each reported in one cell only.
      // (The cell of the intersection's lower corner: cell_of is monotone, so its column is the
      // larger of the query's and the segment's first columns; likewise its row.)
      const int qi = l.frame.cx(lo[0]), qj = l.frame.cy(lo[1]);
      const auto cell = [&](std::size_t slot, int i, int j) {
        for (const Long& e : l.lists[slot]) {
          if (e.box[2] < lo[0] || e.box[0] > hi[0] || e.box[3] < lo[1] || e.box[1] > hi[1]) continue;
          if (std::max(qi, e.first[0]) != i || std::max(qj, e.first[1]) != j) continue;
          // The segment from its box (its ends are two opposite corners): exact, no memory read.
          const double p[2] = {e.box[0], e.rising ? e.box[1] : e.box[3]};
          const double q[2] = {e.box[2], e.rising ? e.box[3] : e.box[1]};
          if (orient2_exact_sign(p, q, a) * orient2_exact_sign(p, q, b) > 0) continue;
          if (f(e.id)) return true;
        }
        return false;
      };
      const double cells = (static_cast<double>(l.frame.cx(hi[0])) - l.frame.cx(lo[0]) + 1) *
                           (static_cast<double>(l.frame.cy(hi[1])) - l.frame.cy(lo[1]) + 1);
      bool done = false;
      if (cells > static_cast<double>(l.table.size())) {  // a long query: every stored cell
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
  static constexpr double kEdgesPerHalfCell = 8;
  /// A level's cells are this many times wider than the previous level's, and a segment goes to
  /// the first level where it is at most this many cells long (so it is registered in a strip of
  /// a few cells, and a cell holds only segments about as long as it or longer). Two concentric
  /// circles of 10^5 points, whose single polygon zigzags between them (27 000 edges of half the
  /// figure): every query had read all of them, bounding box first (refinement 6.7 s).
  static constexpr double kLevelGrowth = 2;
  struct Long {
    Id id;
    bool rising;    // the segment runs from (min x, min y) to (max x, max y), else from (min x, max y)
    int first[2];   // the cell of the box's lower corner, in the segment's level
    double box[4];  // min x, min y, max x, max y
  };
  static int orient2_exact_sign(const double* a, const double* b, const double* c) {
    bool ok = false;
    const int s = orient2_filtered(a, b, c, ok);
    return ok ? s : orient2(a, b, c);
  }
  struct Level {
    GridFrame frame{0, 0, 0, 1, 1, 1};
    CellTable table;                        // cell -> slot (cleared when first used)
    std::vector<std::vector<Long>> lists;   // by slot
    std::vector<std::array<int, 2>> cells;  // slot -> cell
    std::size_t count = 0;                  // registrations
    bool used = false;
    // Calls f(i, j) for the cells of the box [x0, x1] x [y0, y1].
    template <class F>
    void box_cells(double x0, double y0, double x1, double y1, F&& f) const {
      const int i0 = frame.cx(x0), i1 = frame.cx(x1), j1 = frame.cy(y1);
      for (int j = frame.cy(y0); j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(i, j);
    }
  };
  // The level of a long segment: the first where it is at most kLevelGrowth cells long (along
  // either axis); the last level has one cell.
  std::size_t level_of(const double* a, const double* b) const {
    const double extent = std::max(std::fabs(a[0] - b[0]), std::fabs(a[1] - b[1]));
    std::size_t k = 0;
    while (k + 1 < levels_.size() && !(extent <= kLevelGrowth * 2 * levels_[k].frame.half_cell)) ++k;
    return k;
  }
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
    for_cells_of_hull(frame_, seg, 2, [&](int i, int j) {
      if (done) return;
      const int c = table_.find(i, j);
      if (c >= 0) done = f(static_cast<std::size_t>(c));
    });
    return done;
  }
  void add_long(const double* a, const double* b, Id id) {
    const bool rising = (a[0] < b[0]) == (a[1] < b[1]);  // (either when the segment is axis-parallel)
    Level& l = levels_[level_of(a, b)];
    const double x0 = std::min(a[0], b[0]), y0 = std::min(a[1], b[1]);
    const Long e{id, rising, {l.frame.cx(x0), l.frame.cy(y0)}, {x0, y0, std::max(a[0], b[0]), std::max(a[1], b[1])}};
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
    ++long_count_;
  }
  GridFrame frame_{0, 0, 0, 1, 1, 1};
  CellLists<Id> lists_;                   // by slot
  CellTable table_;                       // cell -> slot
  std::vector<Level> levels_;             // the long segments
  std::size_t long_count_ = 0;            // long segments registered
};

}  // namespace constrict::detail
