// SPDX-License-Identifier: GPL-3.0-or-later
// infer_rings2(): the rings the points show (topology.hpp, docs/topology.md §"Method").
// Exactness contract: every decision -- nearest neighbour, half neighbour, degree, cycles, nesting,
// orientation and the gap test -- uses exact predicates (compare_distance2, diametral_side2,
// orient2, compare_gap2) or combinatorics of the Delaunay triangulation; doubles are computed only
// for the report (Ring2::gap_spacings). Ties are broken by the lexicographic order of the points,
// never by their indices, so the rings do not depend on the file order.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"

namespace constrict {
namespace {

bool lex_less(const double* p, const double* q) { return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]); }

// The Delaunay neighbours of every vertex (CSR, each list sorted by index, no repeats).
struct Adjacency {
  std::vector<std::size_t> start;
  std::vector<int> nbr;
  explicit Adjacency(const Delaunay2& dt) : start(dt.n_vertices + 1, 0) {
    std::vector<std::pair<int, int>> e;
    e.reserve(dt.triangles.size() * 6);
    for (const auto& t : dt.triangles)
      for (int i = 0; i < 3; ++i) {
        e.emplace_back(t[static_cast<std::size_t>(i)], t[static_cast<std::size_t>((i + 1) % 3)]);
        e.emplace_back(t[static_cast<std::size_t>((i + 1) % 3)], t[static_cast<std::size_t>(i)]);
      }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    nbr.reserve(e.size());
    for (const auto& [a, b] : e) {
      ++start[static_cast<std::size_t>(a) + 1];
      nbr.push_back(b);
    }
    for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
  }
};

// The NN-crust (Dey–Kumar 1999, §3): p's nearest Delaunay neighbour q, and its nearest Delaunay
// neighbour r in the open half-plane away from q (angle qpr > 90°: p strictly inside the circle
// with diameter qr). "Nearer" is exact; equally near candidates are ordered lexicographically.
class NnCrust {
 public:
  NnCrust(const PointSet& pts, const Adjacency& adj) : pts_(pts), adj_(adj) {}

  // The crust edges as (min, max) pairs, sorted, no repeats.
  std::vector<std::array<int, 2>> edges() const {
    std::vector<std::array<int, 2>> e;
    const std::size_t n = adj_.start.size() - 1;
    e.reserve(2 * n);
    for (std::size_t p = 0; p < n; ++p) {
      const int ip = static_cast<int>(p);
      const int q = nearest(ip, -1);
      if (q < 0) continue;
      e.push_back({std::min(ip, q), std::max(ip, q)});
      const int r = nearest(ip, q);
      if (r >= 0) e.push_back({std::min(ip, r), std::max(ip, r)});
    }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
  }

 private:
  const double* at(int i) const { return pts_[static_cast<std::size_t>(i)]; }
  // Is a strictly preferred to b as p's neighbour? Nearer, or as near and lexicographically smaller.
  bool better(int p, int a, int b) const {
    const int c = compare_distance2(at(p), at(a), at(b));
    return c < 0 || (c == 0 && lex_less(at(a), at(b)));
  }
  // The nearest neighbour of p (away == -1), or the nearest with angle(away, p, r) > 90°.
  int nearest(int p, int away) const {
    int best = -1;
    const std::size_t p_ = static_cast<std::size_t>(p);
    for (std::size_t k = adj_.start[p_]; k < adj_.start[p_ + 1]; ++k) {
      const int r = adj_.nbr[k];
      if (away >= 0 && diametral_side2(at(away), at(r), at(p)) >= 0) continue;
      if (best < 0 || better(p, r, best)) best = r;
    }
    return best;
  }
  const PointSet& pts_;
  const Adjacency& adj_;
};

// The cycles of a 2-regular graph, each as a vertex sequence; ring_of / next_of / prev_of per vertex.
struct Cycles {
  std::vector<std::vector<int>> rings;
  std::vector<int> ring_of, next_of, prev_of;
};

