// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D fallback's bucket grids of the points and of the boundary edges (fallback2.cpp), a
// member of the engine's state (engine2.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/parallel_invoke.h>

#include "constrict/points.hpp"
#include "core/detail/cell_table.hpp"
#include "core/detail/dense_segments.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/sparse_segments.hpp"

namespace constrict::engine2 {

// Bucket grids of the points and of the boundary edges, for the fallback's local tests. Cell
// indices are monotone in the coordinates, so a query over the cells a shape can touch finds
// every point / registered segment in it (exact candidate sets for the exact tests). Two layers:
// - coarse: area-sized cells, every cell an array slot (always);
// - fine: cells of 16 median boundary edges (SparseSegments::sparse_half_cell), only non-empty
//   cells stored (a CellTable for the points, SparseSegments for the edges), when that edge is far
//   below the coarse cell: on a curve sample the coarse cells hold O(√N) points each, and every side search read
//   hundreds of them (the noisy curve's fallback, docs/benchmarks.md). Near queries read the fine cells; a search that
//   grows far (a pair with an empty side) goes on over the coarse cells, where an empty plane is few cells.
// Either layer offers every point and edge a query can need, so the decisions are the same.
class Grid {
 public:
  void build(const PointSet& pts, double median_edge) {
    const std::size_t n = pts.size();
    double minx = pts[0][0], maxx = pts[0][0], miny = pts[0][1], maxy = pts[0][1];
    for (std::size_t i = 1; i < n; ++i) {
      minx = std::min(minx, pts[i][0]);
      maxx = std::max(maxx, pts[i][0]);
      miny = std::min(miny, pts[i][1]);
      maxy = std::max(maxy, pts[i][1]);
    }
    // Half units throughout (grid_cells.hpp): no overflow or underflow at any scale.
    const double w = detail::half_span(minx, maxx), h = detail::half_span(miny, maxy);
    const double mag = detail::box_magnitude(minx, miny, maxx, maxy);
    const double hcs = std::max({detail::balanced_cell(w, h, n), w / kMaxCells, h / kMaxCells});
    coarse_.frame = detail::GridFrame{
        minx, miny, mag, hcs, detail::cell_count(w, hcs, kMaxCells), detail::cell_count(h, hcs, kMaxCells)};
    const double fine = Sparse::sparse_half_cell(median_edge, w, h, mag, hcs);
    fine_on_ = fine > 0;
    std::vector<int> cell(n);
    const std::size_t nc = static_cast<std::size_t>(coarse_.frame.nx) * static_cast<std::size_t>(coarse_.frame.ny);
    for (std::size_t i = 0; i < n; ++i) cell[i] = static_cast<int>(coarse_.index(pts[i]));
    coarse_.group(cell, nc, false);
    if (fine_on_) {
      fine_.frame = detail::GridFrame{minx,
                                      miny,
                                      mag,
                                      fine,
                                      detail::cell_count(w, fine, kMaxFineCells),
                                      detail::cell_count(h, fine, kMaxFineCells)};
      fine_.table.clear(n / 2);
      for (std::size_t i = 0; i < n; ++i)
        cell[i] = fine_.table.insert(fine_.frame.cx(pts[i][0]), fine_.frame.cy(pts[i][1]));
      fine_.group(cell, fine_.table.size(), true);
      edges_fine_.reset(minx, miny, maxx, maxy, fine);
      // The fine search stops where its cells would outnumber a few coarse cells' points.
      std::size_t occupied = 0;
      for (std::size_t c = 0; c < nc; ++c) occupied += coarse_.start[c + 1] > coarse_.start[c];
      const double per_cell = static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(occupied, 1));
      fine_cells_ = kFineBudget * per_cell;
      fine_rings_ = static_cast<int>(std::ceil(0.5 * (std::sqrt(fine_cells_) - 1)));
    }
    edges_coarse_.reset(coarse_.frame);
  }
  /// The coarse cell edge (the search radii add it as a margin).
  double cell_size() const { return coarse_.cell_size(); }

