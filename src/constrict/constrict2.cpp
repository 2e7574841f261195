// SPDX-License-Identifier: GPL-3.0-or-later
// 2D γ-constriction of the Delaunay triangulation (seed paper §4.1, §5; spec §3.1-3.5) with local
// fallbacks after a lock (paper §4.3; spec §3.6, §3.7) and a final repair. See
// docs/reconstruction-2d.md for the algorithm and its guarantees.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "constrict/constrict.hpp"
#include "constrict/criterion.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/memory.hpp"
#include "constrict/predicates.hpp"
#include "constrict/detail/apex_lens2.hpp"
#include "constrict/detail/refine2.hpp"
#include "constrict/detail/share2.hpp"
#include "constrict/detail/segments2.hpp"
#include "constrict/validate.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/edge_key.hpp"
#include "core/detail/dense_segments.hpp"
#include "core/detail/cell_table.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/ordered_pack.hpp"
#include "core/detail/quad_heap.hpp"
#include "core/detail/sparse_segments.hpp"
#include "cgal/detail/delaunay_local.hpp"

namespace constrict {
namespace {
using detail::closed_segments_meet;
using detail::on_closed_segment;
using detail::same_side_collinear;
using detail::orient2_fast;

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::array<int, 3> sorted3(int a, int b, int c) {
  std::array<int, 3> s{{a, b, c}};
  std::sort(s.begin(), s.end());
  return s;
}

// Heap entry: larger key first; equal keys -> smallest sorted vertex triple (spec §3.5).
struct Entry {
  double key;
  std::array<int, 3> ids;  // sorted vertex ids (tie-break)
  int a, b, y;             // boundary edge a->b, apex y
  int t;                   // triangle id (Delaunay stage) or -1
  unsigned version;
};
struct EntryLess {
  bool operator()(const Entry& l, const Entry& r) const {
    if (l.key != r.key) return l.key < r.key;
    return l.ids > r.ids;
  }
};
using Heap = std::priority_queue<Entry, std::vector<Entry>, EntryLess>;

// Entry of the Delaunay-stage heap, 16 bytes (the heap is the constriction's main memory
// traffic): triangle t, its boundary edge index and the triangle's version at the push. The
// order is that of Entry: larger key, then the smaller sorted vertex triple (read from the
// triangle only on equal keys).
struct TriEntry {
  double key;
  std::uint32_t t;
  std::uint32_t version_edge;  // version << 2 | boundary edge index
};
// The tie-break triples (sorted input ids of each triangle), made at the first tie: inputs with
// many equal keys (grids, rasters: right angles everywhere) compare them at almost every heap
// step, and reading them through the id map is a random access per vertex.
struct TieKeys {
  const std::vector<std::array<int, 3>>* tris = nullptr;
  const std::vector<int>* gid = nullptr;  // ranked id -> input id (the tie-break is on input ids)
  std::vector<std::array<int, 3>> sorted;
  const std::array<int, 3>& of(std::uint32_t t) {
    if (sorted.empty()) {
      sorted.resize(tris->size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sorted.size(), 8192),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          const auto& g = *gid;
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                            const auto& a = (*tris)[k];
                            sorted[k] = sorted3(g[U(a[0])], g[U(a[1])], g[U(a[2])]);
                          }
                        });
    }
    return sorted[t];
  }
  static std::size_t U(int i) { return static_cast<std::size_t>(i); }
};
struct TriEntryLess {
  TieKeys* ties;
  bool operator()(const TriEntry& l, const TriEntry& r) const {
    if (l.key != r.key) return l.key < r.key;
    return ties->of(l.t) > ties->of(r.t);
  }
};
using TriHeap = detail::QuadHeap<TriEntry, TriEntryLess>;

