// SPDX-License-Identifier: GPL-3.0-or-later
// Simplicity-preserving 2-opt / Or-opt post-pass of the 2D reconstruction
// (docs/reconstruction-2d.md §"Refinement"). The γ-constriction is greedy: on sparse samples it can
// cut across a thin part, leaving a polygon that is simple but visibly longer than the curve.
// Short local moves between Delaunay neighbours repair most of those cuts; every move is checked
// exactly, so the polygon stays simple and through all points at every step.
#include "constrict/detail/refine2.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "constrict/delaunay.hpp"
#include "constrict/detail/segments2.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/edge_key.hpp"
#include "constrict/validate.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/dense_segments.hpp"
#include "core/detail/sparse_segments.hpp"

namespace constrict::detail {
namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

// f(i) for i in [0, n), on all cores (f must write only its own i's results).
template <class F>
void parallel_blocks(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

// Longest Or-opt segment.
constexpr int kMaxSegment = 8;

// Deep moves (second phase, docs §4c): sequential k-opt moves of at most kMaxDepth exchanged edges
// (a bounded Lin–Kernighan step), trying the kBreadth[i] nearest candidates at level i + 1, and
// double bridges made of two interleaved splitting 2-exchanges.
constexpr int kMaxDepth = 6;
constexpr std::array<std::size_t, kMaxDepth - 1> kBreadth{{5, 5, 5, 3, 3}};
// Edges exchanged by one deep move (a double bridge exchanges 4).
constexpr int kMaxExchanged = kMaxDepth > 4 ? kMaxDepth : 4;
// Search-node bounds of the deep phase, per point plus a floor, so that small inputs are not
// starved (s2d_spiral_e0.9: 189 points, about 25 000 nodes; no shared set uses 300 000):
// - the Lin–Kernighan steps (candidate edges tried);
// - the double bridges (splits collected, pairs tested). A call collects the region's splits and
//   scans their pairs, O(S²) for S splits, and a move leads to another call. On large inputs that
//   is the whole cost and gains nearly nothing: on the noisy 10⁶ curve, 16 600 splits, 3 moves
//   for 450 ms, the perimeter 2·10⁻⁶ shorter (docs/benchmarks.md). So it has its own, smaller
//   bound.
constexpr std::size_t kDeepNodesPerPoint = 256;
constexpr std::size_t kBridgeNodesPerPoint = 16;
constexpr std::size_t kDeepNodesFloor = std::size_t{1} << 20;
// The simplicity tests' bound: polygon edges tested against new edges, per point and in all.
// Measured: at most 63 per point on the 10^5 and 10^6 benchmark and hostile families, at most
// 976 per point (2 M in all) on the shared sets; 30 000 per point on a double logarithmic spiral
// (13 decades of scale in 10^4 points: the grid's cells, sized by the median edge, hold the whole
// centre), whose refinement took 146 s at 10^5 points. The floor stays small: the auto topology
// refines the parts of a small input from kStarts starts, each with its own bound (2^26: 7.3 s for
// that spiral at 10^4 points in auto mode; 2^22: 1.2 s).
constexpr std::size_t kTestsPerPoint = 256;
constexpr std::size_t kTestsFloor = std::size_t{1} << 22;
// Vertices of the deep phase whose searches run side by side (Refiner::speculate): kSpeculate
// after a move, twice as many after a batch without one, up to kSpeculateMax.
constexpr std::size_t kSpeculate = 8;
constexpr std::size_t kSpeculateMax = 32;

struct Edge {
  int u, v;
  bool same(int a, int b) const { return (u == a && v == b) || (u == b && v == a); }
};

// Uniform grid of the polygon edges. Cell indices are monotone in the coordinates, so a query
// finds every edge that can meet the query segment: exact candidate sets for the exact segment
// tests. Two layouts:
// - dense (DenseSegments, core/detail/dense_segments.hpp: area-sized cells, every cell an array
//   slot), when the polygon's edges are about as long as the cells;
// - sparse (SparseSegments, core/detail/sparse_segments.hpp: cells of 16 median edges,
//   sparse_half_cell),
//   when the median polygon edge is far below the area-sized cell: on a curve sample those cells
//   would hold O(√N) edges each, and every move's test would read them all (the 2D noisy-curve
//   refinement, docs/benchmarks.md).
// Either layout finds every edge that can meet a query, so the moves are the same.
class EdgeGrid {
 public:
  void build(const std::vector<double>& xy, double median_edge) {
    const std::size_t n = xy.size() / 2;
    minx_ = maxx_ = xy[0];
    miny_ = maxy_ = xy[1];
    for (std::size_t i = 1; i < n; ++i) {
      minx_ = std::min(minx_, xy[2 * i]); maxx_ = std::max(maxx_, xy[2 * i]);
      miny_ = std::min(miny_, xy[2 * i + 1]); maxy_ = std::max(maxy_, xy[2 * i + 1]);
    }
    // Half units throughout (grid_cells.hpp): no overflow or underflow at any scale.
    const double w = detail::half_span(minx_, maxx_), h = detail::half_span(miny_, maxy_);
    hcs_ = std::max({detail::balanced_cell(w, h, n), w / kMaxCells, h / kMaxCells});
    const double mag = detail::box_magnitude(minx_, miny_, maxx_, maxy_);
    const double fine = Sparse::sparse_half_cell(median_edge, w, h, mag, hcs_);
    sparse_ = fine > 0;
    if (sparse_) {
      sparse_cells_.reset(minx_, miny_, maxx_, maxy_, fine);
    } else {
      dense_cells_.reset(detail::GridFrame{minx_, miny_, mag, hcs_, detail::cell_count(w, hcs_, kMaxCells),
                                           detail::cell_count(h, hcs_, kMaxCells)});
    }
    built_ = true;
  }
  /// Registers count segments on a just built grid, seg(k, a, b, key) giving the k-th: one
  /// counting sort instead of count add() calls.
  template <class Seg> void add_all(std::size_t count, Seg&& seg) {
    if (sparse_) return sparse_cells_.add_all(count, seg);
    dense_cells_.add_all(count, seg);
  }
  bool built() const { return built_; }
  void add(const double* a, const double* b, std::uint64_t key) {
    if (sparse_) return sparse_cells_.add(a, b, key);
    dense_cells_.add(a, b, key);
  }
  void remove(const double* a, const double* b, std::uint64_t key) {
    if (sparse_) return sparse_cells_.remove(a, b, key);
    dense_cells_.remove(a, b, key);
  }
  // Calls f(key) for the registered edges that can meet segment ab (an edge can be reported more
  // than once) until f returns true; true if it did.
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    if (sparse_) return sparse_cells_.any(a, b, f);
    return dense_cells_.any(a, b, f);
  }

 private:
  using Sparse = detail::SparseSegments<std::uint64_t>;
  static constexpr int kMaxCells = 2048;        // per axis, dense
  double minx_ = 0, maxx_ = 0, miny_ = 0, maxy_ = 0, hcs_ = 1;  // hcs_: half the cell edge
  bool built_ = false, sparse_ = false;
  detail::DenseSegments<std::uint64_t> dense_cells_;
  Sparse sparse_cells_;
};

// Starts the polygon at its vertex with the smallest stable id (order[v], or v itself).
void rotate_to_smallest(std::vector<int>& poly, const std::vector<int>* order) {
  const auto first = order ? std::min_element(poly.begin(), poly.end(),
                                              [order](int a, int b) { return (*order)[U(a)] < (*order)[U(b)]; })
                           : std::min_element(poly.begin(), poly.end());
  std::rotate(poly.begin(), first, poly.end());
}

class Refiner {
 public:
  // xy: the coordinates in polygon order (polygon_coordinates()).
  Refiner(const PointSet& points, std::vector<double> xy, const Delaunay2& dt, std::vector<int>& tour,
          std::size_t budget, Refine2Stats& st, const std::vector<int>* order, Adjacency2 adjacency,
          const std::atomic<bool>* cancel)
      : poly_(tour), order_(order), budget_(budget), st_(st), n_(tour.size()), cancel_(cancel) {
    // Local ids = positions in the input polygon: the hot loops walk along the polygon, and the
    // input order of the points is arbitrary (often shuffled), so this relabelling turns random
    // memory accesses into nearly sequential ones.
    id_ = tour;
    xy_ = std::move(xy);
    test_budget_ = kTestsPerPoint * n_ + kTestsFloor;
    std::vector<int> local(n_);
    parallel_blocks(n_, [&](std::size_t i) { local[U(id_[i])] = static_cast<int>(i); });
    if (adjacency.off)
      gather_neighbours(adjacency, points, local);
    else
      build_neighbours(dt, local);
    tour_.resize(n_);
    pos_.resize(n_);
    parallel_blocks(n_, [&](std::size_t i) { tour_[i] = pos_[i] = static_cast<int>(i); });
    non_dt_ = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n_, 8192), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t c) {
          for (std::size_t i = r.begin(); i != r.end(); ++i)
            c += is_dt_edge(static_cast<int>(i), static_cast<int>(i + 1 == n_ ? 0 : i + 1)) ? 0 : 1;
          return c;
        },
        std::plus<>());
  }

  void run() {
    st_.length_before = length();
    // First sweep in parallel and read-only: which vertices have a shortening candidate move at
    // all (simplicity not yet tested)? The flags are a function of the input polygon only, so the
    // queue and the result do not depend on the thread count. Most vertices of a good
    // reconstruction have none, and the sequential pass below visits only the flagged ones and
    // the vertices its moves touch.
    // The region of the deep phase: these vertices, the vertices with a shortening splitting
    // 2-exchange (half of a double bridge), and every vertex a move touches.
    std::vector<char> queued(n_, 0);
    region_.assign(n_, 0);
    std::vector<std::uint8_t> forward(n_);  // or_opt_forward_bits by position
    parallel_blocks(n_, [&](std::size_t i) { forward[i] = or_opt_forward_bits(tour_[i]); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const int v = tour_[i];
        // Or-opt from v: a segment forward from it, or backward from it (forward from the
        // position len - 1 behind it).
        bool or_opt = forward[i] != 0;
        for (std::size_t len = 2; len <= kMaxSegment && !or_opt; ++len)
          or_opt = (forward[(i + n_ - (len - 1) % n_) % n_] >> (len - 1)) & 1u;
        queued[U(v)] = static_cast<char>(try_two_opt<true>(v) || or_opt);
        region_[U(v)] = static_cast<char>(queued[U(v)] || for_each_split(v, [](int, double) { return true; }));
      }
    });
    std::deque<int> queue;
    for (int v : tour_)
      if (queued[U(v)]) queue.push_back(v);
    const auto requeue = [&](int a) {
      for (int v : touched_)
        if (!queued[U(v)]) {
          queued[U(v)] = region_[U(v)] = 1;
          queue.push_back(v);
        }
      if (a >= 0 && !queued[U(a)]) {
        queued[U(a)] = 1;
        queue.push_back(a);
      }
    };
    // Moves from the queued vertices until none has one (deep: also a Lin–Kernighan step).
    // One vertex: sp, when given, is its speculative search on the current polygon.
    const auto visit = [&](int a, bool deep, const Speculation* sp) {
      touched_.clear();
      bool moved = false;
      if (!sp || sp->plain)
        moved = try_two_opt<false>(a) || try_or_opt<false>(a) || (deep && try_lin_kernighan(a));
      else if (sp->search.hit || nodes_ + sp->search.nodes > node_budget_)
        moved = try_lin_kernighan(a);  // the budget ends it sooner: searched again, as it runs
      else
        moved = finish_lin_kernighan(sp->search);
      if (moved) requeue(a);
      check_budget();  // (the simplicity tests' bound: between visits, in visit order)
      return moved;
    };
    std::vector<Speculation> spec;
    std::size_t batch = kSpeculate;
    const auto drain = [&](bool deep) {
      while (!queue.empty() && !st_.budget_hit) {
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) {
          st_.budget_hit = true;  // (ends every loop; the caller drops the polygon)
          break;
        }
        // Deep: the next kSpeculate vertices' searches side by side on the current polygon (few
        // find a move: 2 % on the noisy 10⁶ curve), then visited in queue order until one moves
        // the polygon; the searches after it are dropped (their vertices stay queued). Each
        // visit is what the sequential drain does: the same moves, for any thread count.
        const std::size_t b = deep ? std::min(queue.size(), batch) : 0;
        if (b > 1) {
          speculate(queue, b, spec);
          bool moved = false;
          for (std::size_t i = 0; i < b && !st_.budget_hit && !moved; ++i) {
            const int a = queue.front();
            queue.pop_front();
            queued[U(a)] = 0;
            moved = visit(a, deep, &spec[i]);
          }
          batch = moved ? kSpeculate : std::min(2 * batch, kSpeculateMax);
          continue;
        }
        const int a = queue.front();
        queue.pop_front();
        queued[U(a)] = 0;
        visit(a, deep, nullptr);
      }
    };
    // Phase 1: 2-opt and Or-opt until no vertex has an applicable move.
    drain(false);
    // Phase 2 (deep moves), only in the region of phase 1: from every vertex of the region, the
    // phase-1 moves and then a bounded Lin–Kernighan step; when no vertex has one, a double
    // bridge. Stops at a local optimum of all three or at a work bound.
    node_budget_ = kDeepNodesPerPoint * n_ + kDeepNodesFloor;
    bridge_budget_ = kBridgeNodesPerPoint * n_ + kDeepNodesFloor;
    for (int v : tour_)
      if (region_[U(v)]) {
        queued[U(v)] = 1;
        queue.push_back(v);
      }
    while (!st_.budget_hit) {
      drain(true);
      touched_.clear();
      if (st_.budget_hit || !try_double_bridge()) break;
      requeue(-1);
    }
    normalise();
    st_.length_after = length();
    st_.simplicity_tests = tests_;
  }

  // The edges of the polygon that are not Delaunay edges, in input ids.
  void non_delaunay_edges(std::vector<std::array<int, 2>>& out) const {
    out.clear();
    for (std::size_t i = 0; i < n_; ++i) {
      const int u = tour_[i], v = tour_[(i + 1) % n_];
      if (!is_dt_edge(u, v)) out.push_back({{id_[U(u)], id_[U(v)]}});
    }
  }
 private:
  const double* P(int i) const { return &xy_[2 * U(i)]; }
  [[gnu::always_inline]] double d(int a, int b) const {
    const double dx = P(a)[0] - P(b)[0], dy = P(a)[1] - P(b)[1];
    return std::sqrt(dx * dx + dy * dy);
  }
  int succ(int v) const { const std::size_t i = U(pos_[U(v)]) + 1; return tour_[i == n_ ? 0 : i]; }
  int pred(int v) const { const std::size_t i = U(pos_[U(v)]); return tour_[i == 0 ? n_ - 1 : i - 1]; }
  int step(int v, bool fwd) const { return fwd ? succ(v) : pred(v); }
  static bool improves(double gain, double removed) { return gain > 1e-9 * removed; }

  // Candidate lists: the Delaunay 1-ring of each vertex by (distance, id). Every directed edge
  // u->v of a counter-clockwise triangle gives u its neighbour v once; hull edges (one triangle)
  // also give v its neighbour u. Counting sort: O(N).
  void build_neighbours(const Delaunay2& dt, const std::vector<int>& local) {
    // The passes over the triangles are bound by random memory accesses (input ids are in
    // arbitrary order): run them in parallel with atomic counters. The order inside a list then
    // depends on the schedule, but every list is sorted by (distance, id) below.
    const std::size_t nt = dt.triangles.size();
    std::vector<std::atomic<int>> cnt(n_ + 1);
    for (auto& c : cnt) c.store(0, std::memory_order_relaxed);
    const auto each_edge = [&](auto&& f) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const auto& tr = dt.triangles[t];
          const int l0 = local[U(tr[0])], l1 = local[U(tr[1])], l2 = local[U(tr[2])];
          const int l[3] = {l0, l1, l2};
          for (int i = 0; i < 3; ++i) {
            const int u = l[(i + 1) % 3], v = l[(i + 2) % 3];
            f(u, v);
            if (dt.neighbors[t][U(i)] < 0) f(v, u);
          }
        }
      });
    };
    each_edge([&](int u, int) { cnt[U(u) + 1].fetch_add(1, std::memory_order_relaxed); });
    off_.assign(n_ + 1, 0);
    for (std::size_t v = 0; v < n_; ++v) off_[v + 1] = off_[v] + static_cast<std::size_t>(cnt[v + 1].load(std::memory_order_relaxed));
    for (std::size_t v = 0; v < n_; ++v) cnt[v].store(static_cast<int>(off_[v]), std::memory_order_relaxed);
    near_.assign(off_[n_], 0);
    each_edge([&](int u, int v) { near_[U(cnt[U(u)].fetch_add(1, std::memory_order_relaxed))] = v; });
    sort_neighbours();
  }
  // The same lists from the caller's adjacency (global ids): one parallel pass per vertex. The
  // distances are taken there, from the points by global id (Delaunay neighbours are near each
  // other in that spatially sorted order; local neighbours may be far apart on the polygon), with
  // the same expression as d(): the same doubles.
  void gather_neighbours(Adjacency2 adj, const PointSet& points, const std::vector<int>& local) {
    off_.resize(n_ + 1);
    off_[0] = 0;
    // The degrees by random reads on both cores, then their prefix sums.
    parallel_blocks(n_, [&](std::size_t v) {
      const std::size_t g = U(id_[v]);
      off_[v + 1] = U(adj.off[g + 1] - adj.off[g]);
    });
    for (std::size_t v = 0; v < n_; ++v) off_[v + 1] += off_[v];
    near_.resize(off_[n_]);
    near_d_.resize(off_[n_]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v) {
        const std::size_t g = U(id_[v]);
        const double* p = points[g];
        std::size_t k = off_[v];
        for (int a = adj.off[g]; a < adj.off[g + 1]; ++a, ++k) {
          const double* q = points[U(adj.nb[a])];
          const double dx = p[0] - q[0], dy = p[1] - q[1];
          near_[k] = local[U(adj.nb[a])];
          near_d_[k] = std::sqrt(dx * dx + dy * dy);
        }
      }
    });
    sort_neighbours(true);
  }
  // Sorts every list by (distance, id), recording the distances (have_d: already there).
  static constexpr std::size_t kInsertionSortMax = 64;
  void sort_neighbours(bool have_d = false) {
    if (!have_d) near_d_.resize(near_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<std::pair<double, int>> long_list;
      for (std::size_t v = r.begin(); v != r.end(); ++v) {
        const int vi = static_cast<int>(v);
        if (off_[v + 1] - off_[v] > kInsertionSortMax) {
          // A long list (the apex of a fan of 10^5 points: the insertion sort was quadratic, 11 s
          // of a 12 s run): sorted by the same strict order (distance, id), so the same result.
          long_list.clear();
          for (std::size_t k = off_[v]; k < off_[v + 1]; ++k) long_list.emplace_back(have_d ? near_d_[k] : d(vi, near_[k]), near_[k]);
          std::sort(long_list.begin(), long_list.end());
          for (std::size_t k = off_[v], i = 0; k < off_[v + 1]; ++k, ++i) {
            near_d_[k] = long_list[i].first;
            near_[k] = long_list[i].second;
          }
          continue;
        }
        // Insertion sort by (distance, id): lists are short (6 on average).
        for (std::size_t k = off_[v]; k < off_[v + 1]; ++k) {
          const int w = near_[k];
          const double dw = have_d ? near_d_[k] : d(vi, w);
          std::size_t j = k;
          while (j > off_[v] && (near_d_[j - 1] > dw || (near_d_[j - 1] == dw && near_[j - 1] > w))) {
            near_[j] = near_[j - 1];
            near_d_[j] = near_d_[j - 1];
            --j;
          }
          near_[j] = w;
          near_d_[j] = dw;
        }
      }
    });
  }
  bool is_dt_edge(int u, int v) const {
    for (std::size_t k = off_[U(u)]; k < off_[U(u) + 1]; ++k)
      if (near_[k] == v) return true;
    return false;
  }

  // Does the new edge (u,v) meet the polygon edge (a,b) in a forbidden way? Edges sharing a
  // vertex may only overlap collinearly (a fold-back); others must not meet at all (closed
  // segments), exactly as validate_polygon() decides.
  bool conflict(int u, int v, int a, int b) const {
    if ((u == a && v == b) || (u == b && v == a)) return false;
    int w = -1, o1 = -1, o2 = -1;
    if (u == a) { w = u; o1 = v; o2 = b; }
    else if (u == b) { w = u; o1 = v; o2 = a; }
    else if (v == a) { w = v; o1 = u; o2 = b; }
    else if (v == b) { w = v; o1 = u; o2 = a; }
    if (w >= 0) return orient2(P(w), P(o1), P(o2)) == 0 && same_side_collinear(P(w), P(o1), P(o2));
    return closed_segments_meet(P(u), P(v), P(a), P(b));
  }

  // Would the polygon with edges `rem` replaced by `add` be simple? The current polygon is simple,
  // so only the new edges can create an intersection: each is tested against the new edges and
  // against the current edges near it (minus the removed ones).
  template <std::size_t R, std::size_t A>
  bool valid(const std::array<Edge, R>& rem, const std::array<Edge, A>& add) {
    return valid(rem.data(), R, add.data(), A);
  }
  bool valid(const Edge* rem, std::size_t nr, const Edge* add, std::size_t na) {
    if (!grid_.built() && !all_delaunay(rem, nr, add, na)) build_grid();
    return valid_built(rem, nr, add, na, tests_);
  }
  // Fast path: every polygon edge and every new edge is a Delaunay edge, and distinct edges of a
  // triangulation meet only at shared endpoints (no fold-back either).
  bool all_delaunay(const Edge* rem, std::size_t nr, const Edge* add, std::size_t na) const {
    std::size_t removed_non_dt = 0;
    bool all_dt = true;
    for (std::size_t i = 0; i < nr; ++i) removed_non_dt += is_dt_edge(rem[i].u, rem[i].v) ? 0 : 1;
    for (std::size_t i = 0; i < na; ++i) all_dt = all_dt && is_dt_edge(add[i].u, add[i].v);
    return all_dt && non_dt_ == removed_non_dt;
  }
  // valid() once the grid is built (or the fast path applies). Read-only.
  // tests: counts the polygon edges tested against a new edge.
  bool valid_built(const Edge* rem, std::size_t nr, const Edge* add, std::size_t na, std::size_t& tests) const {
    if (all_delaunay(rem, nr, add, na)) return true;
    for (std::size_t i = 0; i < na; ++i)
      for (std::size_t j = i + 1; j < na; ++j)
        if (conflict(add[i].u, add[i].v, add[j].u, add[j].v)) return false;
    for (std::size_t i = 0; i < na; ++i) {
      const Edge& e = add[i];
      const bool hit = grid_.any(P(e.u), P(e.v), [&](std::uint64_t k) {
        ++tests;
        const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
        for (std::size_t r = 0; r < nr; ++r)
          if (rem[r].same(a, b)) return false;
        return conflict(e.u, e.v, a, b);
      });
      if (hit) return false;
    }
    return true;
  }
  void build_grid() {
    std::vector<double> len(n_);  // the median polygon edge sizes the sparse layout's cells
    for (std::size_t i = 0; i < n_; ++i) {
      const double* p = P(tour_[i]);
      const double* q = P(tour_[(i + 1) % n_]);
      len[i] = std::max(std::fabs(p[0] - q[0]), std::fabs(p[1] - q[1]));
    }
    auto mid = len.begin() + static_cast<std::ptrdiff_t>(n_ / 2);
    std::nth_element(len.begin(), mid, len.end());
    grid_.build(xy_, *mid);
    grid_.add_all(n_, [&](std::size_t i, const double*& a, const double*& b, std::uint64_t& key) {
      const int u = tour_[i], v = tour_[i + 1 == n_ ? 0 : i + 1];
      a = P(u);
      b = P(v);
      key = edge_key(u, v);
    });
  }
  template <std::size_t R, std::size_t A>
  void commit_edges(const std::array<Edge, R>& rem, const std::array<Edge, A>& add) {
    commit_edges(rem.data(), R, add.data(), A);
  }
  void commit_edges(const Edge* rem, std::size_t nr, const Edge* add, std::size_t na) {
    for (std::size_t i = 0; i < nr; ++i) {
      const Edge& e = rem[i];
      non_dt_ -= is_dt_edge(e.u, e.v) ? 0 : 1;
      if (grid_.built()) grid_.remove(P(e.u), P(e.v), edge_key(e.u, e.v));
      touched_.push_back(e.u);
      touched_.push_back(e.v);
    }
    for (std::size_t i = 0; i < na; ++i) {
      const Edge& e = add[i];
      non_dt_ += is_dt_edge(e.u, e.v) ? 0 : 1;
      if (grid_.built()) grid_.add(P(e.u), P(e.v), edge_key(e.u, e.v));
      touched_.push_back(e.u);
      touched_.push_back(e.v);
    }
  }

  // Reverses the tour positions i..j (cyclic, inclusive), or the complement when shorter: both
  // give the same cycle.
  void reverse_positions(std::size_t i, std::size_t j) {
    std::size_t len = (j + n_ - i) % n_ + 1;
    if (2 * len > n_) {
      const std::size_t ni = (j + 1) % n_, nj = (i + n_ - 1) % n_;
      i = ni;
      j = nj;
      len = n_ - len;
    }
    work_ += len;
    // The swaps k of a reversal touch disjoint positions and vertices, so a long one (most of a
    // budget-bound refinement's element work is in reversals of 32 768 and more: 56 of 64 M on
    // the uniform 10^6 square, all 50 M on the noisy curve) runs in blocks on both cores.
    const std::size_t half = len / 2;
    if (half < kParallelReversal)
      swap_ends(i, j, 0, half);
    else
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, half, kParallelReversal / 4),
                        [&](const tbb::blocked_range<std::size_t>& r) { swap_ends(i, j, r.begin(), r.end()); });
    check_budget();
  }
  static constexpr std::size_t kParallelReversal = std::size_t{1} << 15;
  void check_budget() {
    if (work_ > budget_ || tests_ > test_budget_) st_.budget_hit = true;
  }
  // Swaps k = k0..k1-1 of reversing positions i..j: i + k with j - k (cyclic). a walks forward, b
  // backward, both wrapping (no division per element).
  void swap_ends(std::size_t i, std::size_t j, std::size_t k0, std::size_t k1) {
    std::size_t a = i + k0 >= n_ ? i + k0 - n_ : i + k0, b = j >= k0 ? j - k0 : j + n_ - k0;
    for (std::size_t k = k0; k < k1; ++k) {
      std::swap(tour_[a], tour_[b]);
      pos_[U(tour_[a])] = static_cast<int>(a);
      pos_[U(tour_[b])] = static_cast<int>(b);
      a = a + 1 == n_ ? 0 : a + 1;
      b = b == 0 ? n_ - 1 : b - 1;
    }
  }
  // Replaces tour edges {u1,v1}, {u2,v2} (traversed u1->v1 and u2->v2 in the same direction) by
  // {u1,u2}, {v1,v2}: a 2-opt move.
  void two_opt_edges(int u1, int v1, int u2, int v2) {
    if (succ(u1) == v1) {
      CONSTRICT_CHECK(succ(u2) == v2, "refine2: inconsistent 2-opt move");
      reverse_positions(U(pos_[U(v1)]), U(pos_[U(u2)]));
    } else {
      CONSTRICT_CHECK(pred(u1) == v1 && pred(u2) == v2, "refine2: inconsistent 2-opt move");
      reverse_positions(U(pos_[U(u1)]), U(pos_[U(v2)]));
    }
  }

  // 2-opt: replace (a, b=next(a)) and (c, d=next(c)) by (a, c) and (b, d), c a Delaunay neighbour
  // of a closer than b. kDry: only report whether a shortening candidate exists.
  template <bool kDry> bool try_two_opt(int a) {
    for (const bool fwd : {true, false}) {
      const int b = step(a, fwd);
      const double dab = d(a, b);
      for (std::size_t k = off_[U(a)]; k < off_[U(a) + 1]; ++k) {
        const int c = near_[k];
        const double g1 = dab - near_d_[k];
        if (g1 <= 0) break;
        const int dd = step(c, fwd);
        if (c == b || dd == a) continue;
        const double removed = dab + d(c, dd);
        const double gain = g1 + d(c, dd) - d(b, dd);
        if (!improves(gain, removed)) continue;
        if (kDry) return true;
        const std::array<Edge, 2> rem{{{a, b}, {c, dd}}}, add{{{a, c}, {b, dd}}};
        if (!valid(rem, add)) {
          ++st_.rejected;
          continue;
        }
        commit_edges(rem, add);
        if (fwd) two_opt_edges(a, b, c, dd);
        else two_opt_edges(b, a, dd, c);
        ++st_.moves_2opt;
        return true;
      }
    }
    return false;
  }

  // Or-opt: move a segment of 1-kMaxSegment points that starts at a (in either direction) between
  // two adjacent polygon vertices c, c2, with c a Delaunay neighbour of a segment end.
  template <bool kDry> bool try_or_opt(int a) {
    for (const bool fwd : {true, false})
      if (for_each_segment(a, fwd, [&](const Segment& s, int len) { return or_opt_segment<kDry>(s, len, fwd); }))
        return true;
    return false;
  }
  // The first sweep's Or-opt test from every position at once: bit len - 1 of the result says
  // whether the segment of len points forward from a has a shortening move. The segment backward
  // from a vertex is the segment forward from its other end, with the same end points, lengths
  // and candidates (the same doubles: a sum and a distance do not depend on the order of their
  // terms), so try_or_opt<true>(v) is these bits of v and of the positions behind it (run()),
  // with each segment tested once instead of from both ends.
  std::uint8_t or_opt_forward_bits(int a) {
    static_assert(kMaxSegment <= 8, "one bit per segment length");
    std::uint8_t bits = 0;
    for_each_segment(a, true, [&](const Segment& s, int len) {
      if (or_opt_segment<true>(s, len, true)) bits = static_cast<std::uint8_t>(bits | (1u << (len - 1)));
      return false;
    });
    return bits;
  }
  // Calls f(s, len) for the segments of 1 to kMaxSegment points from a in direction fwd (s[0] = a,
  // each next point one step on; at most N - 3 points) until f returns true; true if it did.
  using Segment = std::array<int, kMaxSegment>;
  template <class F> bool for_each_segment(int a, bool fwd, F&& f) {
    Segment s;
    s.fill(-1);
    s[0] = a;
    for (int len = 1; len <= kMaxSegment; ++len) {
      if (n_ < static_cast<std::size_t>(len) + 3) break;
      if (len > 1) s[U(len - 1)] = step(s[U(len - 2)], fwd);
      if (f(static_cast<const Segment&>(s), len)) return true;
    }
    return false;
  }
  // The Or-opt moves of the segment s[0 .. len) (s[0] = a, each next point one step in direction
  // fwd): the first shortening one that keeps the polygon simple is applied (kDry: the first
  // shortening one is reported, simplicity not tested).
  template <bool kDry> bool or_opt_segment(const Segment& s, int len, bool fwd) {
    const int a = s[0], last = s[U(len - 1)];
    const int p = step(a, !fwd), q = step(last, fwd);
    const auto in_seg = [&](int v) { return std::find(s.begin(), s.begin() + len, v) != s.begin() + len; };
    const double rem_len = d(p, a) + d(last, q);
    const double gain_rem = rem_len - d(p, q);
    if (gain_rem <= 0) return false;
    for (const int e : {a, last}) {
      const int other = e == a ? last : a;
      for (std::size_t k = off_[U(e)]; k < off_[U(e) + 1]; ++k) {
        const int c = near_[k];
        const double dce = near_d_[k];
        if (dce >= gain_rem) break;
        if (in_seg(c)) continue;
        for (const int c2 : {succ(c), pred(c)}) {
          if (in_seg(c2)) continue;
          const double dcc2 = d(c, c2);
          const double gain = gain_rem - (dce + d(other, c2) - dcc2);
          if (!improves(gain, rem_len + dcc2)) continue;
          if (kDry) return true;
          const std::array<Edge, 3> rem{{{p, a}, {last, q}, {c, c2}}};
          const std::array<Edge, 3> add{{{p, q}, {c, e}, {other, c2}}};
          if (!valid(rem, add)) {
            ++st_.rejected;
            continue;
          }
          commit_edges(rem, add);
          apply_or_opt(s, len, fwd, p, q, c, c2, e);
          ++st_.moves_oropt;
          return true;
        }
      }
    }
    return false;
  }
  // Performs the Or-opt move as two or three 2-opt moves (each on the current cycle).
  void apply_or_opt(const std::array<int, kMaxSegment>& s, int len, bool fwd, int p, int q, int c, int c2, int e) {
    // Normalise to the traversal p -> s0 .. sL -> q.
    int s0 = s[0], sl = s[U(len - 1)];
    if (!fwd) {
      std::swap(s0, sl);
      std::swap(p, q);
    }
    // After the normalisation p -> s0 is the array's forward direction; x -> y is the edge
    // {c, c2} in that direction.
    const int x = succ(c) == c2 ? c : c2;
    const int y = x == c ? c2 : c;
    if (x == q) {
      two_opt_edges(p, s0, q, y);
    } else if (y == p) {
      two_opt_edges(x, p, sl, q);
    } else {
      two_opt_edges(p, s0, x, y);
      two_opt_edges(p, x, q, sl);
    }
    // Now x - sl and s0 - y are edges; flip the segment when e must touch c the other way.
    const bool want_sl_at_x = (x == c) == (e == sl);
    if (!want_sl_at_x && len > 1) two_opt_edges(x, sl, s0, y);
  }

  // Counts one search node of the deep phase; false when the node bound is reached.
  bool node() {
    if (++nodes_ <= node_budget_) return true;
    st_.budget_hit = true;
    return false;
  }
  bool bridge_node() {
    if (++bridge_nodes_ <= bridge_budget_) return true;
    st_.budget_hit = true;
    return false;
  }
  bool is_tour_edge(int u, int v) const { return succ(u) == v || pred(u) == v; }

  // A k-exchange that removes the tour edges rem[0 .. k) and adds add[0 .. k), when it gives one
  // cycle (plan_exchange, O(k^2), on the segments between the cuts): segment s runs from position
  // cut[s] + 1 to cut[s + 1] (cyclic); the new cycle is segment `keep`, then order[0 .. m)
  // (segment, forward). apply_exchange rewrites the tour: every segment but the longest is copied
  // in its new order (the copy counts as reversal work).
  struct ExchangePlan {
    std::array<std::size_t, kMaxExchanged> cut{};
    std::size_t k = 0, keep = 0, m = 0;
    std::array<std::pair<std::size_t, bool>, kMaxExchanged> order{};
  };
  std::size_t seg_first(const ExchangePlan& p, std::size_t s) const { return (p.cut[s] + 1) % n_; }
  std::size_t seg_last(const ExchangePlan& p, std::size_t s) const { return p.cut[(s + 1) % p.k]; }
  std::size_t seg_length(const ExchangePlan& p, std::size_t s) const {
    return (seg_last(p, s) + n_ - seg_first(p, s)) % n_ + 1;
  }

  // Lin–Kernighan step from t1 (sequential k-opt, 2 <= k <= kMaxDepth): remove (t1, t2) with t2 a
  // polygon neighbour, add (t2, t3) with t3 a near candidate of t2, remove (t3, t4) with t4 a
  // polygon neighbour of t3, and so on; the move closes with (t2k, t1). Every partial gain must
  // stay positive (the LK gain criterion), which prunes the search; the first closing move that
  // shortens the polygon, gives one cycle and keeps it simple is applied.
  // The search (lk_search) is read-only, so that the drain can run the searches of the next
  // queued vertices side by side (Speculation); its state is an LkSearch.
  struct LkSearch {
    std::array<int, 2 * kMaxDepth> lk{};  // the chain t1 t2 ... t2k
    std::size_t nodes = 0;                // search nodes counted
    std::size_t tests = 0;                // polygon edges tested by its simplicity tests
    std::size_t budget = 0;               // nodes allowed
    std::size_t rejected = 0;             // closing moves that were not simple
    std::size_t k = 0;                    // the move found: its k removed edges (0: none)
    ExchangePlan plan;                    // and how it rewrites the tour
    bool hit = false;                     // the budget ended the search
    bool node() {
      if (++nodes <= budget) return true;
      hit = true;
      return false;
    }
  };
  bool try_lin_kernighan(int t1) {
    if (!grid_.built()) build_grid();  // (lk_search reads it)
    LkSearch s;
    s.budget = node_budget_ - nodes_;
    lk_search(t1, s);
    return finish_lin_kernighan(s);
  }
  // A vertex's search ahead of its turn: plain when a 2-opt or Or-opt candidate exists (then
  // the vertex is visited as usual), else its Lin–Kernighan search.
  struct Speculation {
    bool plain = false;
    LkSearch search;
  };
  // The searches of the first b queued vertices on the current polygon, in parallel.
  void speculate(const std::deque<int>& queue, std::size_t b, std::vector<Speculation>& spec) {
    if (!grid_.built()) build_grid();
    spec.assign(b, Speculation{});
    const std::size_t budget = node_budget_ - nodes_;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const int a = queue[i];
        spec[i].plain = try_two_opt<true>(a) || try_or_opt<true>(a);
        if (spec[i].plain) continue;
        spec[i].search.budget = budget;
        lk_search(a, spec[i].search);
      }
    });
  }
  // Books a search's counts and applies its move, if it found one.
  bool finish_lin_kernighan(const LkSearch& s) {
    nodes_ += s.nodes;
    tests_ += s.tests;
    st_.rejected += s.rejected;
    if (s.hit) st_.budget_hit = true;
    if (s.k == 0) return false;
    std::array<Edge, kMaxExchanged> rem{}, add{};
    lk_edges(s, s.k, rem, add);
    commit_deep(rem.data(), add.data(), s.plan);
    return true;
  }
  // Finds the move from t1, both directions (s.k > 0), or none. Read-only; needs the grid built.
  bool lk_search(int t1, LkSearch& s) const {
    for (const bool fwd : {true, false}) {
      s.lk[0] = t1;
      s.lk[1] = step(t1, fwd);
      const double g = d(t1, s.lk[1]);
      if (lin_kernighan_level(s, 1, g, g)) return true;
      if (s.hit) return false;
    }
    return false;
  }
  // s.lk[0 .. 2i) chosen: removed (lk[2j], lk[2j+1]) and added (lk[2j+1], lk[2j+2]), j < i.
  // g: the partial gain, removed: the removed length.
  bool lin_kernighan_level(LkSearch& s, int i, double g, double removed) const {
    const std::size_t I = U(i);
    auto& lk = s.lk;
    const int last = lk[2 * I - 1];
    const std::size_t end = std::min(off_[U(last) + 1], off_[U(last)] + kBreadth[I - 1]);
    // Is (a, b) one of the first `count` removed (first = 0) or added (first = 1) edges?
    const auto in_move = [&](int a, int b, std::size_t first, std::size_t count) {
      for (std::size_t j = 0; j < count; ++j)
        if (Edge{lk[2 * j + first], lk[2 * j + first + 1]}.same(a, b)) return true;
      return false;
    };
    for (std::size_t k = off_[U(last)]; k < end; ++k) {
      const int c = near_[k];
      const double g1 = g - near_d_[k];
      if (g1 <= 0) break;
      if (!s.node()) return false;
      if (is_tour_edge(last, c) || in_move(last, c, 1, I - 1)) continue;
      for (const bool fwd : {true, false}) {
        const int c2 = step(c, fwd);
        if (in_move(c, c2, 0, I)) continue;
        lk[2 * I] = c;
        lk[2 * I + 1] = c2;
        const double dcc2 = d(c, c2);
        const double g2 = g1 + dcc2;
        const int t1 = lk[0];
        if (c2 != t1 && !is_tour_edge(c2, t1) && !in_move(c2, t1, 1, I) && improves(g2 - d(c2, t1), removed + dcc2) &&
            close_lin_kernighan(s, i + 1))
          return true;
        if (i + 1 < kMaxDepth && lin_kernighan_level(s, i + 1, g2, removed + dcc2)) return true;
        if (s.hit) return false;
      }
    }
    return false;
  }
  // The k removed and added edges of the chain: removed lk[0 .. 2k), closed by (lk[2k-1], lk[0]).
  static void lk_edges(const LkSearch& s, std::size_t k, std::array<Edge, kMaxExchanged>& rem,
                       std::array<Edge, kMaxExchanged>& add) {
    for (std::size_t j = 0; j < k; ++j) {
      rem[j] = {s.lk[2 * j], s.lk[2 * j + 1]};
      add[j] = {s.lk[2 * j + 1], j + 1 < k ? s.lk[2 * j + 2] : s.lk[0]};
    }
  }
  // The chain closed after k removed edges: the move when it gives one cycle and a simple polygon.
  bool close_lin_kernighan(LkSearch& s, int k) const {
    std::array<Edge, kMaxExchanged> rem{}, add{};
    lk_edges(s, U(k), rem, add);
    if (!plan_exchange(rem.data(), add.data(), U(k), s.plan)) return false;
    if (!valid_built(rem.data(), U(k), add.data(), U(k), s.tests)) {
      ++s.rejected;
      return false;
    }
    s.k = U(k);
    return true;
  }
  // A deep move: applied when it gives one cycle and keeps the polygon simple.
  bool apply_deep(const Edge* rem, const Edge* add, std::size_t k) {
    ExchangePlan plan;
    if (!plan_exchange(rem, add, k, plan)) return false;
    if (!valid(rem, k, add, k)) {
      ++st_.rejected;
      return false;
    }
    commit_deep(rem, add, plan);
    return true;
  }
  void commit_deep(const Edge* rem, const Edge* add, const ExchangePlan& plan) {
    commit_edges(rem, plan.k, add, plan.k);
    apply_exchange(plan);
    ++st_.moves_deep;
  }

  // The shortening splitting 2-exchanges from t1: remove (t1, t2 = succ t1) and (t3, t4 = succ t3),
  // add (t2, t3) and (t4, t1), with t3 a near candidate of t2 closer than t1. Calls f(t3, gain)
  // until it returns true. Read-only.
  template <class F> bool for_each_split(int t1, F&& f) const {
    const int t2 = succ(t1);
    const double d12 = d(t1, t2);
    for (std::size_t k = off_[U(t2)]; k < off_[U(t2) + 1]; ++k) {
      const int t3 = near_[k];
      if (near_d_[k] >= d12) break;
      const int t4 = succ(t3);
      if (t3 == t1 || t3 == succ(t2) || t4 == t1 || t4 == pred(t1)) continue;
      const double d34 = d(t3, t4);
      const double gain = d12 - near_d_[k] + d34 - d(t4, t1);
      if (improves(gain, d12 + d34) && f(t3, gain)) return true;
    }
    return false;
  }

  // Double bridge: two splitting 2-exchanges, each removing tour edges (t1, t2 = succ t1) and
  // (t3, t4 = succ t3) and adding (t2, t3) and (t4, t1) — alone each cuts the polygon into two
  // cycles — whose removed edges interleave along the polygon, so that together they give one
  // cycle (the segments A B C D become A D C B). Sequential moves cannot reach it: it is how the
  // interleaved cross edges of a sparse spiral are removed. Both exchanges must shorten, and so
  // their sum; the candidates come from the region of the deep phase.
  bool try_double_bridge() {
    // i, j: the positions of t1, t3 (fixed until a move is applied), kept beside them: the pair
    // scan below reads them for every pair, and pos_ is a random access each.
    struct Split {
      double gain;
      int t1, t3;
      std::size_t i, j;
    };
    std::vector<Split> splits;
    for (const int t1 : tour_) {
      if (!region_[U(t1)]) continue;
      if (!bridge_node()) return false;
      for_each_split(t1, [&](int t3, double gain) {
        // The same exchange seen from t3 is (t3, t4, t1, t2): keep the one with t1 first.
        const std::size_t p1 = U(pos_[U(t1)]), p3 = U(pos_[U(t3)]);
        if (p1 < p3) splits.push_back({gain, t1, t3, p1, p3});
        else splits.push_back({gain, t3, t1, p3, p1});
        return false;
      });
    }
    // Largest gain first; ties by polygon position (deterministic), duplicates removed.
    const auto by_pos = [](const Split& a, const Split& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; };
    std::sort(splits.begin(), splits.end(), by_pos);
    splits.erase(std::unique(splits.begin(), splits.end(),
                             [](const Split& a, const Split& b) { return a.t1 == b.t1 && a.t3 == b.t3; }),
                 splits.end());
    std::stable_sort(splits.begin(), splits.end(), [](const Split& a, const Split& b) { return a.gain > b.gain; });
    for (std::size_t x = 0; x < splits.size(); ++x) {
      const Split& A = splits[x];
      const std::size_t i = A.i, j = A.j;  // i < j
      for (std::size_t y = x + 1; y < splits.size(); ++y) {
        const Split& B = splits[y];
        if (!bridge_node()) return false;
        const std::size_t k = B.i, l = B.j;
        if (k == i || k == j || l == i || l == j) continue;
        if ((i < k && k < j) == (i < l && l < j)) continue;  // not interleaved
        const int a2 = succ(A.t1), a4 = succ(A.t3), b2 = succ(B.t1), b4 = succ(B.t3);
        const std::array<Edge, 4> rem{{{A.t1, a2}, {A.t3, a4}, {B.t1, b2}, {B.t3, b4}}};
        const std::array<Edge, 4> add{{{a2, A.t3}, {a4, A.t1}, {b2, B.t3}, {b4, B.t1}}};
        bool distinct = true;
        for (std::size_t p = 0; p < 4; ++p)
          for (std::size_t q = 0; q < 4; ++q)
            distinct = distinct && !add[p].same(rem[q].u, rem[q].v) && (q <= p || !add[p].same(add[q].u, add[q].v));
        if (distinct && apply_deep(rem.data(), add.data(), 4)) return true;
      }
    }
    return false;
  }

  // Plans the exchange (ExchangePlan): false when it does not give one cycle.
  bool plan_exchange(const Edge* rem, const Edge* add, std::size_t k, ExchangePlan& p) const {
    p.k = k;
    auto& cut = p.cut;  // the edge (tour_[cut], tour_[cut + 1]) is removed
    for (std::size_t j = 0; j < k; ++j) {
      const int u = rem[j].u, v = rem[j].v;
      cut[j] = U(succ(u) == v ? pos_[U(u)] : pos_[U(v)]);
    }
    std::sort(cut.begin(), cut.begin() + static_cast<std::ptrdiff_t>(k));
    for (std::size_t j = 1; j < k; ++j)
      if (cut[j] == cut[j - 1]) return false;
    // Slot 2s is the first vertex of segment s, 2s + 1 its last; link[] pairs the slots joined by
    // an added edge.
    std::array<int, 2 * kMaxExchanged> link;
    link.fill(-1);
    const auto free_slot = [&](int v) {
      const std::size_t q = U(pos_[U(v)]);
      for (std::size_t s = 0; s < k; ++s) {
        if (seg_first(p, s) == q && link[2 * s] == -1) return static_cast<int>(2 * s);
        if (seg_last(p, s) == q && link[2 * s + 1] == -1) return static_cast<int>(2 * s + 1);
      }
      return -1;
    };
    for (std::size_t j = 0; j < k; ++j) {
      const int a = free_slot(add[j].u);
      if (a < 0) return false;
      link[U(a)] = -2;  // reserve: add[j].v may be the same vertex's other slot
      const int b = free_slot(add[j].v);
      if (b < 0) return false;
      link[U(a)] = b;
      link[U(b)] = a;
    }
    p.keep = 0;
    for (std::size_t s = 1; s < k; ++s)
      if (seg_length(p, s) > seg_length(p, p.keep)) p.keep = s;
    p.m = 0;
    int slot = static_cast<int>(2 * p.keep + 1);
    for (;;) {
      const int in = link[U(slot)];
      const std::size_t s = U(in) / 2;
      if (s == p.keep) {
        if (U(in) != 2 * p.keep) return false;
        break;
      }
      if (p.m == k - 1) return false;
      const bool fwd = in % 2 == 0;
      p.order[p.m++] = {s, fwd};
      slot = fwd ? static_cast<int>(2 * s + 1) : static_cast<int>(2 * s);
    }
    return p.m == k - 1;
  }
  void apply_exchange(const ExchangePlan& p) {
    buf_.clear();
    for (std::size_t o = 0; o < p.m; ++o) {
      const auto [s, fwd] = p.order[o];
      const std::size_t len = seg_length(p, s);
      for (std::size_t t = 0, q = fwd ? seg_first(p, s) : seg_last(p, s); t < len; ++t) {
        buf_.push_back(tour_[q]);
        q = fwd ? (q + 1 == n_ ? 0 : q + 1) : (q == 0 ? n_ - 1 : q - 1);
      }
    }
    std::size_t q = (seg_last(p, p.keep) + 1) % n_;
    for (const int v : buf_) {
      tour_[q] = v;
      pos_[U(v)] = static_cast<int>(q);
      q = q + 1 == n_ ? 0 : q + 1;
    }
    work_ += buf_.size();
    check_budget();
  }

  // Writes the polygon back in input ids: CCW (exact turn at the lexicographically smallest
  // vertex), starting at the smallest input index.
  void normalise() {
    std::size_t lo = 0;
    for (std::size_t i = 1; i < n_; ++i) {
      const double* a = P(tour_[i]);
      const double* b = P(tour_[lo]);
      if (a[0] < b[0] || (a[0] == b[0] && a[1] < b[1])) lo = i;
    }
    const int v = tour_[lo];
    const bool cw = orient2(P(pred(v)), P(v), P(succ(v))) < 0;
    for (std::size_t i = 0; i < n_; ++i) poly_[i] = id_[U(tour_[cw ? n_ - 1 - i : i])];
    rotate_to_smallest(poly_, order_);
  }
  double length() const {
    double s = 0;
    for (std::size_t i = 0; i < n_; ++i) s += d(tour_[i], tour_[(i + 1) % n_]);
    return s;
  }

  std::vector<int>& poly_;        // the caller's polygon (input ids), written by normalise()
  const std::vector<int>* order_; // stable id of an input id (null: itself)
  std::vector<int> id_;           // local id -> input id
  std::vector<double> xy_;        // coordinates by local id
  std::vector<int> tour_;         // the polygon as local ids
  std::size_t budget_;
  Refine2Stats& st_;
  std::size_t n_;
  const std::atomic<bool>* cancel_;  // stop at the next visited vertex (null: never)
  std::vector<int> pos_;
  std::vector<std::size_t> off_;
  std::vector<int> near_;
  std::vector<double> near_d_;
  std::size_t non_dt_ = 0, work_ = 0;
  EdgeGrid grid_;
  std::vector<int> touched_;
  std::vector<char> region_;      // vertices of the deep phase (queued at least once)
  std::vector<int> buf_;          // segment copy of apply_exchange()
  std::size_t nodes_ = 0, node_budget_ = 0, bridge_nodes_ = 0, bridge_budget_ = 0;
  std::size_t tests_ = 0;  // polygon edges tested by the simplicity tests (valid_built)
  std::size_t test_budget_ = 0;
};

}  // namespace