  /// Ring search around (x, y): calls visit(p) for the points of the square rings of cells
  /// k = 0, 1, ... around the cell of (x, y), skipping a cell wholly farther than limit() (read
  /// before each cell; it may shrink as the search goes), until a ring lies wholly beyond limit()
  /// or done() holds (asked after each cell). visit must not care about order or repeats (a
  /// minimum, a flag): a search that outgrows the fine cells starts again on the coarse ones.
  /// Returns a distance within which every point was visited (limit() < it), or HUGE_VAL when
  /// every ring was read or done() ended the search.
  template <class Limit, class Visit, class Done>
  double rings(double x, double y, Limit&& limit, Visit&& visit, Done&& done) const {
    if (fine_on_) {
      const double r = fine_.rings(x, y, fine_rings_, limit, visit, done);
      if (r >= 0) return r;
    }
    return coarse_.rings(x, y, std::max(coarse_.frame.nx, coarse_.frame.ny), limit, visit, done);
  }
  /// Calls f(p) for every point that can lie in the closed convex hull of the m vertices v
  /// (2 <= m <= kMaxHullVertices, a convex polygon's vertices in order for m > 3), and maybe
  /// more, until done() (asked after each cell).
  template <class F, class Done>
  void points_in_hull(const double* const* v, int m, F&& f, Done&& done) const {
    const Layer& l = fine_on_ && fine_.hull_cells(v, m) <= fine_cells_ ? fine_ : coarse_;
    bool stop = false;
    detail::for_rows_of_hull(l.frame, v, m, [&](int j, int a, int b) {
      if (stop) return;
      l.occupied_in_row(j, a, b, [&](int i) {
        if (stop) return;
        l.points_in_cell(i, j, f);
        stop = done();
      });
    });
  }
  void add_edge(const double* a, const double* b, int id) {
    if (fine_on_) edges_fine_.add(a, b, id);
    edges_coarse_.add(a, b, id);
  }
  /// Takes edge id (added with the same a, b) out of both layers.
  void remove_edge(const double* a, const double* b, int id) {
    if (fine_on_) edges_fine_.remove(a, b, id);
    edges_coarse_.remove(a, b, id);
  }
  /// On a just built grid: add_edge(a, b, id) for count edges, seg(k, a, b, id) giving the k-th
  /// (the same each call), in one counting sort per layer (CellLists::build, or build_in_blocks on both cores for the
  /// coarse layer of a long boundary).
  /// The two layers are filled side by side (seg must allow concurrent calls).
  template <class Seg>
  void add_edges(std::size_t count, Seg&& seg) {
    if (!fine_on_) return edges_coarse_.add_all(count, seg);
    tbb::parallel_invoke([&] { edges_fine_.add_all(count, seg); }, [&] { edges_coarse_.add_all(count, seg); });
  }
  /// Calls f(id) for the registered edges that can meet segment ab (maybe more than once) until f
  /// returns true; true if it did.
  template <class F>
  bool any_edge(const double* a, const double* b, F&& f) const {
    const double* seg[2] = {a, b};
    if (fine_on_ && fine_.hull_cells(seg, 2) <= fine_cells_) return edges_fine_.any(a, b, f);
    return edges_coarse_.any(a, b, f);
  }