// Bucket grids of the points and of the boundary edges, for the fallback's local tests. Cell
// indices are monotone in the coordinates, so a query over the cells a shape can touch finds
// every point / registered segment in it (exact candidate sets for the exact tests). Two layers:
// - coarse: area-sized cells, every cell an array slot (always);
// - fine: cells of 16 median boundary edges (SparseSegments::sparse_half_cell), only non-empty
//   cells stored (a CellTable for the points, SparseSegments for the edges), when that edge is far
//   below the coarse cell: on a curve sample the coarse cells hold O(√N) points each, and every side search read hundreds of
//   them (the noisy curve's fallback, docs/benchmarks.md). Near queries read the fine cells; a
//   search that grows far (a pair with an empty side) goes on over the coarse cells, where an
//   empty plane is few cells.
// Either layer offers every point and edge a query can need, so the decisions are the same.
class Grid {
 public:
  void build(const PointSet& pts, double median_edge) {
    const std::size_t n = pts.size();
    double minx = pts[0][0], maxx = pts[0][0], miny = pts[0][1], maxy = pts[0][1];
    for (std::size_t i = 1; i < n; ++i) {
      minx = std::min(minx, pts[i][0]); maxx = std::max(maxx, pts[i][0]);
      miny = std::min(miny, pts[i][1]); maxy = std::max(maxy, pts[i][1]);
    }
    // Half units throughout (grid_cells.hpp): no overflow or underflow at any scale.
    const double w = detail::half_span(minx, maxx), h = detail::half_span(miny, maxy);
    const double mag = detail::box_magnitude(minx, miny, maxx, maxy);
    const double hcs = std::max({detail::balanced_cell(w, h, n), w / kMaxCells, h / kMaxCells});
    coarse_.frame = detail::GridFrame{minx, miny, mag, hcs, detail::cell_count(w, hcs, kMaxCells), detail::cell_count(h, hcs, kMaxCells)};
    const double fine = Sparse::sparse_half_cell(median_edge, w, h, mag, hcs);
    fine_on_ = fine > 0;
    std::vector<int> cell(n);
    const std::size_t nc = static_cast<std::size_t>(coarse_.frame.nx) * static_cast<std::size_t>(coarse_.frame.ny);
    for (std::size_t i = 0; i < n; ++i) cell[i] = static_cast<int>(coarse_.index(pts[i]));
    coarse_.group(cell, nc, false);
    if (fine_on_) {
      fine_.frame = detail::GridFrame{minx, miny, mag, fine, detail::cell_count(w, fine, kMaxFineCells), detail::cell_count(h, fine, kMaxFineCells)};
      fine_.table.clear(n / 2);
      for (std::size_t i = 0; i < n; ++i) cell[i] = fine_.table.insert(fine_.frame.cx(pts[i][0]), fine_.frame.cy(pts[i][1]));
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
  template <class Limit, class Visit, class Done> double rings(double x, double y, Limit&& limit, Visit&& visit, Done&& done) const {
    if (fine_on_) {
      const double r = fine_.rings(x, y, fine_rings_, limit, visit, done);
      if (r >= 0) return r;
    }
    return coarse_.rings(x, y, std::max(coarse_.frame.nx, coarse_.frame.ny), limit, visit, done);
  }
  /// Calls f(p) for every point that can lie in the closed convex hull of the m vertices v
  /// (2 <= m <= kMaxHullVertices, a convex polygon's vertices in order for m > 3), and maybe
  /// more, until done() (asked after each cell).
  template <class F, class Done> void points_in_hull(const double* const* v, int m, F&& f, Done&& done) const {
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
  /// On a just built grid: add_edge(a, b, id) for count edges, seg(k, a, b, id) giving the k-th
  /// (the same each call), in one counting sort per layer (CellLists::build).
  /// The two layers are filled side by side (seg must allow concurrent calls).
  template <class Seg> void add_edges(std::size_t count, Seg&& seg) {
    if (!fine_on_) return edges_coarse_.add_all(count, seg);
    tbb::parallel_invoke([&] { edges_fine_.add_all(count, seg); }, [&] { edges_coarse_.add_all(count, seg); });
  }
  /// Calls f(id) for the registered edges that can meet segment ab (maybe more than once) until f
  /// returns true; true if it did.
  template <class F> bool any_edge(const double* a, const double* b, F&& f) {
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
      for (std::size_t i = 0; i < cell.size(); ++i) ids[fill[static_cast<std::size_t>(cell[i])]++] = static_cast<int>(i);
      if (sparse) return;
      words_per_row = (static_cast<std::size_t>(frame.nx) + 63) / 64;
      occupied.assign(words_per_row * static_cast<std::size_t>(frame.ny), 0);
      for (int j = 0; j < frame.ny; ++j)
        for (int i = 0; i < frame.nx; ++i)
          if (start[index(i, j) + 1] > start[index(i, j)])
            occupied[static_cast<std::size_t>(j) * words_per_row + static_cast<std::size_t>(i >> 6)] |= std::uint64_t{1} << (i & 63);
    }
    // Calls f(i) for the cells (i, j), a <= i <= b, that may hold points: on the dense layer only
    // the non-empty ones, 64 cells per word of its bitmap (a large shape over an empty plane
    // reads few words); on the sparse one every cell (the table says).
    template <class F> void occupied_in_row(int j, int a, int b, F&& f) const {
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
    template <class F> void points_in_cell(int i, int j, F&& f) const {
      const int c = sparse ? table.find(i, j) : static_cast<int>(index(i, j));
      if (c < 0) return;
      for (std::size_t k = start[static_cast<std::size_t>(c)]; k < start[static_cast<std::size_t>(c) + 1]; ++k) f(ids[k]);
    }
    // About the cells for_cells_of_hull reads for the hull of v: its strip along the edges and
    // the cells inside, at most its bounding box.
    double hull_cells(const double* const* v, int m) const {
      int i0 = frame.cx(v[0][0]), i1 = i0, j0 = frame.cy(v[0][1]), j1 = j0;
      for (int k = 1; k < m; ++k) {
        const int i = frame.cx(v[k][0]), j = frame.cy(v[k][1]);
        i0 = std::min(i0, i); i1 = std::max(i1, i);
        j0 = std::min(j0, j); j1 = std::max(j1, j);
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
  static constexpr int kMaxCells = 4096;        // per axis, coarse
  static constexpr int kMaxFineCells = 1 << 28;  // per axis, fine (SparseSegments' bound)
  static constexpr double kFineBudget = 16;      // fine cells read per coarse cell's points, at most
  Layer coarse_, fine_;
  bool fine_on_ = false;
  double fine_cells_ = 0;  // fine cells a query may read (kFineBudget coarse cells' points)
  int fine_rings_ = 0;     // the rings of about that many cells
  detail::DenseSegments<int> edges_coarse_;
  Sparse edges_fine_;  // with the fine layer (short queries)
};

}  // namespace

// Vertex ids inside the engine are *ranked* ids: the order of CGAL's spatially sorted insertion
// (build_delaunay2_ranked), so that the triangle loops, the heap and the walks along the polygon
// touch nearby memory (input ids are in arbitrary, often shuffled order). Every order-sensitive
// decision (heap ties, the degree-4 cascade, where the polygon starts) compares input ids
// through gid, and every result leaves in input ids: the output is the same as with input ids.
struct Constrictor2::Impl {
  const PointSet* pts = nullptr;  // the ranked points (== &rpts)
  PointSet rpts;
  std::vector<int> gid;           // ranked id -> input id
  Constrict2Options opt;
  Constrict2Visitor* visitor = nullptr;
  bool ready = false;
  Delaunay2 dt;
  std::size_t n = 0;
  std::vector<char> alive, onb;
  std::vector<int> nxt, prv;
  std::vector<unsigned> ver;
  std::size_t n_onb = 0, removed = 0;
  TieKeys ties{&dt.triangles, &gid, {}};
  TriHeap heap{TriEntryLess{&ties}};
  bool locked = false, stopped = false;
  double ms_delaunay = 0, ms_constrict = 0;
  int scale_exp = 0;  // rpts = ranked input * 2^-scale_exp (exact; init)

  // Fallback state (built on lock).
  bool fb_ready = false, adj_ready = false;
  std::vector<int> adj_off, adj;          // DT adjacency (CSR)
  std::vector<int> vt_off, vt;            // vertex -> incident triangles (CSR)
  Grid grid;
  struct BEdge { int u, v; bool alive; };
  std::vector<BEdge> bedges;
  std::vector<int> out_edge;              // boundary edge id of (v, nxt[v])
  std::unordered_map<std::uint64_t, double> delta_cache;
  std::unordered_set<std::uint64_t> aug;  // degree-4 augmentation edges
  std::vector<unsigned> mark;
  unsigned mark_stamp = 0;

  const double* P(int i) const { return (*pts)[static_cast<std::size_t>(i)]; }
  static std::size_t U(int i) { return static_cast<std::size_t>(i); }

  int G(int v) const { return v < 0 ? v : gid[U(v)]; }
  std::array<int, 3> sorted_gid3(int a, int b, int c) const { return sorted3(G(a), G(b), G(c)); }

  // stage: a C string, so that the million removals without a visitor build no std::string;
  // with one (the CLI's progress), the event is reused and its stage name copied only when the
  // stage changes.
  Constrict2Event event;
  void emit(Constrict2Event::Kind k, int a, int b, int y, double crit, const char* stage) {
    if (!visitor) return;
    event.kind = k;
    event.triangle = {{G(a), G(b), G(y)}};
    event.criterion = crit;
    if (event.stage != stage) event.stage = stage;
    visitor->on_event(event);
  }

  // Key of removing triangle (a, b, y) through boundary edge a->b: 1 - γ(ab; y) (§3.4) or the
  // chosen comparison criterion (criterion.hpp); the fallbacks use the same key.
  double criterion_key(int a, int b, int y) const {
    if (opt.criterion == Criterion::Gamma) return 1.0 - apex_gamma2(P(a), P(b), P(y));
    return criterion_key2(opt.criterion, P(a), P(b), P(y));
  }

  // ---------------------------------------------------------------- Delaunay stage (spec §3.5)
  bool is_boundary_edge(int t, int i) const {
    const int nb = dt.neighbors[U(t)][U(i)];
    return nb < 0 || !alive[U(nb)];
  }
  // Removable ⇔ exactly one boundary edge and its opposite vertex not on the boundary (§3.3).
  int removable_edge(int t) const {
    if (!alive[U(t)]) return -1;
    int cnt = 0, which = -1;
    for (int i = 0; i < 3; ++i)
      if (is_boundary_edge(t, i)) { ++cnt; which = i; }
    if (cnt != 1) return -1;
    if (onb[U(dt.triangles[U(t)][U(which)])]) return -1;
    return which;
  }
  void push_triangle(int t) {
    const int i = removable_edge(t);
    if (i < 0) return;
    const auto& tr = dt.triangles[U(t)];
    const int y = tr[U(i)], a = tr[U((i + 1) % 3)], b = tr[U((i + 2) % 3)];
    // The boundary runs a->b with the body on its left; γ(ab; y) is the inner side value (§3.2).
    const double key = criterion_key(a, b, y);
    heap.push(TriEntry{key, static_cast<std::uint32_t>(t), (++ver[U(t)] << 2) | static_cast<unsigned>(i)});
  }

  Status init(const PointSet& points) {
    pts = &rpts;
    if (points.dim != 2) return {StatusCode::InvalidArgument, "reconstruct2: points must be 2D"};
    // Duplicates are found by the triangulation (fewer vertices than points); check_points then
    // names them.
    Status st = detail::check_points_deferred(points);
    if (!st) return st;
    const auto t0 = Clock::now();
    n = points.size();
    // Far from 1 in magnitude, the double parts (apex values, grid cells, search radii) would
    // underflow or overflow: work on a copy scaled by a power of two when that is exact (it
    // changes no predicate, so the polygon is the one of the input at any scale); otherwise keep
    // the input's coordinates (the grid and the searches are scale free, the keys may degrade).
    const PointSet* build_from = &points;
    PointSet scaled;
    if (const int e = max_coordinate_exponent(points); e > kRescaleExponent || e < -kRescaleExponent)
      if (exact_power_of_two_scale(points, scaled, scale_exp).is_ok()) build_from = &scaled;
    st = detail::build_delaunay2_ranked(*build_from, dt, rpts, gid);
    if (st.code() == StatusCode::Duplicate) return check_points(points);
    if (!st) return st;
    ms_delaunay = ms_since(t0);
    const std::size_t nt = dt.triangles.size();
    // The state arrays are made once CGAL's triangulation is gone (beside it, they were the
    // run's peak memory), on both cores.
    tbb::parallel_invoke([&] { alive.assign(nt, 1); }, [&] { ver.assign(nt, 0); },
                         [&] {
                           onb.assign(n, 0);
                           nxt.assign(n, -1);
                           prv.assign(n, -1);
                         });
    // Convex hull: DT edges without a neighbour; collinear hull points are hull vertices. The
    // triangles with such an edge, in triangle order, found on both cores.
    const std::vector<std::uint32_t> hull = detail::ordered_pack<std::uint32_t>(nt, [&](std::size_t t, auto&& push) {
      const auto& nb = dt.neighbors[t];
      if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0) push(static_cast<std::uint32_t>(t));
    });
    for (const std::uint32_t t : hull)
      for (int i = 0; i < 3; ++i)
        if (dt.neighbors[t][U(i)] < 0) {
          const int a = dt.triangles[t][U((i + 1) % 3)], b = dt.triangles[t][U((i + 2) % 3)];
          nxt[U(a)] = b;
          prv[U(b)] = a;
          if (!onb[U(a)]) { onb[U(a)] = 1; ++n_onb; }
          if (!onb[U(b)]) { onb[U(b)] = 1; ++n_onb; }
        }
    for (const std::uint32_t t : hull)
      for (int i = 0; i < 3; ++i)
        if (dt.neighbors[t][U(i)] < 0) push_triangle(static_cast<int>(t));
    ready = true;
    return Status::ok();
  }

  // The heap's top after a pop is most often the next pop: its state, adjacency and vertices
  // are fetched while this removal is made (the pops read the triangles in key order, at random).
  void prefetch_triangle(std::uint32_t t) const {
    __builtin_prefetch(&ver[t]);
    __builtin_prefetch(&alive[t]);
    __builtin_prefetch(&dt.neighbors[t]);
    __builtin_prefetch(&dt.triangles[t]);
  }
  // One removal (or the lock); the caller keeps the time (one clock read per removal would be
  // a tenth of the constriction).
  bool step_untimed() {
    if (!ready || n_onb == n || locked || stopped) return false;
    if (removed >= opt.stop_after) { stopped = true; return false; }
    while (!heap.empty()) {
      const TriEntry e = heap.top();
      heap.pop();
      if (!heap.empty()) prefetch_triangle(heap.top().t);
      const int t = static_cast<int>(e.t);
      if ((e.version_edge >> 2) != (ver[U(t)] & 0x3fffffffu) || removable_edge(t) < 0) continue;  // stale (lazy deletion)
      const auto& tr = dt.triangles[U(t)];
      const unsigned i = e.version_edge & 3u;
      const int y = tr[i], a = tr[(i + 1) % 3], b = tr[(i + 2) % 3];
      alive[U(t)] = 0;
      ++ver[U(t)];
      nxt[U(a)] = y; prv[U(y)] = a;
      nxt[U(y)] = b; prv[U(b)] = y;
      onb[U(y)] = 1;
      ++n_onb;
      ++removed;
      emit(Constrict2Event::Kind::RemoveTriangle, a, b, y, e.key, "gamma");
      for (int j = 0; j < 3; ++j) {
        const int nb = dt.neighbors[U(t)][U(j)];
        if (nb >= 0 && alive[U(nb)]) push_triangle(nb);
      }
      return n_onb < n;
    }
    locked = true;
    emit(Constrict2Event::Kind::Lock, -1, -1, -1, 0, "gamma");
    return false;
  }
  bool step() {
    const auto t0 = Clock::now();
    const bool more = step_untimed();
    ms_constrict += ms_since(t0);
    return more;
  }
  void run_all() {
    const auto t0 = Clock::now();
    while (step_untimed()) {
    }
    ms_constrict += ms_since(t0);
  }

  // ---------------------------------------------------------------- fallback infrastructure
  static constexpr std::size_t kPrefetchAhead = 16;
  void build_fallback() {
    if (fb_ready) return;
    fb_ready = true;
    out_edge.assign(n, -1);
    for (std::size_t v = 0; v < n; ++v)
      if (onb[v]) {
        out_edge[v] = static_cast<int>(bedges.size());
        bedges.push_back(BEdge{static_cast<int>(v), nxt[v], true});
      }
    // The Delaunay adjacency beside the grids (neither reads the other).
    tbb::parallel_invoke([&] { build_adjacency(); }, [&] { build_grid(); });
    mark.assign(n, 0);
  }
  void build_grid() {
    // The median boundary edge (largest coordinate difference) sizes a sparse grid's cells.
    std::vector<double> len(bedges.size());
    for (std::size_t k = 0; k < bedges.size(); ++k) {
      const double* p = P(bedges[k].u);
      const double* q = P(bedges[k].v);
      len[k] = std::max(std::fabs(p[0] - q[0]), std::fabs(p[1] - q[1]));
    }
    const auto mid = len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2);
    std::nth_element(len.begin(), mid, len.end());
    grid.build(*pts, len.empty() ? 0.0 : *mid);
    // The edges run by their first vertex; the second one's coordinates are a random read, so
    // they are prefetched a few edges ahead.
    grid.add_edges(bedges.size(), [&](std::size_t k, const double*& a, const double*& b, int& id) {
      if (k + kPrefetchAhead < bedges.size()) __builtin_prefetch(P(bedges[k + kPrefetchAhead].v));
      a = P(bedges[k].u);
      b = P(bedges[k].v);
      id = static_cast<int>(k);
    });
  }
  void build_adjacency() {
    if (adj_ready) return;
    CONSTRICT_CHECK(dt.neighbors.size() == dt.triangles.size(), "Constrictor2: the adjacency is asked for after the refinement");
    adj_ready = true;
    // Adjacency by counting sort: the counter-clockwise edge u->v of a triangle gives u its
    // neighbour v (the reverse comes from the triangle across), and a hull edge also gives v its
    // neighbour u; so every neighbour comes exactly once. Lists sorted for is_dt_edge(). (Two
    // passes with random reads; in parallel with atomic counters they were slower on 2 cores.)
    adj_off.assign(n + 1, 0);
    const std::size_t nt = dt.triangles.size();
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 3; ++i) {
        const auto& tr = dt.triangles[t];
        ++adj_off[U(tr[U((i + 1) % 3)]) + 1];
        if (dt.neighbors[t][U(i)] < 0) ++adj_off[U(tr[U((i + 2) % 3)]) + 1];
      }
    for (std::size_t v = 0; v < n; ++v) adj_off[v + 1] += adj_off[v];
    adj.assign(U(adj_off[n]), 0);
    std::vector<int> at(adj_off.begin(), adj_off.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 3; ++i) {
        const auto& tr = dt.triangles[t];
        const int u = tr[U((i + 1) % 3)], v = tr[U((i + 2) % 3)];
        adj[U(at[U(u)]++)] = v;
        if (dt.neighbors[t][U(i)] < 0) adj[U(at[U(v)]++)] = u;
      }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v) std::sort(adj.begin() + adj_off[v], adj.begin() + adj_off[v + 1]);
    });
  }
  // Vertex -> incident triangles (CSR, by triangle index), for the degree-4 augmentation only.
  void build_vertex_triangles() {
    if (!vt_off.empty()) return;
    vt_off.assign(n + 1, 0);
    for (const auto& tr : dt.triangles)
      for (const int v : tr) ++vt_off[U(v) + 1];
    for (std::size_t v = 0; v < n; ++v) vt_off[v + 1] += vt_off[v];
    vt.assign(U(vt_off[n]), 0);
    std::vector<int> fill(vt_off.begin(), vt_off.end() - 1);
    for (std::size_t t = 0; t < dt.triangles.size(); ++t)
      for (const int v : dt.triangles[t]) vt[U(fill[U(v)]++)] = static_cast<int>(t);
  }
  bool is_dt_edge(int u, int v) const {
    return std::binary_search(adj.begin() + adj_off[U(u)], adj.begin() + adj_off[U(u) + 1], v);
  }
  int add_edge(int u, int v) {
    const int id = static_cast<int>(bedges.size());
    bedges.push_back(BEdge{u, v, true});
    grid.add_edge(P(u), P(v), id);
    return id;
  }

  // Segment (s, t) with s a boundary vertex and t not: does boundary edge e meet it anywhere
  // other than at s (where only a collinear overlap counts)?
  bool edge_blocks(const BEdge& e, int s, int t) const {
    if (e.u == s || e.v == s) {
      const int o = e.u == s ? e.v : e.u;
      return orient2_fast(P(s), P(o), P(t)) == 0 && same_side_collinear(P(s), P(o), P(t));
    }
    return closed_segments_meet(P(e.u), P(e.v), P(s), P(t));
  }

  // Can apex y (inside) be inserted into boundary edge a->b? The closed triangle (a,b,y) must be
  // empty of other points and no boundary edge may meet the new edges ay, yb (exact). Then the
  // triangle lies inside the polygon and the new polygon is simple (docs, "Local insertion").
  bool valid_insert(int a, int b, int y) {
    if (onb[U(y)] || !onb[U(a)] || nxt[U(a)] != b) return false;
    const double* pa = P(a);
    const double* pb = P(b);
    const double* py = P(y);
    if (orient2_fast(pa, pb, py) <= 0) return false;
    // Only the cells the triangle and its new edges cross (Grid::points_in_hull, any_edge): the
    // same points and edges are tested as over the whole bounding box, far fewer cells are read.
    const double* tri[3] = {pa, pb, py};
    bool empty = true;
    grid.points_in_hull(
        tri, 3,
        [&](int p) {
          if (!empty || p == a || p == b || p == y) return;
          const double* pp = P(p);
          if (orient2_fast(pa, pb, pp) >= 0 && orient2_fast(pb, py, pp) >= 0 && orient2_fast(py, pa, pp) >= 0) empty = false;
        },
        [&] { return !empty; });
    if (!empty) return false;
    for (const int s : {a, b})
      if (grid.any_edge(P(s), py, [&](int id) {
            const BEdge& e = bedges[U(id)];
            return e.alive && !(e.u == a && e.v == b) && edge_blocks(e, s, y);
          }))
        return false;
    return true;
  }

  void insert_point(int a, int b, int y) {
    bedges[U(out_edge[U(a)])].alive = false;
    out_edge[U(a)] = add_edge(a, y);
    out_edge[U(y)] = add_edge(y, b);
    nxt[U(a)] = y; prv[U(y)] = a;
    nxt[U(y)] = b; prv[U(b)] = y;
    onb[U(y)] = 1;
    ++n_onb;
  }

  // Vertices within k DT hops of the seeds (marks them with a fresh stamp).
  std::vector<int> neighbourhood(const std::vector<int>& seeds, int k) {
    ++mark_stamp;
    std::vector<int> out;
    for (int s : seeds)
      if (mark[U(s)] != mark_stamp) { mark[U(s)] = mark_stamp; out.push_back(s); }
    std::size_t lo = 0;
    for (int d = 0; d < k; ++d) {
      const std::size_t hi = out.size();
      if (lo == hi) break;
      for (std::size_t q = lo; q < hi; ++q)
        for (int w = adj_off[U(out[q])]; w < adj_off[U(out[q]) + 1]; ++w) {
          const int v = adj[U(w)];
          if (mark[U(v)] != mark_stamp) { mark[U(v)] = mark_stamp; out.push_back(v); }
        }
      lo = hi;
    }
    return out;
  }

  // The visitor that folds point p into the side values of pair (i, j).
  auto side_visitor(int i, int j, double& ga, double& gb, bool& blocked) const {
    return [this, i, j, &ga, &gb, &blocked](int p) {
      if (p == i || p == j) return;
      const double* a = P(i);
      const double* b = P(j);
      const int o = orient2_fast(a, b, P(p));
      if (o == 0) {
        if (diametral_side2(a, b, P(p)) < 0) blocked = true;
        return;
      }
      const double g = apex_gamma2(a, b, P(p));
      if (o > 0) ga = std::min(ga, g); else gb = std::min(gb, g);
    };
  }

  // Side values of pair (i, j), i < j (spec §2.1; exact signs), over the points within distance
  // `radius` of the midpoint (ring search on the grid; the true minimum on a side is found
  // whenever it is attained inside the radius). Points with apex value below g lie within
  // below_bound(|ij|, g) of the midpoint (they see ij under a wider angle), which ends the search
  // early once both sides have a value.
  void side_values_within(int i, int j, double radius, double& ga, double& gb, bool& blocked) {
    const double* a = P(i);
    const double* b = P(j);
    ga = 1; gb = 1; blocked = false;
    const double mx = 0.5 * a[0] + 0.5 * b[0], my = 0.5 * a[1] + 0.5 * b[1];  // no overflow
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double cs = grid.cell_size();
    auto cut = [&] { return std::max(below_bound(len, ga), below_bound(len, gb)) + cs; };
    // A cell wholly beyond the radius and the cutoff holds nothing to find (the cutoff only
    // shrinks as the minima fall).
    grid.rings(mx, my, [&] { return std::min(radius, cut()); }, side_visitor(i, j, ga, gb, blocked), [&] { return blocked; });
  }
  // Side values of pair (i, j) for a threshold t < 0 (delta_at_least): on each side the exact
  // minimum when it is below t, else a value >= t; or, once both sides have a value below t, those
  // (partial: upper bounds of the minima, which decide Δ < t). Every point with apex value below
  // t lies in the lens(|ij|, t) on its side of the segment, thin at the segment's ends. So the
  // search reads the cells of the lens's cover (ApexLens2::cover): thin ones on both sides first,
  // then on each side the one of that side's value so far (or of t). A long pair's diametral disk
  // can hold long stretches of a sampled band, on both sides and far from the segment but near
  // its ends; the covers read only a few points there (the noisy curve's fallback,
  // docs/benchmarks.md).
  // Cached per pair: an entry answers every threshold up to the one it was searched for (a partial
  // one, every threshold above both its values).
  // The caches are memos only: delta_at_least answers the same with or without them. The graph
  // tests side by side (graph_tests_ahead) read the shared caches and add to their thread's own,
  // which are merged into the shared ones after each batch.
  struct SideCache { double ga, gb; bool blocked; double below; bool partial, one_sided; };
  static bool answers(const SideCache& c, double t) {
    if (c.blocked) return true;
    if (c.partial) return c.ga < t && c.gb < t;
    return t <= c.below && (!c.one_sided || std::min(c.ga, c.gb) < t);
  }
  struct WitnessCache {
    int side;
    double thr;
    bool found;
  };
  struct SideCaches {
    std::unordered_map<std::uint64_t, SideCache> side;
    std::unordered_map<std::uint64_t, WitnessCache> witness;
  };
  SideCaches shared_caches;
  tbb::enumerable_thread_specific<SideCaches> fresh_caches;
  // The entry for key that `usable` accepts, in `fresh` (the caller's own) or else in `shared`;
  // the callers store in `fresh` (which may be `shared`).
  template <class Map, class Usable>
  static const typename Map::mapped_type* cached(const Map& fresh, const Map& shared, std::uint64_t key,
                                                 Usable&& usable) {
    if (const auto it = fresh.find(key); it != fresh.end() && usable(it->second)) return &it->second;
    if (&fresh == &shared) return nullptr;
    const auto it = shared.find(key);
    return it != shared.end() && usable(it->second) ? &it->second : nullptr;
  }
  void merge_fresh_caches() {
    for (SideCaches& f : fresh_caches) {
      for (auto& [k, v] : f.side) shared_caches.side.insert_or_assign(k, v);
      for (auto& [k, v] : f.witness) shared_caches.witness.insert_or_assign(k, v);
      f.side.clear();
      f.witness.clear();
    }
  }
  void sides_below(int i, int j, double t, double& ga, double& gb, bool& blocked, const SideCaches& shared,
                   SideCaches& fresh) const {
    auto& side_cache = fresh.side;
    const std::uint64_t key = detail::edge_key(i, j);
    if (const SideCache* c = cached(fresh.side, shared.side, key, [t](const SideCache& e) { return answers(e, t); })) {
      ga = c->ga;
      gb = c->gb;
      blocked = c->blocked;
      return;
    }
    const double* a = P(i);
    const double* b = P(j);
    ga = 1; gb = 1; blocked = false;
    auto visit = side_visitor(i, j, ga, gb, blocked);
    // The points under one side's arc for threshold tv (ApexLens2), up to height cap: the cells
    // of its cover (cut at that height), and in them the test of each point's offsets.
    bool partial = false;  // both sides below t: Δ < t decided, the search ends
    auto done = [&] { return blocked || partial; };
    auto scan = [&](double side, double tv, double cap) {
      const detail::ApexLens2 lens(a, b, tv);
      const double h = std::min(lens.height(), cap);
      static_assert(detail::ApexLens2::kMaxCover <= detail::kMaxHullVertices, "the lens cover is one grid query");
      double q[detail::ApexLens2::kMaxCover][2];
      int m = 0;
      lens.cover(side, h, q, m);
      const double* v[detail::ApexLens2::kMaxCover] = {};
      for (int k = 0; k < m; ++k) v[k] = q[k];
      auto inside = [&](int p) {
        if (done() || !lens.may_hold(P(p), side, h)) return;
        visit(p);
        partial = ga < t && gb < t;
      };
      grid.points_in_hull(v, m, inside, done);
      return h;
    };
    // Layers of growing height, nearest the segment first (the widest angles, so the smallest
    // values, are there); a side is complete once its layers reach the top of the arc of its
    // value so far (or of t): then its value is exact below t. A side without a value below t
    // is not completed once the other side has one: delta_at_least then asks only whether it has
    // a point below -m > 0 > t (witness_below), which a point below t would be too; the entry
    // answers no other threshold then.
    const double full = detail::ApexLens2(a, b, t).height();
    double scanned[2] = {-1, -1};  // height read on the left, right side
    bool one_sided = false;
    for (const double part : {1.0 / 64, 1.0 / 8, 1.0}) {
      for (int k = 0; k < 2 && !done(); ++k) {
        const double g = std::min(k == 0 ? ga : gb, t), other = k == 0 ? gb : ga;
        if (scanned[k] >= detail::ApexLens2(a, b, g).height()) continue;
        if (g == t && other < t) {
          one_sided = true;
          continue;
        }
        scanned[k] = scan(k == 0 ? 1 : -1, g, part * full);
      }
      if (done()) break;
    }
    if (!done())
      one_sided = one_sided && !(scanned[0] >= detail::ApexLens2(a, b, std::min(ga, t)).height() &&
                                 scanned[1] >= detail::ApexLens2(a, b, std::min(gb, t)).height());
    side_cache[key] = SideCache{ga, gb, blocked, t, partial, one_sided && !done()};
  }
  // Every point whose apex value for a segment of length len is below g lies within this distance
  // of the segment's midpoint (1.001: margin for the rounding of len and of the distances): for
  // g <= 0 inside the diametral disk (a negative value is an obtuse angle at the point, Thales),
  // for 0 < g < 1 within len / (1 - g) (the angle exceeds arcsin(1 - g): inside the two arcs of
  // that inscribed angle, whose points are at most 2R = len / sin of it from the midpoint).
  static double below_bound(double len, double g) {
    if (g <= 0) return 0.5005 * len;
    const double s = 1.0 - g;
    return s <= 0 ? HUGE_VAL : 1.001 * len / s;
  }
  double reach(int i, int j, double g) const {
    const double len = std::hypot(P(j)[0] - P(i)[0], P(j)[1] - P(i)[1]);
    return below_bound(len, g) + grid.cell_size();
  }

  // Δ(u, v) = filtration value (spec §2.2); -inf for a blocked pair. Exhaustive when a side is
  // empty (used only by the degree-4 ranking, on few pairs).
  double delta(int u, int v) {
    const std::uint64_t key = detail::edge_key(u, v);
    auto it = delta_cache.find(key);
    if (it != delta_cache.end()) return it->second;
    const int i = std::min(u, v), j = std::max(u, v);
    double ga = 1, gb = 1;
    bool blocked = false;
    side_values_within(i, j, HUGE_VAL, ga, gb, blocked);
    // A second pass bounded by the values found is not needed: the first pass is exhaustive.
    const double d = blocked ? -HUGE_VAL : filtration_value(ga, gb);
    delta_cache.emplace(key, d);
    return d;
  }

  // Δ(u, v) >= gamma0 (< 0) with two bounded searches: first all points with apex value < gamma0;
  // if a side m < gamma0 exists, the pair is in iff the other side is >= |m| (magnitude rule of
  // filtration_value), decided by the points with apex value < |m|.
  bool delta_at_least(int u, int v, double gamma0, const SideCaches& shared, SideCaches& fresh) const {
    const int i = std::min(u, v), j = std::max(u, v);
    double ga, gb;
    bool blocked;
    // m below is the exact minimum whenever m < gamma0 (sides_below).
    sides_below(i, j, gamma0, ga, gb, blocked, shared, fresh);
    if (blocked) return false;
    // Both sides below gamma0: the smaller m < gamma0 and the other side < gamma0 < 0 <= -m, out
    // by the magnitude rule (also from a partial search).
    if (ga < gamma0 && gb < gamma0) return false;
    const double m = std::min(ga, gb);  // (below gamma0 on one side only from here on)
    if (m >= gamma0) return true;
    // In iff the other side has no point with value < -m. -m can be close to 1, where the region
    // to search is nearly the whole half-plane: stop at the first witness instead (the usual
    // answer); only pairs with a nearly empty other side are searched far.
    // The other side's answer is a property of the pair (m is its exact minimum): kept for the
    // later stages of the γ0 schedule, which test the same pairs again.
    const int side = ga == m ? -1 : 1;
    const std::uint64_t key = detail::edge_key(i, j);
    if (const WitnessCache* c = cached(fresh.witness, shared.witness, key,
                                       [&](const WitnessCache& e) { return e.side == side && e.thr == -m; }))
      return !c->found;
    const bool found = witness_below(i, j, side, -m);
    fresh.witness[key] = WitnessCache{side, -m, found};
    return !found;
  }

  // Is there a point p with orient2(x_i, x_j, p) == side and apex value < thr, or a point in the
  // open segment ij? Ring search around the midpoint, nearest cells first, first witness wins.
  bool witness_below(int i, int j, int side, double thr) const {
    const double* a = P(i);
    const double* b = P(j);
    const double mx = 0.5 * a[0] + 0.5 * b[0], my = 0.5 * a[1] + 0.5 * b[1];  // no overflow
    const double far = reach(i, j, thr);
    bool found = false;
    auto visit = [&](int p) {
      if (found || p == i || p == j) return;
      const int o = orient2_fast(a, b, P(p));
      if (o == 0) {
        if (diametral_side2(a, b, P(p)) < 0) found = true;
        return;
      }
      if (o == side && apex_gamma2(a, b, P(p)) < thr) found = true;
    };
    // The DT neighbours of the pair's ends first: on a long pair's other side, the points next
    // to its ends see it under a right angle or so, witnesses for any threshold above 0.
    for (const int w : {i, j})
      for (int q = adj_off[U(w)]; q < adj_off[U(w) + 1] && !found; ++q) visit(adj[U(q)]);
    if (found) return true;
    grid.rings(mx, my, [far] { return far; }, visit, [&] { return found; });
    return found;
  }
  // ---------------------------------------------------------------- local constriction
  // Graph predicate for the edges (apex, boundary vertex) of a candidate triangle.
  enum class Graph { Gamma0, Degree4, Complete };
  bool in_graph(Graph g, double gamma0, int u, int v) {
    if (g == Graph::Complete) return true;
    if (is_dt_edge(u, v)) return true;
    if (g == Graph::Degree4) return aug.count(detail::edge_key(u, v)) > 0;
    if (const int known = gamma0_answer(u, v); known >= 0) return known == 1;
    const bool in = delta_at_least(u, v, gamma0, shared_caches, shared_caches);
    gamma0_known.emplace(detail::edge_key(u, v), in);
    return in;
  }
  // The γ0 graph's answers of this stage (in_graph, graph_tests_ahead), by pair.
  std::unordered_map<std::uint64_t, bool> gamma0_known;
  // Pair (u, v)'s answer in this γ0 stage if known without a search: 1 (a Delaunay edge, or
  // answered in), 0 (answered out), -1 (not yet).
  int gamma0_answer(int u, int v) const {
    if (is_dt_edge(u, v)) return 1;
    const auto it = gamma0_known.find(detail::edge_key(u, v));
    return it == gamma0_known.end() ? -1 : it->second ? 1 : 0;
  }

  // Δ(u, v) < gamma0 (< 0) shown by the DT neighbours of u and v alone: a point on the open
  // segment, or points with apex value below gamma0 on both sides (the magnitude rule, as for a
  // partial search in delta_at_least). Exact; false when these few points do not decide it.
  bool outside_near(int u, int v, double gamma0) const {
    if (is_dt_edge(u, v)) return false;
    double ga = 1, gb = 1;
    bool blocked = false;
    auto visit = side_visitor(u, v, ga, gb, blocked);
    for (const int w : {u, v})
      for (int q = adj_off[U(w)]; q < adj_off[U(w) + 1]; ++q) {
        visit(adj[U(q)]);
        if (blocked || (ga < gamma0 && gb < gamma0)) return true;
      }
    return false;
  }

  // In the γ0 and degree-4 stages a candidate is queued by its key alone and tested when it comes
  // out of the heap (test_candidate): most stuck points are placed by their best candidate, so
  // the others, among them the long pairs across an empty interior whose side searches are the
  // fallback's main cost, are never tested. The same insertions in the same order as testing
  // before queueing: the graph tests are properties of the pair and the stage, and a valid
  // insertion only becomes invalid (valid_insert), so a candidate that fails when it is queued
  // fails when it comes out. The repair's candidates (every boundary edge within k hops, k up to
  // N) are tested before queueing, so that its heap holds only the valid ones.
  void push_candidate(Heap& h, Graph g, double gamma0, int a, int z) {
    Entry e;
    if (candidate(g, gamma0, a, z, e) && (g != Graph::Complete || test_candidate(e, g, gamma0))) h.push(e);
  }
  // The entry of boundary edge a->nxt[a] and stuck point z, unless ruled out at once.
  bool candidate(Graph g, double gamma0, int a, int z, Entry& e) const {
    const int b = nxt[U(a)];
    if (b < 0 || onb[U(z)]) return false;
    if (orient2_fast(P(a), P(b), P(z)) <= 0) return false;
    // Witnesses among the endpoints' neighbours rule most pairs out at once (a long pair across
    // an empty interior has very obtuse angles behind both ends), which keeps the heap small.
    if (g == Graph::Gamma0 && (outside_near(a, z, gamma0) || outside_near(b, z, gamma0))) return false;
    e = Entry{criterion_key(a, b, z), sorted_gid3(a, b, z), a, b, z, -1, 0};
    return true;
  }
  // Is the entry's triangle still one to insert? (It only stops being one: spec §3.6.)
  bool entry_live(const Entry& e) const { return !onb[U(e.y)] && onb[U(e.a)] && nxt[U(e.a)] == e.b; }
  // The graph test (its side searches read little, sides_below) before the geometric one, which
  // rejects few and reads a long candidate's whole strip.
  bool test_candidate(const Entry& e, Graph g, double gamma0) {
    const int a = e.a, b = e.b, z = e.y;
    if (!entry_live(e)) return false;
    if (!in_graph(g, gamma0, a, z) || !in_graph(g, gamma0, b, z)) return false;
    return valid_insert(a, b, z);
  }

  // Candidate boundary edges for apex z: those with an endpoint within k hops of z (their start
  // vertices, ascending), from the vertices within k hops (in any order).
  std::vector<int> candidate_starts(const std::vector<int>& region) const {
    std::vector<int> starts;
    for (int u : region)
      if (onb[U(u)]) { starts.push_back(u); starts.push_back(prv[U(u)]); }
    std::sort(starts.begin(), starts.end());
    starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
    return starts;
  }
  // The vertices within k DT hops of z, without the shared marks (for the side-by-side first heap;
  // k is 2 there): each hop adds the neighbours of all so far, then sorts and dedups. The same set
  // as neighbourhood({z}, k).
  std::vector<int> within_hops(int z, int k) const {
    std::vector<int> all{z};
    for (int d = 0; d < k; ++d) {
      const std::size_t m = all.size();
      for (std::size_t i = 0; i < m; ++i)
        for (int w = adj_off[U(all[i])]; w < adj_off[U(all[i]) + 1]; ++w) all.push_back(adj[U(w)]);
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
    }
    return all;
  }
  // The first heap of a stage: every stuck point's candidates. For the γ0 and degree-4 graphs
  // they are made side by side (candidate() reads only), by fixed blocks of stuck points joined
  // in order; the heap's order is a strict total order of the entries (key, then the sorted
  // input ids: two entries of one triangle would need its apex both stuck and on the boundary),
  // so the pops do not depend on how the heap was filled. The repair tests each candidate in
  // full (test_candidate), in sequence.
  Heap first_heap(Graph g, double gamma0, int k) {
    std::vector<int> stuck;
    for (std::size_t z = 0; z < n; ++z)
      if (!onb[z]) stuck.push_back(static_cast<int>(z));
    Heap h;
    if (g == Graph::Complete) {
      for (const int z : stuck)
        for (const int a : candidate_starts(neighbourhood({z}, k))) push_candidate(h, g, gamma0, a, z);
      return h;
    }
    constexpr std::size_t kBlock = 256;  // stuck points per block (thousands at 10^6)
    std::vector<Entry> all = detail::ordered_pack<Entry>(
        stuck.size(),
        [&](std::size_t i, auto&& push) {
          Entry e;
          for (const int a : candidate_starts(within_hops(stuck[i], k)))
            if (candidate(g, gamma0, a, stuck[i], e)) push(e);
        },
        kBlock);
    return Heap(EntryLess{}, std::move(all));
  }

  // The γ0 graph tests of the next entries of the heap, side by side; in_graph then finds their
  // answers. An answer is a property of the pair and the stage (delta_at_least, whatever its
  // caches hold), so the insertions are those of testing each entry as it comes out, on any
  // thread count; a test of an entry that a nearer insertion makes dead is wasted, not wrong.
  // Dead entries met on the way are dropped (they would fail when they come out).
  static constexpr std::size_t kMaxTestsAhead = 1024;  // (each batch pops and pushes its entries)
  void graph_tests_ahead(Heap& h, double gamma0, std::size_t count) {
    std::vector<Entry> ahead;
    while (!h.empty() && ahead.size() < count) {
      const Entry e = h.top();
      h.pop();
      if (entry_live(e)) ahead.push_back(e);
    }
    // Per entry its two pairs in test order (a, z), (b, z); answers: -1 untested, 0, 1.
    std::vector<std::array<signed char, 2>> res(ahead.size(), {{-1, -1}});
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, ahead.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
          SideCaches& fresh = fresh_caches.local();
          for (std::size_t i = r.begin(); i != r.end(); ++i)
            for (int s = 0; s < 2; ++s) {
              const int u = s == 0 ? ahead[i].a : ahead[i].b, z = ahead[i].y;
              const int known = gamma0_answer(u, z);  // (gamma0_known is only read here)
              const bool in = known >= 0 ? known == 1 : delta_at_least(u, z, gamma0, shared_caches, fresh);
              if (known < 0) res[i][U(s)] = static_cast<signed char>(in);
              if (!in) break;
            }
        });
    merge_fresh_caches();
    for (std::size_t i = 0; i < ahead.size(); ++i) {
      for (int s = 0; s < 2; ++s)
        if (res[i][U(s)] >= 0)
          gamma0_known.emplace(detail::edge_key(s == 0 ? ahead[i].a : ahead[i].b, ahead[i].y), res[i][U(s)] == 1);
      h.push(ahead[i]);
    }
  }
  // Does the entry's γ0 graph test still need a search (a pair not yet answered, the first of
  // the two in graph)?
  bool graph_pending(const Entry& e) const {
    for (const int u : {e.a, e.b}) {
      const int known = gamma0_answer(u, e.y);
      if (known < 0) return true;
      if (known == 0) return false;
    }
    return false;
  }

  // Constricts the region still inside by inserting stuck points into boundary edges, widest
  // apex angle first (same criterion as §3.4; spec §3.6 "cheaper variant"). Returns points placed.
  std::size_t local_constrict(Graph g, double gamma0, int k, const std::string& stage) {
    emit(Constrict2Event::Kind::StageBegin, -1, -1, -1, 0, stage.c_str());
    gamma0_known.clear();
    Heap h = first_heap(g, gamma0, k);
    std::size_t placed = 0;
    while (!h.empty() && n_onb < n) {
      if (g == Graph::Gamma0 && opt.fallback_tests_ahead > 0 && entry_live(h.top()) && graph_pending(h.top()))
        graph_tests_ahead(h, gamma0, std::min<std::size_t>(opt.fallback_tests_ahead, kMaxTestsAhead));
      if (h.empty()) break;
      const Entry e = h.top();
      h.pop();
      if (!test_candidate(e, g, gamma0)) continue;  // validity only decays (spec §3.6)
      insert_point(e.a, e.b, e.y);
      ++placed;
      emit(Constrict2Event::Kind::InsertPoint, e.a, e.b, e.y, e.key, stage.c_str());
      // Only the two new edges are new candidates; stuck points near them get them offered.
      for (int z : neighbourhood({e.a, e.y, e.b}, k)) {
        if (onb[U(z)]) continue;
        push_candidate(h, g, gamma0, e.a, z);
        push_candidate(h, g, gamma0, e.y, z);
      }
    }
    return placed;
  }

  // Degree-4 augmentation (spec §3.7), restricted to vertices within two hops of the stuck points
  // (only edges at a stuck point can be used by a removal; degrees cascade in index order).
  void augment_degree4() {
    build_vertex_triangles();
    std::vector<int> stuck;
    for (std::size_t v = 0; v < n; ++v)
      if (!onb[v]) stuck.push_back(static_cast<int>(v));
    std::vector<int> verts = neighbourhood(stuck, 2);
    std::sort(verts.begin(), verts.end(), [&](int l, int r) { return G(l) < G(r); });
    std::unordered_map<int, int> extra;  // added degree
    auto degree = [&](int v) { return adj_off[U(v) + 1] - adj_off[U(v)] + extra[v]; };
    auto apex_across = [&](int t, int a, int b) -> int {  // apex of the triangle across edge ab of t
      const auto& tr = dt.triangles[U(t)];
      for (int i = 0; i < 3; ++i)
        if (tr[U(i)] != a && tr[U(i)] != b) {
          const int nb = dt.neighbors[U(t)][U(i)];
          if (nb < 0) return -1;
          for (int q : dt.triangles[U(nb)]) if (q != a && q != b) return q;
        }
      return -1;
    };
    auto neighbour_tri = [&](int t, int a, int b) -> int {
      const auto& tr = dt.triangles[U(t)];
      for (int i = 0; i < 3; ++i)
        if (tr[U(i)] != a && tr[U(i)] != b) return dt.neighbors[U(t)][U(i)];
      return -1;
    };
    for (int v : verts) {
      const int d = degree(v);
      if (d >= 4) continue;
      std::vector<int> cand;
      const int nt = vt_off[U(v) + 1] - vt_off[U(v)];
      for (int q = vt_off[U(v)]; q < vt_off[U(v) + 1]; ++q) {
        const int t = vt[U(q)];
        const auto& tr = dt.triangles[U(t)];
        int a = -1, b = -1;
        for (int x : tr) if (x != v) { if (a < 0) a = x; else b = x; }
        const int c = apex_across(t, a, b);
        if (c < 0) continue;
        cand.push_back(c);
        if (nt == 1) {  // hull vertex of degree 2: also look beyond (a, b, c)
          const int t2 = neighbour_tri(t, a, b);
          const int c1 = apex_across(t2, a, c), c2 = apex_across(t2, b, c);
          if (c1 >= 0) cand.push_back(c1);
          if (c2 >= 0) cand.push_back(c2);
        }
      }
      std::sort(cand.begin(), cand.end());
      cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
      std::vector<std::pair<double, int>> ranked;
      for (int w : cand)
        if (w != v && !is_dt_edge(v, w) && !aug.count(detail::edge_key(v, w)))
          ranked.emplace_back(delta(v, w), w);
      std::sort(ranked.begin(), ranked.end(), [&](const auto& l, const auto& r) {
        return l.first != r.first ? l.first > r.first : G(l.second) < G(r.second);
      });
      for (std::size_t r = 0; r < ranked.size() && static_cast<int>(r) < 4 - d; ++r) {
        if (ranked[r].first == -HUGE_VAL) break;  // blocked pair: in no graph
        aug.insert(detail::edge_key(v, ranked[r].second));
        ++extra[v];
        ++extra[ranked[r].second];
      }
    }
  }

  // Last resort (never observed): a star-shaped polygon around the lowest point; always simple.
  void star_polygon() {
    std::vector<int> ord;
    int o = 0;
    for (std::size_t i = 1; i < n; ++i) {
      const double* p = P(static_cast<int>(i));
      const double* q = P(o);
      if (p[1] < q[1] || (p[1] == q[1] && p[0] < q[0])) o = static_cast<int>(i);
    }
    for (std::size_t i = 0; i < n; ++i)
      if (static_cast<int>(i) != o) ord.push_back(static_cast<int>(i));
    const double* po = P(o);
    auto closer = [&](int p, int q) {  // p, q collinear with o on the same ray
      const double* a = P(p);
      const double* b = P(q);
      return a[0] != b[0] ? std::fabs(a[0] - po[0]) < std::fabs(b[0] - po[0]) : a[1] < b[1];
    };
    std::sort(ord.begin(), ord.end(), [&](int p, int q) {
      const int s = orient2_fast(po, P(p), P(q));
      if (s != 0) return s > 0;
      return closer(p, q);
    });
    // Points on the last ray go outward-in so the polygon closes without overlap.
    std::size_t first_last = ord.size() - 1;
    while (first_last > 0 && orient2_fast(po, P(ord[first_last - 1]), P(ord.back())) == 0) --first_last;
    std::reverse(ord.begin() + static_cast<std::ptrdiff_t>(first_last), ord.end());
    ord.insert(ord.begin(), o);
    for (std::size_t i = 0; i < n; ++i) {
      const int a = ord[i], b = ord[(i + 1) % n];
      nxt[U(a)] = b;
      prv[U(b)] = a;
      onb[U(a)] = 1;
    }
    n_onb = n;
  }

  // The polygon in ranked ids, from the boundary vertex with the smallest input id.
  std::vector<int> boundary_list() const {
    std::vector<int> out;
    int s = -1;
    for (std::size_t v = 0; v < n; ++v)
      if (onb[v] && (s < 0 || gid[v] < gid[U(s)])) s = static_cast<int>(v);
    if (s < 0) return out;
    int v = s;
    do {
      out.push_back(v);
      v = nxt[U(v)];
    } while (v != s && out.size() <= n);
    return out;
  }

  std::unique_ptr<Polygon2Result> finished;  // the result of the first finish()
  Status finish(Polygon2Result& r) {
    if (!ready) return {StatusCode::Internal, "Constrictor2::finish called without a successful init"};
    if (finished) {
      r = *finished;
      return Status::ok();
    }
    const Status st = finish_once(r);
    if (st) finished = std::make_unique<Polygon2Result>(r);
    return st;
  }
  Status finish_once(Polygon2Result& r) {
    run_all();
    r = Polygon2Result{};
    r.removed_simplices = removed;
    r.locked_at_gamma0 = locked;
    r.stuck_points = inside_input_ids();
    r.stages.push_back({"gamma", removed});
    r.method = "gamma";
    const auto t0 = Clock::now();
    if (stopped && n_onb < n) {
      r.method = "stopped";
    } else if (locked && opt.fallback == Fallback::None) {
      r.method = "locked";
    } else if (locked) {
      build_fallback();
      auto run = [&](Graph g, double g0, int k, const std::string& name) {
        if (n_onb == n) return;
        const std::size_t placed = local_constrict(g, g0, k, name);
        r.stages.push_back({name, placed});
        r.fallback_insertions += placed;
        if (placed > 0) r.method = name;
      };
      if (opt.fallback == Fallback::Auto || opt.fallback == Fallback::Gamma0)
        for (double g0 : opt.gamma0_schedule) {
          if (!(g0 < 0 && g0 >= -1)) continue;
          char buf[32];
          std::snprintf(buf, sizeof buf, "gamma0=%g", g0);
          run(Graph::Gamma0, g0, 2, buf);
        }
      if ((opt.fallback == Fallback::Auto || opt.fallback == Fallback::Degree4) && n_onb < n) {
        augment_degree4();
        run(Graph::Degree4, 0, 2, "degree4");
      }
      if (opt.fallback == Fallback::Auto || opt.repair) {
        for (int k = 2; n_onb < n; k *= 2) {
          run(Graph::Complete, 0, k, "repair");
          if (static_cast<std::size_t>(k) > n) break;
        }
        if (n_onb < n) {
          const std::size_t placed = n - n_onb;
          star_polygon();
          r.stages.push_back({"star", placed});
          r.fallback_insertions += placed;
          r.method = "star";
        }
      }
    }
    r.ms_fallback = ms_since(t0);
    r.complete = n_onb == n;
    std::vector<int> poly = boundary_list();  // ranked ids until the end
    release_stepping_state();
    if (fb_ready) detail::return_free_memory();  // (the fallback's threads allocated: memory.hpp)
    bool refined = false;                        // the refinement's search ran
    std::vector<std::array<int, 2>> non_dt;      // the polygon's non-Delaunay edges (ranked ids)
    r.ms_delaunay = ms_delaunay;
    r.ms_constrict = ms_constrict;
    if (r.complete && opt.refine == Refine2::LocalSearch) {
      const auto tr = Clock::now();
      Refine2Stats rs;
      // The refinement copies the adjacency into its own lists, and says which of its result's
      // edges are not Delaunay edges: the engine's adjacency and the triangles' neighbours (the
      // check below reads only the triangles) are freed before the refinement's arrays grow.
      refined = detail::refine_polygon2(*pts, dt, poly, opt.refine_work_per_point * n, rs, &gid, [&] {
        build_adjacency();
        decltype(dt.neighbors)().swap(dt.neighbors);
        return detail::Adjacency2{adj_off.data(), adj.data(), [this] {
          std::vector<int>().swap(adj_off);
          std::vector<int>().swap(adj);
          adj_ready = false;
        }};
      }, r.fallback_insertions == 0,  // after insertions (non-Delaunay edges) moves are the rule
      &non_dt);
      r.refine_moves = rs.moves_2opt + rs.moves_oropt + rs.moves_deep;
      r.refine_budget_hit = rs.budget_hit;
      r.perimeter_before_refine = rs.length_before;
      r.stages.push_back({"refine", 0});
      r.ms_refine = ms_since(tr);
    }
    // The polygon's non-Delaunay edges: the refinement's list when its search ran, else (only
    // after fallback insertions can there be any) from the adjacency.
    const std::size_t m = poly.size();
    if (!refined && r.method != "gamma") {
      build_adjacency();
      for (std::size_t i = 0; i < m; ++i)
        if (!is_dt_edge(poly[i], poly[(i + 1) % m])) non_dt.push_back({{poly[i], poly[(i + 1) % m]}});
    }
    for (const auto& e : non_dt) r.fallback_edges.push_back({{std::min(G(e[0]), G(e[1])), std::max(G(e[0]), G(e[1]))}});
    {
      // Each edge's terms on both cores, then summed in polygon order (the same doubles as one
      // sequential loop).
      std::vector<std::array<double, 2>> term(m);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 16384), [&](const tbb::blocked_range<std::size_t>& rg) {
        for (std::size_t i = rg.begin(); i != rg.end(); ++i) {
          const double* pa = P(poly[i]);
          const double* pb = P(poly[i + 1 == m ? 0 : i + 1]);
          term[i] = {{0.5 * (pa[0] * pb[1] - pa[1] * pb[0]), std::hypot(pb[0] - pa[0], pb[1] - pa[1])}};
        }
      });
      for (const auto& t : term) {
        r.area += t[0];
        r.perimeter += t[1];
      }
    }
    r.area = std::ldexp(r.area, 2 * scale_exp);
    r.perimeter = std::ldexp(r.perimeter, scale_exp);
    r.perimeter_before_refine = std::ldexp(r.perimeter_before_refine, scale_exp);
    if (r.perimeter_before_refine == 0) r.perimeter_before_refine = r.perimeter;
    r.boundary.resize(m);
    for (std::size_t i = 0; i < m; ++i) r.boundary[i] = G(poly[i]);
    if (opt.validate) {
      const auto tv = Clock::now();
      // On the ranked points: a scaled run's coordinates are the input's times an exact power of
      // two, which changes no orientation, so the verdict is the input's.
      Status vs = validate_polygon_in_triangulation(*pts, poly, dt.triangles, &r.check);
      if (!vs) {
        // The diagnostics name points and positions: redo the check in input ids and coordinates.
        std::vector<std::array<int, 3>> tris(dt.triangles.size());
        for (std::size_t t = 0; t < tris.size(); ++t)
          for (int k = 0; k < 3; ++k) tris[t][U(k)] = G(dt.triangles[t][U(k)]);
        vs = validate_polygon_in_triangulation(input_points(), r.boundary, tris, &r.check);
      }
      r.validated = true;
      r.ms_validate = ms_since(tv);
      CONSTRICT_CHECK(vs.is_ok() || !r.complete, "reconstruct2 produced an invalid polygon: " + vs.message());
    }
    return Status::ok();
  }

  // What the constriction and the fallback kept per triangle and per boundary edge is dead once
  // the polygon is complete: freed before the refinement allocates its own arrays, so that the
  // two do not add up (the peak of a 10^6 run). The boundary (nxt, prv, onb) stays for
  // boundary() and inside_points(); a second finish() returns the first result.
  void release_stepping_state() {
    heap = TriHeap{TriEntryLess{&ties}};
    std::vector<std::array<int, 3>>().swap(ties.sorted);
    std::vector<char>().swap(alive);
    std::vector<unsigned>().swap(ver);
    grid = Grid{};
    std::vector<BEdge>().swap(bedges);
    std::vector<int>().swap(out_edge);
    std::vector<unsigned>().swap(mark);
    std::vector<int>().swap(vt_off);
    std::vector<int>().swap(vt);
    decltype(delta_cache)().swap(delta_cache);
    decltype(aug)().swap(aug);
    shared_caches = SideCaches{};
    fresh_caches.clear();
  }

  // The engine's input again (input ids, unscaled), from the ranked points: init's caller need
  // not keep its copy alive.
  PointSet input_points() const {
    PointSet in;
    in.coords.resize(2 * n);
    for (std::size_t v = 0; v < n; ++v)
      for (int k = 0; k < 2; ++k) in.coords[2 * U(gid[v]) + U(k)] = std::ldexp(P(static_cast<int>(v))[k], scale_exp);
    return in;
  }

  std::vector<int> inside_input_ids() const {
    std::vector<int> out;
    for (std::size_t v = 0; v < n; ++v)
      if (!onb[v]) out.push_back(gid[v]);
    std::sort(out.begin(), out.end());
    return out;
  }
};

