// SPDX-License-Identifier: GPL-3.0-or-later
// Exact polygon validation: indices, every point once, simplicity (Shamos–Hoey sweep), CCW.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "constrict/predicates.hpp"
#include "constrict/detail/segments2.hpp"
#include "constrict/validate.hpp"
#include "core/detail/grid_cells.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace {
using detail::closed_segments_meet;
using detail::on_closed_segment;
using detail::same_side_collinear;

// Lexicographic (x, y) comparison of two points: exact.
bool lex_less(const double* p, const double* q) {
  return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]);
}




struct Poly {
  const PointSet& pts;
  const std::vector<int>& b;
  std::size_t n;
  const double* vtx(std::size_t i) const { return pts[static_cast<std::size_t>(b[i])]; }
  // Edge i = (b[i], b[i+1]).
  std::size_t nxt(std::size_t i) const { return i + 1 == n ? 0 : i + 1; }
  bool adjacent(std::size_t e, std::size_t f) const { return e == f || nxt(e) == f || nxt(f) == e; }
  // Edges meet in a forbidden way? Adjacent edges may only share their common vertex.
  bool conflict(std::size_t e, std::size_t f) const {
    if (e == f) return false;
    if (nxt(e) == f || nxt(f) == e) {
      const std::size_t first = nxt(e) == f ? e : f;  // edges (u,v), (v,w)
      const double* u = vtx(first);
      const double* v = vtx(nxt(first));
      const double* w = vtx(nxt(nxt(first)));
      if (orient2(u, v, w) != 0) return false;
      return same_side_collinear(v, u, w);  // fold-back
    }
    return closed_segments_meet(vtx(e), vtx(nxt(e)), vtx(f), vtx(nxt(f)));
  }
};

Status fail(PolygonCheck* d, const std::string& why) {
  if (d) d->reason = why;
  return {StatusCode::InvalidArgument, why};
}

// Checks indices and "every point exactly once". Returns Ok or the failure.
Status check_indices(const PointSet& points, const std::vector<int>& boundary, PolygonCheck* d) {
  if (points.dim != 2) return fail(d, "validate_polygon: points must be 2D");
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    if (boundary[i] < 0 || static_cast<std::size_t>(boundary[i]) >= n)
      return fail(d, "index out of range at position " + std::to_string(i));
  }
  if (d) d->indices_ok = true;
  std::vector<char> seen(n, 0);
  for (int v : boundary) {
    if (seen[static_cast<std::size_t>(v)]) {
      if (d) d->repeated_point = v;
      return fail(d, "point " + std::to_string(v) + " appears more than once");
    }
    seen[static_cast<std::size_t>(v)] = 1;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!seen[i]) {
      if (d) d->missing_point = static_cast<int>(i);
      return fail(d, "point " + std::to_string(i) + " is missing");
    }
  }
  if (d) d->all_points = true;
  if (n < 3) return fail(d, "a polygon needs at least 3 vertices");
  return Status::ok();
}

Status check_ccw(const Poly& P, PolygonCheck* d) {
  // The lexicographically smallest vertex is convex; its turn gives the orientation.
  std::size_t m = 0;
  for (std::size_t i = 1; i < P.n; ++i)
    if (lex_less(P.vtx(i), P.vtx(m))) m = i;
  const double* prev = P.vtx(m == 0 ? P.n - 1 : m - 1);
  const int o = orient2(prev, P.vtx(m), P.vtx(P.nxt(m)));
  if (o <= 0) return fail(d, o < 0 ? "polygon is clockwise" : "polygon is degenerate");
  if (d) d->ccw = true;
  return Status::ok();
}

// Shamos–Hoey sweep. Edges are oriented left (lexicographically smaller endpoint) to right.
class Sweep {
 public:
  explicit Sweep(const Poly& P) : P_(P), left_(P.n), right_(P.n) {
    for (std::size_t e = 0; e < P.n; ++e) {
      const double* a = P.vtx(e);
      const double* b = P.vtx(P.nxt(e));
      if (lex_less(a, b)) { left_[e] = a; right_[e] = b; } else { left_[e] = b; right_[e] = a; }
    }
  }

