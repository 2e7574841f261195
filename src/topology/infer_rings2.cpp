// SPDX-License-Identifier: GPL-3.0-or-later
// infer_rings2(): the rings the points show (topology.hpp, docs/topology.md §"Method").
// Exactness contract: every decision -- nearest neighbour, half neighbour, mutual edges, the gap
// test, cycles, nesting and orientation -- uses exact predicates (compare_distance2,
// diametral_side2, compare_gap2, orient2) or combinatorics; doubles are computed only for the report
// (gap_spacings, split_gap_spacings), and for the order in which the nearest-neighbour walk starts
// its paths (NearestWalk::seed_less: the edges' squared lengths in double, a deterministic function
// of the points). Ties are broken by the lexicographic order of the points, never by their
// indices, so the parts do not depend on the file order.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "core/detail/semi_static.hpp"
#include "core/detail/union_find.hpp"
#include "topology/detail/infer_rings2.hpp"
#include "topology/detail/nearest_walk2.hpp"
#include "topology/detail/ring_nesting.hpp"

namespace constrict {
namespace {

bool lex_less(const double* p, const double* q) { return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]); }

}  // namespace

// The Delaunay neighbours of every vertex (CSR). Each edge is taken once, from the triangle with
// the smaller id (or the hull triangle): O(N), no sorting. The order within a list does not matter:
// every choice made from a list is by exact comparisons with lexicographic ties.
detail::RingsAdjacency::RingsAdjacency(Delaunay2&& d)
    : start(d.n_vertices + 2, 0), triangles(std::move(d.triangles)), neighbors(std::move(d.neighbors)) {
  const auto for_edges = [&](const auto& f) {
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (std::size_t i = 0; i < 3; ++i) {
        const int u = neighbors[t][i];
        if (u >= 0 && static_cast<std::size_t>(u) < t) continue;
        f(triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]);
      }
  };
  for_edges([&](int a, int b) {
    ++start[static_cast<std::size_t>(a) + 2];
    ++start[static_cast<std::size_t>(b) + 2];
  });
  for (std::size_t v = 2; v < start.size(); ++v) start[v] += start[v - 1];
  nbr.resize(start.back());
  for_edges([&](int a, int b) {
    nbr[start[static_cast<std::size_t>(a) + 1]++] = b;
    nbr[start[static_cast<std::size_t>(b) + 1]++] = a;
  });
  start.pop_back();
}

namespace {
using Adjacency = detail::RingsAdjacency;

// The NN-crust (Dey–Kumar 1999, §3): p chooses its nearest Delaunay neighbour q, and its nearest
// Delaunay neighbour r in the open half-plane away from q (angle qpr > 90°: p strictly inside the
// circle with diameter qr). "Nearer" is exact; equally near candidates go lexicographically.
class NnCrust {
 public:
  NnCrust(const PointSet& pts, const Adjacency& adj) : pts_(pts), adj_(adj), chosen_(adj.start.size() - 1) {
    // Each point's choices on both cores (each its own, the same whatever the threads).
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chosen_.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t p = range.begin(); p != range.end(); ++p) {
        const int q = nearest(static_cast<int>(p), -1);
        chosen_[p] = {q, q < 0 ? -1 : nearest(static_cast<int>(p), q)};
      }
    });
    // The crust edges at each point: its choices and the points that chose it, without repeats
    // (CSR by counting; each list holds a few entries, deduplicated in place).
    start_.assign(chosen_.size() + 2, 0);
    const auto for_choices = [&](const auto& f) {
      for (std::size_t p = 0; p < chosen_.size(); ++p)
        for (int q : chosen_[p])
          if (q >= 0) f(static_cast<int>(p), q);
    };
    for_choices([&](int p, int q) {
      ++start_[static_cast<std::size_t>(p) + 2];
      ++start_[static_cast<std::size_t>(q) + 2];
    });
    for (std::size_t v = 2; v < start_.size(); ++v) start_[v] += start_[v - 1];
    std::vector<int> all(start_.back());
    for_choices([&](int p, int q) {
      all[start_[static_cast<std::size_t>(p) + 1]++] = q;
      all[start_[static_cast<std::size_t>(q) + 1]++] = p;
    });
    start_.pop_back();
    nbr_.reserve(all.size());
    std::vector<std::size_t> compact(start_.size(), 0);
    for (std::size_t v = 0; v + 1 < start_.size(); ++v) {
      const auto b = all.begin() + static_cast<std::ptrdiff_t>(start_[v]), e = all.begin() + static_cast<std::ptrdiff_t>(start_[v + 1]);
      std::sort(b, e);
      nbr_.insert(nbr_.end(), b, std::unique(b, e));
      compact[v + 1] = nbr_.size();
    }
    start_ = std::move(compact);
  }
  // Chosen by both ends.
  bool mutual(int p, int q) const { return chose(p, q) && chose(q, p); }
  // For a crust edge chosen by one end only, and as its half-neighbour (not its nearest
  // neighbour): the other end, else -1.
  int unwilling_end(int p, int q) const {
    const int chooser = chose(p, q) ? p : q, other = chooser == p ? q : p;
    const auto& c = chosen_[static_cast<std::size_t>(chooser)];
    return chose(other, chooser) || c[0] == other ? -1 : other;
  }
  const std::array<int, 2>& choices(int p) const { return chosen_[static_cast<std::size_t>(p)]; }
  std::size_t degree(int p) const { return start_[static_cast<std::size_t>(p) + 1] - start_[static_cast<std::size_t>(p)]; }
  const int* begin(int p) const { return nbr_.data() + start_[static_cast<std::size_t>(p)]; }
  const int* end(int p) const { return nbr_.data() + start_[static_cast<std::size_t>(p) + 1]; }
  // The crust edges at all points as slots 0 .. slots() - 1 (r in [begin(p), end(p)) is slot(r)).
  std::size_t slots() const { return nbr_.size(); }
  std::size_t slot(const int* r) const { return static_cast<std::size_t>(r - nbr_.data()); }

 private:
  const double* at(int i) const { return pts_[static_cast<std::size_t>(i)]; }
  bool chose(int p, int q) const {
    const auto& c = chosen_[static_cast<std::size_t>(p)];
    return c[0] == q || c[1] == q;
  }
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
  std::vector<std::array<int, 2>> chosen_;
  std::vector<std::size_t> start_;
  std::vector<int> nbr_;
};

using detail::UnionFind;

