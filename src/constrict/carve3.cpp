// SPDX-License-Identifier: GPL-3.0-or-later
// Stages "carve" and "fill" of the 3D engine (docs/reconstruction-3d.md §4.6, §4.7).
// The constriction rules keep the surface a 2-manifold at every single removal, which blocks the
// "bridges": regions labelled outside whose vertices are all on the surface already (removing
// any of their tetrahedra pinches a vertex). The carve takes each connected region of outside
// tetrahedra from the surface inwards, through non-manifold intermediate states, and keeps the
// state only where it is valid again: every vertex touched has a single-cycle surface link
// (vertex- and edge-manifold, still in the body) and the surface has 2N-4 faces (Euler
// characteristic 2). The region's removals after its last valid state are undone. Connectivity
// is checked once at the end. The fill is the mirror image after the growth: it adds the regions
// of inside tetrahedra the body left out; a region whose end state is invalid at a few vertices
// only is first repaired by single toggles at those vertices (docs/reconstruction-3d.md §4.9).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <queue>
#include <set>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "constrict/detail/stages3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/link_cycle.hpp"

namespace constrict::detail {
namespace {

// Rounds of putting back the removals at non-manifold vertices before a region is undone.
constexpr int kRepairRounds = 16;
// Block of the parallel set-up passes (tetrahedra or points).
constexpr std::size_t kSetupGrain = std::size_t{1} << 14;
// Moves at a pinched vertex (star_moves): the most tetrahedra one move toggles, the most
// non-manifold vertices a handle's region may end its peel with for them to be tried, and the
// most moves taken in a row.
constexpr std::size_t kStarMoveMax = 24;
constexpr std::size_t kStarMoveMaxBad = 2;
constexpr int kStarRounds = 4;
// The fill's local repair: regions with at most this many bad vertices, at most this many single
// toggles kept, at most this many tried per region.
constexpr std::size_t kLocalMaxBad = 8, kLocalTrials = 4096, kLocalMaxBadHandles = 32, kLocalTrialsPerPoint = 4;
constexpr int kLocalSteps = 16;

enum class Toggle { Remove, Add };  // carve: take tetrahedra out of the body; fill: put them in
// Genus0: a valid state is a closed genus-0 2-manifold through every point (F = 2N - 4, manifold
// vertices). Handles: any genus (manifold vertices, every point in the body); a region's end
// state is then kept only when it changed the topology (F grew: a handle) and `decide` agrees.
enum class Rule { Genus0, Handles };

class Regions {
 public:
  // Candidates: the Delaunay tetrahedra with sign * score >= threshold (carve: label >= min_conf;
  // fill: -label >= min_conf; bridges: edge ratio >= the bridge ratio), most scored first.
  Regions(Body3& b, const std::vector<float>& score, float sign, double threshold, Toggle dir, Carve3Stats& st,
          Rule rule = Rule::Genus0, const HandleDecision* decide = nullptr, bool local_repair = true)
      : b_(b), score_(score), sign_(sign), min_conf_(threshold), add_(dir == Toggle::Add), s_(st), rule_(rule),
        decide_(decide), local_repair_(add_ && local_repair) {}
  // The fill during the growth (fill_inside3's `reach`): points not yet in the body may stay out,
  // and a valid state has 2R - 4 faces over the R points in it (every one manifold).
  Regions& reaching() {
    reach_ = add_ && rule_ == Rule::Genus0;
    return *this;
  }
  // The fill: a region it had to undo, in part or whole, is peeled a second time from where it
  // settled, by `lrad` (ln circumradius), largest first.
  Regions& second_try_by(const std::vector<double>& lrad) {
    if (add_ && rule_ == Rule::Genus0) by_radius_ = &lrad;
    return *this;
  }

