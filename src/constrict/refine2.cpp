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

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/delaunay.hpp"
#include "constrict/detail/segments2.hpp"
#include "constrict/predicates.hpp"
#include "constrict/validate.hpp"

namespace constrict::detail {
namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

// Longest Or-opt segment.
constexpr int kMaxSegment = 8;

std::uint64_t edge_key(int u, int v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) |
         static_cast<std::uint32_t>(v);
}

struct Edge {
  int u, v;
  bool same(int a, int b) const { return (u == a && v == b) || (u == b && v == a); }
};

// Uniform grid of the polygon edges (each edge registered in every cell its bounding box meets).
// Cell indices are monotone in the coordinates, so a bounding-box query finds every edge whose box
// meets the query box: exact candidate sets for the exact segment tests.
class EdgeGrid {
 public:
  void build(const std::vector<double>& xy) {
    const std::size_t n = xy.size() / 2;
    minx_ = maxx_ = xy[0];
    miny_ = maxy_ = xy[1];
    for (std::size_t i = 1; i < n; ++i) {
      minx_ = std::min(minx_, xy[2 * i]); maxx_ = std::max(maxx_, xy[2 * i]);
      miny_ = std::min(miny_, xy[2 * i + 1]); maxy_ = std::max(maxy_, xy[2 * i + 1]);
    }
    const double w = std::max(maxx_ - minx_, 1e-300), h = std::max(maxy_ - miny_, 1e-300);
    cs_ = std::sqrt(w * h / static_cast<double>(n));
    cs_ = std::max({cs_, w / 2048.0, h / 2048.0});
    nx_ = std::min<int>(2048, std::max(1, static_cast<int>(std::ceil(w / cs_))));
    ny_ = std::min<int>(2048, std::max(1, static_cast<int>(std::ceil(h / cs_))));
    cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
    built_ = true;
  }
  bool built() const { return built_; }
  void add(const double* a, const double* b, std::uint64_t key) {
    for_cells(a, b, [&](std::vector<std::uint64_t>& c) { c.push_back(key); });
  }
  void remove(const double* a, const double* b, std::uint64_t key) {
    for_cells(a, b, [&](std::vector<std::uint64_t>& c) {
      auto it = std::find(c.begin(), c.end(), key);
      if (it != c.end()) {
        *it = c.back();
        c.pop_back();
      }
    });
  }
  // Calls f(key) for every registered edge in the cells met by the box of segment ab (an edge can
  // be reported more than once).
  template <class F> bool any(const double* a, const double* b, F&& f) const {
    const int i0 = cx(std::min(a[0], b[0])), i1 = cx(std::max(a[0], b[0]));
    const int j0 = cy(std::min(a[1], b[1])), j1 = cy(std::max(a[1], b[1]));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (std::uint64_t k : cells_[index(i, j)])
          if (f(k)) return true;
    return false;
  }

 private:
  template <class F> void for_cells(const double* a, const double* b, F&& f) {
    const int i0 = cx(std::min(a[0], b[0])), i1 = cx(std::max(a[0], b[0]));
    const int j0 = cy(std::min(a[1], b[1])), j1 = cy(std::max(a[1], b[1]));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(cells_[index(i, j)]);
  }
  static int clampi(int v, int n) { return v < 0 ? 0 : (v >= n ? n - 1 : v); }
  int cx(double x) const { return clampi(static_cast<int>(std::floor((x - minx_) / cs_)), nx_); }
  int cy(double y) const { return clampi(static_cast<int>(std::floor((y - miny_) / cs_)), ny_); }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }
  double minx_ = 0, maxx_ = 0, miny_ = 0, maxy_ = 0, cs_ = 1;
  int nx_ = 1, ny_ = 1;
  bool built_ = false;
  std::vector<std::vector<std::uint64_t>> cells_;
};