// Traces the cycles when every vertex has degree 2; returns false (and counts) otherwise.
bool trace_cycles(std::size_t n, const std::vector<std::array<int, 2>>& edges, Cycles& c, RingsInference& out) {
  std::vector<std::array<int, 2>> nb(n, {{-1, -1}});
  std::vector<int> deg(n, 0);
  for (const auto& e : edges)
    for (int s = 0; s < 2; ++s) {
      const auto v = static_cast<std::size_t>(e[static_cast<std::size_t>(s)]);
      if (deg[v] < 2) nb[v][static_cast<std::size_t>(deg[v])] = e[static_cast<std::size_t>(1 - s)];
      ++deg[v];
    }
  for (std::size_t v = 0; v < n; ++v)
    if (deg[v] != 2) {
      if (out.first_bad_point < 0) out.first_bad_point = static_cast<int>(v);
      ++out.bad_degree_points;
    }
  if (out.bad_degree_points) return false;
  c.ring_of.assign(n, -1);
  c.next_of.assign(n, -1);
  c.prev_of.assign(n, -1);
  for (std::size_t s = 0; s < n; ++s) {
    if (c.ring_of[s] >= 0) continue;
    const int id = static_cast<int>(c.rings.size());
    std::vector<int> ring;
    int prev = -1, v = static_cast<int>(s);
    while (c.ring_of[static_cast<std::size_t>(v)] < 0) {
      c.ring_of[static_cast<std::size_t>(v)] = id;
      ring.push_back(v);
      const auto& w = nb[static_cast<std::size_t>(v)];
      const int next = w[0] != prev ? w[0] : w[1];
      prev = v;
      v = next;
    }
    c.rings.push_back(std::move(ring));
  }
  return true;
}

// Orders the cycles by their lexicographically smallest point (a containing ring's smallest point
// precedes every point inside it, so parents come first) and fills next_of / prev_of in the
// traced direction.
void order_cycles(const PointSet& pts, Cycles& c) {
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  std::vector<int> lowest(c.rings.size());
  for (std::size_t k = 0; k < c.rings.size(); ++k)
    lowest[k] = *std::min_element(c.rings[k].begin(), c.rings[k].end(), [&](int a, int b) { return lex_less(at(a), at(b)); });
  std::vector<std::size_t> order(c.rings.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lex_less(at(lowest[a]), at(lowest[b])); });
  std::vector<std::vector<int>> sorted;
  sorted.reserve(order.size());
  for (std::size_t k : order) sorted.push_back(std::move(c.rings[k]));
  c.rings = std::move(sorted);
  for (std::size_t k = 0; k < c.rings.size(); ++k) {
    const auto& r = c.rings[k];
    for (std::size_t i = 0; i < r.size(); ++i) {
      const auto v = static_cast<std::size_t>(r[i]);
      c.ring_of[v] = static_cast<int>(k);
      c.next_of[v] = r[(i + 1) % r.size()];
      c.prev_of[v] = r[(i + r.size() - 1) % r.size()];
    }
  }
}

// +1 if the ring (traced order) runs counter-clockwise: the turn at its lexicographically smallest
// vertex (a convex vertex) is the orientation. Exact.
int ring_orientation(const PointSet& pts, const std::vector<int>& r) {
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  std::size_t m = 0;
  for (std::size_t i = 1; i < r.size(); ++i)
    if (lex_less(at(r[i]), at(r[m]))) m = i;
  return orient2(at(r[(m + r.size() - 1) % r.size()]), at(r[m]), at(r[(m + 1) % r.size()]));
}

