// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "grow" of the 3D engine (docs/reconstruction-3d.md §4.7). The body grows from the inside
// instead of shrinking from the hull: it starts with the inside tetrahedron of the largest
// circumradius and adds Delaunay tetrahedra only by the mirror images of the removal rules (seed
// paper §4.2), so it stays a triangulated ball: a tetrahedron glued along one face whose fourth
// vertex is not yet in the body, or glued along two faces whose free edge is not yet in the body
// (never three faces: that would bury a vertex). Every vertex in the body is therefore on its
// surface. Order: tetrahedra labelled inside by the largest circumradius first (from the medial
// axis outwards, which keeps the growth front from wrapping around pockets); when none is left, a
// tetrahedron labelled outside only if it brings a new point into the body (one-face rule), or if
// it is a small two-face step that lets a small next one do so (into a wall the labels miss,
// §4.11), the smallest first relative to the spacing (thin parts the labels miss: a point is
// reached by the shortest step, through its own part, not across the gap to a nearby part); a
// crossing toward a part labelled inside goes on from its own steps until it is inside (§4.14).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "constrict/detail/stages3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/bucket_sort.hpp"
#include "core/detail/rank_queue.hpp"
#include "core/detail/union_find.hpp"

namespace constrict::detail {
namespace {

// Keys: inside tetrahedra kInsideKeyBase + ln r (ln r clamped below at kMinLogRadius); outside
// tetrahedra (their own heap, popped only when no inside one is left) minus their size ratio.
constexpr double kInsideKeyBase = 1000.0, kMinLogRadius = -500.0;
// The largest outside tetrahedron (bridge ratio) that may join by the two-face rule to open the
// way into a thin part (crawls()). Measured 2, 2.5, 3, 4 (docs/reconstruction-3d.md §4.11).
constexpr double kCrawlRatio = 3.0;
// How many two-face steps ahead crawls() looks for the step that brings in a point (measured 0, 1,
// 2: 1 fixes more sets than 0; 2 the same as 1).
constexpr int kCrawlDepth = 1;
// The smallest region of tetrahedra labelled inside (not in the body, connected through faces) that
// a crossing heads for (Growth3::mark_large_inside_regions). Scattered inside labels in a wall a
// few spacings thick form regions of 1-20 (docs/reconstruction-3d.md §4.14); measured 32, 64, 128,
// 256, 1024: a part beside a body is reached by one crossing from 32 on, and from 256 on an unevenly
// sampled figure-eight tube keeps the handle that 32-128 lose.
constexpr std::uint32_t kCrossingRegion = 256;

// The fill in its reaching mode (docs/reconstruction-3d.md §4.13): pockets labelled inside that hold
// points still out of the body come in with those points. Returns the tetrahedra it added.
std::size_t fill_pockets(Body3& b, const Labels3& l, double conf, Growth3Stats& st) {
  const std::size_t before = b.n_onb;
  Carve3Stats fs;
  const std::size_t filled = fill_inside3(b, l, conf, fs, /*reach=*/true);
  st.pocket_filled += filled;
  st.pocket_reached += b.n_onb - before;
  return filled;
}

class Growth3 {
 public:
  // fill_conf > 0: the fill runs when the inside tetrahedra are exhausted with points left (below).
  Growth3(Body3& b, const Labels3& l, Growth3Stats& st, const std::vector<double>* spacing, double fill_conf)
      : b_(b), l_(l), s_(st), given_spacing_(spacing), fill_conf_(fill_conf) {}