// The gap of a Delaunay edge pq against the local spacing (the crust edges at p and q).
class Gaps {
 public:
  // The crust edges across a gap are marked once (both ends' slots; on both cores).
  Gaps(const PointSet& pts, const Adjacency& adj, const NnCrust& crust, double t)
      : pts_(pts), crust_(crust), t_(t), across_(crust.slots(), 0), corner_(pts.size(), 0) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t p = range.begin(); p != range.end(); ++p) corner_[p] = corner_jump(adj, static_cast<int>(p)) ? 1 : 0;
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t p = range.begin(); p != range.end(); ++p)
        for (const int* r = crust.begin(static_cast<int>(p)); r != crust.end(static_cast<int>(p)); ++r)
          across_[crust.slot(r)] = across_gap(static_cast<int>(p), *r) ? 1 : 0;
    });
  }
  // Does the crust edge pq join p and q into one piece? A mutual crust edge does, unless it leaves
  // a corner at both ends (corner_jump: two small polygons took each other's vertices).
  bool joins(int p, int q) const { return crust_.mutual(p, q) && !(corner_at(p, q) && corner_at(q, p)); }
  // A crust edge that is itself a gap: one that leaves its chooser's ring at a corner
  // (corner_jump), or one chosen by one end only, as its half-neighbour, and longer than 2t times
  // the spacing of the other end's own choices (the root mean square of their lengths). A point
  // moved off its curve by noise finds no half-neighbour on its own curve and takes one across the
  // gap to the next curve; that edge would make the spacing at the gap as wide as the gap. (A
  // nearest-neighbour edge is never one: an outlier keeps its spacing.)
  bool across_gap(int p, int r) const { return corner_at(p, r) || corner_at(r, p) || one_sided_gap(p, r); }
  bool one_sided_gap(int p, int r) const {
    const int o = crust_.unwilling_end(p, r);
    if (o < 0) return false;
    const int from = o == p ? r : p;
    const double* a[2];
    const double* b[2];
    int k = 0;
    for (const int c : crust_.choices(o))
      if (c >= 0) {
        a[k] = at(o);
        b[k++] = at(c);
      }
    return k > 0 && compare_gap2(at(from), at(o), a, b, k, 2 * t_) > 0;
  }
  // The spacing edges at p and q: their crust edges but those across a gap and pq itself (an edge
  // is not measured against itself: a point at a sharp corner takes its half-neighbour across the
  // gap, and that edge made the spacing at the gap as wide as the gap), or all of them when that
  // leaves none.
  template <class F> void spacing_edges(int p, int q, F&& f) const {
    bool any = false;
    for (int pass = 0; pass < 2 && !any; ++pass)
      for (int end : {p, q})
        for (const int* r = crust_.begin(end); r != crust_.end(end); ++r)
          if (pass == 1 || (!across_[crust_.slot(r)] && *r != (end == p ? q : p))) {
            f(end, *r);
            any = true;
          }
  }
  // |pq| < t · rms(spacing edges at p and q)? Exact.
  bool shorter(int p, int q, double t) const { return first_shorter(p, q, &t, 1) == 0; }
  // The smallest k with |pq| < t[k] · rms(spacing edges), for t ascending (the spacing edges
  // gathered once); n when none. Exact.
  std::size_t first_shorter(int p, int q, const double* t, std::size_t n) const { return first_shorter(p, q, collect(p, q), t, n); }
  // |pq| / rms(spacing edges at p and q), double arithmetic (for the report), the squared lengths
  // summed in ascending order: the same double for the same points in any file order.
  double ratio(int p, int q) const { return ratio(p, q, collect(p, q)); }
  // ratio() and shorter(p, q, t) from one gathering of the spacing edges.
  std::pair<double, bool> ratio_and_shorter(int p, int q, double t) const {
    const Edges& s = collect(p, q);
    return {ratio(p, q, s), first_shorter(p, q, s, &t, 1) == 0};
  }

 private:
  struct Edges {  // the spacing edges of one pair (per thread: the methods run on both cores)
    std::vector<const double*> a, b;
  };
  const double* at(int i) const { return pts_[static_cast<std::size_t>(i)]; }
  static double len2(const double* a, const double* b) {
    const double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy;
  }
  // The spacing edges of p and q, in a buffer of the calling thread (the methods run on both cores).
  const Edges& collect(int p, int q) const {
    thread_local Edges s;
    s.a.clear();
    s.b.clear();
    spacing_edges(p, q, [&](int end, int r) {
      s.a.push_back(at(end));
      s.b.push_back(at(r));
    });
    return s;
  }
  // compare_gap2's own filter (gap_filtered) on the lengths summed once for all the factors, in
  // the same order and doubles, and its exact arithmetic where the filter cannot decide.
  std::size_t first_shorter(int p, int q, const Edges& s, const double* t, std::size_t n) const {
    const int k = static_cast<int>(s.a.size());
    double sum = 0;
    for (std::size_t i = 0; i < s.a.size(); ++i) sum += len2(s.a[i], s.b[i]);
    const double lhs = static_cast<double>(k) * len2(at(p), at(q));
    const auto less = [&](double f) {  // sign(k·|pq|² - f²·Σ) < 0
      bool ok = false;
      const int sign = detail::gap_filtered(lhs, sum, f, k, 2, ok);
      return (ok ? sign : compare_gap2(at(p), at(q), s.a.data(), s.b.data(), k, f)) < 0;
    };
    std::size_t j = n;
    while (j > 0 && less(t[j - 1])) --j;
    return j;
  }
  double ratio(int p, int q, const Edges& s) const {
    thread_local std::vector<double> l;
    l.clear();
    for (std::size_t i = 0; i < s.a.size(); ++i) l.push_back(len2(s.a[i], s.b[i]));
    std::sort(l.begin(), l.end());
    double sum = 0;
    for (const double x : l) sum += x;
    return std::sqrt(len2(at(p), at(q)) / (sum / static_cast<double>(l.size())));
  }
  // p's half-neighbour leaves p's own ring at a corner: at a vertex of at most 90° the NN-crust's
  // half-neighbour (beyond 90° from the nearest neighbour a) cannot be the ring's other
  // neighbour. So when p has another Delaunay neighbour c, more than t times nearer than the
  // half-neighbour r (the gap rule's own ratio), that does not lie past a (the angle at a of the
  // triangle p a c is at most 90°), c is p's ring neighbour and r lies beyond a gap. (On a curve
  // sampled unevenly the second-nearest point lies past the nearest: no corner.) The guard asked
  // for the angle at p to be the largest of that triangle (c at least as far from a as from p),
  // which an equilateral triangle meets only by a rounding's luck: islands of 3 points 17 of
  // their sides apart came out as one ring. Exact (compare_gap2, diametral_side2).
  bool corner_jump(const Adjacency& adj, int p) const {
    const auto& ch = crust_.choices(p);
    const int a = ch[0], r = ch[1];
    if (a < 0 || r < 0) return false;
    const std::size_t p_ = static_cast<std::size_t>(p);
    for (std::size_t k = adj.start[p_]; k < adj.start[p_ + 1]; ++k) {
      const int c = adj.nbr[k];
      if (c == a || c == r) continue;
      const double* x[1] = {at(p)};
      const double* y[1] = {at(c)};
      if (compare_gap2(at(p), at(r), x, y, 1, t_) > 0 && diametral_side2(at(p), at(c), at(a)) >= 0) return true;
    }
    return false;
  }
  bool corner_at(int p, int r) const { return corner_[static_cast<std::size_t>(p)] && crust_.choices(p)[1] == r; }
  const PointSet& pts_;
  const NnCrust& crust_;
  double t_;  // the gap threshold (across_gap)
  std::vector<char> across_;  // per crust slot: across_gap()
  std::vector<char> corner_;  // per point: corner_jump()
};

// The parts: components of the mutual crust edges and of the Delaunay edges shorter than
// gap · local spacing. Also the split gap: the bottleneck of the single-linkage tree over the
// mutual-crust pieces (the largest threshold that still splits), in double, for the report.
// links: the Delaunay edges between pieces with their ratio (Gaps::ratio), ascending; every edge
// between two parts is one of them.
using Links = std::vector<std::pair<double, std::array<int, 2>>>;
std::vector<int> find_parts(const PointSet& pts, const Adjacency& adj, const Gaps& gaps, double gap,
                            Links& links, RingsInference& out) {
  const std::size_t n = pts.size();
  UnionFind pieces(n), parts(n);
  const auto for_edges = [&](const auto& f) {
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t k = adj.start[p]; k < adj.start[p + 1]; ++k)
        if (adj.nbr[k] > static_cast<int>(p)) f(static_cast<int>(p), adj.nbr[k]);
  };
  for_edges([&](int p, int q) {
    if (gaps.joins(p, q)) {
      pieces.join(p, q);
      parts.join(p, q);
    }
  });
  // Only edges between two pieces can split: the gap test runs on those alone (on both cores).
  std::vector<std::array<int, 2>> between;
  for_edges([&](int p, int q) {
    if (pieces.find(p) != pieces.find(q)) between.push_back({p, q});
  });
  links.assign(between.size(), {});
  std::vector<char> short_link(between.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, between.size(), 2048), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const auto [ratio, shorter] = gaps.ratio_and_shorter(between[i][0], between[i][1], gap);
      links[i] = {ratio, between[i]};
      short_link[i] = shorter ? 1 : 0;
    }
  });
  for (std::size_t i = 0; i < between.size(); ++i)
    if (short_link[i]) parts.join(between[i][0], between[i][1]);
  std::sort(links.begin(), links.end());
  for (const auto& [g, e] : links)
    if (pieces.join(e[0], e[1])) out.split_gap_spacings = g;
  std::vector<int> part_of(n);
  for (std::size_t v = 0; v < n; ++v) part_of[v] = parts.find(static_cast<int>(v));
  return part_of;
}

// Point lists (parts, or rings in their cyclic order) ordered by their lexicographically smallest
// point: an order of the points' coordinates, not of their indices.
void order_by_lowest_point(const PointSet& pts, std::vector<std::vector<int>>& lists) {
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  std::vector<int> low(lists.size());
  for (std::size_t k = 0; k < lists.size(); ++k)
    low[k] = *std::min_element(lists[k].begin(), lists[k].end(), [&](int a, int b) { return lex_less(at(a), at(b)); });
  std::vector<std::size_t> order(lists.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lex_less(at(low[a]), at(low[b])); });
  std::vector<std::vector<int>> sorted;
  for (std::size_t k : order) sorted.push_back(std::move(lists[k]));
  lists = std::move(sorted);
}