namespace {

// Could any vertex have a shortening candidate move? A superset test of the Refiner's first sweep
// that needs no candidate lists: one pass over the triangle edges (like the O(N) validation).
// 2-opt moves through a Delaunay edge are tested exactly as the search does; for Or-opt, a
// candidate c of a segment end e is a Delaunay neighbour closer than the largest length the
// removal of a segment ending at e saves. When
// this returns false the search would make no move, so the expensive set-up is skipped: on a
// good reconstruction of a dense curve the pass costs about as much as the validation.
bool may_improve(const std::vector<double>& xy, const Delaunay2& dt, const std::vector<int>& poly, double& perimeter) {
  const std::size_t n = poly.size();
  const auto dpos = [&](std::size_t i, std::size_t j) {
    const double dx = xy[2 * i] - xy[2 * j], dy = xy[2 * i + 1] - xy[2 * j + 1];
    return std::sqrt(dx * dx + dy * dy);
  };
  // (Both arrays are written in full by the parallel loops: not zero-filled first.)
  BigArray<double> el;  // el[i] = |poly[i] poly[i+1]|
  el.allocate(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) el[i] = dpos(i, (i + 1) % n);
  });
  perimeter = 0;
  for (std::size_t i = 0; i < n; ++i) perimeter += el[i];
  // Or-opt: the largest saving el(p,s0) + el(sL,q) - d(p,q) over the segments of 1..kMaxSegment
  // points that start (g_start) or end (g_end) at a position; 2-opt: the longer polygon edge.
  // Per vertex id, packed so that the triangle pass below loads one cache line per vertex.
  struct VInfo {
    double x, y, two, gain;  // coordinates, longer polygon edge, largest Or-opt saving
    int succ, pred;
  };
  BigArray<VInfo> vi;  // (poly is a permutation of 0..n-1: each record written once)
  vi.allocate(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    // The chord that closes a removed segment, d(j, j + L + 1), is the same for the segment of L
    // points that starts at j + 1 and the one that ends at j + L: each is computed once per block
    // (chord[(L - 1) * w + k] for j = r.begin() - kMaxSegment + k, mod n), half the square roots.
    const std::size_t K = U(kMaxSegment), w = r.size() + K, base = (r.begin() + n - K % n) % n;
    const std::size_t max_len = n >= 3 ? std::min(K, n - 3) : 0;
    // Positions below 2n wrapped by one subtraction (a 64-bit division each was most of this pass).
    const auto wrap = [n](std::size_t x) { return x >= n ? x - n : x; };
    std::vector<double> chord(max_len * w);
    for (std::size_t L = 1; L <= max_len; ++L)
      for (std::size_t k = 0, j = base; k < w; ++k, j = j + 1 == n ? 0 : j + 1)
        chord[(L - 1) * w + k] = dpos(j, wrap(j + L + 1));
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t ip = wrap(i + n - 1), m = i - r.begin();
      double gs = 0, ge = 0;
      for (std::size_t L = 1; L <= max_len; ++L) {
        const double* c = &chord[(L - 1) * w];
        // segment i .. i+L-1 (starts here): the chord d(i-1, i+L)
        const std::size_t last = wrap(i + L - 1);
        gs = std::max(gs, el[ip] + el[last] - c[m + K - 1]);
        // segment i-L+1 .. i (ends here): the chord d(i-L, i+1)
        const std::size_t pp = wrap(i + n - L);
        ge = std::max(ge, el[pp] + el[i] - c[m + K - L]);
      }
      vi[U(poly[i])] = {xy[2 * i],        xy[2 * i + 1],     std::max(el[ip], el[i]),
                        std::max(gs, ge), poly[wrap(i + 1)], poly[ip]};
    }
  });
  std::atomic<bool> any{false};
  const auto dv = [&](const VInfo& p, const VInfo& q) {
    const double dx = p.x - q.x, dy = p.y - q.y;
    return std::sqrt(dx * dx + dy * dy);
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, dt.triangles.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    if (any.load(std::memory_order_relaxed)) return;
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const auto& tr = dt.triangles[t];
      for (int k = 0; k < 3; ++k) {
        // Each undirected edge once: from the triangle with the smaller index (or the hull).
        const int across = dt.neighbors[t][U((k + 2) % 3)];
        if (across >= 0 && U(across) < t) continue;
        const int a = tr[U(k)], b = tr[U((k + 1) % 3)];
        const VInfo& A = vi[U(a)];
        const VInfo& B = vi[U(b)];
        const double d = dv(A, B);
        for (int side = 0; side < 2; ++side) {
          const int u = side ? b : a, v = side ? a : b;
          const VInfo& Uu = side ? B : A;
          const VInfo& Vv = side ? A : B;
          bool hit = d < Uu.gain;
          if (!hit && d < Uu.two) {
            // The exact 2-opt test of Refiner::try_two_opt for c = v, both directions.
            for (const bool fwd : {true, false}) {
              const int nb = fwd ? Uu.succ : Uu.pred, dd = fwd ? Vv.succ : Vv.pred;
              if (v == nb || dd == u) continue;
              const VInfo& Nb = vi[U(nb)];
              const VInfo& Dd = vi[U(dd)];
              const double dab = dv(Uu, Nb), dcd = dv(Vv, Dd);
              const double g = dab - d + dcd - dv(Nb, Dd);
              if (g > 1e-9 * (dab + dcd)) hit = true;
            }
            // The splitting 2-exchange of Refiner::for_each_split with t2 = u, t3 = v: it puts t1
            // in the region of the deep phase (double bridges), so the search must run.
            const int t1 = Uu.pred, t4 = Vv.succ;
            if (!hit && v != t1 && v != Uu.succ && t4 != t1) {
              const VInfo& T1 = vi[U(t1)];
              const double d12 = dv(T1, Uu);
              if (t4 != T1.pred && d < d12) {
                const VInfo& T4 = vi[U(t4)];
                const double d34 = dv(Vv, T4);
                const double g = d12 - d + d34 - dv(T4, T1);
                if (g > 1e-9 * (d12 + d34)) hit = true;
              }
            }
          }
          if (hit) {
            any.store(true, std::memory_order_relaxed);
            return;
          }
        }
      }
    }
  });
  return any.load();
}

