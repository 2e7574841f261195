// SPDX-License-Identifier: GPL-3.0-or-later
// Exact polygon validation: indices, every point once, simplicity (Shamos–Hoey sweep), CCW.
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "constrict/predicates.hpp"
#include "constrict/detail/segments2.hpp"
#include "constrict/validate.hpp"

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

  // Returns true and the pair if two edges conflict.
  bool run(std::size_t& e_out, std::size_t& f_out) {
    const std::size_t n = P_.n;
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
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
        if (right_[e] != v || where[e] == active.end()) continue;
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
        if (left_[e] != v) continue;
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

Status report_crossing(const Poly& P, std::size_t e, std::size_t f, PolygonCheck* d) {
  if (e > f) std::swap(e, f);
  if (d) d->crossing_edges = {{static_cast<int>(e), static_cast<int>(f)}};
  return fail(d, "edges (" + std::to_string(P.b[e]) + "," + std::to_string(P.b[P.nxt(e)]) + ") and (" +
                     std::to_string(P.b[f]) + "," + std::to_string(P.b[P.nxt(f)]) + ") intersect");
}

}  // namespace

Status validate_polygon(const PointSet& points, const std::vector<int>& boundary,
                        PolygonCheck* details) {
  if (details) *details = PolygonCheck{};
  Status st = check_indices(points, boundary, details);
  if (!st) return st;
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
  Status st = check_indices(points, boundary, details);
  if (!st) return st;
  // Mark the polygon edges met as triangle edges: succ[u] is the vertex after u on the polygon.
  const std::size_t n = points.size();
  std::vector<int> succ(n, -1);
  for (std::size_t k = 0; k < boundary.size(); ++k)
    succ[static_cast<std::size_t>(boundary[k])] = boundary[(k + 1) % boundary.size()];
  std::vector<char> found(n, 0);
  bool all_edges_in = true;
  for (const auto& t : triangles) {
    for (int v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= n) all_edges_in = false;
    if (!all_edges_in) break;
    for (int i = 0; i < 3; ++i) {
      const int u = t[static_cast<std::size_t>(i)], v = t[static_cast<std::size_t>((i + 1) % 3)];
      if (succ[static_cast<std::size_t>(u)] == v) found[static_cast<std::size_t>(u)] = 1;
      if (succ[static_cast<std::size_t>(v)] == u) found[static_cast<std::size_t>(v)] = 1;
    }
  }
  for (std::size_t u = 0; u < n && all_edges_in; ++u) all_edges_in = found[u] != 0;
  Poly P{points, boundary, boundary.size()};
  if (!all_edges_in) {  // some edge is not a triangulation edge: the general sweep decides
    Sweep sweep(P);
    std::size_t e = 0, f = 0;
    if (sweep.run(e, f)) return report_crossing(P, e, f, details);
  }
  // Edges of one triangulation meet only at common endpoints, and the cycle visits every vertex
  // once: a simple polygon (two edges at a vertex cannot overlap, so no fold-back either).
  if (details) details->simple = true;
  return check_ccw(P, details);
}

}  // namespace constrict