  // Returns true and the pair if two edges conflict. only (optional): the edges to sweep (a pair
  // of edges outside it is known not to conflict).
  bool run(std::size_t& e_out, std::size_t& f_out, const std::vector<char>* only = nullptr) {
    const std::size_t n = P_.n;
    const auto in = [&](std::size_t e) { return !only || (*only)[e] != 0; };
    std::vector<std::size_t> order;
    order.reserve(only ? 0 : n);
    for (std::size_t i = 0; i < n; ++i)
      if (in(i) || in(i == 0 ? n - 1 : i - 1)) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](std::size_t i, std::size_t j) { return lex_less(P_.vtx(i), P_.vtx(j)); });
    Cmp cmp{this};
    std::set<std::size_t, Cmp> active(cmp);
    std::vector<std::set<std::size_t, Cmp>::iterator> where(n, active.end());
    for (std::size_t vi : order) {
      const double* v = P_.vtx(vi);
      const std::size_t e_in = vi == 0 ? n - 1 : vi - 1, e_out_edge = vi;
      const std::size_t inc[2] = {e_in, e_out_edge};
      // Deletions first (edges whose right endpoint is v).
      for (std::size_t e : inc) {
        if (!in(e) || right_[e] != v || where[e] == active.end()) continue;
        auto it = where[e];
        auto above = std::next(it);
        if (it != active.begin() && above != active.end()) {
          auto below = std::prev(it);
          if (P_.conflict(*below, *above)) { e_out = *below; f_out = *above; return true; }
        }
        active.erase(it);
        where[e] = active.end();
      }
      for (std::size_t e : inc) {
        if (!in(e) || left_[e] != v) continue;
        if (e == e_in && e_in == e_out_edge) continue;
        auto res = active.insert(e);
        if (bad_) { e_out = bad_e_; f_out = bad_f_; return true; }
        if (!res.second) { e_out = e; f_out = *res.first; return true; }
        auto it = res.first;
        where[e] = it;
        auto above = std::next(it);
        if (above != active.end() && P_.conflict(e, *above)) { e_out = e; f_out = *above; return true; }
        if (it != active.begin()) {
          auto below = std::prev(it);
          if (P_.conflict(e, *below)) { e_out = e; f_out = *below; return true; }
        }
      }
    }
    return false;
  }

 private:
  struct Cmp {
    Sweep* s;
    bool operator()(std::size_t a, std::size_t b) const { return s->below(a, b); }
  };

  void flag(std::size_t a, std::size_t b) const {
    if (!bad_) { bad_ = true; bad_e_ = a; bad_f_ = b; }
  }

  // Is edge a below edge b (both active: their x-ranges overlap at the sweep)? For disjoint
  // segments the answer is consistent; a zero orientation means the segments meet (flagged).
  bool below(std::size_t a, std::size_t b) const {
    if (a == b) return false;
    bool swap = false;
    if (lex_less(left_[b], left_[a])) { std::swap(a, b); swap = true; }
    int o = orient2(left_[a], right_[a], left_[b]);
    if (o == 0) {
      if (left_[b] != left_[a]) flag(a, b);  // b starts on a (touching)
      o = orient2(left_[a], right_[a], right_[b]);
      if (o == 0) { flag(a, b); o = lex_less(right_[a], right_[b]) ? 1 : -1; }
    }
    const bool a_below_b = o > 0;
    return swap ? !a_below_b : a_below_b;
  }

  const Poly& P_;
  std::vector<const double*> left_, right_;
  mutable bool bad_ = false;
  mutable std::size_t bad_e_ = 0, bad_f_ = 0;
};