// Nesting from the triangulation: the faces of the arrangement of the disjoint cycles are the
// connected sets of triangles not separated by a cycle edge (region 0 is the unbounded face, with
// the triangles behind a hull edge that is not a cycle edge). A cycle bounds exactly two faces; the
// one on its interior side is bounded by no other cycle from outside, so parent(K) is the cycle whose
// interior face is K's exterior face. O(N).
std::vector<int> parents_from_faces(const Delaunay2& dt, const Cycles& c, const std::vector<int>& ccw) {
  const std::size_t nt = dt.triangles.size();
  const auto cycle_edge = [&](int a, int b) {
    return c.next_of[static_cast<std::size_t>(a)] == b || c.next_of[static_cast<std::size_t>(b)] == a;
  };
  std::vector<int> region(nt, -1);
  std::vector<std::size_t> stack;
  int regions = 1;
  // Seeds: region 0 first (behind open hull edges), then every unlabelled triangle.
  const auto flood = [&](std::size_t seed, int id) {
    region[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      for (std::size_t i = 0; i < 3; ++i) {
        const int u = dt.neighbors[t][i];
        if (u < 0 || region[static_cast<std::size_t>(u)] >= 0) continue;
        if (cycle_edge(dt.triangles[t][(i + 1) % 3], dt.triangles[t][(i + 2) % 3])) continue;
        region[static_cast<std::size_t>(u)] = id;
        stack.push_back(static_cast<std::size_t>(u));
      }
    }
  };
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t i = 0; i < 3; ++i)
      if (region[t] < 0 && dt.neighbors[t][i] < 0 && !cycle_edge(dt.triangles[t][(i + 1) % 3], dt.triangles[t][(i + 2) % 3]))
        flood(t, 0);
  for (std::size_t t = 0; t < nt; ++t)
    if (region[t] < 0) flood(t, regions++);
  // The faces left and right of each cycle in its traced direction (unbounded face by default: a
  // cycle edge on the hull has no triangle on its outer side).
  const std::size_t nr = c.rings.size();
  std::vector<int> left(nr, 0), right(nr, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t i = 0; i < 3; ++i) {
      const int a = dt.triangles[t][i], b = dt.triangles[t][(i + 1) % 3];  // t is left of a->b
      const auto ra = static_cast<std::size_t>(c.ring_of[static_cast<std::size_t>(a)]);
      if (c.next_of[static_cast<std::size_t>(a)] == b) left[ra] = region[t];
      if (c.next_of[static_cast<std::size_t>(b)] == a) right[ra] = region[t];
    }
  std::vector<int> owner(static_cast<std::size_t>(regions), -1);  // the cycle a face is interior to
  for (std::size_t k = 0; k < nr; ++k) owner[static_cast<std::size_t>(ccw[k] > 0 ? left[k] : right[k])] = static_cast<int>(k);
  std::vector<int> parent(nr, -1);
  for (std::size_t k = 0; k < nr; ++k) {
    const int outside = ccw[k] > 0 ? right[k] : left[k];
    parent[k] = outside == 0 ? -1 : owner[static_cast<std::size_t>(outside)];
  }
  return parent;
}

// Roles by depth parity, orientation fixed (shells CCW, holes CW), each ring from its smallest index.
void assign_roles(const Cycles& c, const std::vector<int>& ccw, const std::vector<int>& parent, RingsInference& out) {
  out.rings.assign(c.rings.size(), Ring2{});
  std::vector<int> depth(c.rings.size(), 0);
  for (std::size_t k = 0; k < c.rings.size(); ++k) {  // parents precede children (order_cycles)
    Ring2& r = out.rings[k];
    r.parent = parent[k];
    depth[k] = r.parent < 0 ? 0 : depth[static_cast<std::size_t>(r.parent)] + 1;
    r.role = depth[k] % 2 == 0 ? RingRole::Shell : RingRole::Hole;
    r.indices = c.rings[k];
    if ((ccw[k] > 0) != (r.role == RingRole::Shell)) std::reverse(r.indices.begin(), r.indices.end());
    std::rotate(r.indices.begin(), std::min_element(r.indices.begin(), r.indices.end()), r.indices.end());
  }
}