  // Largest circumradius among the inside tetrahedra, ties -> smallest sorted vertex ids (a strict
  // total order: the same seed from any split of the range).
  int seed() const {
    const auto better = [&](int t, int than) {
      if (t < 0) return false;
      if (than < 0) return true;
      if (l_.lrad[uz(t)] != l_.lrad[uz(than)]) return l_.lrad[uz(t)] > l_.lrad[uz(than)];
      return sorted4(b_.tets[uz(t)]) < sorted4(b_.tets[uz(than)]);
    };
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, b_.T0, 1 << 16), -1,
        [&](const tbb::blocked_range<std::size_t>& r, int best) {
          for (std::size_t t = r.begin(); t != r.end(); ++t)
            if (l_.label[t] < 0 && l_.lrad[t] > kFlatLogRadius && better(static_cast<int>(t), best))
              best = static_cast<int>(t);
          return best;
        },
        [&](int a, int b) { return better(b, a) ? b : a; });
  }
  void run(int seed, const GrowthPrep3* prep) {
    b_.state.resize(b_.T0);
    cell_.allocate(b_.T0);  // (written whole below: not zero-filled)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b_.T0, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        b_.state[t] = kOutside;
        ++b_.ver[t];
        cell_[t] = {0, 0, 0, l_.label[t] < 0};
      }
    });
    for (std::size_t t = b_.T0; t < b_.ver.size(); ++t) ++b_.ver[t];
    rank_inside();
    b_.onb.assign(b_.n, 0);
    b_.n_onb = 0;
    edges_.reset(b_, prep ? *prep : prepare_growth3(b_));
    const auto& sv = b_.tets[uz(seed)];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges_.add(sv[uz(i)], sv[uz(j)]);
    add(seed);
    for (;;) {
      if (heap_.empty() && !outside_ready_) ready_outside();
      // Outside (labelled so: its own heap): the one-face rule (its fourth vertex is a new point), or
      // the two-face rule into a thin part (crawls()).
      const bool outside = heap_.empty();
      if (outside && out_heap_.empty() && crossing_heap_.empty()) break;
      int t;
      if (!outside) {
        const std::uint32_t r = heap_.pop();
        t = by_rank_[r];
        look_ahead(r);
        if (!heap_.empty()) prefetch(by_rank_[heap_.top()]);
      } else {
        TetHeap& from = crossing_heap_.empty() ? out_heap_ : crossing_heap_;
        t = from.pop(b_.tets).tet;
        if (!from.empty()) prefetch(from.top().tet);
      }
      cell_[uz(t)].queued = 0;
      if (cell_[uz(t)].alive) continue;
      int glued[2];
      const int rule = addable(t, outside, glued);
      if (!rule) continue;
      if (outside) {
        ++s_.grown_outside;
        s_.crawled += rule == 2 ? 1 : 0;
      }
      // A crossing: outside steps toward a part labelled inside that is not in the body yet (the
      // new point has a tetrahedron labelled inside), and the two-face steps that go on with it.
      const bool crossing = outside && (rule == 1 ? touches_inside_[uz(b_.tets[uz(t)][uz(glued[0])])] != 0 : crossing_);
      if (crossing_ && !crossing) end_crossing();
      crossing_ = crossing;
      new_edges(t, rule, glued);
      add(t);
    }
  }

 private:
  // The next pop is most often the heap's top now: its records are fetched while this one is
  // examined (the walk through the heap order reads the tetrahedra at random). (Every helper that
  // only fetches is always_inline: GCC 12 finds such a function free of side effects and deletes
  // its calls before inlining; docs/benchmarks.md, thirty-third 2026-12-07 session.)
  [[gnu::always_inline]] void prefetch(int t) const {
    __builtin_prefetch(&cell_[uz(t)]);
    __builtin_prefetch(&b_.nbr[uz(t)]);
    __builtin_prefetch(&b_.tets[uz(t)]);
  }
  // The inside tetrahedra pop nearly in rank order (RankQueue), so the ones a few steps ahead are
  // known: their records are fetched in three waves (each wave's addresses come from the loads
  // of the one before), so that the misses of several steps overlap instead of following each
  // other. Only fetches: what the growth does is unchanged.
  [[gnu::always_inline]] void look_ahead(std::uint32_t r) const {
    const std::size_t n = by_rank_.size();
    if (r + kFar < n) {
      const int u = by_rank_[r + kFar];
      __builtin_prefetch(&b_.nbr[uz(u)]);
      __builtin_prefetch(&b_.tets[uz(u)]);
      __builtin_prefetch(&cell_[uz(u)]);
    }
    if (r + kMid < n) {
      const int u = by_rank_[r + kMid];
      for (int m : b_.nbr[uz(u)])
        if (m >= 0 && uz(m) < b_.T0) __builtin_prefetch(&cell_[uz(m)]);
      for (int x : b_.tets[uz(u)]) edges_.prefetch_size(x);
      __builtin_prefetch(&b_.state[uz(u)], 1);
      __builtin_prefetch(&b_.ver[uz(u)], 1);
    }
    if (r + kNear < n) {
      const int u = by_rank_[r + kNear];
      for (int x : b_.tets[uz(u)]) {
        __builtin_prefetch(&b_.onb[uz(x)], 1);
        edges_.prefetch_list(x);
      }
    }
  }
  static constexpr std::size_t kFar = 24, kMid = 12, kNear = 5;
  bool in_body(int t) const { return t >= 0 && uz(t) < b_.T0 && cell_[uz(t)].alive; }
  // 1 / 2: t can join the body glued along one / two faces (their indices in glued); 0: it cannot.
  // outside (labelled so): the two-face rule only into a thin part (crawls()).
  int addable(int t, bool outside, int glued[2]) const {
    int ng = 0;
    for (int i = 0; i < 4; ++i)
      if (in_body(b_.nbr[uz(t)][uz(i)])) {
        if (ng < 2) glued[ng] = i;
        ++ng;
      }
    const auto& v = b_.tets[uz(t)];
    if (ng == 1) return b_.onb[uz(v[uz(glued[0])])] ? 0 : 1;
    if (ng == 2 && !edges_.has(v[uz(glued[0])], v[uz(glued[1])])) return !outside || crawls(t) ? 2 : 0;
    return 0;
  }
  // An outside tetrahedron glued along two faces joins too (the two-face rule) when it opens the
  // way into a thin part: it is small (bridge ratio at most kCrawlRatio) and, once it is in, a
  // tetrahedron beyond one of its free faces, as small, is glued along that face alone and brings
  // in a point not yet in the body, or is glued along two faces and opens the way in turn
  // (kCrawlDepth such steps ahead). A wall about a spacing thick has no inside the labels can see
  // (the balls of its tetrahedra reach through both its faces), and each of its tetrahedra has
  // its four points on both faces: the one-face rule alone cannot walk along it, and its points
  // were reached by large steps across the gap to the nearest part instead (sheets of long faces;
  // docs/reconstruction-3d.md §4.11).
  bool crawls(int t, int depth = 0) const {
    if (depth == 0 && -key(t) > kCrawlRatio) return false;
    for (int i = 0; i < 4; ++i) {
      const int m = b_.nbr[uz(t)][uz(i)];
      if (m < 0 || uz(m) >= b_.T0 || in_body(m) || cell_[uz(m)].inside) continue;
      int glued = 0, apex = -1;  // (after t: glued along their common face and `glued` others)
      for (int j = 0; j < 4; ++j) {
        const int w = b_.nbr[uz(m)][uz(j)];
        if (w == t) apex = b_.tets[uz(m)][uz(j)];
        else if (in_body(w)) ++glued;
      }
      if (apex < 0 || bridge_ratio3(*b_.pts, *spacing_, b_.tets[uz(m)]) > kCrawlRatio) continue;
      if (glued == 0 && !b_.onb[uz(apex)]) return true;
      if (glued == 1 && depth < kCrawlDepth && crawls(m, depth + 1)) return true;
    }
    return false;
  }
  // The edges t brings into the body, glued by the one-face rule (the three from its new apex,
  // the vertex opposite the glued face) or the two-face rule (its free edge, joining the vertices
  // opposite the glued faces); its other edges are on its glued faces already.
  void new_edges(int t, int rule, const int glued[2]) {
    const auto& v = b_.tets[uz(t)];
    if (rule == 1) {
      for (int i = 0; i < 4; ++i)
        if (i != glued[0]) edges_.add(v[uz(glued[0])], v[uz(i)]);
    } else {
      edges_.add(v[uz(glued[0])], v[uz(glued[1])]);
    }
  }
  double key(int t) const {
    if (cell_[uz(t)].inside) return inside_key(uz(t));
    // Outside: the smallest first, by the size ratio of the bridge measure (longest edge over the
    // largest nearest-neighbour distance of its vertices). Measured against "least confident
    // first" on the shared models and their random halves and quarters (docs/reconstruction-3d.md
    // §4.9): the labels are near 1 on both a thin part's own tetrahedra and those across a gap.
    return -bridge_ratio3(*b_.pts, *spacing_, b_.tets[uz(t)]);
  }
  // Inside tetrahedra: by the largest circumradius first (ln r, clamped below at kMinLogRadius),
  // equal keys by the smallest sorted vertex ids (a geometric key, as TetHeap).
  double inside_key(std::size_t t) const { return kInsideKeyBase + std::max(kMinLogRadius, l_.lrad[t]); }
  // The inside tetrahedra in the order the growth takes them (by_rank_), and each one's rank (a
  // strict total order: the same ranks whatever the sort does, on any number of threads).
  void rank_inside() {
    struct Item {
      std::uint64_t key;  // the complemented bits of inside_key (> 0): ascending as the key descends
      int tet;
    };
    // The inside tetrahedra with their keys, in index order (fixed blocks: counts, then each
    // block written at its offset).
    constexpr std::size_t kBlock = std::size_t{1} << 16;
    const std::size_t blocks = (b_.T0 + kBlock - 1) / kBlock;
    std::vector<std::size_t> at(blocks + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k)
        for (std::size_t t = k * kBlock, e = std::min(b_.T0, t + kBlock); t < e; ++t) at[k + 1] += cell_[t].inside;
    });
    for (std::size_t k = 0; k < blocks; ++k) at[k + 1] += at[k];
    BigArray<Item> order;
    order.allocate(at[blocks]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        std::size_t i = at[k];
        for (std::size_t t = k * kBlock, e = std::min(b_.T0, t + kBlock); t < e; ++t) {
          if (!cell_[t].inside) continue;
          // (inside_key >= kInsideKeyBase + kMinLogRadius > 0: its bits order as its values)
          std::uint64_t bits;
          const double key = inside_key(t);
          std::memcpy(&bits, &key, sizeof bits);
          order[i++] = Item{~bits, static_cast<int>(t)};
        }
      }
    });
    bucket_sort(
        order, [](const Item& x) { return x.key; },
        [&](const Item& x, const Item& y) {
          if (x.key != y.key) return x.key < y.key;
          return sorted4(b_.tets[uz(x.tet)]) < sorted4(b_.tets[uz(y.tet)]);
        });
    by_rank_.resize(order.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 1 << 14),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          by_rank_[k] = order[k].tet;
                          cell_[uz(order[k].tet)].rank = static_cast<std::uint32_t>(k);
                        }
                      });
    heap_.reset(order.size());
  }
  // The outside tetrahedra met so far go to their own heap once no inside one is left (their keys
  // need the spacing: the engine's, computed beside the labels, or computed here). With every
  // point in the body none of them can join.
  void ready_outside() {
    if (fill_conf_ > 0 && b_.n_onb < b_.n) join_pockets();
    outside_ready_ = true;
    if (waiting_.empty() || b_.n_onb == b_.n) {
      waiting_.clear();
      return;
    }
    if (given_spacing_ == nullptr) own_spacing_ = nearest_spacing3(b_);
    mark_large_inside_regions();
    spacing_ = given_spacing_ ? given_spacing_ : &own_spacing_;
    for (int m : waiting_)
      if (!cell_[uz(m)].alive) out_heap_.push({key(m), m, 0}, b_.tets);
      else cell_[uz(m)].queued = 0;
    waiting_.clear();
  }
  // When no inside tetrahedron can join and points are left, they are often inside a pocket of
  // tetrahedra labelled inside that the front closed around (every tetrahedron there next to the
  // body has its four points in the body already, so neither rule adds it). The outside steps would
  // then reach such a point across a gap, or a cavity place it (docs/reconstruction-3d.md §4.13):
  // the fill, in its reaching mode, takes such pockets first, with their points, and its
  // tetrahedra join the growth's state (their edges, their neighbours queued).
  void join_pockets() {
    if (fill_pockets(b_, l_, fill_conf_, s_) == 0) return;
    std::vector<int> joined;
    for (std::size_t t = 0; t < b_.T0; ++t)
      if (b_.state[t] == kAlive && !cell_[t].alive) joined.push_back(static_cast<int>(t));
    for (int t : joined) {
      cell_[uz(t)].alive = 1;
      const auto& v = b_.tets[uz(t)];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if (!edges_.has(v[uz(i)], v[uz(j)])) edges_.add(v[uz(i)], v[uz(j)]);
    }
    for (int t : joined)
      for (int m : b_.nbr[uz(t)])
        if (m >= 0 && uz(m) < b_.T0 && !cell_[uz(m)].alive && !cell_[uz(m)].queued) {
          cell_[uz(m)].queued = 1;
          if (cell_[uz(m)].inside)
            heap_.push(cell_[uz(m)].rank);
          else
            waiting_.push_back(m);
        }
  }
  void add(int t) {
    b_.state[uz(t)] = kAlive;
    cell_[uz(t)].alive = 1;
    ++b_.ver[uz(t)];
    ++s_.grown;
    b_.mark_on_surface(t);
    // A tetrahedron whose glued faces change is examined again; one heap entry per tetrahedron
    // suffices (static key), so the pop order is that of a re-push per change.
    for (int m : b_.nbr[uz(t)])
      if (m >= 0 && uz(m) < b_.T0 && !cell_[uz(m)].alive && !cell_[uz(m)].queued) {
        cell_[uz(m)].queued = 1;
        if (cell_[uz(m)].inside)
          heap_.push(cell_[uz(m)].rank);
        else if (spacing_ != nullptr)
          (crossing_ ? crossing_heap_ : out_heap_).push({key(m), m, 0}, b_.tets);
        else if (!outside_ready_) waiting_.push_back(m);
        // (else: every point was in the body when the inside heap ran dry; none can join.)
      }
  }

  // The points of the regions of tetrahedra labelled inside (connected through their faces) with
  // at least kCrossingRegion tetrahedra not in the body.
  void mark_large_inside_regions() {
    const auto in_region = [&](std::size_t t) { return cell_[t].inside && !cell_[t].alive; };
    UnionFind uf(b_.T0);
    for (std::size_t t = 0; t < b_.T0; ++t)
      if (in_region(t))
        for (int m : b_.nbr[t])
          if (m >= 0 && uz(m) < b_.T0 && in_region(uz(m))) uf.join(static_cast<int>(t), m);
    std::vector<std::uint32_t> size(b_.T0, 0);
    for (std::size_t t = 0; t < b_.T0; ++t)
      if (in_region(t)) ++size[uz(uf.find(static_cast<int>(t)))];
    touches_inside_.assign(b_.n, 0);
    for (std::size_t t = 0; t < b_.T0; ++t)
      if (in_region(t) && size[uz(uf.find(static_cast<int>(t)))] >= kCrossingRegion)
        for (int v : b_.tets[t]) touches_inside_[uz(v)] = 1;
  }
  // A crossing (outside steps since the last inside tetrahedron) has reached the inside again: the
  // outside tetrahedra it met wait with the others.
  void end_crossing() {
    while (!crossing_heap_.empty()) out_heap_.push(crossing_heap_.pop(b_.tets), b_.tets);
  }

  // The body's edges as lists of neighbours per vertex (an edge walk per two-face test was half
  // of the growth's time). Each vertex has room for its Delaunay degree (prepare_growth3).
  class BodyEdges {
   public:
    void reset(const Body3& b, const GrowthPrep3& prep) {
      off_ = prep.edge_room;
      size_.assign(b.n, 0);
      nb_.allocate(off_[b.n]);  // (an entry is read only once written: not zero-filled)
    }
    bool has(int a, int c) const {
      if (size_[uz(c)] < size_[uz(a)]) std::swap(a, c);
      const int* p = nb_.data() + off_[uz(a)];
      const int n = size_[uz(a)];
#if defined(__SSE2__)
      // Four entries per compare: on random samples (17 tetrahedra per point, long lists) the
      // scan was a fifth of the growth's samples; 2 596-2 620 against 2 747-3 034 samples of
      // Growth3::run on a random torus of 3·10^5 points (eight per step measured: no better).
      const __m128i key = _mm_set1_epi32(c);
      int i = 0;
      for (; i + 4 <= n; i += 4)
        if (_mm_movemask_epi8(_mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i)), key)) != 0) return true;
      for (; i < n; ++i)
        if (p[i] == c) return true;
      return false;