// Multi-start (small inputs): kStarts runs from evenly spaced starts, the shortest result kept.
constexpr std::size_t kStarts = 8;

// Where the search starts: the position of the point farthest from the centre of the bounding
// box (pt(i): the coordinates of polygon position i). Both are computed exactly the same way
// however the input is numbered, and after an exact rotation by 90° (min/max and negation are
// exact, dx² + dy² is commutative); ties go to the smallest stable id.
template <class Pt>
std::size_t start_position(const Pt& pt, const std::vector<int>& poly, const std::vector<int>* order) {
  const std::size_t n = poly.size();
  double x0 = pt(0)[0], x1 = x0, y0 = pt(0)[1], y1 = y0;
  for (std::size_t i = 1; i < n; ++i) {
    x0 = std::min(x0, pt(i)[0]); x1 = std::max(x1, pt(i)[0]);
    y0 = std::min(y0, pt(i)[1]); y1 = std::max(y1, pt(i)[1]);
  }
  const double cx = 0.5 * x0 + 0.5 * x1, cy = 0.5 * y0 + 0.5 * y1;
  const auto stable = [&](std::size_t i) { return order ? (*order)[U(poly[i])] : poly[i]; };
  std::size_t best = 0;
  double best_d = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = pt(i)[0] - cx, dy = pt(i)[1] - cy;
    const double d = dx * dx + dy * dy;
    if (d > best_d || (d == best_d && stable(i) < stable(best))) { best = i; best_d = d; }
  }
  return best;
}