// The engine runs on the points in a canonical order of their coordinates
// (core/detail/canonical_order.hpp), so that the same points in any file order give the same
// polygon: every tie the engine breaks "by id" is then decided by the coordinates. The results and
// the visitor's events are mapped back to input ids here.
struct Constrictor2::Canonical {
  const PointSet* input = nullptr;
  std::vector<int> order;  // engine id k = input point order[k]
  PointSet points;         // the input in that order
  struct IdMap final : Constrict2Visitor {
    Constrict2Visitor* inner = nullptr;
    const std::vector<int>* order = nullptr;
    void on_event(const Constrict2Event& e) override {
      Constrict2Event m = e;
      for (int& v : m.triangle)
        if (v >= 0) v = (*order)[static_cast<std::size_t>(v)];
      inner->on_event(m);
    }
  } id_map;
  int to_input(int v) const { return v < 0 ? v : order[static_cast<std::size_t>(v)]; }
  std::vector<int> to_input_sorted(std::vector<int> ids) const {
    for (int& v : ids) v = to_input(v);
    std::sort(ids.begin(), ids.end());
    return ids;
  }
  // A polygon in input ids, started at its smallest input id (the orientation kept).
  std::vector<int> to_input_polygon(std::vector<int> poly) const {
    for (int& v : poly) v = to_input(v);
    std::rotate(poly.begin(), std::min_element(poly.begin(), poly.end()), poly.end());
    return poly;
  }
};