// The edges a conflict could involve when every edge with dt[e] set is an edge of one
// triangulation: two such edges never conflict (they meet only at a shared endpoint, and
// consecutive ones cannot fold back), so a conflict involves an edge without the flag and an
// edge whose bounding box meets its box. Those are found with a uniform grid of the unflagged
// edges' boxes (exact closed-box comparisons). Returns false when the subset would not be much
// smaller than the polygon (then the whole polygon is swept).
bool conflict_candidates(const Poly& P, const std::vector<char>& dt, std::vector<char>& only) {
  const std::size_t n = P.n;
  std::vector<std::size_t> odd;  // edges that are not triangulation edges
  for (std::size_t e = 0; e < n; ++e)
    if (!dt[e]) odd.push_back(e);
  if (odd.size() * 8 > n) return false;
  struct Box { double x0, x1, y0, y1; };
  const auto box = [&](std::size_t e) {
    const double* a = P.vtx(e);
    const double* b = P.vtx(P.nxt(e));
    return Box{std::min(a[0], b[0]), std::max(a[0], b[0]), std::min(a[1], b[1]), std::max(a[1], b[1])};
  };
  const auto meet = [](const Box& p, const Box& q) {
    return p.x0 <= q.x1 && q.x0 <= p.x1 && p.y0 <= q.y1 && q.y0 <= p.y1;
  };
  const int G = static_cast<int>(std::min<std::size_t>(1024, 4 + 4 * static_cast<std::size_t>(std::sqrt(static_cast<double>(odd.size())))));
  // Columns and rows cut at quantiles of the unflagged boxes' lower corners, so that the grid
  // follows where those edges are: a uniform grid over the polygon's box put them all in one cell
  // on heavy-tailed inputs (10^6 Cauchy-distributed points: 27 s of pair tests). A box meets the
  // columns from that of its x0 to that of its x1 (upper_bound is monotone, so two boxes that
  // overlap share a column; exact comparisons).
  std::vector<double> cut_x(odd.size()), cut_y(odd.size());
  for (std::size_t k = 0; k < odd.size(); ++k) {
    const Box b = box(odd[k]);
    cut_x[k] = b.x0;
    cut_y[k] = b.y0;
  }
  std::sort(cut_x.begin(), cut_x.end());
  std::sort(cut_y.begin(), cut_y.end());
  const auto quantiles = [&](std::vector<double>& v) {
    std::vector<double> q(static_cast<std::size_t>(G - 1));
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = v[(k + 1) * v.size() / static_cast<std::size_t>(G)];
    v = std::move(q);
  };
  quantiles(cut_x);
  quantiles(cut_y);
  const auto cx = [&](double x) {
    return static_cast<int>(std::upper_bound(cut_x.begin(), cut_x.end(), x) - cut_x.begin());
  };
  const auto cy = [&](double y) {
    return static_cast<int>(std::upper_bound(cut_y.begin(), cut_y.end(), y) - cut_y.begin());
  };
  constexpr long long kBig = 4096;  // boxes over more cells are compared with every edge
  const auto cells_of = [&](const Box& b, int& i0, int& i1, int& j0, int& j1) {
    i0 = cx(b.x0); i1 = cx(b.x1); j0 = cy(b.y0); j1 = cy(b.y1);
    return static_cast<long long>(i1 - i0 + 1) * (j1 - j0 + 1);
  };
  // CSR of the unflagged edges by cell (a counting pass, then a filling pass); the big ones in a
  // list.
  const auto cell = [&](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(G) + static_cast<std::size_t>(i); };
  const auto for_cells = [&](std::size_t e, const auto& f) {
    int i0, i1, j0, j1;
    if (cells_of(box(e), i0, i1, j0, j1) > kBig) return false;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(cell(i, j));
    return true;
  };
  std::vector<std::size_t> start(static_cast<std::size_t>(G) * static_cast<std::size_t>(G) + 1, 0), big;
  for (std::size_t e : odd)
    if (!for_cells(e, [&](std::size_t c) { ++start[c + 1]; })) big.push_back(e);
  if (big.size() > 64) return false;
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  std::vector<std::size_t> items(start.back()), at(start.begin(), start.end() - 1);
  for (std::size_t e : odd) for_cells(e, [&](std::size_t c) { items[at[c]++] = e; });
  // The candidates: the unflagged edges, and every edge whose box meets one of theirs (each edge
  // on its own: both cores).
  only.assign(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) {
      if (!dt[f]) {  // (one of odd)
        only[f] = 1;
        continue;
      }
      const Box bf = box(f);
      bool hit = false;
      for (std::size_t g : big) hit = hit || meet(bf, box(g));
      int i0 = 0, i1 = -1, j0 = 0, j1 = -1;                         // (an empty range when the box test already hit)
      if (!hit && cells_of(bf, i0, i1, j0, j1) > kBig) hit = true;  // long edge: keep it
      for (int j = j0; j <= j1 && !hit; ++j)
        for (int i = i0; i <= i1 && !hit; ++i)
          for (std::size_t k = start[cell(i, j)]; k < start[cell(i, j) + 1] && !hit; ++k) hit = meet(bf, box(items[k]));
      only[f] = hit ? 1 : 0;
    }
  });
  return true;
}

Status report_crossing(const Poly& P, std::size_t e, std::size_t f, PolygonCheck* d) {
  if (e > f) std::swap(e, f);
  if (d) d->crossing_edges = {{static_cast<int>(e), static_cast<int>(f)}};
  return fail(d, "edges (" + std::to_string(P.b[e]) + "," + std::to_string(P.b[P.nxt(e)]) + ") and (" +
                     std::to_string(P.b[f]) + "," + std::to_string(P.b[P.nxt(f)]) + ") intersect");
}

// A polygon that misses points (an incomplete result: a lock with the fallbacks off, a stop on
// request) is still checked for what it is, so that the flags say whether it is simple and
// counter-clockwise over its own vertices; the status stays the missing point's.
Status with_partial_flags(const PointSet& points, const std::vector<int>& boundary, PolygonCheck* d, Status st) {
  if (!d || !d->indices_ok || d->repeated_point >= 0 || d->missing_point < 0 || boundary.size() < 3) return st;
  const Poly P{points, boundary, boundary.size()};
  Sweep sweep(P);
  std::size_t e = 0, f = 0;
  if (sweep.run(e, f)) return st;
  d->simple = true;
  PolygonCheck orientation;
  d->ccw = check_ccw(P, &orientation).is_ok();
  return st;
}

}  // namespace

