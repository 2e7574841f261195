// SPDX-License-Identifier: GPL-3.0-or-later
// Shortest Voronoi skeleton growth, dimension independent (seed paper §2.7, O'Rourke, Booth &
// Washington 1987). K = vertices per simplex: 3 (Delaunay triangles) or 4 (tetrahedra).
// The body grows from a seed simplex across its free faces; a neighbour simplex may join only if
// its apex (the vertex opposite the shared face) is not yet in the body. Then the neighbour
// shares exactly that face with the body, so the body stays a disk / ball with every vertex on
// its boundary, and its dual graph is exactly the tree of the growth edges (docs/comparison-
// methods.md, "Why the growth keeps the boundary valid").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "constrict/voronoi_skeleton.hpp"

namespace constrict::detail {

template <int K>
class SkeletonGrowth {
 public:
  using Simplex = std::array<int, K>;

  /// @param simplices, neighbors the Delaunay output (neighbors[t][i] across the face opposite i)
  /// @param dual_len dual_len[t][i] = length of the Voronoi edge across face i (ignored on the hull)
  SkeletonGrowth(const std::vector<Simplex>& simplices, const std::vector<Simplex>& neighbors,
                 const std::vector<std::array<double, K>>& dual_len, std::size_t n_points)
      : s_(simplices), nb_(neighbors), len_(dual_len), n_(n_points) {
    const std::size_t T = s_.size();
    mirror_.assign(T, Simplex{});
    std::vector<double> all;
    for (std::size_t t = 0; t < T; ++t)
      for (int i = 0; i < K; ++i) {
        const int m = nb_[t][U(i)];
        mirror_[t][U(i)] = -1;
        if (m < 0) continue;
        for (int j = 0; j < K; ++j)
          if (nb_[U(m)][U(j)] == static_cast<int>(t)) mirror_[t][U(i)] = j;
        if (static_cast<std::size_t>(m) > t) all.push_back(len_[t][U(i)]);  // each dual edge once
      }
    std::sort(all.begin(), all.end());
    prefix_.assign(all.size() + 1, 0.0);
    for (std::size_t k = 0; k < all.size(); ++k) prefix_[k + 1] = prefix_[k] + all[k];
    body_.assign(T, 0);
    pt_.assign(n_, 0);
  }

  struct Outcome {
    std::vector<int> added;  // simplex ids in growth order (seed first)
    double length = 0;       // tree length
    std::size_t points = 0;  // points in the body
    bool pruned = false;
  };

  /// Grows from @p seed. With bound < inf the growth stops (pruned) as soon as it cannot end with
  /// a complete tree strictly shorter than @p bound.
  void grow(int seed, double bound, Outcome& out) {
    ++stamp_;
    out.added.clear();
    out.length = 0;
    out.points = 0;
    out.pruned = false;
    heap_.clear();
    body_[U(seed)] = stamp_;
    for (int v : s_[U(seed)]) mark(v, out);
    out.added.push_back(seed);
    push_faces(seed, out);
    while (out.points < n_ && !heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), greater);
      const Front f = heap_.back();
      heap_.pop_back();
      const int apex = s_[U(f.t)][U(f.apex_local)];
      if (pt_[U(apex)] == stamp_) continue;  // the apex joined meanwhile: never valid again
      out.length += f.len;
      body_[U(f.t)] = stamp_;
      mark(apex, out);
      out.added.push_back(f.t);
      if (bound < HUGE_VAL) {
        const std::size_t rest = std::min(n_ - out.points, prefix_.size() - 1);
        if (out.length >= bound || out.length + prefix_[rest] > bound) {
          out.pruned = true;
          return;
        }
      }
      push_faces(f.t, out);
    }
  }

 private:
  struct Front {
    double len;
    Simplex ids;     // sorted vertex ids of the candidate (tie-break: stable ids)
    int t;           // candidate simplex
    int apex_local;  // its vertex opposite the face shared with the body
  };
  static bool greater(const Front& a, const Front& b) {  // min-heap on (len, ids)
    if (a.len != b.len) return a.len > b.len;
    return a.ids > b.ids;
  }
  static std::size_t U(int i) { return static_cast<std::size_t>(i); }

  void mark(int v, Outcome& out) {
    if (pt_[U(v)] != stamp_) {
      pt_[U(v)] = stamp_;
      ++out.points;
    }
  }
  void push_faces(int t, const Outcome&) {
    for (int i = 0; i < K; ++i) {
      const int m = nb_[U(t)][U(i)];
      if (m < 0 || body_[U(m)] == stamp_) continue;
      const int j = mirror_[U(t)][U(i)];
      if (pt_[U(s_[U(m)][U(j)])] == stamp_) continue;
      Simplex ids = s_[U(m)];
      std::sort(ids.begin(), ids.end());
      heap_.push_back(Front{len_[U(t)][U(i)], ids, m, j});
      std::push_heap(heap_.begin(), heap_.end(), greater);
    }
  }

  const std::vector<Simplex>& s_;
  const std::vector<Simplex>& nb_;
  const std::vector<std::array<double, K>>& len_;
  std::size_t n_;
  std::vector<Simplex> mirror_;
  std::vector<double> prefix_;
  std::vector<std::uint32_t> body_, pt_;
  std::uint32_t stamp_ = 0;
  std::vector<Front> heap_;
};