// The parts as point lists (ascending indices), ordered by their lexicographically smallest point.
std::vector<std::vector<int>> group_parts(const PointSet& pts, const std::vector<int>& part_of) {
  std::vector<std::vector<int>> by_root(part_of.size());
  for (std::size_t v = 0; v < part_of.size(); ++v) by_root[static_cast<std::size_t>(part_of[v])].push_back(static_cast<int>(v));
  std::vector<std::vector<int>> parts;
  for (auto& g : by_root)
    if (!g.empty()) parts.push_back(std::move(g));
  order_by_lowest_point(pts, parts);
  return parts;
}

// The regions the parts enclose (docs/topology.md, "Open arcs"). A wall is a Delaunay edge within
// a part that the part's own points would not split at: mutual crust, or shorter than gap · local
// spacing (find_parts' rule). The regions are the classes of triangles joined across every other
// edge; the one that reaches past the convex hull is unbounded. The interior of a ring is a bounded
// region that is fat against its walls (compare_region_fatness2 > 0 at kMinRingFatness, the
// measure of the polygon rule); between the two sides of a noisy band the regions are slivers. A
// part next to no bounded region that is fat or that other parts bound too encloses nothing: an
// open arc, known without its polygon. Exact decisions and combinatorics: the same in any order.
// The levels of walls: a ring's own sparse spot wider than the threshold leaks its interior (its
// polygon closes it), sealed at one of the wider levels; a wide level alone would fill a small
// ring's interior with walls (no fat region left), which the narrower levels keep.
constexpr double kSealFactors[] = {1.0, 2.0, 4.0};
constexpr std::uint8_t kLevels = 3;

// The ends of edge slot e = 3t + i (the edge of triangle t opposite its vertex i).
std::array<int, 2> edge_ends(const Adjacency& adj, std::size_t e) {
  const auto& t = adj.triangles[e / 3];
  return {t[(e % 3 + 1) % 3], t[(e % 3 + 2) % 3]};
}

// For each Delaunay edge (as 3t + i, from the triangle that takes it), the first level at which it
// is a wall if its ends are in one part: 0 mutual crust or shorter than the threshold (never
// between two parts), 1 and 2 shorter than 2 and 4 times it; kLevels: never. Exact (compare_gap2).
std::vector<std::uint8_t> wall_levels(const Adjacency& adj, const Gaps& gaps, double gap) {
  std::vector<std::uint8_t> level(3 * adj.triangles.size(), kLevels);
  double factors[kLevels];
  for (std::uint8_t k = 0; k < kLevels; ++k) factors[k] = kSealFactors[k] * gap;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.size(), 6144), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t e = range.begin(); e != range.end(); ++e) {
      const int u = adj.neighbors[e / 3][e % 3];
      if (u >= 0 && static_cast<std::size_t>(u) < e / 3) continue;
      const auto [a, b] = edge_ends(adj, e);
      level[e] = gaps.joins(a, b) ? 0 : static_cast<std::uint8_t>(gaps.first_shorter(a, b, factors, kLevels));
    }
  });
  return level;
}

class Enclosures {
 public:
  // The regions with the walls of `level` within the parts of part_of.
  Enclosures(const PointSet& pts, const Adjacency& adj, const std::vector<std::uint8_t>& wall_level, std::uint8_t level,
             const std::vector<int>& part_of) {
    const std::size_t n_tris = adj.triangles.size();
    const int outside = static_cast<int>(n_tris);
    const auto other = [&](std::uint32_t e) {  // the triangle across edge e = 3t + i, or outside
      const int u = adj.neighbors[e / 3][e % 3];
      return u >= 0 ? u : outside;
    };
    const auto ends = [&](std::uint32_t e) { return edge_ends(adj, e); };
    UnionFind regions(n_tris + 1);
    std::vector<std::uint32_t> walls_at;  // each wall once, as 3t + i
    for (std::uint32_t e = 0; e < 3 * n_tris; ++e) {
      const int u = adj.neighbors[e / 3][e % 3];
      if (u >= 0 && static_cast<std::uint32_t>(u) < e / 3) continue;
      const auto [a, b] = ends(e);
      const bool wall = wall_level[e] <= level && part_of[static_cast<std::size_t>(a)] == part_of[static_cast<std::size_t>(b)];
      if (wall)
        walls_at.push_back(e);
      else
        regions.join(static_cast<int>(e / 3), other(e));
    }
    // The bounded regions, numbered in the order of their first triangle; for each, the parts of
    // its walls (ends[0] stands for its part) and its fatness: the filter summed in place, and the
    // few regions it cannot decide gathered for the exact predicate.
    const int unbounded = regions.find(outside);
    std::vector<int> rid(n_tris, -1);  // region of each triangle, -1: the unbounded one
    unbounded_.assign(n_tris, 1);
    std::size_t count = 0;
    {
      std::vector<int> id(n_tris + 1, -1);
      for (std::size_t t = 0; t < n_tris; ++t) {
        const int r = regions.find(static_cast<int>(t));
        if (r == unbounded) continue;
        int& k = id[static_cast<std::size_t>(r)];
        if (k < 0) k = static_cast<int>(count++);
        rid[t] = k;
        unbounded_[t] = 0;
      }
    }
    // Per region its wall sides (a wall inside a region counts twice) and the parts at its walls.
    std::vector<std::uint32_t> sides(count, 0);
    std::vector<int> last_part(count, -1);
    const auto at = [&](int v) { return pts[static_cast<std::size_t>(v)]; };
    const auto region_of = [&](int t) { return t == outside ? -1 : rid[static_cast<std::size_t>(t)]; };
    for (const std::uint32_t e : walls_at)
      for (const int t : {static_cast<int>(e / 3), other(e)}) {
        const int k = region_of(t);
        if (k < 0) continue;
        ++sides[static_cast<std::size_t>(k)];
        const int a = ends(e)[0];
        int& last = last_part[static_cast<std::size_t>(k)];
        if (last != part_of[static_cast<std::size_t>(a)]) sides_.push_back({k, a});
        last = part_of[static_cast<std::size_t>(a)];
      }
    // A region with at most kThinWallSides wall sides is never fat (detail/infer_rings2.hpp), so only the
    // others are measured: the filter summed in place, the few it cannot decide then gathered for
    // the exact predicate.
    std::vector<int> slot(count, -1);  // region -> its filter
    std::size_t measured = 0;
    for (std::size_t k = 0; k < count; ++k)
      if (sides[k] > detail::kThinWallSides) slot[k] = static_cast<int>(measured++);
    std::vector<RegionFatness2Filter> filter(measured);
    const auto filter_of = [&](int t) -> RegionFatness2Filter* {
      const int k = region_of(t);
      return k < 0 || slot[static_cast<std::size_t>(k)] < 0 ? nullptr : &filter[static_cast<std::size_t>(slot[static_cast<std::size_t>(k)])];
    };
    for (std::size_t t = 0; t < n_tris; ++t)
      if (RegionFatness2Filter* f = filter_of(static_cast<int>(t)))
        f->add_triangle(at(adj.triangles[t][0]), at(adj.triangles[t][1]), at(adj.triangles[t][2]));
    for (const std::uint32_t e : walls_at)
      for (const int t : {static_cast<int>(e / 3), other(e)})
        if (RegionFatness2Filter* f = filter_of(t)) f->add_wall(at(ends(e)[0]), at(ends(e)[1]));
    fat_.assign(count, 0);
    std::vector<int> exact(count, -1);  // undecided region -> its slot among the gathered ones
    std::vector<std::vector<int>> tris, walls;
    for (std::size_t k = 0; k < count; ++k) {
      if (slot[k] < 0) continue;
      const int sign = filter[static_cast<std::size_t>(slot[k])].sign(kMinRingFatness);
      fat_[k] = sign > 0;
      if (sign == 0) {
        exact[k] = static_cast<int>(tris.size());
        tris.emplace_back();
        walls.emplace_back();
      }
    }
    if (!tris.empty()) {
      for (std::size_t t = 0; t < n_tris; ++t)
        if (const int k = rid[t]; k >= 0 && exact[static_cast<std::size_t>(k)] >= 0)
          tris[static_cast<std::size_t>(exact[static_cast<std::size_t>(k)])].insert(tris[static_cast<std::size_t>(exact[static_cast<std::size_t>(k)])].end(), adj.triangles[t].begin(), adj.triangles[t].end());
      for (const std::uint32_t e : walls_at)
        for (const int t : {static_cast<int>(e / 3), other(e)})
          if (const int k = region_of(t); k >= 0 && exact[static_cast<std::size_t>(k)] >= 0) {
            auto& w = walls[static_cast<std::size_t>(exact[static_cast<std::size_t>(k)])];
            w.push_back(ends(e)[0]);
            w.push_back(ends(e)[1]);
          }
      for (std::size_t k = 0; k < count; ++k)
        if (const int x = exact[k]; x >= 0) {
          const auto& r = tris[static_cast<std::size_t>(x)];
          const auto& w = walls[static_cast<std::size_t>(x)];
          fat_[k] = compare_region_fatness2(pts.coords.data(), r.data(), r.size() / 3, w.data(), w.size() / 2, kMinRingFatness) > 0;
        }
    }
  }
  // For the current parts (ring_of: vertex -> part): does part k enclose a region -- next to a
  // bounded region that is fat, or that other parts' walls bound too?
  std::vector<char> enclosing(const std::vector<int>& ring_of, std::size_t parts) const {
    std::vector<int> part(fat_.size(), -1);
    std::vector<char> shared(fat_.size(), 0);
    for (const auto& [r, a] : sides_) {
      const int k = ring_of[static_cast<std::size_t>(a)];
      int& p = part[static_cast<std::size_t>(r)];
      if (p >= 0 && p != k) shared[static_cast<std::size_t>(r)] = 1;
      p = k;
    }
    std::vector<char> out(parts, 0);
    for (const auto& [r, a] : sides_)
      if (shared[static_cast<std::size_t>(r)] || fat_[static_cast<std::size_t>(r)]) out[static_cast<std::size_t>(ring_of[static_cast<std::size_t>(a)])] = 1;
    return out;
  }