#else
      return std::find(p, p + n, c) != p + n;
#endif
    }
    void add(int a, int c) {
      push(a, c);
      push(c, a);
    }
    [[gnu::always_inline]] void prefetch_size(int a) const {
      __builtin_prefetch(&off_[uz(a)]);
      __builtin_prefetch(&size_[uz(a)]);
    }
    [[gnu::always_inline]] void prefetch_list(int a) const { __builtin_prefetch(nb_.data() + off_[uz(a)]); }

   private:
    void push(int a, int c) {
      CONSTRICT_CHECK(off_[uz(a)] + size_[uz(a)] < off_[uz(a) + 1], "growth: a vertex has more body edges than Delaunay edges");
      nb_[off_[uz(a)] + size_[uz(a)]++] = c;
    }
    std::vector<std::size_t> off_;
    std::vector<int> size_;
    BigArray<int> nb_;
  };

  Body3& b_;
  const Labels3& l_;
  Growth3Stats& s_;
  BodyEdges edges_;
  RankQueue heap_;            // inside tetrahedra, by rank (rank_inside)
  std::vector<int> by_rank_;  // the inside tetrahedron of each rank
  TetHeap out_heap_;          // outside ones (only when no inside one is left)
  TetHeap crossing_heap_;     // outside ones met by the current crossing (popped first)
  bool crossing_ = false;     // the last tetrahedron added was a step of a crossing
  std::vector<char> touches_inside_;  // per point: a tetrahedron labelled inside has it
  std::vector<int> waiting_;  // outside tetrahedra met before the first outside step
  bool outside_ready_ = false;
  const std::vector<double>* given_spacing_;  // the engine's spacing, or null
  std::vector<double> own_spacing_;           // else computed at the first outside step
  const std::vector<double>* spacing_ = nullptr;  // the one in use, once outside steps began
  double fill_conf_;                              // the fill's label confidence, or <= 0: no fill during the growth
  // What the growth reads of each Delaunay tetrahedron, in one record of 8 bytes (in separate
  // arrays each neighbour cost four misses): its rank (inside ones), in the body (mirrors state),
  // queued (its key is static: one entry is enough), labelled inside.
  struct Cell {
    std::uint32_t rank;  // (inside: its rank, rank_inside)
    std::uint8_t alive, queued, inside;
  };
  BigArray<Cell> cell_;
};

