// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D engine's state, Constrictor2::Impl, and the types it is made of. The state is declared
// here once; the methods are grouped by the file that implements them:
// - constrict2.cpp: the Delaunay stage (spec §3.5), the fallback ladder (finish) and the results;
// - fallback2.cpp: the local constriction after a lock (paper §4.3; spec §3.6, §3.7): the grids,
//   the γ0 graph tests, the candidate queues, the degree-4 augmentation and the star polygon
//   (its grids: grid2.hpp).
// Private to those two files.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
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

#include "constrict/constrict.hpp"
#include "constrict/criterion.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "constrict/detail/grid2.hpp"
#include "constrict/detail/segments2.hpp"
#include "core/detail/edge_key.hpp"
#include "core/detail/quad_heap.hpp"

namespace constrict {
namespace engine2 {
using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

inline std::array<int, 3> sorted3(int a, int b, int c) {
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
using TriHeap = detail::TwoTierHeap<TriEntry, TriEntryLess>;

}  // namespace engine2

// Vertex ids inside the engine are *ranked* ids: the order of CGAL's spatially sorted insertion
// (build_delaunay2_ranked), so that the triangle loops, the heap and the walks along the polygon
// touch nearby memory (input ids are in arbitrary, often shuffled order). Every order-sensitive
// decision (heap ties, the degree-4 cascade, where the polygon starts) compares input ids
// through gid, and every result leaves in input ids: the output is the same as with input ids.
struct Constrictor2::Impl {
  using Entry = engine2::Entry;
  using Heap = engine2::Heap;
  using TriEntry = engine2::TriEntry;
  using TriEntryLess = engine2::TriEntryLess;
  using TriHeap = engine2::TriHeap;
  using TieKeys = engine2::TieKeys;
  using Grid = engine2::Grid;

  // The Delaunay stage's state (constrict2.cpp).
  const PointSet* pts = nullptr;  // the ranked points (== &rpts)
  PointSet rpts;
  std::vector<int> gid;  // ranked id -> input id
  Constrict2Options opt;
  Constrict2Visitor* visitor = nullptr;
  // Set by a caller that may drop the result (detail::reconstruct2_sharing): once it reads true,
  // finish() stops at the next check and returns kCancelled (no result).
  const std::atomic<bool>* cancel = nullptr;
  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
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
  int scale_exp = 0;                         // rpts = ranked input * 2^-scale_exp (exact; init)
  Constrict2Event event;                     // reused by emit()
  bool visitor_triangles = true;             // visitor->wants_triangles(), asked by init()
  std::unique_ptr<Polygon2Result> finished;  // the result of the first finish()

  // The Delaunay adjacency (built beside the constriction, or at the lock; freed by the
  // refinement or at the end of finish).
  bool adj_ready = false;
  std::vector<int> adj_off, adj;  // DT adjacency (CSR)

  // Fallback state (built on lock; fallback2.cpp).
  bool fb_ready = false;
  std::vector<int> vt_off, vt;    // vertex -> incident triangles (CSR)
  Grid grid;
  struct BEdge {
    int u, v;
    bool alive;
  };
  std::vector<BEdge> bedges;
  std::vector<int> out_edge;  // boundary edge id of (v, nxt[v])
  std::unordered_map<std::uint64_t, double> delta_cache;
  std::unordered_set<std::uint64_t> aug;  // degree-4 augmentation edges
  std::vector<unsigned> mark;
  unsigned mark_stamp = 0;
  static constexpr std::size_t kPrefetchAhead = 16;  // build_grid's prefetch distance, in edges
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
  struct SideCache {
    double ga, gb;
    bool blocked;
    double below;
    bool partial, one_sided;
  };
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
  // Graph predicate for the edges (apex, boundary vertex) of a candidate triangle.
  enum class Graph { Gamma0, Degree4, Complete };
  // The γ0 graph's answers of this stage (in_graph, graph_tests_ahead), by pair.
  std::unordered_map<std::uint64_t, bool> gamma0_known;
  std::size_t stage_candidates = 0;  // candidates queued in the current fallback stage (Constrict2Stage)
  static constexpr std::size_t kMaxTestsAhead = 1024;  // graph_tests_ahead's batch, at most

