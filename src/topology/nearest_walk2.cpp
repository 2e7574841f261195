// SPDX-License-Identifier: GPL-3.0-or-later
// The nearest-neighbour walk of infer_rings2() (docs/topology.md, Method 6): rings traced point by
// point, a second opinion on holes nearer than the gap rule's threshold. Exact comparisons
// (compare_distance2, compare_gap2 behind a double filter), ties by the points' lexicographic
// order; the order in which paths start is by the squared length in double (a deterministic
// function of the points).
#include "topology/detail/nearest_walk2.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "constrict/predicates.hpp"
#include "core/detail/semi_static.hpp"
#include "topology/detail/ring_nesting.hpp"

namespace constrict::detail {
namespace {

using Adjacency = RingsAdjacency;

// The walk closes a path only after this many steps (a path of kWalkMinSteps + 2 points): before
// that its two ends are near each other because they are its first points.
constexpr std::size_t kWalkMinSteps = 4;
// The walk reads each neighbour list about twice (each end looks again when it moves); it gives up
// past this many times the adjacency's size.
constexpr std::size_t kWalkWorkPerEdge = 8;
// Up to this many Delaunay neighbours a point's nearest free one is found by a scan; above, from
// a heap of its neighbours (NearestWalk::nearest_free_sorted).
constexpr std::size_t kWalkScanDegree = 16;
// Squared lengths computed in double are compared by the project's semi-static filter
// (gap_filtered: one segment against one, factor 1); what it cannot decide, exactly.
inline bool surely_longer(double x, double y) {
  bool ok = false;
  return gap_filtered(x, y, 1.0, 1, 2, ok) > 0 && ok;
}

// Rings traced point by point, an idea of Parakkat and Muthuganapathy ("Crawl through neighbors",
// SGP 2016): a path starts at the shortest Delaunay edge between nearest neighbours whose ends are
// both free; each step takes, at the end whose nearest free Delaunay neighbour is nearer, that
// neighbour; the path closes when, after kWalkMinSteps steps, one end is among the other's two
// nearest Delaunay neighbours. A curve whose own spacing is smaller than its distance to the next
// curve is traced whole, however near that curve is in units of the gap rule's spacing (an outline
// with an inner loop 1.1 spacings away). The answer is all or nothing: every point on a closed
// path. "Nearer" is exact (compare_distance2, compare_gap2); ties go by the points' lexicographic
// order, so the rings do not depend on the file order.
class NearestWalk {
 public:
  NearestWalk(const PointSet& pts, const Adjacency& adj) : pts_(pts), adj_(adj), near_(pts.size()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t p = range.begin(); p != range.end(); ++p) {
        // The two smallest squared distances in double first; better() only among the
        // neighbours within their rounding of the second.
        const int ip = static_cast<int>(p);
        double d0 = std::numeric_limits<double>::infinity(), d1 = d0;
        for (std::size_t k = adj_.start[p]; k < adj_.start[p + 1]; ++k) {
          const double d = len2(ip, adj_.nbr[k]);
          if (d < d0) d1 = d0, d0 = d;
          else if (d < d1) d1 = d;
        }
        std::array<int, 2>& n = near_[p];
        n = {-1, -1};
        for (std::size_t k = adj_.start[p]; k < adj_.start[p + 1]; ++k) {
          const int q = adj_.nbr[k];
          if (surely_longer(len2(ip, q), d1)) continue;  // (two are nearer)
          if (n[0] < 0 || better(ip, q, n[0])) {
            n[1] = n[0];
            n[0] = q;
          } else if (n[1] < 0 || better(ip, q, n[1])) {
            n[1] = q;
          }
        }
      }
    });
  }

  // The rings, or false when a path cannot go on, a point is left over, or the neighbour lists
  // read exceed kWalkWorkPerEdge times their total (an end with very many neighbours whose nearest
  // free one the other end keeps taking: a circle of points around its centre).
  bool trace(std::vector<std::vector<int>>& rings) const {
    const std::size_t n = pts_.size();
    work_ = 0;
    work_limit_ = kWalkWorkPerEdge * adj_.nbr.size() + 1024;
    heaps_.clear();
    std::vector<Seed> seeds;  // each edge to a nearest neighbour, lexicographically smaller end first
    seeds.reserve(n);
    for (std::size_t p = 0; p < n; ++p) {
      const int q = near_[p][0];
      if (q < 0) return false;
      Seed e{0, {static_cast<int>(p), q}};
      if (lex_less2(at(e.v[1]), at(e.v[0]))) std::swap(e.v[0], e.v[1]);
      // (q's own nearest neighbour is p: the same edge, taken once, from its smaller end.)
      if (near_[static_cast<std::size_t>(q)][0] == static_cast<int>(p) && e.v[0] != static_cast<int>(p)) continue;
      e.len2 = len2(e.v[0], e.v[1]);
      seeds.push_back(e);
    }
    tbb::parallel_sort(seeds.begin(), seeds.end(), [&](const Seed& x, const Seed& y) { return seed_less(x, y); });
    std::vector<char> used(n, 0);
    std::size_t placed = 0;
    std::vector<int> front, back;  // the path: front reversed, then back
    rings.clear();
    for (const Seed& s : seeds) {
      const auto& seed = s.v;
      if (used[static_cast<std::size_t>(seed[0])] || used[static_cast<std::size_t>(seed[1])]) continue;
      front.assign(1, seed[0]);
      back.assign(1, seed[1]);
      used[static_cast<std::size_t>(seed[0])] = used[static_cast<std::size_t>(seed[1])] = 1;
      int ca = nearest_free(seed[0], used), cb = nearest_free(seed[1], used);  // each end's next point
      for (std::size_t steps = 0;; ++steps) {
        const int a = front.back(), b = back.back();
        if (steps >= kWalkMinSteps && (near_of(a, b) || near_of(b, a))) break;
        if ((ca < 0 && cb < 0) || work_ > work_limit_) return false;  // an open path, or out of work
        const bool at_front = cb < 0 || (ca >= 0 && step_less(a, ca, b, cb));
        const int c = at_front ? ca : cb;
        (at_front ? front : back).push_back(c);
        used[static_cast<std::size_t>(c)] = 1;
        // The end that moved looks again; the other only if its next point was this one.
        if (at_front) ca = nearest_free(c, used);
        else cb = nearest_free(c, used);
        if (ca == c) ca = nearest_free(a, used);
        if (cb == c) cb = nearest_free(b, used);
      }
      std::vector<int> ring(front.rbegin(), front.rend());
      ring.insert(ring.end(), back.begin(), back.end());
      placed += ring.size();
      rings.push_back(std::move(ring));
    }
    return placed == n;
  }

 private:
  const double* at(int i) const { return pts_[static_cast<std::size_t>(i)]; }
  // Is a strictly preferred to b as p's neighbour? Nearer, or as near and lexicographically smaller.
  bool better(int p, int a, int b) const {
    const int c = compare_distance2(at(p), at(a), at(b));
    return c < 0 || (c == 0 && lex_less2(at(a), at(b)));
  }
  bool near_of(int p, int q) const { return near_[static_cast<std::size_t>(p)][0] == q || near_[static_cast<std::size_t>(p)][1] == q; }
  // p's nearest Delaunay neighbour not yet used, or -1. The squared distances in double decide
  // where they differ by more than their rounding; the candidates within it, better().
  int nearest_free(int p, const std::vector<char>& used) const {
    const std::size_t b = adj_.start[static_cast<std::size_t>(p)], e = adj_.start[static_cast<std::size_t>(p) + 1];
    if (e - b > kWalkScanDegree) return nearest_free_sorted(p, b, e, used);
    work_ += e - b;
    double low = std::numeric_limits<double>::infinity();
    for (std::size_t k = b; k < e; ++k) {
      const int q = adj_.nbr[k];
      if (!used[static_cast<std::size_t>(q)]) low = std::min(low, len2(p, q));
    }
    if (low == std::numeric_limits<double>::infinity()) return -1;
    int best = -1;
    for (std::size_t k = b; k < e; ++k) {
      const int q = adj_.nbr[k];
      if (used[static_cast<std::size_t>(q)] || surely_longer(len2(p, q), low)) continue;
      if (best < 0 || better(p, q, best)) best = q;
    }
    return best;
  }
  // The same for a point of many neighbours (a centre of cocircular points has them all): its
  // neighbours in a heap by better(), made once (O(d) comparisons), then the used ones popped (an
  // end whose next point the other end keeps taking would otherwise read its whole list each time).
  int nearest_free_sorted(int p, std::size_t b, std::size_t e, const std::vector<char>& used) const {
    const auto after = [&](int x, int y) { return better(p, y, x); };  // a min-heap by better()
    auto it = heaps_.find(p);
    if (it == heaps_.end()) {
      std::vector<int> h(adj_.nbr.begin() + static_cast<std::ptrdiff_t>(b), adj_.nbr.begin() + static_cast<std::ptrdiff_t>(e));
      std::make_heap(h.begin(), h.end(), after);
      work_ += h.size();
      it = heaps_.emplace(p, std::move(h)).first;
    }
    std::vector<int>& h = it->second;
    while (!h.empty() && used[static_cast<std::size_t>(h.front())]) {
      std::pop_heap(h.begin(), h.end(), after);
      h.pop_back();
      ++work_;
    }
    return h.empty() ? -1 : h.front();
  }
  double len2(int p, int q) const {
    const double dx = at(p)[0] - at(q)[0], dy = at(p)[1] - at(q)[1];
    return dx * dx + dy * dy;
  }
  // sign(|pq| - |rs|), exactly: the filter on the squared lengths in double, else compare_gap2.
  int compare_lengths(int p, int q, int r, int s) const {
    bool ok = false;
    const int c = gap_filtered(len2(p, q), len2(r, s), 1.0, 1, 2, ok);
    if (ok) return c;
    const double* a[1] = {at(r)};
    const double* b[1] = {at(s)};
    return compare_gap2(at(p), at(q), a, b, 1, 1.0);
  }
  // The step a -> ca before b -> cb: shorter; as long: the lexicographically smaller new point.
  bool step_less(int a, int ca, int b, int cb) const {
    const int c = compare_lengths(a, ca, b, cb);
    return c < 0 || (c == 0 && lex_less2(at(ca), at(cb)));
  }
  // Seeds by their squared length in double, then by their ends' lexicographic order. (Only the
  // order in which paths start: a deterministic function of the two points' coordinates, the same
  // in any file order, under a rotation by 90° and a power-of-two scale. Exact comparisons here
  // cost O(N log N) multiprecision ones on regular samples, whose edges are all as long up to
  // rounding: a 10^6-point circle with its centre took 2 s more.)
  struct Seed {
    double len2;
    std::array<int, 2> v;
  };
  bool seed_less(const Seed& x, const Seed& y) const {
    if (x.len2 != y.len2) return x.len2 < y.len2;
    if (x.v[0] != y.v[0]) return lex_less2(at(x.v[0]), at(y.v[0]));
    return x.v[1] != y.v[1] && lex_less2(at(x.v[1]), at(y.v[1]));
  }

  const PointSet& pts_;
  const Adjacency& adj_;
  std::vector<std::array<int, 2>> near_;  // each point's two nearest Delaunay neighbours
  mutable std::size_t work_ = 0, work_limit_ = 0;  // neighbour entries read by trace()
  mutable std::unordered_map<int, std::vector<int>> heaps_;  // (nearest_free_sorted)
};

}  // namespace

bool nearest_walk_rings2(const PointSet& points, const RingsAdjacency& adjacency, std::vector<std::vector<int>>& rings) {
  return NearestWalk(points, adjacency).trace(rings);
}

bool walk_adds_holes(const std::vector<Ring2>& walk, const std::vector<int>& ring_of, std::size_t ours) {
  if (walk.size() <= ours) return false;
  std::vector<int> group(walk.size());
  for (std::size_t w = 0; w < walk.size(); ++w) {
    group[w] = ring_of[static_cast<std::size_t>(walk[w].indices.front())];
    for (int v : walk[w].indices)
      if (ring_of[static_cast<std::size_t>(v)] != group[w]) return false;
  }
  std::vector<int> outer(ours, 0);
  for (std::size_t w = 0; w < walk.size(); ++w) {
    const int p = walk[w].parent;
    if (p < 0 || group[static_cast<std::size_t>(p)] != group[w]) ++outer[static_cast<std::size_t>(group[w])];
  }
  return std::all_of(outer.begin(), outer.end(), [](int c) { return c == 1; });
}


}  // namespace constrict::detail