/// Seeds per VoronoiSkeletonOptions::seed_limit: every simplex, or an even stride through the
/// simplices sorted by sorted vertex ids.
template <int K>
std::vector<int> skeleton_seeds(const std::vector<std::array<int, K>>& simplices, std::size_t limit) {
  const std::size_t T = simplices.size();
  std::vector<int> order(T);
  for (std::size_t t = 0; t < T; ++t) order[t] = static_cast<int>(t);
  auto sorted = [&](int t) {
    std::array<int, K> a = simplices[static_cast<std::size_t>(t)];
    std::sort(a.begin(), a.end());
    return a;
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return sorted(a) < sorted(b); });
  if (limit == 0 || limit >= T) return order;
  std::vector<int> out;
  out.reserve(limit);
  for (std::size_t k = 0; k < limit; ++k) out.push_back(order[k * T / limit]);
  return out;
}

/// Runs every seed, keeps the best: complete with the shortest tree (first seed wins ties);
/// without a complete one, most points, then shortest tree.
template <int K>
void skeleton_search(SkeletonGrowth<K>& g, const std::vector<int>& seeds, std::size_t n, bool prune,
                     typename SkeletonGrowth<K>::Outcome& best, std::size_t& tried, std::size_t& pruned,
                     std::size_t& complete, int& best_seed) {
  typename SkeletonGrowth<K>::Outcome cur;
  bool have = false, have_complete = false;
  for (int seed : seeds) {
    ++tried;
    g.grow(seed, prune && have_complete ? best.length : HUGE_VAL, cur);
    if (cur.pruned) {
      ++pruned;
      continue;
    }
    const bool full = cur.points == n;
    if (full) ++complete;
    bool better;
    if (!have) better = true;
    else if (full != (best.points == n)) better = full;
    else if (full) better = cur.length < best.length;
    else better = cur.points > best.points || (cur.points == best.points && cur.length < best.length);
    if (better) {
      best = cur;
      best_seed = seed;
      have = true;
      have_complete = full;
    }
  }
}

/// The winning body of a skeleton search, in the terms both dimensions extract their result from.
struct SkeletonBody {
  std::vector<int> added;      // simplex ids in growth order (seed first)
  std::vector<char> in_body;   // per simplex
  std::vector<char> reached;   // per point
  std::vector<int> unplaced;   // points not reached, ascending
};

/// The search shared by voronoi_skeleton2/3: dual edge lengths from the circumcentres (infinite
/// across the hull), the seeds, the growth from each; fills the search fields of @p st.
/// @param cc circumcentre of each simplex (double arithmetic; only ranks dual edge lengths)
template <int K>
SkeletonBody skeleton_best_body(const std::vector<std::array<int, K>>& simplices,
                                const std::vector<std::array<int, K>>& neighbors,
                                const std::vector<std::array<double, K - 1>>& cc, std::size_t n,
                                const VoronoiSkeletonOptions& options, VoronoiSkeletonStats& st) {
  const auto U = [](int i) { return static_cast<std::size_t>(i); };
  const std::size_t T = simplices.size();
  std::vector<std::array<double, K>> len(T);
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < K; ++i) {
      const int m = neighbors[t][U(i)];
      if (m < 0) {
        len[t][U(i)] = HUGE_VAL;
        continue;
      }
      const auto& a = cc[t];
      const auto& b = cc[U(m)];
      // 2D has always used std::hypot and 3D the plain root; each keeps its rounding so that the
      // lengths, and with them the ties of the search, stay bit-identical.
      if constexpr (K == 3) {
        len[t][U(i)] = std::hypot(b[0] - a[0], b[1] - a[1]);
      } else {
        const double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
        len[t][U(i)] = std::sqrt(dx * dx + dy * dy + dz * dz);
      }
    }
  SkeletonGrowth<K> growth(simplices, neighbors, len, n);
  const std::vector<int> seeds = skeleton_seeds<K>(simplices, options.seed_limit);
  typename SkeletonGrowth<K>::Outcome best;
  st.simplices = T;
  skeleton_search<K>(growth, seeds, n, options.prune, best, st.seeds_tried, st.seeds_pruned, st.seeds_complete,
                     st.best_seed);
  st.tree_length = best.length;

  SkeletonBody body;
  body.in_body.assign(T, 0);
  body.reached.assign(n, 0);
  for (int t : best.added) {
    body.in_body[U(t)] = 1;
    for (int v : simplices[U(t)]) body.reached[U(v)] = 1;
  }
  for (std::size_t v = 0; v < n; ++v)
    if (!body.reached[v]) body.unplaced.push_back(static_cast<int>(v));
  body.added = std::move(best.added);
  return body;
}

}  // namespace constrict::detail