  // ---------------------------------------------------------------- inline helpers
  // Defined here because the two files' inner loops call them: the ids and points (both files),
  // emit, criterion_key and the removability of a triangle (the constriction's loop), the side
  // searches' visitor and caches, the γ0 answers and the entries' liveness (the fallback's).
  const double* P(int i) const { return (*pts)[static_cast<std::size_t>(i)]; }
  static std::size_t U(int i) { return static_cast<std::size_t>(i); }
  int G(int v) const { return v < 0 ? v : gid[U(v)]; }
  std::array<int, 3> sorted_gid3(int a, int b, int c) const { return engine2::sorted3(G(a), G(b), G(c)); }
  // stage: a C string, so that the million removals without a visitor build no std::string;
  // with one (the CLI's progress), the event is reused and its stage name copied only when the
  // stage changes.
  void emit(Constrict2Event::Kind k, int a, int b, int y, double crit, const char* stage) {
    if (!visitor) return;
    event.kind = k;
    if (visitor_triangles) {
      event.triangle = {{G(a), G(b), G(y)}};
      event.criterion = crit;
    }
    if (event.stage != stage) event.stage = stage;
    visitor->on_event(event);
  }
  // Key of removing triangle (a, b, y) through boundary edge a->b: 1 - γ(ab; y) (§3.4) or the
  // chosen comparison criterion (criterion.hpp); the fallbacks use the same key.
  double criterion_key(int a, int b, int y) const {
    if (opt.criterion == Criterion::Gamma) return 1.0 - apex_gamma2(P(a), P(b), P(y));
    return criterion_key2(opt.criterion, P(a), P(b), P(y));
  }
  bool is_boundary_edge(int t, int i) const {
    const int nb = dt.neighbors[U(t)][U(i)];
    return nb < 0 || !alive[U(nb)];
  }
  // Removable ⇔ exactly one boundary edge and its opposite vertex not on the boundary (§3.3).
  int removable_edge(int t) const {
    if (!alive[U(t)]) return -1;
    int cnt = 0, which = -1;
    for (int i = 0; i < 3; ++i)
      if (is_boundary_edge(t, i)) {
        ++cnt;
        which = i;
      }
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
  // The heap's top after a pop is most often the next pop: its state, adjacency and vertices
  // are fetched while this removal is made (the pops read the triangles in key order, at random).
  [[gnu::always_inline]] void prefetch_triangle(std::uint32_t t) const {
    __builtin_prefetch(&ver[t]);
    __builtin_prefetch(&alive[t]);
    __builtin_prefetch(&dt.neighbors[t]);
    __builtin_prefetch(&dt.triangles[t]);
  }
  // Point y joins the boundary between a and b = nxt[a] (a removal through edge a->b, or a
  // fallback insertion).
  void splice_boundary(int a, int y, int b) {
    nxt[U(a)] = y;
    prv[U(y)] = a;
    nxt[U(y)] = b;
    prv[U(b)] = y;
    onb[U(y)] = 1;
    ++n_onb;
  }
  bool is_dt_edge(int u, int v) const {
    return std::binary_search(adj.begin() + adj_off[U(u)], adj.begin() + adj_off[U(u) + 1], v);
  }
  // The visitor that folds point p into the side values of pair (i, j).
  auto side_visitor(int i, int j, double& ga, double& gb, bool& blocked) const {
    return [this, i, j, &ga, &gb, &blocked](int p) {
      if (p == i || p == j) return;
      const double* a = P(i);
      const double* b = P(j);
      const int o = detail::orient2_fast(a, b, P(p));
      if (o == 0) {
        if (diametral_side2(a, b, P(p)) < 0) blocked = true;
        return;
      }
      const double g = apex_gamma2(a, b, P(p));
      if (o > 0)
        ga = std::min(ga, g);
      else
        gb = std::min(gb, g);
    };
  }
  static bool answers(const SideCache& c, double t) {
    if (c.blocked) return true;
    if (c.partial) return c.ga < t && c.gb < t;
    return t <= c.below && (!c.one_sided || std::min(c.ga, c.gb) < t);
  }
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
  // Pair (u, v)'s answer in this γ0 stage if known without a search: 1 (a Delaunay edge, or
  // answered in), 0 (answered out), -1 (not yet).
  int gamma0_answer(int u, int v) const {
    if (is_dt_edge(u, v)) return 1;
    const auto it = gamma0_known.find(detail::edge_key(u, v));
    return it == gamma0_known.end() ? -1 : it->second ? 1 : 0;
  }
  // Is the entry's triangle still one to insert? (It only stops being one: spec §3.6.)
  bool entry_live(const Entry& e) const { return !onb[U(e.y)] && onb[U(e.a)] && nxt[U(e.a)] == e.b; }

  // ---------------------------------------------------------------- constrict2.cpp
  Status init(const PointSet& points);
  bool step_untimed();
  bool step();
  void run_all();
  std::vector<int> boundary_list() const;
  Status finish(Polygon2Result& r);
  Status finish_once(Polygon2Result& r);
  void release_stepping_state();
  PointSet input_points() const;
  std::vector<int> inside_input_ids() const;

  // ---------------------------------------------------------------- fallback2.cpp
  void build_fallback();
  void build_grid();
  void build_adjacency();
  void build_vertex_triangles();
  int add_edge(int u, int v);
  bool edge_blocks(const BEdge& e, int s, int t) const;
  bool valid_insert(int a, int b, int y) const;  // (read-only: called side by side)
  void insert_point(int a, int b, int y);
  // The vertices within k DT hops of the seeds; through_hubs false: a hub's neighbours are not
  // reached through it (the γ0 and degree-4 stages' candidates; the repair reaches everything).
  std::vector<int> neighbourhood(const std::vector<int>& seeds, int k, bool through_hubs = true);
  // A vertex of more than kHubDegree Delaunay neighbours (an outlier inside a sampled curve sees
  // a whole arc): "near" it says nothing, and every insertion at it offered its whole arc again.
  static constexpr int kHubDegree = 64;
  bool hub(int v) const { return adj_off[U(v) + 1] - adj_off[U(v)] > kHubDegree; }
  // Which stages' candidate regions hop through hubs: only the repair's (it must reach everything).
  static bool through_hubs(Graph g) { return g == Graph::Complete; }
  void side_values_within(int i, int j, double radius, double& ga, double& gb, bool& blocked);
  void merge_fresh_caches();
  void sides_below(int i, int j, double t, double& ga, double& gb, bool& blocked, const SideCaches& shared,
                   SideCaches& fresh) const;
  double reach(int i, int j, double g) const;
  double delta(int u, int v);
  bool delta_at_least(int u, int v, double gamma0, const SideCaches& shared, SideCaches& fresh) const;
  bool witness_below(int i, int j, int side, double thr) const;
  bool in_graph(Graph g, double gamma0, int u, int v);
  // The graph test of a candidate is implied by valid_insert: for the complete graph, and for
  // γ0 = -1, where Δ >= -1 holds for every pair but a blocked one (a point on the open segment,
  // spec §2.1), and such a point lies in the closed triangle that valid_insert requires empty.
  // (The side searches of γ0 = -1 read the whole strip of each pair: 825 M points on a noisy
  // spiral of 10^6 points, 21 s.)
  static bool graph_implied(Graph g, double gamma0) {
    return g == Graph::Complete || (g == Graph::Gamma0 && gamma0 <= -1);
  }
  bool outside_near(int u, int v, double gamma0) const;
  void push_candidate(Heap& h, Graph g, double gamma0, int a, int z);
  bool candidate(Graph g, double gamma0, int a, int z, Entry& e) const;
  bool needle(int a, int b, int z) const;
  bool test_candidate(const Entry& e, Graph g, double gamma0);
  std::vector<int> candidate_starts(const std::vector<int>& region) const;
  std::vector<int> within_hops(int z, int k, bool through_hubs) const;
  bool boundary_within_two_hops(int z, bool through_hubs) const;
  Heap first_heap(Graph g, double gamma0, int k);
  void graph_tests_ahead(Heap& h, double gamma0, std::size_t count);
  std::array<int, 2> test_ends(const Entry& e) const;
  bool graph_pending(const Entry& e) const;
  std::size_t local_constrict(Graph g, double gamma0, int k, const std::string& stage);
  void augment_degree4();
  void star_polygon();
};

}  // namespace constrict