  // Runs the pass; returns false when the start state is not a valid surface (nothing done).
  // Precondition (both callers: after a complete constriction or growth): every vertex of the
  // start state is manifold — only the vertices a toggle touches are evaluated, and the edge
  // flips (valid_flip) not even those.
  bool run() {
    index_vertex_tets();
    // The surface faces, and the body tetrahedra of each point (from its list: the carve's lists
    // hold the body's tetrahedra only, the fill's every one not replaced).
    F_ = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, b_.tets.size(), kSetupGrain), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t f) {
          for (std::size_t t = r.begin(); t != r.end(); ++t)
            if (b_.state[t] == kAlive) f += uz(b_.surface_faces_of(static_cast<int>(t)));
          return f;
        },
        [](std::size_t a, std::size_t c) { return a + c; });
    alive_at_.assign(b_.n, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b_.n, kSetupGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v != r.end(); ++v) {
                          int k = 0;
                          for (int j = vt_off_[v]; j < vt_off_[v + 1]; ++j) k += b_.state[uz(vt_idx_[uz(j)])] == kAlive;
                          alive_at_[v] = k;
                        }
                      });
    std::size_t in_body = b_.n;
    if (reach_)
      in_body =
          static_cast<std::size_t>(std::count_if(alive_at_.begin(), alive_at_.end(), [](int k) { return k > 0; }));
    targetF_ = 2 * in_body - 4;
    if (rule_ == Rule::Genus0 && F_ != targetF_) return false;
    anchor_.assign(b_.tets.size(), 0);
    if (!add_) choose_anchors();
    seen_.assign(b_.tets.size(), 0);
    touched_at_.assign(b_.tets.size(), 0);
    bad_of_.assign(b_.n, 0);
    dirty_.assign(b_.n, 0);
    work_budget_ = kWorkPerIncidence * vt_idx_.size() + kWorkFloor;
    for (std::size_t s0 = 0; s0 < b_.T0; ++s0) {
      if (over_budget()) {  // the state is valid here (every region ends valid): stop
        s_.capped = true;
        break;
      }
      if (seen_[s0] || !cand(static_cast<int>(s0))) continue;
      if (!collect_region(static_cast<int>(s0))) continue;
      ++s_.regions;
      const std::size_t F0 = F_;
      regionF0_ = F0;
      pinched_ = false;
      peel_region();
      const std::size_t bad_peel = nbad_;
      if (local_repair_) local_search();
      const std::size_t bad_search = nbad_;
      repair_and_settle();
      if (by_radius_ && !over_budget() && region_still_open()) {
        // The fill's second try of a region it did not add whole (its repair took back or undid
        // some of it): the peel again from the state the first one settled in, largest
        // circumball first (docs/reconstruction-3d.md §4.16).
        retry_ = true;
        peel_region();
        if (local_repair_) local_search();
        repair_and_settle();
        retry_ = false;
      }
      if (rule_ == Rule::Handles && debug_)
        std::fprintf(stderr,
                     "handle region: %zu tets (%s), bad points after the peel %zu, after the search %zu, F %+lld\n",
                     region_.size(), add_ ? "add" : "remove", bad_peel, bad_search,
                     static_cast<long long>(F_) - static_cast<long long>(F0));
      if (rule_ == Rule::Handles) decide_region(F0);
      for (int t : touched_) touched_at_[uz(t)] = 0;
      touched_.clear();
    }
    s_.capped = s_.capped || over_budget();  // (also when the last region's search reached it)
    return true;
  }

 private:
  bool outside_label(std::size_t t) const { return t < b_.T0 && sign_ * score_[t] >= min_conf_; }
  bool cand(int t) const {
    if (add_) return uz(t) < b_.T0 && b_.state[uz(t)] == kOutside && outside_label(uz(t));
    return b_.alive(t) && outside_label(uz(t)) && !anchor_[uz(t)];
  }
  // Label order: most confident first (outside: largest label; inside: smallest); the fill's
  // second try: largest circumball first.
  double prio(int t) const { return retry_ ? (*by_radius_)[uz(t)] : static_cast<double>(sign_ * score_[uz(t)]); }
  // Carve: a body tetrahedron with a surface face; fill: an outside one glued to the body (it has
  // fewer than 4 surface faces).
  bool at_front(int t) const {
    return add_ ? !b_.alive(t) && b_.surface_faces_of(t) < 4 : b_.alive(t) && b_.surface_faces_of(t) > 0;
  }

  // The body tetrahedra of each vertex (the fill's: every one not replaced), ascending. Fixed
  // blocks of tetrahedra count their vertices, then each block writes its tetrahedra in order at
  // its offset in each vertex's list: no atomics and no sort (they were a third of the carve on
  // the 10^6 ellipsoid), the same lists on any thread count.
  void index_vertex_tets() {
    const auto in = [&](std::size_t t) { return add_ ? b_.state[t] != kReplaced : b_.state[t] == kAlive; };
    const std::size_t T = b_.tets.size(), n = b_.n;
    constexpr std::size_t kBlocks = 4;
    const std::size_t per = (T + kBlocks - 1) / kBlocks;
    std::vector<int> at(kBlocks * n, 0);  // block b's count, then its next slot, of vertex v: at[b * n + v]
    const auto each_block = [&](const auto& f) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kBlocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) f(at.data() + b * n, b * per, std::min(T, (b + 1) * per));
      });
    };
    each_block([&](int* c, std::size_t t0, std::size_t t1) {
      for (std::size_t t = t0; t < t1; ++t)
        if (in(t))
          for (int x : b_.tets[t]) ++c[uz(x)];
    });
    vt_off_.assign(n + 1, 0);
    for (std::size_t v = 0; v < n; ++v) {
      int k = 0;
      for (std::size_t b = 0; b < kBlocks; ++b) k += at[b * n + v];
      vt_off_[v + 1] = vt_off_[v] + k;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kSetupGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v != r.end(); ++v) {
                          int next = vt_off_[v];
                          for (std::size_t b = 0; b < kBlocks; ++b) {
                            const int k = at[b * n + v];
                            at[b * n + v] = next;
                            next += k;
                          }
                        }
                      });
    vt_idx_.allocate(uz(vt_off_[n]));  // (every slot written below: not zero-filled)
    each_block([&](int* c, std::size_t t0, std::size_t t1) {
      for (std::size_t t = t0; t < t1; ++t)
        if (in(t))
          for (int x : b_.tets[t]) vt_idx_[uz(c[uz(x)]++)] = static_cast<int>(t);
    });
  }

  // A vertex whose body tetrahedra are all labelled outside (a thin part the labels miss) keeps
  // one of them, its anchor: the one with the shortest longest edge (ties: the smallest index).
  // (The carve's lists hold the body's tetrahedra, ascending; such vertices are few.)
  void choose_anchors() {
    std::vector<int> arg(b_.n, -1);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b_.n, kSetupGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v != r.end(); ++v) {
                          bool keep = true;
                          for (int j = vt_off_[v]; j < vt_off_[v + 1] && keep; ++j)
                            keep = outside_label(uz(vt_idx_[uz(j)]));
                          if (!keep) continue;
                          double best = HUGE_VAL;
                          for (int j = vt_off_[v]; j < vt_off_[v + 1]; ++j) {
                            const int t = vt_idx_[uz(j)];
                            const auto& q = b_.tets[uz(t)];
                            double le = 0;
                            for (int i = 0; i < 4; ++i)
                              for (int k = i + 1; k < 4; ++k) {
                                const double* a = b_.P(q[uz(i)]);
                                const double* c = b_.P(q[uz(k)]);
                                le = std::max(le, (a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) +
                                                      (a[2] - c[2]) * (a[2] - c[2]));
                              }
                            if (le < best) {
                              best = le;
                              arg[v] = t;
                            }
                          }
                        }
                      });
    for (std::size_t v = 0; v < b_.n; ++v)
      if (arg[v] >= 0) anchor_[uz(arg[v])] = 1;
  }

  // Is the surface around v a single disk (the link of v one simple cycle)?
  bool vertex_manifold(int v) {
    if (reach_ && alive_at_[uz(v)] == 0) return true;  // (not in the body: allowed while reaching)
    work_ += uz(vt_off_[uz(v) + 1] - vt_off_[uz(v)]);
    link_.clear();
    for (int k = vt_off_[uz(v)]; k < vt_off_[uz(v) + 1]; ++k) {
      const int t = vt_idx_[uz(k)];
      if (!b_.alive(t)) continue;
      const int li = b_.local_index(t, v);
      for (int i = 0; i < 4; ++i) {
        if (i == li || b_.alive(b_.nbr[uz(t)][uz(i)])) continue;
        std::array<int, 2> e{};
        int c = 0;
        for (int l = 0; l < 4; ++l)
          if (l != i && l != li) e[uz(c++)] = b_.tets[uz(t)][uz(l)];
        link_.push_back(e);
      }
    }
    return link_is_one_cycle(link_);
  }

  // Carve: is removing body tetrahedron t from the current valid state an edge flip of the
  // surface (exactly two surface faces, the edge joining the vertices opposite them not on the
  // surface: the two-face rule, spec gamma-graph.md §3.3)? Then the new state is valid again —
  // the same closed 2-manifold count F, every link still one cycle of at least 3 edges (a link
  // of 3 through the new edge would mean that edge was on the surface already) — and the links of
  // its 4 vertices need no evaluation. Most of a carve's removals are such flips.
  bool valid_flip(int t) const {
    if (!dirty_list_.empty() || nbad_ != 0 || (rule_ == Rule::Genus0 && F_ != targetF_)) return false;
    int si[4], ns = 0;
    for (int i = 0; i < 4; ++i)
      if (!b_.alive(b_.nbr[uz(t)][uz(i)])) si[ns++] = i;
    return ns == 2 && !b_.edge_on_boundary(t, si[0], si[1]);
  }

  // mark_dirty false: the caller knows the links of t's vertices stay single cycles (valid_flip).
  void toggle(int t, bool make_alive, bool mark_dirty = true) {
    if (!touched_at_[uz(t)]) {  // the region's changes, with each tetrahedron's state before it
      touched_at_[uz(t)] = b_.alive(t) ? 2 : 1;
      touched_.push_back(t);
    }
    if (make_alive) {
      for (int x : b_.tets[uz(t)])
        if (++alive_at_[uz(x)] == 1 && reach_) targetF_ += 2;  // (a point brought in)
      b_.state[uz(t)] = kAlive;
      F_ = F_ - 4 + 2 * uz(b_.surface_faces_of(t));
    } else {
      F_ = F_ + 4 - 2 * uz(b_.surface_faces_of(t));
      for (int x : b_.tets[uz(t)])
        if (--alive_at_[uz(x)] == 0 && reach_) targetF_ -= 2;
      b_.state[uz(t)] = kOutside;
    }
    ++b_.ver[uz(t)];
    if (!mark_dirty) return;
    for (int x : b_.tets[uz(t)])
      if (!dirty_[uz(x)]) {
        dirty_[uz(x)] = 1;
        dirty_list_.push_back(x);
      }
  }
  // The manifold flags of the vertices touched since the last flush are evaluated lazily: a valid
  // state needs F == 2N-4 first (O(1)), so long invalid runs (a genus-1 hole carved through,
  // high-degree vertices) do not pay a link evaluation per toggle.
  void flush() {
    for (int x : dirty_list_) {
      dirty_[uz(x)] = 0;
      const char bad = vertex_manifold(x) ? 0 : 1;
      if (bad != bad_of_[uz(x)]) {
        nbad_ = bad ? nbad_ + 1 : nbad_ - 1;
        bad_of_[uz(x)] = bad;
      }
    }
    dirty_list_.clear();
  }
  bool valid_now() {
    if (rule_ == Rule::Genus0 && F_ != targetF_) return false;
    flush();
    return nbad_ == 0;
  }
  // The local search's goal: a valid state, and for a handle's closing region one that changed
  // the topology. A valid state with the region's start count of faces has opened the loop again
  // (the repair took back the tetrahedra that closed it): the search goes on from there.
  static constexpr std::size_t kReopened = 1000;  // above any defect the search starts from
  bool reopened() const { return rule_ == Rule::Handles && add_ && nbad_ == 0 && F_ == regionF0_; }
  bool closed_now() { return valid_now() && !reopened(); }

  // Whether a tetrahedron of the current region is still a candidate (for the fill's second try).
  bool region_still_open() const {
    return std::any_of(region_.begin(), region_.end(), [&](int t) { return cand(t) && at_front(t); });
  }
  // The face-connected region of candidates around s0; false if it does not touch the surface.
  bool collect_region(int s0) {
    region_.clear();
    region_.push_back(s0);
    seen_[uz(s0)] = 1;
    bool touches_surface = false;
    for (std::size_t q = 0; q < region_.size(); ++q)
      for (int m : b_.nbr[uz(region_[q])]) {
        if (add_ ? b_.alive(m) : !b_.alive(m)) {
          touches_surface = true;
        } else if (m >= 0 && !seen_[uz(m)] && cand(m)) {
          seen_[uz(m)] = 1;
          region_.push_back(m);
        }
      }
    return touches_surface;
  }

  // Most confident first, ties -> smaller id; a tetrahedron is toggled once it is at the front
  // (no cavities) and (carve) is not the last body tetrahedron of a vertex.
  void peel_region() {
    std::priority_queue<std::pair<double, int>> pq;
    for (int t : region_)
      if (at_front(t)) pq.push({prio(t), -t});
    pending_.clear();
    while (!pq.empty() && !over_budget()) {
      const int t = -pq.top().second;
      pq.pop();
      if (!at_front(t)) continue;
      bool last = false;
      for (int x : b_.tets[uz(t)]) last = last || (!add_ && alive_at_[uz(x)] == 1);
      if (last) continue;
      toggle(t, add_, add_ || !valid_flip(t));
      pending_.push_back(t);
      for (int m : b_.nbr[uz(t)])
        if (m >= 0 && cand(m)) pq.push({prio(m), -m});
      if (valid_now()) {  // a valid state: keep it
        pending_.clear();
        dimples_.clear();
      }
    }
    flush();
  }

  // The local search's trials of all regions of a pass together: a bound linear in the points
  // (noisy samples have a pocket of inside tetrahedra every few points, each of which may try up to
  // kLocalTrials toggles; measured: at most 0.6 trials per point, noisy frames and igea with noise).
  std::size_t trial_budget() const { return kLocalTrialsPerPoint * b_.n + kLocalTrials; }
  // The non-manifold vertices of the region's pending additions, ascending.
  std::vector<int> bad_vertices() const { return bad_vertices_of(pending_); }
  // ... of the given tetrahedra.
  std::vector<int> bad_vertices_of(const std::vector<int>& tets) const {
    std::vector<int> bad;
    for (int x : tets)
      for (int y : b_.tets[uz(x)])
        if (bad_of_[uz(y)]) bad.push_back(y);
    std::sort(bad.begin(), bad.end());
    bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
    return bad;
  }
  // Fill and handle closing: when the region's end state is not valid only at a few vertices,
  // single toggles at those vertices (adding an outside tetrahedron of the vertex, or taking back
  // one the region added; for a handle also a dimple), each time the one that leaves the fewest
  // non-manifold vertices, while that number drops (for a handle: or stays, under a tabu list).
  std::size_t defect() const {
    if (rule_ == Rule::Handles) return reopened() ? kReopened : nbad_;
    const std::size_t dF = F_ > targetF_ ? F_ - targetF_ : targetF_ - F_;
    return 4 * nbad_ + dF;
  }
  void local_search() {
    flush();
    if (valid_now()) return;
    const bool handles = rule_ == Rule::Handles;
    const std::size_t max_bad = handles ? kLocalMaxBadHandles : kLocalMaxBad;
    if (nbad_ > max_bad) return;
    const int max_steps = handles ? static_cast<int>(2 * max_bad) : kLocalSteps;
    // Trials (each re-evaluates the links of 4 vertices) per region: a bound for the stars of
    // degenerate inputs with thousands of tetrahedra at one point.
    std::size_t trials = 0;
    std::set<int> tabu;
    std::vector<int> mine = pending_;  // the region's additions since the last valid state, sorted
    std::sort(mine.begin(), mine.end());
    // The start, for the moves at pinches below.
    const bool star = nbad_ <= kStarMoveMaxBad;
    const std::vector<int> pending0 = star ? pending_ : std::vector<int>{},
                           dimples0 = star ? dimples_ : std::vector<int>{};
    const std::vector<int> mine0 = star ? mine : std::vector<int>{};
    std::vector<int> walk;
    // (The pass's work bound too: on points along curves in space every trial evaluates links of
    // thousands of tetrahedra; a circle and a point on its axis, 4 000 points, took 77 s here.)
    for (int step = 0; step < max_steps && !closed_now() && trials < kLocalTrials && s_.trials < trial_budget() &&
                       !over_budget();
         ++step) {
      const std::vector<int> bad = bad_vertices();
      if (bad.empty()) return;
      const std::size_t d0 = defect();
      std::size_t best_d = d0;
      int best_t = -1;
      for (int v : bad)
        for (int k = vt_off_[uz(v)]; k < vt_off_[uz(v) + 1]; ++k) {
          const int t = vt_idx_[uz(k)];
          const bool alive = b_.alive(t);
          // Only the region's own additions are taken back; for a handle also a body tetrahedron
          // at the surface (a dimple that uncovers a point the closed loop buried).
          if (alive && !std::binary_search(mine.begin(), mine.end(), t) && (!handles || b_.surface_faces_of(t) == 0))
            continue;
          if (handles && tabu.count(t)) continue;
          if (++trials > kLocalTrials || ++s_.trials > trial_budget() || over_budget()) break;
          toggle(t, !alive);
          flush();
          const std::size_t d = defect();
          toggle(t, alive);
          flush();
          // (A handle may take a sideways step: a closed loop's rim has plateaus of one or two
          // bad vertices; the tabu list keeps the walk from going back.)
          if (d < best_d || (d == best_d && (best_t < 0 ? handles : t < best_t) && (d < d0 || handles))) {
            best_d = d;
            best_t = t;
          }
        }
      if (best_t < 0) break;
      if (handles) tabu.insert(best_t);
      if (star) walk.push_back(best_t);
      const bool alive = b_.alive(best_t);
      toggle(best_t, !alive);
      flush();
      if (!alive) {
        pending_.push_back(best_t);
        mine.insert(std::upper_bound(mine.begin(), mine.end(), best_t), best_t);
      } else if (!std::binary_search(mine.begin(), mine.end(), best_t)) {
        dimples_.push_back(best_t);
      }
      if (closed_now()) {
        pending_.clear();
        dimples_.clear();
        mine.clear();
      }
    }
    // A handle whose single toggles fail at a few pinched vertices (two fans of body tetrahedra
    // around one point): moves of several tetrahedra there (star_moves), the best one while it
    // lowers the defect, when at most kStarMoveMaxBad are left (with many bad vertices such moves
    // let regions through that close several loops at once across a sparse spot). The fill too
    // (docs/reconstruction-3d.md §4.12), with moves that add only tetrahedra labelled inside and
    // take out only the region's own: a pocket inside a sparse tube whose full addition pinches a
    // point or two was left out, and the surface cut through the tube. A region whose
    // peel ended almost valid (star) tries them from where the single toggles started; one whose
    // peel ended with more tries them where the toggles end (they are kept from opening the loop
    // again, so that end still closes it: 2 of 28 noisy tori, chains and links closed this way).
    const bool star_end = !star && nbad_ <= kStarMoveMaxBad;
    if ((!star && !star_end) || closed_now()) return;
    if (star) {
      // (From the start: the single toggles' sideways walk can leave the pinch where no move
      // joins it. When the moves fail as well, the region settles from that start, not from where
      // the walk ended: on the uneven tubes the walk's end once settled into a false loop.)
      for (auto it = walk.rbegin(); it != walk.rend(); ++it) toggle(*it, !b_.alive(*it));
      flush();
      pending_ = pending0;
      dimples_ = dimples0;
      mine = mine0;
    }
    for (int round = 0; round < kStarRounds && !closed_now() && nbad_ <= kStarMoveMaxBad && !over_budget(); ++round) {
      const std::vector<int> bad = bad_vertices();
      const std::size_t d0 = defect();
      std::size_t best_d = d0;
      std::vector<int> best_m;
      for (int v : bad) {
        star_moves(v, moves_);
        for (const auto& m : moves_) {
          if (s_.trials > trial_budget() || over_budget()) break;
          // (The fill: only tetrahedra labelled inside added, only the region's own taken out.
          // Moves through outside ones or the grown body dented a thin tip of a random half of horse.)
          if (!handles && std::any_of(m.begin(), m.end(), [&](int t) {
                return b_.alive(t) ? !std::binary_search(mine.begin(), mine.end(), t)
                                   : !(uz(t) < b_.T0 && sign_ * score_[uz(t)] > 0);
              }))
            continue;
          s_.trials += m.size();
          toggle_all(m);
          const std::size_t d = defect();
          toggle_all(m);
          if (d < best_d) {
            best_d = d;
            best_m = m;
          }
        }
      }
      if (best_m.empty()) return;
      pinched_ = true;
      for (int t : best_m) {
        const bool alive = b_.alive(t);
        toggle(t, !alive);
        if (!alive)
          pending_.push_back(t);
        else if (!std::binary_search(mine.begin(), mine.end(), t))
          dimples_.push_back(t);
      }
      flush();
      if (closed_now()) {
        pending_.clear();
        dimples_.clear();
        mine.clear();
      }
    }
  }

  // A handle's closing region often ends with a vertex whose surface is pinched: its body
  // tetrahedra form two fans (or one fan around a hole of outside ones), so its link is two
  // cycles, and no single toggle joins them. The moves of several tetrahedra around such a
  // vertex v (its star; neighbours through the faces that hold v), each evaluated whole:
  // a component of outside tetrahedra added, a component of body tetrahedra taken out, and the
  // shortest path of tetrahedra of one state that joins two components of the other.
  void star_moves(int v, std::vector<std::vector<int>>& moves) {
    moves.clear();
    star_.clear();
    for (int k = vt_off_[uz(v)]; k < vt_off_[uz(v) + 1]; ++k) star_.push_back(vt_idx_[uz(k)]);
    std::sort(star_.begin(), star_.end());
    const int S = static_cast<int>(star_.size());
    const auto at = [&](int t) {
      const auto it = std::lower_bound(star_.begin(), star_.end(), t);
      return it != star_.end() && *it == t ? static_cast<int>(it - star_.begin()) : -1;
    };
    // Star adjacency (at most 3 neighbours each: the faces through v).
    star_nbr_.assign(uz(S) * 3, -1);
    for (int a = 0; a < S; ++a) {
      const int t = star_[uz(a)], li = b_.local_index(t, v);
      int c = 0;
      for (int i = 0; i < 4; ++i)
        if (i != li) star_nbr_[uz(a) * 3 + uz(c++)] = b_.nbr[uz(t)][uz(i)] >= 0 ? at(b_.nbr[uz(t)][uz(i)]) : -1;
    }
    const auto state = [&](int a) { return b_.alive(star_[uz(a)]) ? 1 : 0; };
    star_comp_.assign(uz(S), -1);
    int ncomp[2] = {0, 0};
    std::vector<int> comp_state, queue;
    for (int a0 = 0; a0 < S; ++a0) {
      if (star_comp_[uz(a0)] >= 0) continue;
      const int id = static_cast<int>(comp_state.size());
      comp_state.push_back(state(a0));
      ++ncomp[state(a0)];
      star_comp_[uz(a0)] = id;
      queue.assign(1, a0);
      for (std::size_t q = 0; q < queue.size(); ++q)
        for (int k = 0; k < 3; ++k) {
          const int b = star_nbr_[uz(queue[q]) * 3 + uz(k)];
          if (b >= 0 && star_comp_[uz(b)] < 0 && state(b) == state(a0)) {
            star_comp_[uz(b)] = id;
            queue.push_back(b);
          }
        }
    }
    // Whole components: an outside one added, a body one taken out (small ones only).
    for (int id = 0; id < static_cast<int>(comp_state.size()); ++id) {
      if (ncomp[comp_state[uz(id)]] < 2 && ncomp[1 - comp_state[uz(id)]] < 2) continue;
      std::vector<int> m;
      for (int a = 0; a < S; ++a)
        if (star_comp_[uz(a)] == id) m.push_back(star_[uz(a)]);
      if (m.size() <= kStarMoveMax) moves.push_back(std::move(m));
    }
    // Paths: through tetrahedra of state x, from a component of the other state to another one.
    for (int x = 0; x < 2; ++x) {
      if (ncomp[1 - x] < 2) continue;
      int c0 = -1;  // the component of the other state holding the smallest tetrahedron
      for (int a = 0; a < S && c0 < 0; ++a)
        if (state(a) != x) c0 = star_comp_[uz(a)];
      const auto touches = [&](int a, bool same) {
        for (int k = 0; k < 3; ++k) {
          const int b = star_nbr_[uz(a) * 3 + uz(k)];
          if (b >= 0 && state(b) != x && (star_comp_[uz(b)] == c0) == same) return true;
        }
        return false;
      };
      std::vector<int> from(uz(S), -2);
      queue.clear();
      for (int a = 0; a < S; ++a)
        if (state(a) == x && touches(a, true)) {
          from[uz(a)] = -1;
          queue.push_back(a);
        }
      int end = -1;
      for (std::size_t q = 0; q < queue.size() && end < 0; ++q) {
        const int a = queue[q];
        if (touches(a, false)) {
          end = a;
          break;
        }
        for (int k = 0; k < 3; ++k) {
          const int b = star_nbr_[uz(a) * 3 + uz(k)];
          if (b >= 0 && state(b) == x && from[uz(b)] == -2) {
            from[uz(b)] = a;
            queue.push_back(b);
          }
        }
      }
      if (end < 0) continue;
      std::vector<int> m;
      for (int a = end; a >= 0; a = from[uz(a)]) m.push_back(star_[uz(a)]);
      if (m.size() <= kStarMoveMax) moves.push_back(std::move(m));
    }
  }
  // Applies a move (toggles each of its tetrahedra) or takes it back.
  void toggle_all(const std::vector<int>& m) {
    for (int t : m) toggle(t, !b_.alive(t));
    flush();
  }

  // Repair: put back toggled tetrahedra at the vertices that are not manifold, latest first, a
  // few rounds; keep the state if it is valid then, else undo back to the last valid state.
  void repair_and_settle() {
    for (int round = 0; round < kRepairRounds && nbad_ > 0 && !pending_.empty() && !over_budget(); ++round)
      for (std::size_t j = pending_.size(); j-- > 0 && nbad_ > 0 && !over_budget();) {
        const int t = pending_[j];
        if (b_.alive(t) != add_) continue;
        bool at_bad = false;
        for (int x : b_.tets[uz(t)]) at_bad = at_bad || bad_of_[uz(x)];
        if (at_bad) {
          toggle(t, !add_);
          flush();
        }
      }
    std::vector<int> still;
    for (int t : pending_)
      if (b_.alive(t) == add_) still.push_back(t);
    const bool keep = nbad_ == 0 && (F_ == targetF_ || rule_ == Rule::Handles);
    if (keep) still.clear();
    // (flush re-evaluates every vertex a toggle touched: the only ones whose links change.) A
    // tetrahedron the local repair took back and added again is in the list twice: undone once.
    for (auto it = still.rbegin(); it != still.rend(); ++it)
      if (b_.alive(*it) == add_) {
        toggle(*it, !add_);
        ++s_.undone;
      }
    if (!keep)
      for (auto it = dimples_.rbegin(); it != dimples_.rend(); ++it)
        if (b_.alive(*it) != add_) toggle(*it, add_);
    dimples_.clear();
    flush();
    CONSTRICT_CHECK((F_ == targetF_ || rule_ == Rule::Handles) && nbad_ == 0, "carve undo did not restore the surface");
  }

  // Handles: keep the region's changes only if they changed the topology (F = 2N - 4c + 4g over
  // c surfaces of total genus g: a handle raises F, a sealed cavity lowers it) and the decision
  // agrees; else put the region back as it was.
  void decide_region(std::size_t F0) {
    collect_changed();
    if (changed_.empty()) return;
    // Carving must not split the body (F would drop); a fill that drops F seals a cavity (an inner
    // shell: the caller decides whether enclosed voids are allowed).
    std::vector<int> trim;
    if (topology_changed(F0) && (*decide_)(b_, changed_, add_, dF_since(F0), pinched_, &trim)) {
      s_.changed += changed_.size();
      return;
    }
    // A refused change whose decision named a part to put back (a closing region that also sealed
    // a void, or closed a second, short loop): the rest, once, if it is a valid state.
    if (!trim.empty() && trimmed_is_kept(trim, F0)) return;
    s_.undone += changed_.size();
    for (int t : changed_) toggle(t, !b_.alive(t));
    flush();
    CONSTRICT_CHECK(F_ == F0 && nbad_ == 0, "handle undo did not restore the surface");
  }
  // The region's tetrahedra whose state differs from the start (changed_).
  void collect_changed() {
    changed_.clear();
    for (int t : touched_)
      if (b_.alive(t) != (touched_at_[uz(t)] == 2)) changed_.push_back(t);
  }
  long long dF_since(std::size_t F0) const { return static_cast<long long>(F_) - static_cast<long long>(F0); }
  bool topology_changed(std::size_t F0) const { return dF_since(F0) > 0 || (add_ && dF_since(F0) < 0); }
  // Puts `trim` back, then the region's changes at the points that leaves non-manifold (the region
  // only shrinks; kTrimRounds rounds), and asks the decision again if that is a valid state. True
  // when the rest is kept; otherwise changed_ holds what differs from the start.
  static constexpr int kTrimRounds = 8;
  bool trimmed_is_kept(const std::vector<int>& trim, std::size_t F0) {
    const auto put_back = [&](int t) {
      if (touched_at_[uz(t)] && b_.alive(t) != (touched_at_[uz(t)] == 2)) toggle(t, !b_.alive(t));
    };
    const std::size_t before = changed_.size();
    for (int t : trim) put_back(t);
    flush();
    for (int round = 0; round < kTrimRounds && nbad_ > 0; ++round) {
      for (int v : bad_vertices_of(touched_))
        for (int k = vt_off_[uz(v)]; k < vt_off_[uz(v) + 1]; ++k) put_back(vt_idx_[uz(k)]);
      flush();
    }
    if (debug_)
      std::fprintf(stderr, "handle trim: %zu tets put back, bad points %zu, F %+lld\n", trim.size(), nbad_, dF_since(F0));
    collect_changed();
    s_.undone += before - changed_.size();  // (the trim only puts back)
    if (nbad_ == 0 && !changed_.empty() && topology_changed(F0) &&
        (*decide_)(b_, changed_, add_, dF_since(F0), pinched_, nullptr)) {
      s_.changed += changed_.size();
      return true;
    }
    return false;
  }

  Body3& b_;
  const std::vector<float>& score_;
  const float sign_;
  const double min_conf_;
  const bool add_;
  Carve3Stats& s_;
  const Rule rule_;
  const HandleDecision* decide_;
  const bool local_repair_;  // fill and handle closing: single-toggle repair of an invalid end state
  const bool debug_ = std::getenv("CONSTRICT_DEBUG_HANDLES") != nullptr;  // (docs/cli.md)
  std::vector<int> changed_;
  // The pass's bound: link evaluations cost the tetrahedra at the vertex (work_), at most
  // kWorkPerIncidence per tetrahedron-vertex incidence of the start plus kWorkFloor. The shared
  // models and their noisy and sparse copies use at most 5; points along a curve in space, whose
  // Delaunay tetrahedra are quadratic in number and meet at every vertex by the thousand, used
  // hundreds (500 points on a helix: 770, 2.2 s; 2 000 points: 207 s). Past the bound the pass
  // stops at its last valid state: the current region's repair is skipped and the region undone.
  // The floor was 2^24 until the fill's local search on a circle and a point on its axis (4 000
  // points, 12 000 tetrahedra, one vertex at thousands of them) spent 4 s within it; the largest
  // use measured stays under 5 per incidence, far below either term.
  static constexpr std::size_t kWorkPerIncidence = 64;
  static constexpr std::size_t kWorkFloor = std::size_t{1} << 20;
  bool over_budget() const { return work_ > work_budget_; }
  std::size_t work_ = 0, work_budget_ = 0;
  std::vector<int> vt_off_;
  BigArray<int> vt_idx_;
  std::size_t F_ = 0, targetF_ = 0, nbad_ = 0;
  std::size_t regionF0_ = 0;   // F before the current region
  std::vector<int> alive_at_;  // body tetrahedra per vertex
  std::vector<char> anchor_, seen_, bad_of_, dirty_;
  std::vector<char> touched_at_;  // 0: not toggled in this region; 1 / 2: outside / alive before
  std::vector<int> touched_;
  std::vector<int> dirty_list_, region_, pending_;
  std::vector<int> dimples_;  // body tetrahedra the handle's local search took out since the last valid state
  std::vector<std::array<int, 2>> link_;
  std::vector<int> star_, star_nbr_, star_comp_;  // star_moves' scratch
  std::vector<std::vector<int>> moves_;
  bool pinched_ = false;  // the region used a move of star_moves
  bool reach_ = false;    // reaching(): points may stay out of the body
  const std::vector<double>* by_radius_ = nullptr;  // second_try_by()
  bool retry_ = false;                              // in the second try
};