Constrictor2::Constrictor2() : impl_(new Impl) {}
Constrictor2::~Constrictor2() = default;

Status Constrictor2::init(const PointSet& points, const Constrict2Options& options,
                          Constrict2Visitor* visitor) {
  impl_.reset(new Impl);
  impl_->opt = options;
  impl_->visitor = visitor;
  canon_.reset();
  // Non-finite or non-2D input: no canonical order (it needs a total order of the coordinates).
  if (points.dim != 2 || !detail::check_finite(points, "reconstruct2")) return impl_->init(points);
  canon_ = std::make_unique<Canonical>();
  canon_->input = &points;
  canon_->order = detail::canonical_order(points);
  canon_->points = detail::permuted(points, canon_->order);
  canon_->id_map.inner = visitor;
  canon_->id_map.order = &canon_->order;
  impl_->visitor = visitor ? &canon_->id_map : nullptr;
  const Status st = impl_->init(canon_->points);
  if (st) {
    PointSet().coords.swap(canon_->points.coords);  // the engine has its own (ranked) copy
    return st;
  }
  // The error in the input's own indices (duplicates, ...).
  if (Status in = check_points(points); !in) return in;
  return st;
}
bool Constrictor2::step() { return impl_->step(); }
std::vector<int> Constrictor2::boundary() const {
  std::vector<int> b = impl_->boundary_list();
  for (int& v : b) v = impl_->G(v);
  if (!canon_) return b;
  for (int& v : b) v = canon_->to_input(v);
  return b;
}
std::vector<int> Constrictor2::inside_points() const {
  return canon_ ? canon_->to_input_sorted(impl_->inside_input_ids()) : impl_->inside_input_ids();
}
Status Constrictor2::finish(Polygon2Result& result) {
  const Status st = impl_->finish(result);
  if (!st || !canon_) return st;
  const Canonical& c = *canon_;
  result.boundary = c.to_input_polygon(std::move(result.boundary));
  result.stuck_points = c.to_input_sorted(std::move(result.stuck_points));
  for (auto& e : result.fallback_edges) {
    e = {{c.to_input(e[0]), c.to_input(e[1])}};
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  }
  std::sort(result.fallback_edges.begin(), result.fallback_edges.end());
  if (!result.check.reason.empty()) {  // (positions and ids of a failed check: on the input again)
    PolygonCheck chk;
    (void)validate_polygon(*c.input, result.boundary, &chk);
    result.check = chk;
  }
  return st;
}

struct detail::Constrictor2Access {
  static void share(const Constrictor2& c, const detail::Triangulation2Hook& hook) {
    const Constrictor2::Impl& e = *c.impl_;
    std::vector<int> to_input(e.n);
    for (std::size_t v = 0; v < e.n; ++v) to_input[v] = c.canon_ ? c.canon_->to_input(e.gid[v]) : e.gid[v];
    hook(e.rpts, e.dt, to_input);
  }
};

Status detail::reconstruct2_sharing(const PointSet& points, const Constrict2Options& options, Polygon2Result& result,
                                    Constrict2Visitor* visitor, const Triangulation2Hook& hook) {
  result = Polygon2Result{};
  Constrictor2 c;
  Status st = c.init(points, options, visitor);
  if (!st) return st;
  if (hook) Constrictor2Access::share(c, hook);
  return c.finish(result);
}

Status reconstruct2(const PointSet& points, const Constrict2Options& options,
                    Polygon2Result& result, Constrict2Visitor* visitor) {
  result = Polygon2Result{};
  Constrictor2 c;
  Status st = c.init(points, options, visitor);
  if (!st) return st;
  return c.finish(result);  // runs the constriction to its end
}

}  // namespace constrict