  // Per triangle: in the unbounded region?
  const std::vector<char>& unbounded() const { return unbounded_; }

 private:
  std::vector<char> unbounded_;
  std::vector<std::array<int, 2>> sides_;  // (bounded region, an end of a wall): each part at each region, about once
  std::vector<char> fat_;                  // per bounded region
};

// Walls of `level` (wall_levels) and their components: the points joined by them.
bool is_wall(const Adjacency& adj, const std::vector<std::uint8_t>& wall_level, std::uint8_t level, const std::vector<int>& part_of,
             int t, int i) {
  const auto& tri = adj.triangles[static_cast<std::size_t>(t)];
  const int a = tri[static_cast<std::size_t>((i + 1) % 3)], b = tri[static_cast<std::size_t>((i + 2) % 3)];
  if (part_of[static_cast<std::size_t>(a)] != part_of[static_cast<std::size_t>(b)]) return false;
  int u = adj.neighbors[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)];
  if (u >= 0 && u < t)  // the edge is listed at u
    for (int j = 0; j < 3; ++j)
      if (adj.neighbors[static_cast<std::size_t>(u)][static_cast<std::size_t>(j)] == t)
        return wall_level[3 * static_cast<std::size_t>(u) + static_cast<std::size_t>(j)] <= level;
  return wall_level[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(i)] <= level;
}

UnionFind wall_components(const PointSet& pts, const Adjacency& adj, const std::vector<std::uint8_t>& wall_level, std::uint8_t level,
                          const std::vector<int>& part_of) {
  UnionFind c(pts.size());
  for (std::size_t e = 0; e < wall_level.size(); ++e) {
    if (wall_level[e] > level) continue;
    const auto [a, b] = edge_ends(adj, e);
    if (part_of[static_cast<std::size_t>(a)] == part_of[static_cast<std::size_t>(b)]) c.join(a, b);
  }
  return c;
}

// After parts were joined: do the walls that the joins added at `level` change its regions in a
// way that matters? A new wall between two wall components hangs in a region (the region's
// triangles stay the same); one that closes a loop cuts a region in two. When the side cut off is
// a small region (kSmallFace triangles) that is thin and bounded by one part, the decisions
// stand; otherwise the level's regions are made again. (The noisy arcs of one curve, joined at
// their gaps, close only such small loops across each gap.) comps: the wall components, updated.
constexpr std::size_t kSmallFace = 4096;
// (Up to Rings2Options::open_arc_rebuild_max points the levels are simply made again after every
// round of joins, O(N) each; above it regions_changed() decides, which can miss a change that a
// new loop makes away from the walls it checks: measured, 4 of 144 generated random-angle sets
// differ when it decides for them too.)
bool regions_changed(const PointSet& pts, const Adjacency& adj, const std::vector<std::uint8_t>& wall_level, std::uint8_t level,
                     const std::vector<int>& part_of, const std::vector<int>& built_part_of, const std::vector<char>& unbounded,
                     const std::vector<std::uint32_t>& candidates, UnionFind& comps) {
  std::vector<int> face;
  std::vector<int> seen(adj.triangles.size(), -1);  // the flood that last took a triangle
  int flood = 0;
  const auto wall = [&](int t, int i) { return is_wall(adj, wall_level, level, part_of, t, i); };
  // The region of t0 if it is small and bounded (false: it reaches the hull or grows past the cap).
  const auto small_face = [&](int t0, std::size_t cap) {
    ++flood;
    face.assign(1, t0);
    seen[static_cast<std::size_t>(t0)] = flood;
    for (std::size_t q = 0; q < face.size(); ++q)
      for (int i = 0; i < 3; ++i) {
        if (wall(face[q], i)) continue;
        const int u = adj.neighbors[static_cast<std::size_t>(face[q])][static_cast<std::size_t>(i)];
        if (u < 0) return false;
        if (seen[static_cast<std::size_t>(u)] == flood) continue;
        seen[static_cast<std::size_t>(u)] = flood;
        face.push_back(u);
        if (face.size() > cap) return false;
      }
    return true;
  };
  const auto harmless = [&]() {  // the small face in `face`: thin, and of one part
    std::vector<int> tris, walls;
    int part = -1;
    for (const int t : face) {
      const auto& tri = adj.triangles[static_cast<std::size_t>(t)];
      tris.insert(tris.end(), tri.begin(), tri.end());
      for (int i = 0; i < 3; ++i)
        if (wall(t, i)) {
          const int a = tri[static_cast<std::size_t>((i + 1) % 3)], b = tri[static_cast<std::size_t>((i + 2) % 3)];
          walls.push_back(a);
          walls.push_back(b);
          if (part >= 0 && part != part_of[static_cast<std::size_t>(a)]) return false;
          part = part_of[static_cast<std::size_t>(a)];
        }
    }
    return compare_region_fatness2(pts.coords.data(), tris.data(), tris.size() / 3, walls.data(), walls.size() / 2, kMinRingFatness) <= 0;
  };
  // Each loop closed adds one bounded region (Euler); every new region borders a wall that closed
  // one. The joins are harmless when those regions are all small, thin and of one part, and the
  // other side of each such wall lay in the unbounded region (no bounded region changed).
  std::size_t loops = 0;
  std::vector<int> found;  // the small regions, by their first triangle
  for (const std::uint32_t e : candidates) {
    if (wall_level[e] > level) continue;
    const auto [a, b] = edge_ends(adj, e);
    const std::size_t ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
    if (part_of[ia] != part_of[ib] || built_part_of[ia] == built_part_of[ib]) continue;  // not new
    if (comps.join(a, b)) continue;
    ++loops;
    const int sides[2] = {static_cast<int>(e / 3), adj.neighbors[e / 3][e % 3]};
    // (Tiny regions first: most loops close across a gap between two of its edges.)
    std::vector<int> small[2];
    bool open_side[2] = {false, false};
    for (const std::size_t cap : {std::size_t{64}, kSmallFace}) {
      for (int k = 0; k < 2; ++k)
        if (sides[k] >= 0 && small[k].empty()) {
          if (small_face(sides[k], cap)) {
            if (!harmless()) return true;
            small[k] = face;
          }
        }
      if (!small[0].empty() || !small[1].empty()) break;
    }
    for (int k = 0; k < 2; ++k) open_side[k] = small[k].empty();
    if (!open_side[0] && !open_side[1]) {  // both sides small: a small region cut in two, not a new one
      --loops;
      continue;
    }
    for (int k = 0; k < 2; ++k) {
      if (!open_side[k]) {
        const int id = *std::min_element(small[k].begin(), small[k].end());
        if (std::find(found.begin(), found.end(), id) == found.end()) found.push_back(id);
      } else if (sides[k] >= 0 && !unbounded[static_cast<std::size_t>(sides[k])]) {
        return true;  // a bounded region changed
      }
    }
    if (found.size() > loops) return true;
  }
  return found.size() != loops;
}