class Refiner {
 public:
  // xy: the coordinates in polygon order (polygon_coordinates()).
  Refiner(std::vector<double> xy, const Delaunay2& dt, std::vector<int>& tour, std::size_t budget,
          Refine2Stats& st)
      : poly_(tour), budget_(budget), st_(st), n_(tour.size()) {
    // Local ids = positions in the input polygon: the hot loops walk along the polygon, and the
    // input order of the points is arbitrary (often shuffled), so this relabelling turns random
    // memory accesses into nearly sequential ones.
    id_ = tour;
    xy_ = std::move(xy);
    std::vector<int> local(n_);
    for (std::size_t i = 0; i < n_; ++i) local[U(id_[i])] = static_cast<int>(i);
    build_neighbours(dt, local);
    tour_.resize(n_);
    pos_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) tour_[i] = pos_[i] = static_cast<int>(i);
    for (std::size_t i = 0; i < n_; ++i)
      if (!is_dt_edge(tour_[i], tour_[(i + 1) % n_])) ++non_dt_;
  }

  void run() {
    st_.length_before = length();
    // First sweep in parallel and read-only: which vertices have a shortening candidate move at
    // all (simplicity not yet tested)? The flags are a function of the input polygon only, so the
    // queue and the result do not depend on the thread count. Most vertices of a good
    // reconstruction have none, and the sequential pass below visits only the flagged ones and
    // the vertices its moves touch.
    std::vector<char> queued(n_, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const int v = tour_[i];
        queued[U(v)] = static_cast<char>(try_two_opt<true>(v) || try_or_opt<true>(v));
      }
    });
    std::deque<int> queue;
    for (int v : tour_)
      if (queued[U(v)]) queue.push_back(v);
    while (!queue.empty() && !st_.budget_hit) {
      const int a = queue.front();
      queue.pop_front();
      queued[U(a)] = 0;
      touched_.clear();
      if (!try_two_opt<false>(a) && !try_or_opt<false>(a)) continue;
      for (int v : touched_)
        if (!queued[U(v)]) {
          queued[U(v)] = 1;
          queue.push_back(v);
        }
      if (!queued[U(a)]) {
        queued[U(a)] = 1;
        queue.push_back(a);
      }
    }
    normalise();
    st_.length_after = length();
  }

 private:
  const double* P(int i) const { return &xy_[2 * U(i)]; }
  double d(int a, int b) const {
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
    near_d_.assign(near_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v) {
        const int vi = static_cast<int>(v);
        // Insertion sort by (distance, id): lists are short (6 on average).
        for (std::size_t k = off_[v]; k < off_[v + 1]; ++k) {
          const int w = near_[k];
          const double dw = d(vi, w);
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
    // Fast path: every polygon edge and every new edge is a Delaunay edge, and distinct edges of a
    // triangulation meet only at shared endpoints (no fold-back either).
    std::size_t removed_non_dt = 0;
    bool all_dt = true;
    for (const Edge& e : rem) removed_non_dt += is_dt_edge(e.u, e.v) ? 0 : 1;
    for (const Edge& e : add) all_dt = all_dt && is_dt_edge(e.u, e.v);
    if (all_dt && non_dt_ == removed_non_dt) return true;
    for (std::size_t i = 0; i < A; ++i)
      for (std::size_t j = i + 1; j < A; ++j)
        if (conflict(add[i].u, add[i].v, add[j].u, add[j].v)) return false;
    if (!grid_.built()) build_grid();
    for (const Edge& e : add) {
      const bool hit = grid_.any(P(e.u), P(e.v), [&](std::uint64_t k) {
        const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
        for (const Edge& r : rem)
          if (r.same(a, b)) return false;
        return conflict(e.u, e.v, a, b);
      });
      if (hit) return false;
    }
    return true;
  }
  void build_grid() {
    grid_.build(xy_);
    for (std::size_t i = 0; i < n_; ++i) {
      const int u = tour_[i], v = tour_[(i + 1) % n_];
      grid_.add(P(u), P(v), edge_key(u, v));
    }
  }
  template <std::size_t R, std::size_t A>
  void commit_edges(const std::array<Edge, R>& rem, const std::array<Edge, A>& add) {
    for (const Edge& e : rem) {
      non_dt_ -= is_dt_edge(e.u, e.v) ? 0 : 1;
      if (grid_.built()) grid_.remove(P(e.u), P(e.v), edge_key(e.u, e.v));
      touched_.push_back(e.u);
      touched_.push_back(e.v);
    }
    for (const Edge& e : add) {
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
    for (std::size_t k = 0; k < len / 2; ++k) {
      const std::size_t a = (i + k) % n_, b = (j + n_ - k) % n_;
      std::swap(tour_[a], tour_[b]);
      pos_[U(tour_[a])] = static_cast<int>(a);
      pos_[U(tour_[b])] = static_cast<int>(b);
    }
    if (work_ > budget_) st_.budget_hit = true;
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

  // Or-opt: move a segment of 1-3 points that starts at a (in either direction) between two
  // adjacent polygon vertices c, c2, with c a Delaunay neighbour of a segment end.
  template <bool kDry> bool try_or_opt(int a) {
    for (const bool fwd : {true, false}) {
      std::array<int, kMaxSegment> s;
      s.fill(-1);
      s[0] = a;
      for (int len = 1; len <= kMaxSegment; ++len) {
        if (n_ < static_cast<std::size_t>(len) + 3) break;
        if (len > 1) s[U(len - 1)] = step(s[U(len - 2)], fwd);
        const int last = s[U(len - 1)];
        const int p = step(a, !fwd), q = step(last, fwd);
        const auto in_seg = [&](int v) { return std::find(s.begin(), s.begin() + len, v) != s.begin() + len; };
        const double rem_len = d(p, a) + d(last, q);
        const double gain_rem = rem_len - d(p, q);
        if (gain_rem <= 0) continue;
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
    std::rotate(poly_.begin(), std::min_element(poly_.begin(), poly_.end()), poly_.end());
  }
  double length() const {
    double s = 0;
    for (std::size_t i = 0; i < n_; ++i) s += d(tour_[i], tour_[(i + 1) % n_]);
    return s;
  }

  std::vector<int>& poly_;        // the caller's polygon (input ids), written by normalise()
  std::vector<int> id_;           // local id -> input id
  std::vector<double> xy_;        // coordinates by local id
  std::vector<int> tour_;         // the polygon as local ids
  std::size_t budget_;
  Refine2Stats& st_;
  std::size_t n_;
  std::vector<int> pos_;
  std::vector<std::size_t> off_;
  std::vector<int> near_;
  std::vector<double> near_d_;
  std::size_t non_dt_ = 0, work_ = 0;
  EdgeGrid grid_;
  std::vector<int> touched_;
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
  std::vector<double> el(n);  // el[i] = |poly[i] poly[i+1]|
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) el[i] = dpos(i, (i + 1) % n);
  });
  perimeter = 0;
  for (double l : el) perimeter += l;
  // Or-opt: the largest saving el(p,s0) + el(sL,q) - d(p,q) over the segments of 1..kMaxSegment
  // points that start (g_start) or end (g_end) at a position; 2-opt: the longer polygon edge.
  // Per vertex id, packed so that the triangle pass below loads one cache line per vertex.
  struct VInfo {
    double x, y, two, gain;  // coordinates, longer polygon edge, largest Or-opt saving
    int succ, pred;
  };
  std::vector<VInfo> vi(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t ip = (i + n - 1) % n;
      double gs = 0, ge = 0;
      for (int len = 1; len <= kMaxSegment && n >= static_cast<std::size_t>(len) + 3; ++len) {
        const std::size_t L = U(len);
        // segment i .. i+L-1 (starts here)
        const std::size_t last = (i + L - 1) % n, q = (i + L) % n;
        gs = std::max(gs, el[ip] + el[last] - dpos(ip, q));
        // segment i-L+1 .. i (ends here)
        const std::size_t st = (i + n - L + 1) % n, pp = (st + n - 1) % n;
        ge = std::max(ge, el[pp] + el[i] - dpos(pp, (i + 1) % n));
      }
      vi[U(poly[i])] = {xy[2 * i], xy[2 * i + 1], std::max(el[ip], el[i]), std::max(gs, ge),
                        poly[(i + 1) % n], poly[ip]};
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
void normalise_polygon(const PointSet& pts, std::vector<int>& poly) {
  const std::size_t n = poly.size();
  std::size_t lo = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double* a = pts[U(poly[i])];
    const double* b = pts[U(poly[lo])];
    if (a[0] < b[0] || (a[0] == b[0] && a[1] < b[1])) lo = i;
  }
  if (orient2(pts[U(poly[(lo + n - 1) % n])], pts[U(poly[lo])], pts[U(poly[(lo + 1) % n])]) < 0)
    std::reverse(poly.begin(), poly.end());
  std::rotate(poly.begin(), std::min_element(poly.begin(), poly.end()), poly.end());
}

}  // namespace

void refine_polygon2(const PointSet& points, const Delaunay2& dt, std::vector<int>& polygon,
                     std::size_t work_budget, Refine2Stats& stats) {
  stats = Refine2Stats{};
  if (polygon.size() < 4 || polygon.size() != points.size()) return;
  std::vector<double> xy = polygon_coordinates(points, polygon);
  double len = 0;
  if (!may_improve(xy, dt, polygon, len)) {
    normalise_polygon(points, polygon);
    stats.length_before = stats.length_after = len;
    return;
  }
  Refiner r(std::move(xy), dt, polygon, work_budget, stats);
  r.run();
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