// Perimeter summed in CCW order from the start_position() point: the same double for the same
// polygon, however it is numbered or rotated by 90°.
double geometric_length(const PointSet& pts, const std::vector<int>& poly, const std::vector<int>* order) {
  const std::size_t n = poly.size();
  const std::size_t lo = start_position([&](std::size_t i) { return pts[U(poly[i])]; }, poly, order);
  double s = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double* a = pts[U(poly[(lo + k) % n])];
    const double* b = pts[U(poly[(lo + k + 1) % n])];
    s += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return s;
}

// The coordinates in polygon order (one pass of random reads, in parallel): both the pre-test and
// the search work on them.
std::vector<double> polygon_coordinates(const PointSet& pts, const std::vector<int>& poly) {
  const std::size_t n = poly.size();
  std::vector<double> xy(2 * n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      xy[2 * i] = pts[U(poly[i])][0];
      xy[2 * i + 1] = pts[U(poly[i])][1];
    }
  });
  return xy;
}

// CCW (exact turn at the lexicographically smallest vertex), starting at the smallest index.
void normalise_polygon(const PointSet& pts, std::vector<int>& poly, const std::vector<int>* order) {
  const std::size_t n = poly.size();
  std::size_t lo = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double* a = pts[U(poly[i])];
    const double* b = pts[U(poly[lo])];
    if (a[0] < b[0] || (a[0] == b[0] && a[1] < b[1])) lo = i;
  }
  if (orient2(pts[U(poly[(lo + n - 1) % n])], pts[U(poly[lo])], pts[U(poly[(lo + 1) % n])]) < 0)
    std::reverse(poly.begin(), poly.end());
  rotate_to_smallest(poly, order);
}

}  // namespace