// The part as one crust cycle, if it is one (every point of degree 2, the trace covers the part).
bool crust_cycle(const NnCrust& crust, const std::vector<int>& part, const std::vector<int>& part_of, std::vector<int>& ring) {
  const auto same = [&](int a, int b) { return part_of[static_cast<std::size_t>(a)] == part_of[static_cast<std::size_t>(b)]; };
  for (int v : part)
    if (crust.degree(v) != 2 || !same(v, crust.begin(v)[0]) || !same(v, crust.begin(v)[1])) return false;
  ring.clear();
  int prev = -1, v = part.front();
  do {
    ring.push_back(v);
    const int* w = crust.begin(v);
    const int next = w[0] != prev ? w[0] : w[1];
    prev = v;
    v = next;
  } while (v != part.front() && ring.size() <= part.size());
  return ring.size() == part.size();
}

// reconstruct2() on the points of a part; false when they hold no polygon (< 3, collinear).
bool part_polygon(const PointSet& pts, const std::vector<int>& part, const Constrict2Options& o, std::vector<int>& ring) {
  PointSet sub;
  sub.dim = 2;
  sub.coords.reserve(2 * part.size());
  for (int v : part) sub.coords.insert(sub.coords.end(), pts[static_cast<std::size_t>(v)], pts[static_cast<std::size_t>(v)] + 2);
  Polygon2Result r;
  if (part.size() < 3 || !reconstruct2(sub, o, r) || !r.valid()) return false;
  ring.clear();
  for (int i : r.boundary) ring.push_back(part[static_cast<std::size_t>(i)]);
  return true;
}

// +1 if the ring runs counter-clockwise: the turn at its lexicographically smallest vertex (a
// convex vertex of a simple ring). Exact.
int ring_orientation(const PointSet& pts, const std::vector<int>& r) {
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  std::size_t m = 0;
  for (std::size_t i = 1; i < r.size(); ++i)
    if (lex_less(at(r[i]), at(r[m]))) m = i;
  return orient2(at(r[(m + r.size() - 1) % r.size()]), at(r[m]), at(r[(m + 1) % r.size()]));
}

// Parents (innermost container), roles by depth parity, orientation fixed (shells CCW, holes CW),
// each ring from its smallest index.
void nest(const PointSet& pts, std::vector<std::vector<int>>& rings, RingsInference& out) {
  std::vector<const std::vector<int>*> view;
  for (const auto& r : rings) view.push_back(&r);
  const auto containers = detail::ring_containers(pts, view, true);
  const auto parent = detail::innermost_parents(containers);
  out.rings.assign(rings.size(), Ring2{});
  for (std::size_t k = 0; k < rings.size(); ++k) {
    Ring2& r = out.rings[k];
    r.parent = parent[k];
    r.role = containers[k].size() % 2 == 0 ? RingRole::Shell : RingRole::Hole;
    r.indices = std::move(rings[k]);
    if ((ring_orientation(pts, r.indices) > 0) != (r.role == RingRole::Shell)) std::reverse(r.indices.begin(), r.indices.end());
    std::rotate(r.indices.begin(), std::min_element(r.indices.begin(), r.indices.end()), r.indices.end());
  }
}

// Each ring's smallest gap to another part and the overall smallest (double, for the report).
void report_gaps(const Adjacency& adj, const Gaps& gaps, const std::vector<int>& ring_of, RingsInference& out) {
  for (std::size_t p = 0; p < ring_of.size(); ++p)
    for (std::size_t k = adj.start[p]; k < adj.start[p + 1]; ++k) {
      const int ip = static_cast<int>(p), q = adj.nbr[k];
      const int rp = ring_of[p], rq = ring_of[static_cast<std::size_t>(q)];
      if (q < ip || rp == rq) continue;
      const double g = gaps.ratio(ip, q);
      for (const auto& [r, other] : {std::pair<int, int>{rp, rq}, std::pair<int, int>{rq, rp}}) {
        Ring2& ring = out.rings[static_cast<std::size_t>(r)];
        if (g < ring.gap_spacings) {
          ring.gap_spacings = g;
          ring.nearest_ring = other;
        }
      }
      out.min_gap_spacings = std::min(out.min_gap_spacings, g);
    }
}

}  // namespace

const char* to_string(RingsDecision d) noexcept {
  switch (d) {
    case RingsDecision::OneCurve: return "one-curve";
    case RingsDecision::SmallPart: return "small-part";
    case RingsDecision::Crossing: return "crossing";
    case RingsDecision::Rings: return "rings";
    case RingsDecision::Capped: return "capped";
  }
  return "?";
}

std::size_t RingsInference::shells() const noexcept {
  return static_cast<std::size_t>(std::count_if(rings.begin(), rings.end(), [](const Ring2& r) { return r.role == RingRole::Shell; }));
}
std::size_t RingsInference::holes() const noexcept { return rings.size() - shells(); }