std::size_t count_changed(const std::vector<std::uint8_t>& before, const std::vector<std::uint8_t>& after, bool to_alive) {
  std::size_t k = 0;
  for (std::size_t t = 0; t < before.size(); ++t)
    k += to_alive ? (before[t] != kAlive && after[t] == kAlive) : (before[t] == kAlive && after[t] != kAlive);
  return k;
}

}  // namespace

std::size_t carve_outside3(Body3& body, const Labels3& labels, double min_conf, Carve3Stats& stats) {
  const std::vector<std::uint8_t> state0 = body.state;
  if (!Regions(body, labels.label, 1.0f, min_conf, Toggle::Remove, stats).run()) return 0;
  // Every region ends valid and genus 0 (2N-4 faces); a split into a sphere and a torus would
  // also have 2N-4 faces: excluded here (then the whole pass is undone).
  if (!body.side_connected(kAlive)) {
    body.state = state0;
    return 0;
  }
  stats.changed = count_changed(state0, body.state, false);
  return stats.changed;
}

std::size_t fill_inside3(Body3& body, const Labels3& labels, double min_conf, Carve3Stats& stats, bool reach) {
  // Nothing to fill (the usual case): no left-out inside tetrahedron touches the body. Reaching:
  // nothing to reach either unless such a tetrahedron has a point out of the body (a point comes
  // in only with a tetrahedron of its own; the fill after the growth takes the other pockets).
  bool any = false, reachable = !reach;
  for (std::size_t t = 0; t < body.T0 && !(any && reachable); ++t) {
    if (body.state[t] != kOutside || !(labels.label[t] <= -min_conf)) continue;
    for (int m : body.nbr[t]) any = any || body.alive(m);
    for (int x : body.tets[t]) reachable = reachable || !body.onb[uz(x)];
  }
  if (!any || !reachable) return 0;
  const std::vector<std::uint8_t> state0 = body.state;
  Regions regions(body, labels.label, -1.0f, min_conf, Toggle::Add, stats);
  if (reach) regions.reaching();
  regions.second_try_by(labels.lrad);
  if (!regions.run()) return 0;
  // Every region ends valid (2N-4 faces, manifold vertices); a torus-shaped enclosed void would
  // also have 2N-4 faces in total: excluded here (then the whole pass is undone). Reaching, a
  // pocket may also end as a second part of the body, a torus apart from the ball (2R-4 faces in
  // all as well: a thick noisy shell of 3*10^5 points): the body must stay one part.
  stats.changed = count_changed(state0, body.state, true);
  if (stats.changed > 0 && (!body.side_connected(kOutside) || (reach && !body.side_connected(kAlive)))) {
    body.state = state0;
    stats.changed = 0;
  }
  if (reach && stats.changed > 0)  // the points brought in are on the surface (every state is valid)
    for (std::size_t t = 0; t < body.tets.size(); ++t)
      if (body.state[t] == kAlive && state0[t] != kAlive) body.mark_on_surface(static_cast<int>(t));
  return stats.changed;
}

std::size_t handles3(Body3& body, const Labels3& labels, double min_conf, const HandleDecision& decide,
                     Carve3Stats& closed, Carve3Stats& opened, bool local_repair) {
  // Loops first (the genus-0 growth leaves a cut in every handle of the object), then tunnels;
  // each pass only when a candidate touches the surface (usually none: O(T) to find out).
  bool close = false, open = false;
  for (std::size_t t = 0; t < body.T0 && !(close && open); ++t) {
    const float l = labels.label[t];
    const bool alive = body.state[t] == kAlive;
    if (alive ? !(l >= min_conf) : !(l <= -min_conf)) continue;
    for (int m : body.nbr[t])
      if (alive ? !body.alive(m) : body.alive(m)) (alive ? open : close) = true;
  }
  if (close) Regions(body, labels.label, -1.0f, min_conf, Toggle::Add, closed, Rule::Handles, &decide, local_repair).run();
  if (open) Regions(body, labels.label, 1.0f, min_conf, Toggle::Remove, opened, Rule::Handles, &decide).run();
  return closed.changed + opened.changed;
}

}  // namespace constrict::detail