bool refine_polygon2(const PointSet& points, const Delaunay2& dt, std::vector<int>& polygon, std::size_t work_budget,
                     Refine2Stats& stats, const std::vector<int>* order, const std::function<Adjacency2()>& adjacency,
                     bool pretest, std::vector<std::array<int, 2>>* non_delaunay, bool multi_start,
                     const std::atomic<bool>* cancel) {
  stats = Refine2Stats{};
  if (polygon.size() != points.size()) return false;
  if (polygon.size() < 4) {
    // A triangle has no other polygon: only the normal form (counter-clockwise, smallest first);
    // it used to come back unchanged, clockwise too.
    normalise_polygon(points, polygon, order);
    return false;
  }
  std::vector<double> xy = polygon_coordinates(points, polygon);
  double len = 0;
  if (pretest && !may_improve(xy, dt, polygon, len)) {
    normalise_polygon(points, polygon, order);
    stats.length_before = stats.length_after = len;
    return false;
  }
  // The search visits the vertices in polygon order from the first one, and that order decides
  // which local optimum it reaches. So the starts are geometric (start_position(), then evenly
  // spaced positions after it: the result does not depend on how the input is numbered), and on
  // small inputs several starts run and the shortest result is kept.
  const Adjacency2 adj = adjacency ? adjacency() : Adjacency2{};
  const std::size_t n = polygon.size();
  const std::size_t lo = start_position([&](std::size_t i) { return &xy[2 * i]; }, polygon, order);
  const std::size_t starts = multi_start && n <= kRefineMultiStartMaxPoints ? kStarts : 1;
  // One start's run: its polygon, length (0 for a single start: nothing to compare, and a pass of
  // random reads saved), stats and non-Delaunay edges.
  struct Run {
    std::vector<int> poly;
    double len = 0;
    Refine2Stats st;
    std::vector<std::array<int, 2>> non_dt;
  };
  const auto run_start = [&](std::size_t k, Run& out) {
    const std::size_t first = (lo + k * n / starts) % n;
    std::vector<double> pxy;
    if (starts == 1) {  // (large inputs: rotated in place, no second copy)
      std::rotate(polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(first), polygon.end());
      std::rotate(xy.begin(), xy.begin() + static_cast<std::ptrdiff_t>(2 * first), xy.end());
      out.poly.swap(polygon);
      pxy.swap(xy);
    } else {
      out.poly.assign(polygon.begin() + static_cast<std::ptrdiff_t>(first), polygon.end());
      out.poly.insert(out.poly.end(), polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(first));
      pxy.assign(xy.begin() + static_cast<std::ptrdiff_t>(2 * first), xy.end());
      pxy.insert(pxy.end(), xy.begin(), xy.begin() + static_cast<std::ptrdiff_t>(2 * first));
    }
    Refiner r(points, std::move(pxy), dt, out.poly, work_budget, out.st, order, adj, cancel);
    if (starts == 1 && adj.release) adj.release();  // (the lists are the Refiner's now)
    r.run();
    out.len = starts == 1 ? 0.0 : geometric_length(points, out.poly, order);
    if (non_delaunay) r.non_delaunay_edges(out.non_dt);
  };
  // The first start alone: no move from it means the polygon is a local optimum of every move,
  // whatever the start (the order only chooses among applicable moves). Otherwise the other starts
  // side by side, and the shortest result kept, the earliest start on ties: the same as one after
  // another, whatever the thread count.
  std::vector<Run> runs(1);
  run_start(0, runs[0]);
  const Refine2Stats& s0 = runs[0].st;
  const bool settled = s0.moves_2opt + s0.moves_oropt + s0.moves_deep == 0;
  if (starts > 1 && !settled && !(cancel && cancel->load(std::memory_order_relaxed))) {
    runs.resize(starts);
    tbb::parallel_for(std::size_t{1}, starts, [&](std::size_t k) { run_start(k, runs[k]); });
  }
  std::size_t b = 0;
  for (std::size_t k = 1; k < runs.size(); ++k)
    if (runs[k].len < runs[b].len) b = k;
  std::vector<int> best = std::move(runs[b].poly);
  stats = runs[b].st;
  if (non_delaunay) *non_delaunay = std::move(runs[b].non_dt);
  polygon.swap(best);
  if (starts > 1 && adj.release) adj.release();
  return true;
}

}  // namespace constrict::detail

namespace constrict {

Status refine_polygon2(const PointSet& points, std::vector<int>& polygon, Refine2Stats* stats,
                       std::size_t work_per_point) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, "refine_polygon2: points must be 2D"};
  if (Status st = check_points(points); !st) return st;
  PolygonCheck chk;
  if (Status st = validate_polygon(points, polygon, &chk); !st) {
    // Either orientation is accepted (the result is counter-clockwise).
    const bool only_clockwise = chk.indices_ok && chk.all_points && chk.simple && !chk.ccw;
    if (!only_clockwise)
      return {StatusCode::InvalidArgument, "refine_polygon2: the polygon is not valid: " + st.message()};
  }
  Delaunay2 dt;
  if (Status st = build_delaunay2(points, dt); !st) return st;
  Refine2Stats local;
  detail::refine_polygon2(points, dt, polygon, work_per_point * points.size(), stats ? *stats : local);
  return Status::ok();
}

}  // namespace constrict