// Growth lock: a point that no Delaunay tetrahedron can bring into the body (its star is cut off
// from the body by tetrahedra whose fourth vertex is already in it) gets a cone over a body face
// it sees: the star cavity of §3 mirrored to the outside of the body (it re-tetrahedralizes a
// star-shaped region of outside tetrahedra, exactly, and leaves the body unchanged); the cone
// tetrahedron over the body face then joins the body by the one-face rule. Points in ascending
// id, passes while one succeeds.
void place_unreached(Body3& b, const Constrict3Options& opt, Constrict3Visitor* visitor, Growth3Stats& st) {
  CavityState3 cs;
  Cavity3 cavity(b, cs, opt, CavitySide::Outside, visitor);
  cavity.index_vertices();
  CavityMade made;
  for (bool progress = true; progress && b.n_onb < b.n;) {
    progress = false;
    for (std::size_t p = 0; p < b.n; ++p) {
      if (b.onb[p] || !cavity.place(static_cast<int>(p), made)) continue;
      // The cone over the target face (the best-ranked body face p sees) joins the body.
      int cone = -1;
      for (int t : made.created) {
        std::array<int, 3> base{{b.tets[uz(t)][0], b.tets[uz(t)][1], b.tets[uz(t)][2]}};
        std::sort(base.begin(), base.end());
        if (base == made.target) {
          cone = t;
          break;
        }
      }
      CONSTRICT_CHECK(cone >= 0 && b.alive(b.nbr[uz(cone)][3]), "growth cavity without a cone over its target face");
      b.state[uz(cone)] = kAlive;
      ++b.ver[uz(cone)];
      ++st.grown;
      b.mark_on_surface(cone);
      ++st.cavities;
      progress = true;
    }
  }
  st.cavity_capped = cs.capped;
}

}  // namespace