namespace {

// CONSTRICT_DEBUG_RINGS (docs/cli.md): a part's ring by the measures of the open-arc rule, in
// double (the decision is exact): 2|A| / Σ|e|², and the two longest edges in median edges.
void debug_part(const PointSet& pts, const std::vector<int>& ring, std::size_t k, std::size_t parts, bool thin) {
  static const bool on = std::getenv("CONSTRICT_DEBUG_RINGS") != nullptr;
  if (!on) return;
  const std::size_t m = ring.size();
  const double* o = pts[static_cast<std::size_t>(ring[0])];
  double area = 0, edges = 0;
  std::vector<double> el;
  for (std::size_t i = 0; i < m; ++i) {
    const double* a = pts[static_cast<std::size_t>(ring[i])];
    const double* b = pts[static_cast<std::size_t>(ring[(i + 1) % m])];
    area += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    edges += (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    el.push_back(std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  std::sort(el.begin(), el.end());
  std::fprintf(stderr, "rings: part %zu of %zu, %zu points, fatness %.3f, longest %.1f median edges, 2nd %.1f%s\n", k,
               parts, m, edges > 0 ? std::abs(area) / edges : 0.0, el[m - 1] / el[m / 2], el[m - 2] / el[m / 2],
               thin ? " (thin)" : "");
}

void debug_open_part(std::size_t points, std::size_t k, std::size_t parts) {
  static const bool on = std::getenv("CONSTRICT_DEBUG_RINGS") != nullptr;
  if (on) std::fprintf(stderr, "rings: part %zu of %zu, %zu points, encloses no region or is a line (thin, no polygon)\n", k, parts, points);
}

// Are the part's points on one line? Exact.
bool collinear(const PointSet& pts, const std::vector<int>& part) {
  const auto at = [&](std::size_t i) { return pts[static_cast<std::size_t>(part[i])]; };
  if (part.size() < 3) return true;
  for (std::size_t i = 2; i < part.size(); ++i)
    if (orient2(at(0), at(1), at(i)) != 0) return false;
  return true;
}

// Does the ring have an edge longer than `factor` times its median edge? Exact (compare_gap2 on
// the squared lengths, the median by exact comparisons).
bool has_chord(const PointSet& pts, const std::vector<int>& ring, double factor) {
  const std::size_t m = ring.size();
  const auto at = [&](std::size_t i) { return pts[static_cast<std::size_t>(ring[i % m])]; };
  const auto longer = [&](std::size_t i, std::size_t j) {  // |edge i| > |edge j| (edge i: ring[i] ring[i+1])
    const double* a[1] = {at(j)};
    const double* b[1] = {at(j + 1)};
    return compare_gap2(at(i), at(i + 1), a, b, 1, 1.0) > 0;
  };
  std::vector<std::size_t> edges(m);
  std::iota(edges.begin(), edges.end(), std::size_t{0});
  const auto mid = edges.begin() + static_cast<std::ptrdiff_t>(m / 2);
  std::nth_element(edges.begin(), mid, edges.end(), [&](std::size_t i, std::size_t j) { return longer(j, i); });
  const double* a[1] = {at(*mid)};
  const double* b[1] = {at(*mid + 1)};
  for (std::size_t i = 0; i < m; ++i)
    if (compare_gap2(at(i), at(i + 1), a, b, 1, factor) > 0) return true;
  return false;
}

// The fatness an isolated part's polygon must pass: kTinyRingFatness times a regular m-gon's
// 2|A|/Σ|e|² = cot(π/m)/2 while that is below kMinRingFatness (3 <= m <= kTinyRingPoints), else
// kMinRingFatness, the rule of every other part. As constants (a library's tan need not be
// correctly rounded; these are the same everywhere).
double isolated_ring_fatness(std::size_t m) {
  static_assert(kTinyRingPoints == 12 && kTinyRingFatness == 0.5 && kMinRingFatness == 1.0,
                "the table is for 3..12 points at half the n-gon (from 13 on half the n-gon is over 1)");
  constexpr std::array<double, 13> t{0, 0, 0, 0.1443375672974065, 0.25, 0.3440954801177934, 0.43301270189221935,
                                     0.5191303491430842, 0.6035533905932737, 0.6868693548636556, 0.7694208842938135,
                                     0.8514218097223124, 0.9330127018922194};
  return m <= kTinyRingPoints ? t[m] : kMinRingFatness;
}

// For each part k, the part across its smallest gap (Gaps::ratio; equal gaps: the
// lexicographically smaller pair of points), -1 for none. The edges between parts are links.
std::vector<int> nearest_parts(const PointSet& pts, const Links& links, const std::vector<int>& ring_of, std::size_t parts) {
  struct Best { double gap; int p, q; };
  std::vector<Best> best(parts, Best{HUGE_VAL, -1, -1});
  const auto at = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  const auto better = [&](double g, int p, int q, const Best& b) {
    if (b.p < 0 || g < b.gap) return true;
    if (g > b.gap) return false;
    if (lex_less(at(p), at(b.p))) return true;
    return !lex_less(at(b.p), at(p)) && lex_less(at(q), at(b.q));
  };
  for (const auto& [g, e] : links) {
    const int rp = ring_of[static_cast<std::size_t>(e[0])], rq = ring_of[static_cast<std::size_t>(e[1])];
    if (rp == rq) continue;
    for (const auto& [r, p, q] : {std::array<int, 3>{rp, e[0], e[1]}, std::array<int, 3>{rq, e[1], e[0]}}) {
      Best& b = best[static_cast<std::size_t>(r)];
      if (better(g, p, q, b)) b = Best{g, p, q};
    }
  }
  std::vector<int> out(parts, -1);
  for (std::size_t k = 0; k < parts; ++k)
    if (best[k].q >= 0) out[k] = ring_of[static_cast<std::size_t>(best[k].q)];
  return out;
}

// The ladder of infer_rings2() (docs/topology.md, Method) over its state, a round at a time:
//   rings_of_parts()   a clean crust cycle is its part's ring as it is; the other parts need one;
//   judge_parts()      with their regions (enclosing(), per level): an open arc, a line or a part
//                      that encloses nothing is thin without a polygon; the others get one;
//   make_polygons()    the polygons on both cores; a sliver or an arc closed by a chord is thin;
//   undo_thin_joins()  a thin part made of thin parts joined to an accepted ring is split back
//                      (the round is made again);
//   accept_rings()     no part thin: the rings nested and checked (done), or a crossing pair
//                      joined; else join_thin(): each thin part joins the part across its gap;
//   regroup()          the parts made again from the joins, the unchanged parts' rings kept;
// until the rings are accepted, one part is left (one curve, unless the walk finds holes), a part
// has no polygon, or the work bound is reached.
class RingsLadder {
 public:
  RingsLadder(const PointSet& points, const Adjacency& adj, const Rings2Options& options,
              const Constrict2Options& part_options, RingsInference& out)
      : points_(points), adj_(adj), options_(options), part_options_(part_options), out_(out), gap_(options.topology_gap),
        crust_(points, adj) {}

  void run() {
    for (std::size_t v = 0; v < points_.size(); ++v) out_.bad_degree_points += crust_.degree(static_cast<int>(v)) != 2;
    gaps_.emplace(points_, adj_, crust_, gap_);
    part_of_ = find_parts(points_, adj_, *gaps_, gap_, links_, out_);
    parts_ = group_parts(points_, part_of_);
    out_.parts = parts_.size();
    if (parts_.size() == 1) return one_part_or_walk();
    rings_.resize(parts_.size());
    ring_of_.resize(points_.size());
    known_.assign(parts_.size(), 0);
    kept_.resize(parts_.size());
    made_of_.resize(parts_.size());
    work_limit_ = options_.infer_work_limit > 0 ? options_.infer_work_limit : kInferWorkPerPoint * points_.size() + kInferWorkBase;
    for (;;) {
      Round r;
      rings_of_parts(r);
      judge_parts(r);
      polygon_work_ += points_.size();  // the round itself: its regions and links are O(N)
      for (const std::size_t k : r.need) polygon_work_ += parts_[k].size();
      if (polygon_work_ > work_limit_) {
        out_.decision = RingsDecision::Capped;
        return;
      }
      if (!make_polygons(r)) {
        out_.decision = RingsDecision::SmallPart;
        return;
      }
      if (undo_thin_joins(r)) continue;
      UnionFind joined(parts_.size());
      if (!r.any_thin) {
        if (accept_rings(joined)) return;
      } else {
        join_thin(r, joined);
      }
      regroup(r, joined);
      if (parts_.size() == 1) {
        out_.decision = RingsDecision::OneCurve;
        out_.parts_polygon = 0;
        return one_part_or_walk();
      }
    }
  }

 private:
  // A part that the last round made by joining thin parts to an accepted ring: what it was made
  // of (each constituent's points, its ring when it was accepted), to take the join back. A thin
  // constituent keeps the polygon it was judged by, if it had one (the one part_polygon() would
  // make again for the test of taking the join back).
  struct Constituent {
    std::vector<int> points, ring;
    bool accepted;
  };
  // One round's judgement of the parts (per part unless said).
  struct Round {
    std::vector<char> thin, polygon_part, ok, made, isolated, line;
    std::vector<std::size_t> todo;  // the parts without a ring known from the last round
    std::vector<std::size_t> need;  // the parts whose polygon is made this round
    bool any_thin = false;
  };

  // Method 6: the nearest-neighbour walk's rings replace ours (each point's ring in ours_of, `ours`
  // rings) when they add holes to them. Traced once, when first asked.
  void take_walk_rings(const std::vector<int>& ours_of, std::size_t ours) {
    if (!options_.walk_holes) return;
    if (!walk_) {
      walk_.emplace();
      if (!detail::nearest_walk_rings2(points_, adj_, *walk_)) walk_->clear();
      order_by_lowest_point(points_, *walk_);  // (nest(): parents first)
    }
    if (walk_->size() <= ours) return;
    RingsInference w;
    std::vector<std::vector<int>> rings = *walk_;
    nest(points_, rings, w);
    if (!detail::walk_adds_holes(w.rings, ours_of, ours)) return;
    std::vector<int> walk_of(points_.size());
    for (std::size_t k = 0; k < w.rings.size(); ++k)
      for (int v : w.rings[k].indices) walk_of[static_cast<std::size_t>(v)] = static_cast<int>(k);
    // Its rings at least kWalkGapShare · T local spacings apart (every closest pair of two rings is
    // a Delaunay edge): the option moves this threshold too. Then the exact check of the set.
    for (std::size_t p = 0; p < points_.size(); ++p)
      for (std::size_t k = adj_.start[p]; k < adj_.start[p + 1]; ++k) {
        const int q = adj_.nbr[k];
        if (q > static_cast<int>(p) && walk_of[p] != walk_of[static_cast<std::size_t>(q)] &&
            gaps_->shorter(static_cast<int>(p), q, detail::kWalkGapShare * gap_))
          return;
      }
    if (!validate_rings2(points_, w.rings, &w.check)) return;
    out_.rings = std::move(w.rings);
    out_.check = w.check;
    out_.min_gap_spacings = std::numeric_limits<double>::infinity();
    report_gaps(adj_, *gaps_, walk_of, out_);
    out_.rings_from_walk = out_.rings.size() - ours;
    out_.decision = RingsDecision::Rings;
  }

  // OneCurve, unless the walk finds holes. (Only where the crust is not clean: a part that is one
  // clean NN-crust cycle is a curve by the crust's own reading, which the walk cannot add a hole to.)
  void one_part_or_walk() {
    if (!crust_cycle(crust_, parts_[0], part_of_, cycle_)) take_walk_rings(std::vector<int>(points_.size(), 0), 1);
  }

  // The rings of the parts: a clean crust cycle as it is; the others are to be judged (todo).
  void rings_of_parts(Round& r) {
    out_.parts_polygon = 0;
    r.thin.assign(parts_.size(), 0);
    r.polygon_part.assign(parts_.size(), 0);
    r.ok.assign(parts_.size(), 1);
    for (std::size_t k = 0; k < parts_.size(); ++k) {
      for (int v : parts_[k]) ring_of_[static_cast<std::size_t>(v)] = static_cast<int>(k);
      if (crust_cycle(crust_, parts_[k], part_of_, cycle_)) {
        rings_[k].swap(cycle_);
        continue;
      }
      r.polygon_part[k] = 1;
      ++out_.parts_polygon;
      if (!known_[k]) r.todo.push_back(k);
    }
  }

  // The regions of this round's parts, per level on both cores. Joined parts are sealed at the
  // gaps between them, so levels 1.. are made again after a round of joins (level 0 never lies
  // between two parts): always up to open_arc_rebuild_max points, else where regions_changed().
  // Made when a part is not a clean crust cycle: at the gap threshold, and with the walls of a
  // part's own sparse spots up to kSealFactors times the threshold.
  void make_regions() {
    const bool incremental = points_.size() > options_.open_arc_rebuild_max;
    const bool first = enclosures_.empty();
    if (first) {
      wall_level_ = wall_levels(adj_, *gaps_, gap_);
      enclosures_.resize(kLevels);
      for (std::uint8_t level = 0; level < kLevels; ++level) components_.emplace_back(incremental ? points_.size() : 0);
      // The edges that a join can make walls: between two parts, at a level > 0.
      for (std::size_t e = 0; e < wall_level_.size(); ++e) {
        if (wall_level_[e] == 0 || wall_level_[e] >= kLevels) continue;
        const auto [a, b] = edge_ends(adj_, e);
        if (part_of_[static_cast<std::size_t>(a)] != part_of_[static_cast<std::size_t>(b)])
          joinable_.push_back(static_cast<std::uint32_t>(e));
      }
    }
    std::vector<char> again(kLevels, first ? 1 : 0);
    tbb::parallel_for(std::uint8_t{0}, kLevels, [&](std::uint8_t level) {
      if (!first && level > 0)
        again[level] = !incremental || undone_ || regions_changed(points_, adj_, wall_level_, level, part_of_, built_part_of_,
                                                                  enclosures_[level]->unbounded(), joinable_, components_[level]);
      if (!again[level]) return;
      enclosures_[level].emplace(points_, adj_, wall_level_, level, part_of_);
      if (incremental) components_[level] = wall_components(points_, adj_, wall_level_, level, part_of_);
    });
    built_part_of_ = part_of_;
    undone_ = false;
  }

  // A part of fewer than 3 points or on one line has no polygon, and a part that encloses no
  // region (Enclosures) is an open arc: thin without a polygon, joined like a thin one. But a
  // part far from every other part (kTinyRingGap) gets its polygon whatever its regions: a small
  // ring's interior is cut by its own short diagonals (walls), and a small ring's polygon is
  // judged against the regular m-gon (isolated_ring_fatness). Its links to other parts, each
  // tested exactly against the gap. The others need a polygon.
  void judge_parts(Round& r) {
    const bool test_open = options_.open_arc_test && !r.todo.empty();
    if (test_open) make_regions();
    std::vector<char> encl(parts_.size(), !test_open);
    for (const auto& level : enclosures_) {
      if (!test_open) break;
      const std::vector<char> e = level->enclosing(ring_of_, parts_.size());
      for (std::size_t k = 0; k < parts_.size(); ++k) encl[k] = encl[k] || e[k];
    }
    r.isolated.assign(parts_.size(), 0);
    r.line.assign(parts_.size(), 0);
    bool any = false;
    for (const std::size_t k : r.todo) {
      r.line[k] = collinear(points_, parts_[k]) ? 1 : 0;
      r.isolated[k] = parts_[k].size() >= 3 && !r.line[k] ? 1 : 0;
      any = any || r.isolated[k];
    }
    if (any)
      for (const auto& [g, e] : links_) {
        const int rp = ring_of_[static_cast<std::size_t>(e[0])], rq = ring_of_[static_cast<std::size_t>(e[1])];
        if (rp == rq || !(r.isolated[static_cast<std::size_t>(rp)] || r.isolated[static_cast<std::size_t>(rq)])) continue;
        if (gaps_->shorter(e[0], e[1], kTinyRingGap)) r.isolated[static_cast<std::size_t>(rp)] = r.isolated[static_cast<std::size_t>(rq)] = 0;
      }
    for (const std::size_t k : r.todo) {
      if (!r.line[k] && (encl[k] || r.isolated[k] || parts_[k].size() <= kTinyRingPoints)) {
        r.need.push_back(k);
        continue;
      }
      r.thin[k] = 1;
      r.any_thin = true;
      ++out_.open_parts;
      debug_open_part(parts_[k].size(), k, parts_.size());
    }
  }

  // The polygons of the parts that need one (independent: on both cores, each the same whatever
  // the threads). A polygon that is a sliver along its points, or an arc closed by a chord across
  // its opening, is not a ring the points show: a piece of a longer curve, split off at a gap
  // that a large random sample has somewhere (docs/topology.md, "Open arcs"). (A ring kept from
  // the last round passed already: a thin one joined another part.) False: a part without one.
  bool make_polygons(Round& r) {
    r.made.assign(parts_.size(), 0);
    for (const std::size_t k : r.need) r.made[k] = 1;
    tbb::parallel_for(std::size_t{0}, r.need.size(), [&](std::size_t i) {
      const std::size_t k = r.need[i];
      if (!kept_[k].empty()) {  // (made in the round a join was taken back; the same again)
        rings_[k] = std::move(kept_[k]);
        return;
      }
      r.ok[k] = part_polygon(points_, parts_[k], part_options_, rings_[k]) ? 1 : 0;
    });
    kept_.assign(parts_.size(), {});
    for (const std::size_t k : r.need) {
      if (!r.ok[k]) return false;
      r.thin[k] = compare_ring_fatness2(points_.coords.data(), rings_[k].data(), rings_[k].size(),
                                        r.isolated[k] ? isolated_ring_fatness(rings_[k].size()) : kMinRingFatness) <= 0 ||
                  has_chord(points_, rings_[k], kMaxRingEdge);
      r.any_thin = r.any_thin || r.thin[k];
      debug_part(points_, rings_[k], k, parts_.size(), r.thin[k]);
    }
    return true;
  }

  // A thin part made by joining thin parts to an accepted ring is two rings across a gap, not
  // one curve (a noisy arc of the ring's own curve leaves it fat): the join is taken back and
  // each thin constituent is a ring of its own, when it has a polygon (else the joins stand).
  // Every constituent is then known, so nothing else changes and the round is made again (true).
  bool undo_thin_joins(Round& r) {
    std::vector<std::size_t> undo;
    for (std::size_t k = 0; k < parts_.size(); ++k)
      if (r.thin[k] && !made_of_[k].empty()) undo.push_back(k);
    std::vector<char> can(undo.size(), 1);
    tbb::parallel_for(std::size_t{0}, undo.size(), [&](std::size_t i) {
      for (Constituent& c : made_of_[undo[i]]) {
        if (!c.accepted && c.ring.empty() &&
            (collinear(points_, c.points) || !part_polygon(points_, c.points, part_options_, c.ring))) {
          can[i] = 0;
          break;
        }
        // Each is a ring by the measure of an isolated part (isolated_ring_fatness): a loop of
        // a noisy band (a clean crust cycle of a few points) with the band's arcs joined to it
        // is not two rings.
        if (compare_ring_fatness2(points_.coords.data(), c.ring.data(), c.ring.size(),
                                  isolated_ring_fatness(c.ring.size())) <= 0) {
          can[i] = 0;
          break;
        }
      }
    });
    bool any_undone = false;
    std::vector<char> split(parts_.size(), 0);
    for (std::size_t i = 0; i < undo.size(); ++i)
      if (can[i]) {
        split[undo[i]] = 1;
        any_undone = true;
        for (const Constituent& c : made_of_[undo[i]]) polygon_work_ += c.accepted ? 0 : c.points.size();
      }
    if (!any_undone) return false;
    std::vector<std::pair<std::vector<int>, std::vector<int>>> all;  // (points, ring)
    std::vector<std::vector<int>> all_kept;                          // (a thin part's polygon)
    for (std::size_t k = 0; k < parts_.size(); ++k) {
      if (!split[k]) {  // (a thin part's polygon is no ring: it is evaluated again, and joins)
        all_kept.emplace_back(r.thin[k] && r.made[k] ? std::move(rings_[k]) : std::vector<int>{});
        all.emplace_back(std::move(parts_[k]), r.thin[k] ? std::vector<int>{} : std::move(rings_[k]));
        continue;
      }
      for (Constituent& c : made_of_[k]) {
        ++out_.joins_undone;
        all.emplace_back(std::move(c.points), std::move(c.ring));
        all_kept.emplace_back();
      }
    }
    // The parts again in their canonical order (group_parts: by the lexicographically
    // smallest point); every one is known but those that were not evaluated this round.
    for (std::size_t j = 0; j < all.size(); ++j)
      for (int v : all[j].first) part_of_[static_cast<std::size_t>(v)] = static_cast<int>(j);
    std::vector<std::vector<int>> regrouped = group_parts(points_, part_of_);
    std::vector<std::vector<int>> regrouped_rings(regrouped.size());
    std::vector<char> regrouped_known(regrouped.size(), 0);
    kept_.assign(regrouped.size(), {});
    for (std::size_t j = 0; j < regrouped.size(); ++j) {
      const std::size_t from = static_cast<std::size_t>(part_of_[static_cast<std::size_t>(regrouped[j].front())]);
      regrouped_rings[j] = std::move(all[from].second);
      regrouped_known[j] = regrouped_rings[j].empty() ? 0 : 1;
      kept_[j] = std::move(all_kept[from]);
    }
    parts_ = std::move(regrouped);  // (part_of keeps its labels: one per part, as after a join)
    rings_ = std::move(regrouped_rings);
    known_ = std::move(regrouped_known);
    made_of_.assign(parts_.size(), {});
    undone_ = true;
    return true;
  }

  // Every part is a ring: nested, oriented and checked (true: done). Two parts whose rings meet
  // are interleaved, not apart: they are joined and made again (kMaxCrossingJoins), the others
  // kept; past that, decision Crossing (true).
  bool accept_rings(UnionFind& joined) {
    std::vector<std::vector<int>> nested = rings_;  // (kept: a repair goes on with them)
    nest(points_, nested, out_);
    report_gaps(adj_, *gaps_, ring_of_, out_);
    if (validate_rings2(points_, out_.rings, &out_.check)) {
      out_.decision = RingsDecision::Rings;
      if (out_.parts_polygon > 0) take_walk_rings(ring_of_, rings_.size());
      return true;
    }
    const int a = out_.check.met_a, b = out_.check.met_b;
    if (a < 0 || b < 0 || a == b || out_.crossings_joined >= kMaxCrossingJoins) {
      out_.decision = RingsDecision::Crossing;
      return true;
    }
    const auto part_of_ring = [&](int k) { return ring_of_[static_cast<std::size_t>(out_.rings[static_cast<std::size_t>(k)].indices.front())]; };
    joined.join(part_of_ring(a), part_of_ring(b));
    ++out_.crossings_joined;
    out_.rings.clear();
    out_.check = RingsCheck{};
    out_.min_gap_spacings = std::numeric_limits<double>::infinity();
    return false;
  }

  // Each thin part joins the part across its smallest gap.
  void join_thin(const Round& r, UnionFind& joined) {
    const std::vector<int> nearest = nearest_parts(points_, links_, ring_of_, parts_.size());
    for (std::size_t k = 0; k < parts_.size(); ++k)
      if (r.thin[k] && nearest[k] >= 0 && joined.join(static_cast<int>(k), nearest[k])) ++out_.thin_parts_joined;
  }

  // The parts made again from the joins (the rings of parts that did not change are kept), with
  // what each join of thin parts to an accepted ring was made of (made_of_).
  void regroup(const Round& r, UnionFind& joined) {
    std::vector<std::size_t> members(parts_.size(), 0);
    for (std::size_t k = 0; k < parts_.size(); ++k) ++members[static_cast<std::size_t>(joined.find(static_cast<int>(k)))];
    for (std::size_t v = 0; v < points_.size(); ++v) part_of_[v] = joined.find(ring_of_[v]);
    std::vector<std::vector<int>> next = group_parts(points_, part_of_);
    std::vector<std::vector<int>> next_rings(next.size());
    std::vector<char> next_known(next.size(), 0);
    std::vector<std::vector<Constituent>> next_made_of(next.size());
    {
      // Which old parts each new one is made of (a join of thin parts to an accepted ring only).
      std::vector<int> new_of_root(parts_.size(), -1);
      for (std::size_t j = 0; j < next.size(); ++j)
        new_of_root[static_cast<std::size_t>(joined.find(ring_of_[static_cast<std::size_t>(next[j].front())]))] = static_cast<int>(j);
      std::vector<char> has_ring(next.size(), 0), has_thin(next.size(), 0);
      for (std::size_t k = 0; k < parts_.size(); ++k) {
        const std::size_t j = static_cast<std::size_t>(new_of_root[static_cast<std::size_t>(joined.find(static_cast<int>(k)))]);
        (r.thin[k] ? has_thin : has_ring)[j] = 1;
      }
      for (std::size_t k = 0; k < parts_.size(); ++k) {
        const std::size_t j =
            static_cast<std::size_t>(new_of_root[static_cast<std::size_t>(joined.find(static_cast<int>(k)))]);
        if (has_ring[j] && has_thin[j] && members[static_cast<std::size_t>(joined.find(static_cast<int>(k)))] > 1)
          next_made_of[j].push_back(
              Constituent{parts_[k], r.thin[k] && !r.made[k] ? std::vector<int>{} : rings_[k], !r.thin[k]});
      }
    }
    for (std::size_t j = 0; j < next.size(); ++j) {
      const std::size_t old = static_cast<std::size_t>(ring_of_[static_cast<std::size_t>(next[j].front())]);
      if (members[static_cast<std::size_t>(joined.find(static_cast<int>(old)))] == 1) {
        next_rings[j] = std::move(rings_[old]);
        next_known[j] = 1;
      }
    }
    kept_.assign(next.size(), {});
    parts_ = std::move(next);
    rings_ = std::move(next_rings);
    known_ = std::move(next_known);
    made_of_ = std::move(next_made_of);
  }

  // Inputs.
  const PointSet& points_;
  const Adjacency& adj_;
  const Rings2Options& options_;
  const Constrict2Options& part_options_;  // the part polygons' options
  RingsInference& out_;
  const double gap_;
  const NnCrust crust_;
  std::optional<Gaps> gaps_;  // (made in run(), after the crust)
  Links links_;               // the Delaunay edges between parts, with their gaps (find_parts)
  // The parts and their rings.
  std::vector<int> part_of_;             // per point
  std::vector<std::vector<int>> parts_;  // per part, its points
  std::vector<std::vector<int>> rings_;  // per part
  std::vector<int> ring_of_;             // per point: its part this round
  std::vector<char> known_;              // rings_[k] is still the ring of parts_[k]
  // The polygon of a thin part that a round taking joins back left as it was: the part is judged
  // again (its links changed) from this polygon, the one part_polygon() would make again.
  std::vector<std::vector<int>> kept_;
  std::vector<std::vector<Constituent>> made_of_;  // per part (Constituent)
  bool undone_ = false;  // the last round took joins back: the regions are made again
  // The regions (make_regions()).
  std::vector<std::optional<Enclosures>> enclosures_;  // per level
  std::vector<std::uint8_t> wall_level_;
  std::vector<int> built_part_of_;        // part_of_ when the levels were last looked at
  std::vector<UnionFind> components_;     // per level: the points joined by its walls
  std::vector<std::uint32_t> joinable_;   // the edges that joins can make walls
  // The work bound (Rings2Options::infer_work_limit): N per round and the points of the part
  // polygons made.
  std::size_t polygon_work_ = 0, work_limit_ = 0;
  std::optional<std::vector<std::vector<int>>> walk_;  // the walk's rings (empty: it failed)
  std::vector<int> cycle_;                              // (crust_cycle's output)
};

}  // namespace

std::shared_ptr<const detail::RingsAdjacency> detail::rings_adjacency(Delaunay2&& dt) {
  return std::make_shared<const RingsAdjacency>(std::move(dt));
}

Status infer_rings2(const PointSet& points, const Delaunay2& dt, const Rings2Options& options, RingsInference& out) {
  out = RingsInference{};
  if (points.dim != 2 || dt.n_vertices != points.size() || dt.triangles.size() != dt.neighbors.size())
    return {StatusCode::InvalidArgument, "infer_rings2: the triangulation is not one of these 2D points"};
  return detail::infer_rings2(points, detail::RingsAdjacency(Delaunay2(dt)), options, out);
}

Status detail::infer_rings2(const PointSet& points, const RingsAdjacency& adj, const Rings2Options& options, RingsInference& out) {
  out = RingsInference{};
  const double gap = options.topology_gap;
  out.gap_threshold = gap;
  Constrict2Options part_options = options.polygon;  // the part polygons' options
  part_options.refine_multi_start = options.polygon.refine_multi_start && options.infer_multi_start;
  if (!(gap >= 0) || !std::isfinite(gap))
    return {StatusCode::InvalidArgument, "topology gap must be a finite number >= 0, not " + number_text(gap)};
  if (points.dim != 2 || adj.start.size() != points.size() + 1)
    return {StatusCode::InvalidArgument, "infer_rings2: the triangulation is not one of these 2D points"};
  RingsLadder(points, adj, options, part_options, out).run();
  return Status::ok();
}

}  // namespace constrict