// The gap test on every Delaunay edge pq between two cycles: |pq| >= gap · rms(the cycle edges at p
// and q), exactly. Fills each ring's smallest gap (double, for the report). @return all clear
bool gaps_clear(const PointSet& pts, const Adjacency& adj, const Cycles& c, double gap, RingsInference& out) {
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  const auto len2 = [&](int a, int b) {
    const double dx = at(a)[0] - at(b)[0], dy = at(a)[1] - at(b)[1];
    return dx * dx + dy * dy;
  };
  bool clear = true;
  for (std::size_t p = 0; p + 1 < adj.start.size(); ++p)
    for (std::size_t k = adj.start[p]; k < adj.start[p + 1]; ++k) {
      const int ip = static_cast<int>(p), q = adj.nbr[k];
      const int rp = c.ring_of[p], rq = c.ring_of[static_cast<std::size_t>(q)];
      if (q < ip || rp == rq) continue;
      const std::size_t qs = static_cast<std::size_t>(q);
      const int ends[4] = {c.prev_of[p], c.next_of[p], c.prev_of[qs], c.next_of[qs]};
      const double* a[4] = {at(ip), at(ip), at(q), at(q)};
      const double* b[4] = {at(ends[0]), at(ends[1]), at(ends[2]), at(ends[3])};
      if (compare_gap2(at(ip), at(q), a, b, 4, gap) < 0) clear = false;
      const double rms = std::sqrt((len2(ip, ends[0]) + len2(ip, ends[1]) + len2(q, ends[2]) + len2(q, ends[3])) / 4);
      const double g = std::sqrt(len2(ip, q)) / rms;
      for (const auto& [r, other] : {std::pair<int, int>{rp, rq}, std::pair<int, int>{rq, rp}}) {
        Ring2& ring = out.rings[static_cast<std::size_t>(r)];
        if (g < ring.gap_spacings) {
          ring.gap_spacings = g;
          ring.nearest_ring = other;
        }
      }
      out.min_gap_spacings = std::min(out.min_gap_spacings, g);
    }
  return clear;
}

}  // namespace

const char* to_string(RingsDecision d) noexcept {
  switch (d) {
    case RingsDecision::NotDegree2: return "not-degree-2";
    case RingsDecision::OneCycle: return "one-cycle";
    case RingsDecision::GapTooSmall: return "gap-too-small";
    case RingsDecision::Rings: return "rings";
  }
  return "?";
}

std::size_t RingsInference::shells() const noexcept {
  return static_cast<std::size_t>(std::count_if(rings.begin(), rings.end(), [](const Ring2& r) { return r.role == RingRole::Shell; }));
}
std::size_t RingsInference::holes() const noexcept { return rings.size() - shells(); }

Status infer_rings2(const PointSet& points, const Delaunay2& dt, double gap, RingsInference& out) {
  out = RingsInference{};
  out.gap_threshold = gap;
  if (!(gap >= 0) || !std::isfinite(gap))
    return {StatusCode::InvalidArgument, "topology gap must be a finite number >= 0, not " + std::to_string(gap)};
  if (points.dim != 2 || dt.n_vertices != points.size() || dt.triangles.size() != dt.neighbors.size())
    return {StatusCode::InvalidArgument, "infer_rings2: the triangulation is not one of these 2D points"};
  const Adjacency adj(dt);
  const NnCrust crust(points, adj);
  Cycles c;
  if (!trace_cycles(points.size(), crust.edges(), c, out)) return Status::ok();  // NotDegree2
  order_cycles(points, c);
  std::vector<int> ccw(c.rings.size());
  for (std::size_t k = 0; k < c.rings.size(); ++k) ccw[k] = ring_orientation(points, c.rings[k]);
  assign_roles(c, ccw, parents_from_faces(dt, c, ccw), out);
  if (c.rings.size() == 1) {
    out.decision = RingsDecision::OneCycle;
    return Status::ok();
  }
  out.decision = gaps_clear(points, adj, c, gap, out) ? RingsDecision::Rings : RingsDecision::GapTooSmall;
  return Status::ok();
}

}  // namespace constrict