 private:
  using Sparse = detail::SparseSegments<int>;
  // One layer: its cells, and the points grouped by cell (by dense index or by table slot).
  struct Layer {
    detail::GridFrame frame{0, 0, 0, 1, 1, 1};
    detail::CellTable table;  // fine layer: cell -> slot
    bool sparse = false;
    std::vector<std::size_t> start;
    std::vector<int> ids;
    std::vector<std::uint64_t> occupied;  // dense layer: a bit per non-empty cell, rows of words
    std::size_t words_per_row = 0;
    double cell_size() const { return 2 * frame.half_cell; }  // +inf at most for a box near the double range
    std::size_t index(int i, int j) const {
      return static_cast<std::size_t>(j) * static_cast<std::size_t>(frame.nx) + static_cast<std::size_t>(i);
    }
    std::size_t index(const double* p) const { return index(frame.cx(p[0]), frame.cy(p[1])); }
    // Groups the points by cell (cell[i]: point i's dense index, or its table slot when sparse).
    void group(const std::vector<int>& cell, std::size_t nc, bool sparse_layer) {
      sparse = sparse_layer;
      start.assign(nc + 1, 0);
      for (const int c : cell) ++start[static_cast<std::size_t>(c) + 1];
      for (std::size_t c = 0; c < nc; ++c) start[c + 1] += start[c];
      ids.assign(cell.size(), 0);
      std::vector<std::size_t> fill(start.begin(), start.end() - 1);
      for (std::size_t i = 0; i < cell.size(); ++i)
        ids[fill[static_cast<std::size_t>(cell[i])]++] = static_cast<int>(i);
      if (sparse) return;
      words_per_row = (static_cast<std::size_t>(frame.nx) + 63) / 64;
      occupied.assign(words_per_row * static_cast<std::size_t>(frame.ny), 0);
      for (int j = 0; j < frame.ny; ++j)
        for (int i = 0; i < frame.nx; ++i)
          if (start[index(i, j) + 1] > start[index(i, j)])
            occupied[static_cast<std::size_t>(j) * words_per_row + static_cast<std::size_t>(i >> 6)] |= std::uint64_t{1}
                                                                                                        << (i & 63);
    }
    // Calls f(i) for the cells (i, j), a <= i <= b, that may hold points: on the dense layer only
    // the non-empty ones, 64 cells per word of its bitmap (a large shape over an empty plane
    // reads few words); on the sparse one every cell (the table says).
    template <class F>
    void occupied_in_row(int j, int a, int b, F&& f) const {
      if (sparse) {
        for (int i = a; i <= b; ++i) f(i);
        return;
      }
      const std::uint64_t* row = occupied.data() + static_cast<std::size_t>(j) * words_per_row;
      for (int w = a >> 6; w <= b >> 6; ++w) {
        std::uint64_t bits = row[w];
        if (w == a >> 6) bits &= ~std::uint64_t{0} << (a & 63);
        if (w == b >> 6 && (b & 63) != 63) bits &= (std::uint64_t{1} << ((b & 63) + 1)) - 1;
        while (bits) {
          f((w << 6) + __builtin_ctzll(bits));
          bits &= bits - 1;
        }
      }
    }
    template <class F>
    void points_in_cell(int i, int j, F&& f) const {
      const int c = sparse ? table.find(i, j) : static_cast<int>(index(i, j));
      if (c < 0) return;
      for (std::size_t k = start[static_cast<std::size_t>(c)]; k < start[static_cast<std::size_t>(c) + 1]; ++k)
        f(ids[k]);
    }
    // About the cells for_cells_of_hull reads for the hull of v: its strip along the edges and
    // the cells inside, at most its bounding box.
    double hull_cells(const double* const* v, int m) const {
      int i0 = frame.cx(v[0][0]), i1 = i0, j0 = frame.cy(v[0][1]), j1 = j0;
      for (int k = 1; k < m; ++k) {
        const int i = frame.cx(v[k][0]), j = frame.cy(v[k][1]);
        i0 = std::min(i0, i);
        i1 = std::max(i1, i);
        j0 = std::min(j0, j);
        j1 = std::max(j1, j);
      }
      const double cols = static_cast<double>(i1) - i0 + 1, rows = static_cast<double>(j1) - j0 + 1;
      double inside = 0;
      if (m >= 3) {  // the area (shoelace, from v[0]) in cells
        const double cs = cell_size();
        double twice = 0;
        for (int k = 1; k + 1 < m; ++k)
          twice += (v[k][0] - v[0][0]) * (v[k + 1][1] - v[0][1]) - (v[k][1] - v[0][1]) * (v[k + 1][0] - v[0][0]);
        inside = 0.5 * std::fabs(twice) / cs / cs;
      }
      return std::min(cols * rows, 3 * (cols + rows) + inside);
    }
    // Grid::rings on this layer, out to ring max_k: -1 if the search would go beyond it.
    template <class Limit, class Visit, class Done>
    double rings(double x, double y, int max_k, Limit&& limit, Visit&& visit, Done&& done) const {
      const int ci = frame.cx(x), cj = frame.cy(y);
      const double cs = cell_size();
      for (int k = 0; k <= max_k; ++k) {
        if (k >= 2) {
          const double d = static_cast<double>(k - 1) * cs;
          if (d > limit()) return d;
        }
        for (int jj = cj - k; jj <= cj + k; ++jj) {
          if (jj < 0 || jj >= frame.ny) continue;
          const bool edge_row = (jj == cj - k || jj == cj + k);
          for (int ii = ci - k; ii <= ci + k; ii += (edge_row ? 1 : 2 * k)) {
            if (ii >= 0 && ii < frame.nx && cell_within(ii - ci, jj - cj, cs, limit())) points_in_cell(ii, jj, visit);
            if (done()) return HUGE_VAL;
            if (k == 0) break;
          }
        }
      }
      return max_k >= std::max(frame.nx, frame.ny) ? HUGE_VAL : -1;
    }
  };
  // Can a point of the cell di, dj cells away from a point's own cell lie within `limit` of it?
  // A whole cell less per axis (the point may sit anywhere in its cell, and cell_of rounds), so a
  // cell is skipped only when all of it is farther. Compared in squared cell units (no root).
  static bool cell_within(int di, int dj, double cs, double limit) {
    const double x = std::max(0, std::abs(di) - 1), y = std::max(0, std::abs(dj) - 1);
    const double r = limit / cs;
    return !(x * x + y * y > r * r);
  }
  static constexpr int kMaxCells = 4096;         // per axis, coarse
  static constexpr int kMaxFineCells = 1 << 28;  // per axis, fine (SparseSegments' bound)
  static constexpr double kFineBudget = 16;      // fine cells read per coarse cell's points, at most
  Layer coarse_, fine_;
  bool fine_on_ = false;
  double fine_cells_ = 0;  // fine cells a query may read (kFineBudget coarse cells' points)
  int fine_rings_ = 0;     // the rings of about that many cells
  detail::DenseSegments<int> edges_coarse_;
  Sparse edges_fine_;  // with the fine layer (short queries)
};

}  // namespace constrict::engine2