Status validate_polygon(const PointSet& points, const std::vector<int>& boundary,
                        PolygonCheck* details) {
  if (details) *details = PolygonCheck{};
  if (Status f = detail::check_finite(points, "validate_polygon"); !f) return f;
  Status st = check_indices(points, boundary, details);
  if (!st) return with_partial_flags(points, boundary, details, st);
  Poly P{points, boundary, boundary.size()};
  Sweep sweep(P);
  std::size_t e = 0, f = 0;
  if (sweep.run(e, f)) return report_crossing(P, e, f, details);
  if (details) details->simple = true;
  return check_ccw(P, details);
}

Status validate_polygon_brute_force(const PointSet& points, const std::vector<int>& boundary,
                                    PolygonCheck* details) {
  if (details) *details = PolygonCheck{};
  if (Status f = detail::check_finite(points, "validate_polygon"); !f) return f;
  Status st = check_indices(points, boundary, details);
  if (!st) return st;
  Poly P{points, boundary, boundary.size()};
  for (std::size_t e = 0; e < P.n; ++e)
    for (std::size_t f = e + 1; f < P.n; ++f)
      if (P.conflict(e, f)) return report_crossing(P, e, f, details);
  if (details) details->simple = true;
  return check_ccw(P, details);
}

Status validate_polygon_in_triangulation(const PointSet& points, const std::vector<int>& boundary,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          PolygonCheck* details) {
  if (details) *details = PolygonCheck{};
  if (Status f = detail::check_finite(points, "validate_polygon"); !f) return f;
  Status st = check_indices(points, boundary, details);
  if (!st) return with_partial_flags(points, boundary, details, st);
  // Mark the polygon edges met as triangle edges: succ[u] is the vertex after u on the polygon.
  const std::size_t n = points.size();
  // (check_indices: the boundary is a permutation of the points, so every write has its own slot.)
  std::vector<int> succ(n, -1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boundary.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        succ[static_cast<std::size_t>(boundary[k])] = boundary[k + 1 == boundary.size() ? 0 : k + 1];
                    });
  // found[u]: the polygon edge from u is a triangle edge. The pass over the triangles reads succ
  // at random and runs in parallel; a flag is only ever set to 1 (relaxed atomic stores), so the
  // flags do not depend on the schedule.
  std::vector<std::atomic<unsigned char>> found(n);
  std::atomic<bool> indices_ok{true};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t u = r.begin(); u != r.end(); ++u) found[u].store(0, std::memory_order_relaxed);
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const auto& t = triangles[k];
      bool in = true;
      for (int v : t) in = in && v >= 0 && static_cast<std::size_t>(v) < n;
      if (!in) {
        indices_ok.store(false, std::memory_order_relaxed);
        return;
      }
      for (int i = 0; i < 3; ++i) {
        const int u = t[static_cast<std::size_t>(i)], v = t[static_cast<std::size_t>((i + 1) % 3)];
        if (succ[static_cast<std::size_t>(u)] == v) found[static_cast<std::size_t>(u)].store(1, std::memory_order_relaxed);
        if (succ[static_cast<std::size_t>(v)] == u) found[static_cast<std::size_t>(v)].store(1, std::memory_order_relaxed);
      }
    }
  });
  const bool indices_in = indices_ok.load();
  const bool all_edges_in = indices_in && tbb::parallel_reduce(
                                              tbb::blocked_range<std::size_t>(0, n, 16384), true,
                                              [&](const tbb::blocked_range<std::size_t>& r, bool all) {
                                                for (std::size_t u = r.begin(); u != r.end() && all; ++u)
                                                  all = found[u].load(std::memory_order_relaxed) != 0;
                                                return all;
                                              },
                                              [](bool x, bool y) { return x && y; });
  Poly P{points, boundary, boundary.size()};
  if (!all_edges_in) {
    // Some edge is not a triangulation edge: the sweep decides, over the edges near those when
    // there are few of them.
    Sweep sweep(P);
    std::size_t e = 0, f = 0;
    std::vector<char> dt_edge, only;
    bool subset = false;
    if (indices_in) {
      dt_edge.resize(P.n);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, P.n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k)
          dt_edge[k] = static_cast<char>(found[static_cast<std::size_t>(boundary[k])].load(std::memory_order_relaxed));
      });
      subset = conflict_candidates(P, dt_edge, only);
    }
    if (sweep.run(e, f, subset ? &only : nullptr)) return report_crossing(P, e, f, details);
  }
  // Edges of one triangulation meet only at common endpoints, and the cycle visits every vertex
  // once: a simple polygon (two edges at a vertex cannot overlap, so no fold-back either).
  if (details) details->simple = true;
  return check_ccw(P, details);
}

}  // namespace constrict