// Each vertex's Delaunay degree, which its star gives by Euler's formula: f tetrahedra and h hull
// faces at the vertex have (f + h) / 2 + 1 neighbours on the hull (a disk link), f / 2 + 2 inside
// (a sphere link).
GrowthPrep3 prepare_growth3(const Body3& b) {
  std::vector<int> f(b.n, 0), h(b.n, 0);
  for (std::size_t t = 0; t < b.T0; ++t)
    for (int i = 0; i < 4; ++i) {
      ++f[uz(b.tets[t][uz(i)])];
      if (b.nbr[t][uz(i)] < 0)
        for (int k = 0; k < 3; ++k) ++h[uz(b.tets[t][uz(kFaceOut[i][k])])];
    }
  GrowthPrep3 prep;
  prep.edge_room.assign(b.n + 1, 0);
  for (std::size_t v = 0; v < b.n; ++v) {
    const int deg = f[v] == 0 ? 0 : h[v] > 0 ? (f[v] + h[v]) / 2 + 1 : f[v] / 2 + 2;
    prep.edge_room[v + 1] = prep.edge_room[v] + static_cast<std::size_t>(deg);
  }
  return prep;
}

bool grow_body3(Body3& body, const Labels3& labels, const Constrict3Options& opt, Constrict3Visitor* visitor,
                Growth3Stats& stats, Tets& nbr_delaunay, const std::vector<double>* spacing, const GrowthPrep3* prep) {
  // (Fallback3::None: the growth's own rules only, no pocket fill and no cavity.)
  Growth3 g(body, labels, stats, spacing, opt.fallback != Fallback3::None ? fill_confidence(opt) : -1.0);
  const int seed = g.seed();
  if (seed < 0) return false;
  g.run(seed, prep);
  if (body.n_onb < body.n && opt.fallback != Fallback3::None) {
    // The pockets once more before the cavities (those the outside steps closed): a cavity would
    // put its tetrahedra into such a pocket, which the fill then can no longer take whole (§4.13).
    fill_pockets(body, labels, fill_confidence(opt), stats);
    if (body.n_onb < body.n) {
      nbr_delaunay = body.nbr;
      place_unreached(body, opt, visitor, stats);
    }
  }
  return body.n_onb == body.n;
}

}  // namespace constrict::detail
