// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D engine's local constriction after a lock (paper §4.3; spec §3.6, §3.7): the grids and
// the Delaunay adjacency it searches, the γ0 graph's side tests and their caches, the candidate
// queues of the γ0 and degree-4 stages, the degree-4 augmentation and the star polygon. The
// ladder that calls them is Constrictor2::Impl::finish_once (constrict2.cpp); the state is
// declared in detail/engine2.hpp. See docs/reconstruction-2d.md §4.
#include <tbb/parallel_invoke.h>

#include <climits>

#include "constrict/detail/apex_lens2.hpp"
#include "constrict/detail/engine2.hpp"
#include "core/detail/ordered_pack.hpp"

namespace constrict {
using detail::closed_segments_meet;
using detail::orient2_fast;
using detail::same_side_collinear;
using engine2::EntryLess;  // (the engine's names: detail/engine2.hpp)

// ---- infrastructure: the boundary edges, the Delaunay adjacency, the grids ----------------------
void Constrictor2::Impl::build_fallback() {
  if (fb_ready) return;
  fb_ready = true;
  out_edge.assign(n, -1);
  for (std::size_t v = 0; v < n; ++v)
    if (onb[v]) {
      out_edge[v] = static_cast<int>(bedges.size());
      bedges.push_back(BEdge{static_cast<int>(v), nxt[v], true});
    }
  // The Delaunay adjacency beside the grids (neither reads the other).
  tbb::parallel_invoke([&] { build_adjacency(); }, [&] { build_grid(); });
  mark.assign(n, 0);
}

void Constrictor2::Impl::build_grid() {
  // The median boundary edge (largest coordinate difference) sizes a sparse grid's cells.
  std::vector<double> len(bedges.size());
  for (std::size_t k = 0; k < bedges.size(); ++k) {
    const double* p = P(bedges[k].u);
    const double* q = P(bedges[k].v);
    len[k] = std::max(std::fabs(p[0] - q[0]), std::fabs(p[1] - q[1]));
  }
  const auto mid = len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2);
  std::nth_element(len.begin(), mid, len.end());
  grid.build(*pts, len.empty() ? 0.0 : *mid);
  // The edges run by their first vertex; the second one's coordinates are a random read, so
  // they are prefetched a few edges ahead.
  grid.add_edges(bedges.size(), [&](std::size_t k, const double*& a, const double*& b, int& id) {
    if (k + kPrefetchAhead < bedges.size()) __builtin_prefetch(P(bedges[k + kPrefetchAhead].v));
    a = P(bedges[k].u);
    b = P(bedges[k].v);
    id = static_cast<int>(k);
  });
}

void Constrictor2::Impl::build_adjacency() {
  if (adj_ready) return;
  CONSTRICT_CHECK(dt.neighbors.size() == dt.triangles.size(),
                  "Constrictor2: the adjacency is asked for after the refinement");
  // Adjacency by counting sort: the counter-clockwise edge u->v of a triangle gives u its
  // neighbour v (the reverse comes from the triangle across), and a hull edge also gives v its
  // neighbour u; so every neighbour comes exactly once. Lists sorted for is_dt_edge(). (Two
  // passes with random reads; in parallel with atomic counters they were slower on 2 cores.)
  adj_off.assign(n + 1, 0);
  const std::size_t nt = dt.triangles.size();
  for (std::size_t t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i) {
      const auto& tr = dt.triangles[t];
      ++adj_off[U(tr[U((i + 1) % 3)]) + 1];
      if (dt.neighbors[t][U(i)] < 0) ++adj_off[U(tr[U((i + 2) % 3)]) + 1];
    }
  for (std::size_t v = 0; v < n; ++v) adj_off[v + 1] += adj_off[v];
  adj.assign(U(adj_off[n]), 0);
  std::vector<int> at(adj_off.begin(), adj_off.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i) {
      const auto& tr = dt.triangles[t];
      const int u = tr[U((i + 1) % 3)], v = tr[U((i + 2) % 3)];
      adj[U(at[U(u)]++)] = v;
      if (dt.neighbors[t][U(i)] < 0) adj[U(at[U(v)]++)] = u;
    }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      std::sort(adj.begin() + adj_off[v], adj.begin() + adj_off[v + 1]);
  });
  adj_ready = true;  // (last: an exception above leaves it unset)
}

// Vertex -> incident triangles (CSR, by triangle index), for the degree-4 augmentation only.
void Constrictor2::Impl::build_vertex_triangles() {
  if (!vt_off.empty()) return;
  vt_off.assign(n + 1, 0);
  for (const auto& tr : dt.triangles)
    for (const int v : tr) ++vt_off[U(v) + 1];
  for (std::size_t v = 0; v < n; ++v) vt_off[v + 1] += vt_off[v];
  vt.assign(U(vt_off[n]), 0);
  std::vector<int> fill(vt_off.begin(), vt_off.end() - 1);
  for (std::size_t t = 0; t < dt.triangles.size(); ++t)
    for (const int v : dt.triangles[t]) vt[U(fill[U(v)]++)] = static_cast<int>(t);
}

int Constrictor2::Impl::add_edge(int u, int v) {
  const int id = static_cast<int>(bedges.size());
  bedges.push_back(BEdge{u, v, true});
  grid.add_edge(P(u), P(v), id);
  return id;
}

// Segment (s, t) with s a boundary vertex and t not: does boundary edge e meet it anywhere
// other than at s (where only a collinear overlap counts)?
bool Constrictor2::Impl::edge_blocks(const BEdge& e, int s, int t) const {
  if (e.u == s || e.v == s) {
    const int o = e.u == s ? e.v : e.u;
    return orient2_fast(P(s), P(o), P(t)) == 0 && same_side_collinear(P(s), P(o), P(t));
  }
  return closed_segments_meet(P(e.u), P(e.v), P(s), P(t));
}

// Can apex y (inside) be inserted into boundary edge a->b? The closed triangle (a,b,y) must be
// empty of other points and no boundary edge may meet the new edges ay, yb (exact). Then the
// triangle lies inside the polygon and the new polygon is simple (docs, "Local insertion").
bool Constrictor2::Impl::valid_insert(int a, int b, int y) const {
  if (onb[U(y)] || !onb[U(a)] || nxt[U(a)] != b) return false;
  const double* pa = P(a);
  const double* pb = P(b);
  const double* py = P(y);
  if (orient2_fast(pa, pb, py) <= 0) return false;
  // Only the cells the triangle and its new edges cross (Grid::points_in_hull, any_edge): the
  // same points and edges are tested as over the whole bounding box, far fewer cells are read.
  const double* tri[3] = {pa, pb, py};
  bool empty = true;
  grid.points_in_hull(
      tri, 3,
      [&](int p) {
        if (!empty || p == a || p == b || p == y) return;
        const double* pp = P(p);
        if (orient2_fast(pa, pb, pp) >= 0 && orient2_fast(pb, py, pp) >= 0 && orient2_fast(py, pa, pp) >= 0)
          empty = false;
      },
      [&] { return !empty; });
  if (!empty) return false;
  for (const int s : {a, b})
    if (grid.any_edge(P(s), py, [&](int id) {
          const BEdge& e = bedges[U(id)];
          return e.alive && !(e.u == a && e.v == b) && edge_blocks(e, s, y);
        }))
      return false;
  return true;
}

// The edge a->b leaves the grid too: a dead edge left in its cells was read by every later query
// there, and insertions at one vertex of a long fan (an outlier inside a sampled circle, joined
// to arc point after arc point) piled up thousands of long dead edges along it (10^6 points,
// 1 % outliers: 40 000 edges read per query).
void Constrictor2::Impl::insert_point(int a, int b, int y) {
  const int dead = out_edge[U(a)];
  bedges[U(dead)].alive = false;
  grid.remove_edge(P(bedges[U(dead)].u), P(bedges[U(dead)].v), dead);
  out_edge[U(a)] = add_edge(a, y);
  out_edge[U(y)] = add_edge(y, b);
  splice_boundary(a, y, b);
}

// Vertices within k DT hops of the seeds (marks them with a fresh stamp).
std::vector<int> Constrictor2::Impl::neighbourhood(const std::vector<int>& seeds, int k, bool through_hubs) {
  ++mark_stamp;
  std::vector<int> out;
  for (int s : seeds)
    if (mark[U(s)] != mark_stamp) {
      mark[U(s)] = mark_stamp;
      out.push_back(s);
    }
  std::size_t lo = 0;
  for (int d = 0; d < k; ++d) {
    const std::size_t hi = out.size();
    if (lo == hi) break;
    for (std::size_t q = lo; q < hi; ++q) {
      if (!through_hubs && hub(out[q])) continue;
      for (int w = adj_off[U(out[q])]; w < adj_off[U(out[q]) + 1]; ++w) {
        const int v = adj[U(w)];
        if (mark[U(v)] != mark_stamp) {
          mark[U(v)] = mark_stamp;
          out.push_back(v);
        }
      }
    }
    lo = hi;
  }
  return out;
}

// Side values of pair (i, j), i < j (spec §2.1; exact signs), over the points within distance
// `radius` of the midpoint (ring search on the grid; the true minimum on a side is found
// whenever it is attained inside the radius). Points with apex value below g lie within
// below_bound(|ij|, g) of the midpoint (they see ij under a wider angle), which ends the search
// early once both sides have a value.
void Constrictor2::Impl::side_values_within(int i, int j, double radius, double& ga, double& gb, bool& blocked) {
  const double* a = P(i);
  const double* b = P(j);
  ga = 1;
  gb = 1;
  blocked = false;
  const double mx = 0.5 * a[0] + 0.5 * b[0], my = 0.5 * a[1] + 0.5 * b[1];  // no overflow
  const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
  const double cs = grid.cell_size();
  auto cut = [&] { return std::max(below_bound(len, ga), below_bound(len, gb)) + cs; };
  // A cell wholly beyond the radius and the cutoff holds nothing to find (the cutoff only
  // shrinks as the minima fall).
  grid.rings(
      mx, my, [&] { return std::min(radius, cut()); }, side_visitor(i, j, ga, gb, blocked), [&] { return blocked; });
}

void Constrictor2::Impl::merge_fresh_caches() {
  for (SideCaches& f : fresh_caches) {
    for (auto& [k, v] : f.side) shared_caches.side.insert_or_assign(k, v);
    for (auto& [k, v] : f.witness) shared_caches.witness.insert_or_assign(k, v);
    f.side.clear();
    f.witness.clear();
  }
}

void Constrictor2::Impl::sides_below(int i, int j, double t, double& ga, double& gb, bool& blocked,
                                     const SideCaches& shared, SideCaches& fresh) const {
  auto& side_cache = fresh.side;
  const std::uint64_t key = detail::edge_key(i, j);
  if (const SideCache* c = cached(fresh.side, shared.side, key, [t](const SideCache& e) { return answers(e, t); })) {
    ga = c->ga;
    gb = c->gb;
    blocked = c->blocked;
    return;
  }
  const double* a = P(i);
  const double* b = P(j);
  ga = 1;
  gb = 1;
  blocked = false;
  auto visit = side_visitor(i, j, ga, gb, blocked);
  // The points under one side's arc for threshold tv (ApexLens2), up to height cap: the cells
  // of its cover (cut at that height), and in them the test of each point's offsets.
  bool partial = false;  // both sides below t: Δ < t decided, the search ends
  auto done = [&] { return blocked || partial; };
  auto scan = [&](double side, double tv, double cap) {
    const detail::ApexLens2 lens(a, b, tv);
    const double h = std::min(lens.height(), cap);
    static_assert(detail::ApexLens2::kMaxCover <= detail::kMaxHullVertices, "the lens cover is one grid query");
    double q[detail::ApexLens2::kMaxCover][2];
    int m = 0;
    lens.cover(side, h, q, m);
    const double* v[detail::ApexLens2::kMaxCover] = {};
    for (int k = 0; k < m; ++k) v[k] = q[k];
    auto inside = [&](int p) {
      if (done() || !lens.may_hold(P(p), side, h)) return;
      visit(p);
      partial = ga < t && gb < t;
    };
    grid.points_in_hull(v, m, inside, done);
    return h;
  };
  // Layers of growing height, nearest the segment first (the widest angles, so the smallest
  // values, are there); a side is complete once its layers reach the top of the arc of its
  // value so far (or of t): then its value is exact below t. A side without a value below t
  // is not completed once the other side has one: delta_at_least then asks only whether it has
  // a point below -m > 0 > t (witness_below), which a point below t would be too; the entry
  // answers no other threshold then.
  const double full = detail::ApexLens2(a, b, t).height();
  double scanned[2] = {-1, -1};  // height read on the left, right side
  bool one_sided = false;
  for (const double part : {1.0 / 64, 1.0 / 8, 1.0}) {
    for (int k = 0; k < 2 && !done(); ++k) {
      const double g = std::min(k == 0 ? ga : gb, t), other = k == 0 ? gb : ga;
      if (scanned[k] >= detail::ApexLens2(a, b, g).height()) continue;
      if (g == t && other < t) {
        one_sided = true;
        continue;
      }
      scanned[k] = scan(k == 0 ? 1 : -1, g, part * full);
    }
    if (done()) break;
  }
  if (!done())
    one_sided = one_sided && !(scanned[0] >= detail::ApexLens2(a, b, std::min(ga, t)).height() &&
                               scanned[1] >= detail::ApexLens2(a, b, std::min(gb, t)).height());
  side_cache[key] = SideCache{ga, gb, blocked, t, partial, one_sided && !done()};
}

double Constrictor2::Impl::reach(int i, int j, double g) const {
  const double len = std::hypot(P(j)[0] - P(i)[0], P(j)[1] - P(i)[1]);
  return below_bound(len, g) + grid.cell_size();
}

// Δ(u, v) = filtration value (spec §2.2); -inf for a blocked pair. Exhaustive when a side is
// empty (used only by the degree-4 ranking, on few pairs).
double Constrictor2::Impl::delta(int u, int v) {
  const std::uint64_t key = detail::edge_key(u, v);
  auto it = delta_cache.find(key);
  if (it != delta_cache.end()) return it->second;
  const int i = std::min(u, v), j = std::max(u, v);
  double ga = 1, gb = 1;
  bool blocked = false;
  side_values_within(i, j, HUGE_VAL, ga, gb, blocked);
  // A second pass bounded by the values found is not needed: the first pass is exhaustive.
  const double d = blocked ? -HUGE_VAL : filtration_value(ga, gb);
  delta_cache.emplace(key, d);
  return d;
}

// Δ(u, v) >= gamma0 (< 0) with two bounded searches: first all points with apex value < gamma0;
// if a side m < gamma0 exists, the pair is in iff the other side is >= |m| (magnitude rule of
// filtration_value), decided by the points with apex value < |m|.
bool Constrictor2::Impl::delta_at_least(int u, int v, double gamma0, const SideCaches& shared,
                                        SideCaches& fresh) const {
  const int i = std::min(u, v), j = std::max(u, v);
  double ga, gb;
  bool blocked;
  // m below is the exact minimum whenever m < gamma0 (sides_below).
  sides_below(i, j, gamma0, ga, gb, blocked, shared, fresh);
  if (blocked) return false;
  // Both sides below gamma0: the smaller m < gamma0 and the other side < gamma0 < 0 <= -m, out
  // by the magnitude rule (also from a partial search).
  if (ga < gamma0 && gb < gamma0) return false;
  const double m = std::min(ga, gb);  // (below gamma0 on one side only from here on)
  if (m >= gamma0) return true;
  // In iff the other side has no point with value < -m. -m can be close to 1, where the region
  // to search is nearly the whole half-plane: stop at the first witness instead (the usual
  // answer); only pairs with a nearly empty other side are searched far.
  // The other side's answer is a property of the pair (m is its exact minimum): kept for the
  // later stages of the γ0 schedule, which test the same pairs again.
  const int side = ga == m ? -1 : 1;
  const std::uint64_t key = detail::edge_key(i, j);
  if (const WitnessCache* c = cached(fresh.witness, shared.witness, key,
                                     [&](const WitnessCache& e) { return e.side == side && e.thr == -m; }))
    return !c->found;
  const bool found = witness_below(i, j, side, -m);
  fresh.witness[key] = WitnessCache{side, -m, found};
  return !found;
}

// Is there a point p with orient2(x_i, x_j, p) == side and apex value < thr, or a point in the
// open segment ij? Ring search around the midpoint, nearest cells first, first witness wins.
bool Constrictor2::Impl::witness_below(int i, int j, int side, double thr) const {
  const double* a = P(i);
  const double* b = P(j);
  const double mx = 0.5 * a[0] + 0.5 * b[0], my = 0.5 * a[1] + 0.5 * b[1];  // no overflow
  const double far = reach(i, j, thr);
  bool found = false;
  auto visit = [&](int p) {
    if (found || p == i || p == j) return;
    const int o = orient2_fast(a, b, P(p));
    if (o == 0) {
      if (diametral_side2(a, b, P(p)) < 0) found = true;
      return;
    }
    if (o == side && apex_gamma2(a, b, P(p)) < thr) found = true;
  };
  // The DT neighbours of the pair's ends first: on a long pair's other side, the points next
  // to its ends see it under a right angle or so, witnesses for any threshold above 0.
  for (const int w : {i, j})
    for (int q = adj_off[U(w)]; q < adj_off[U(w) + 1] && !found; ++q) visit(adj[U(q)]);
  if (found) return true;
  grid.rings(
      mx, my, [far] { return far; }, visit, [&] { return found; });
  return found;
}

// ---- local constriction: the candidate queues of the γ0 and degree-4 stages ---------------------
bool Constrictor2::Impl::in_graph(Graph g, double gamma0, int u, int v) {
  if (g == Graph::Complete) return true;
  if (is_dt_edge(u, v)) return true;
  if (g == Graph::Degree4) return aug.count(detail::edge_key(u, v)) > 0;
  if (const int known = gamma0_answer(u, v); known >= 0) return known == 1;
  const bool in = delta_at_least(u, v, gamma0, shared_caches, shared_caches);
  gamma0_known.emplace(detail::edge_key(u, v), in);
  return in;
}

// Δ(u, v) < gamma0 (< 0) shown by the DT neighbours of u and v alone: a point on the open
// segment, or points with apex value below gamma0 on both sides (the magnitude rule, as for a
// partial search in delta_at_least). Exact; false when these few points do not decide it.
// At most opt.fallback_witness_reads neighbours of each end are read (the first ones of its
// sorted list): a point of thousands of neighbours (an outlier inside a sampled curve, a
// cluster's point facing a long arc) is an end of most pairs near it, and reading its whole
// list for each of them made the stage quadratic (a circle of 10^5 points with 1 % outliers:
// 20 s). Any subset gives the same insertions: a pair this test does not rule out is tested
// exactly when it comes out of the heap (test_candidate).
bool Constrictor2::Impl::outside_near(int u, int v, double gamma0) const {
  if (is_dt_edge(u, v)) return false;
  double ga = 1, gb = 1;
  bool blocked = false;
  auto visit = side_visitor(u, v, ga, gb, blocked);
  const int reads = opt.fallback_witness_reads == 0 || opt.fallback_witness_reads > static_cast<std::size_t>(INT_MAX)
                        ? INT_MAX
                        : static_cast<int>(opt.fallback_witness_reads);
  for (const int w : {u, v})
    for (int q = adj_off[U(w)], end = adj_off[U(w)] + std::min(reads, adj_off[U(w) + 1] - adj_off[U(w)]); q < end;
         ++q) {
      visit(adj[U(q)]);
      if (blocked || (ga < gamma0 && gb < gamma0)) return true;
    }
  return false;
}

// In the γ0 and degree-4 stages a candidate is queued by its key alone and tested when it comes
// out of the heap (test_candidate): most stuck points are placed by their best candidate, so
// the others, among them the long pairs across an empty interior whose side searches are the
// fallback's main cost, are never tested. The same insertions in the same order as testing
// before queueing: the graph tests are properties of the pair and the stage, and a valid
// insertion only becomes invalid (valid_insert), so a candidate that fails when it is queued
// fails when it comes out. The repair's candidates (every boundary edge within k hops, k up to
// N) are tested before queueing, so that its heap holds only the valid ones.
void Constrictor2::Impl::push_candidate(Heap& h, Graph g, double gamma0, int a, int z) {
  Entry e;
  if (candidate(g, gamma0, a, z, e) && (g != Graph::Complete || test_candidate(e, g, gamma0))) {
    h.push(e);
    ++stage_candidates;
  }
}

// The entry of boundary edge a->nxt[a] and stuck point z, unless ruled out at once.
bool Constrictor2::Impl::candidate(Graph g, double gamma0, int a, int z, Entry& e) const {
  const int b = nxt[U(a)];
  if (b < 0 || onb[U(z)]) return false;
  if (orient2_fast(P(a), P(b), P(z)) <= 0) return false;
  if (g != Graph::Complete && needle(a, b, z)) return false;  // left to the repair
  // Witnesses among the endpoints' neighbours rule most pairs out at once (a long pair across
  // an empty interior has very obtuse angles behind both ends), which keeps the heap small.
  if (g == Graph::Gamma0 && (outside_near(a, z, gamma0) || outside_near(b, z, gamma0))) return false;
  e = Entry{criterion_key(a, b, z), sorted_gid3(a, b, z), a, b, z, -1, 0};
  return true;
}

// Is the triangle (a, b, z) a needle: |az| or |bz| longer than opt.fallback_needle_ratio · |ab|?
// Exact (compare_gap2). Such an insertion joins z to an edge far across the region still inside.
bool Constrictor2::Impl::needle(int a, int b, int z) const {
  const double t = opt.fallback_needle_ratio;
  if (!(t > 0) || !std::isfinite(t)) return false;
  const double* ab[2] = {P(a), P(b)};
  return compare_gap2(P(z), P(a), &ab[0], &ab[1], 1, t) > 0 || compare_gap2(P(z), P(b), &ab[0], &ab[1], 1, t) > 0;
}

// The graph test (its side searches read little, sides_below) before the geometric one, which
// rejects few and reads a long candidate's whole strip.
bool Constrictor2::Impl::test_candidate(const Entry& e, Graph g, double gamma0) {
  const int a = e.a, b = e.b, z = e.y;
  if (!entry_live(e)) return false;
  const std::array<int, 2> ends = test_ends(e);
  if (!graph_implied(g, gamma0) && (!in_graph(g, gamma0, ends[0], z) || !in_graph(g, gamma0, ends[1], z))) return false;
  return valid_insert(a, b, z);
}

// The order in which an entry's two pairs (a, z), (b, z) are tested: the shorter one first. Both
// must be in the graph, so the order changes no answer; a short pair's side search reads few
// points, and it fails as often (an arc point joined to a hub inside a sampled circle: the long
// pair from the hub reads the arc, the short one is out at once).
std::array<int, 2> Constrictor2::Impl::test_ends(const Entry& e) const {
  auto d2 = [&](int u) {
    const double dx = P(u)[0] - P(e.y)[0], dy = P(u)[1] - P(e.y)[1];
    return dx * dx + dy * dy;
  };
  if (d2(e.b) < d2(e.a)) return {{e.b, e.a}};
  return {{e.a, e.b}};
}

// Candidate boundary edges for apex z: those with an endpoint within k hops of z (their start
// vertices, ascending), from the vertices within k hops (in any order).
std::vector<int> Constrictor2::Impl::candidate_starts(const std::vector<int>& region) const {
  std::vector<int> starts;
  for (int u : region)
    if (onb[U(u)]) {
      starts.push_back(u);
      starts.push_back(prv[U(u)]);
    }
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  return starts;
}

// Is a boundary vertex within two DT hops of z, by the hops of within_hops(z, 2, through_hubs)?
// Without it z has no candidate (candidate_starts of that region is empty): most stuck points of
// a deep lock are far from the boundary, and this asks without building and sorting the region
// (a noisy spiral of 10^6 points: 190 000 stuck points per stage, about 180 ms each stage).
bool Constrictor2::Impl::boundary_within_two_hops(int z, bool through_hubs) const {
  if (!through_hubs && hub(z)) return false;
  for (int q = adj_off[U(z)]; q < adj_off[U(z) + 1]; ++q) {
    const int w = adj[U(q)];
    if (onb[U(w)]) return true;
    if (!through_hubs && hub(w)) continue;
    for (int r = adj_off[U(w)]; r < adj_off[U(w) + 1]; ++r)
      if (onb[U(adj[U(r)])]) return true;
  }
  return false;
}

// The vertices within k DT hops of z, without the shared marks (for the side-by-side first heap;
// k is 2 there): each hop adds the neighbours of all so far (but hubs' unless through_hubs), then
// sorts and dedups. The same set as neighbourhood({z}, k, through_hubs).
std::vector<int> Constrictor2::Impl::within_hops(int z, int k, bool through_hubs) const {
  std::vector<int> all{z};
  for (int d = 0; d < k; ++d) {
    const std::size_t m = all.size();
    for (std::size_t i = 0; i < m; ++i)
      if (through_hubs || !hub(all[i]))
        for (int w = adj_off[U(all[i])]; w < adj_off[U(all[i]) + 1]; ++w) all.push_back(adj[U(w)]);
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
  }
  return all;
}

// The first heap of a stage: every stuck point's candidates. For the γ0 and degree-4 graphs
// they are made side by side (candidate() reads only), by fixed blocks of stuck points joined
// in order; the heap's order is a strict total order of the entries (key, then the sorted
// input ids: two entries of one triangle would need its apex both stuck and on the boundary),
// so the pops do not depend on how the heap was filled. The repair tests each candidate in
// full (valid_insert, read-only) before queueing: side by side too in its first round (k = 2:
// a noisy spiral of 10^6 points tested 261 000 in 2 s there), in sequence in the later ones
// (within_hops re-reads every vertex at each hop).
auto Constrictor2::Impl::first_heap(Graph g, double gamma0, int k) -> Heap {
  std::vector<int> stuck;
  for (std::size_t z = 0; z < n; ++z)
    if (!onb[z]) stuck.push_back(static_cast<int>(z));
  Heap h;
  if (g == Graph::Complete && k > 2) {
    for (const int z : stuck)
      for (const int a : candidate_starts(neighbourhood({z}, k))) push_candidate(h, g, gamma0, a, z);
    return h;
  }
  constexpr std::size_t kBlock = 256;  // stuck points per block (thousands at 10^6)
  std::vector<Entry> all = detail::ordered_pack<Entry>(
      stuck.size(),
      [&](std::size_t i, auto&& push) {
        Entry e;
        if (k == 2 && !boundary_within_two_hops(stuck[i], through_hubs(g))) return;
        for (const int a : candidate_starts(within_hops(stuck[i], k, through_hubs(g))))
          if (candidate(g, gamma0, a, stuck[i], e) && (g != Graph::Complete || valid_insert(e.a, e.b, e.y))) push(e);
      },
      kBlock);
  stage_candidates += all.size();
  return Heap(EntryLess{}, std::move(all));
}

// The γ0 graph tests of the next entries of the heap, side by side; in_graph then finds their
// answers. An answer is a property of the pair and the stage (delta_at_least, whatever its
// caches hold), so the insertions are those of testing each entry as it comes out, on any
// thread count; a test of an entry that a nearer insertion makes dead is wasted, not wrong.
// Dead entries met on the way are dropped (they would fail when they come out). Each batch
// (at most kMaxTestsAhead) pops and pushes its entries.
void Constrictor2::Impl::graph_tests_ahead(Heap& h, double gamma0, std::size_t count) {
  std::vector<Entry> ahead;
  while (!h.empty() && ahead.size() < count) {
    const Entry e = h.top();
    h.pop();
    if (entry_live(e)) ahead.push_back(e);
  }
  // Per entry its two pairs in test order (test_ends); answers: -1 untested, 0, 1.
  std::vector<std::array<signed char, 2>> res(ahead.size(), {{-1, -1}});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ahead.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
    SideCaches& fresh = fresh_caches.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      for (int s = 0; s < 2; ++s) {
        const int u = test_ends(ahead[i])[U(s)], z = ahead[i].y;
        const int known = gamma0_answer(u, z);  // (gamma0_known is only read here)
        const bool in = known >= 0 ? known == 1 : delta_at_least(u, z, gamma0, shared_caches, fresh);
        if (known < 0) res[i][U(s)] = static_cast<signed char>(in);
        if (!in) break;
      }
  });
  merge_fresh_caches();
  for (std::size_t i = 0; i < ahead.size(); ++i) {
    for (int s = 0; s < 2; ++s)
      if (res[i][U(s)] >= 0)
        gamma0_known.emplace(detail::edge_key(test_ends(ahead[i])[U(s)], ahead[i].y), res[i][U(s)] == 1);
    h.push(ahead[i]);
  }
}

// Does the entry's γ0 graph test still need a search (a pair not yet answered, the first of
// the two in graph)?
bool Constrictor2::Impl::graph_pending(const Entry& e) const {
  for (const int u : test_ends(e)) {
    const int known = gamma0_answer(u, e.y);
    if (known < 0) return true;
    if (known == 0) return false;
  }
  return false;
}

// Constricts the region still inside by inserting stuck points into boundary edges, widest
// apex angle first (same criterion as §3.4; spec §3.6 "cheaper variant"). Returns points placed.
std::size_t Constrictor2::Impl::local_constrict(Graph g, double gamma0, int k, const std::string& stage) {
  emit(Constrict2Event::Kind::StageBegin, -1, -1, -1, 0, stage.c_str());
  gamma0_known.clear();
  stage_candidates = 0;
  Heap h = first_heap(g, gamma0, k);
  std::size_t placed = 0;
  for (std::size_t popped = 1; !h.empty() && n_onb < n; ++popped) {
    if ((popped & 255) == 0 && cancelled()) break;  // (finish() then returns no result)
    if (g == Graph::Gamma0 && !graph_implied(g, gamma0) && opt.fallback_tests_ahead > 0 && entry_live(h.top()) &&
        graph_pending(h.top()))
      graph_tests_ahead(h, gamma0, std::min<std::size_t>(opt.fallback_tests_ahead, kMaxTestsAhead));
    if (h.empty()) break;
    const Entry e = h.top();
    h.pop();
    if (!test_candidate(e, g, gamma0)) continue;  // validity only decays (spec §3.6)
    insert_point(e.a, e.b, e.y);
    ++placed;
    emit(Constrict2Event::Kind::InsertPoint, e.a, e.b, e.y, e.key, stage.c_str());
    // Only the two new edges are new candidates; stuck points near them get them offered.
    for (int z : neighbourhood({e.a, e.y, e.b}, k, through_hubs(g))) {
      if (onb[U(z)]) continue;
      push_candidate(h, g, gamma0, e.a, z);
      push_candidate(h, g, gamma0, e.y, z);
    }
  }
  return placed;
}

// Degree-4 augmentation (spec §3.7), restricted to vertices within two hops of the stuck points
// (only edges at a stuck point can be used by a removal; degrees cascade in index order).
void Constrictor2::Impl::augment_degree4() {
  build_vertex_triangles();
  std::vector<int> stuck;
  for (std::size_t v = 0; v < n; ++v)
    if (!onb[v]) stuck.push_back(static_cast<int>(v));
  std::vector<int> verts = neighbourhood(stuck, 2);
  std::sort(verts.begin(), verts.end(), [&](int l, int r) { return G(l) < G(r); });
  std::unordered_map<int, int> extra;  // added degree
  auto degree = [&](int v) { return adj_off[U(v) + 1] - adj_off[U(v)] + extra[v]; };
  auto apex_across = [&](int t, int a, int b) -> int {  // apex of the triangle across edge ab of t
    const auto& tr = dt.triangles[U(t)];
    for (int i = 0; i < 3; ++i)
      if (tr[U(i)] != a && tr[U(i)] != b) {
        const int nb = dt.neighbors[U(t)][U(i)];
        if (nb < 0) return -1;
        for (int q : dt.triangles[U(nb)])
          if (q != a && q != b) return q;
      }
    return -1;
  };
  auto neighbour_tri = [&](int t, int a, int b) -> int {
    const auto& tr = dt.triangles[U(t)];
    for (int i = 0; i < 3; ++i)
      if (tr[U(i)] != a && tr[U(i)] != b) return dt.neighbors[U(t)][U(i)];
    return -1;
  };
  for (std::size_t i = 0; i < verts.size(); ++i) {
    if ((i & 63) == 63 && cancelled()) return;  // (finish() then returns no result)
    const int v = verts[i];
    const int d = degree(v);
    if (d >= 4) continue;
    std::vector<int> cand;
    const int nt = vt_off[U(v) + 1] - vt_off[U(v)];
    for (int q = vt_off[U(v)]; q < vt_off[U(v) + 1]; ++q) {
      const int t = vt[U(q)];
      const auto& tr = dt.triangles[U(t)];
      int a = -1, b = -1;
      for (int x : tr)
        if (x != v) {
          if (a < 0)
            a = x;
          else
            b = x;
        }
      const int c = apex_across(t, a, b);
      if (c < 0) continue;
      cand.push_back(c);
      if (nt == 1) {  // hull vertex of degree 2: also look beyond (a, b, c)
        const int t2 = neighbour_tri(t, a, b);
        const int c1 = apex_across(t2, a, c), c2 = apex_across(t2, b, c);
        if (c1 >= 0) cand.push_back(c1);
        if (c2 >= 0) cand.push_back(c2);
      }
    }
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    std::vector<std::pair<double, int>> ranked;
    for (int w : cand)
      if (w != v && !is_dt_edge(v, w) && !aug.count(detail::edge_key(v, w))) ranked.emplace_back(delta(v, w), w);
    std::sort(ranked.begin(), ranked.end(), [&](const auto& l, const auto& r) {
      return l.first != r.first ? l.first > r.first : G(l.second) < G(r.second);
    });
    for (std::size_t r = 0; r < ranked.size() && static_cast<int>(r) < 4 - d; ++r) {
      if (ranked[r].first == -HUGE_VAL) break;  // blocked pair: in no graph
      aug.insert(detail::edge_key(v, ranked[r].second));
      ++extra[v];
      ++extra[ranked[r].second];
    }
  }
}

// Last resort (never observed): a star-shaped polygon around the lowest point; always simple.
void Constrictor2::Impl::star_polygon() {
  std::vector<int> ord;
  int o = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double* p = P(static_cast<int>(i));
    const double* q = P(o);
    if (p[1] < q[1] || (p[1] == q[1] && p[0] < q[0])) o = static_cast<int>(i);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (static_cast<int>(i) != o) ord.push_back(static_cast<int>(i));
  const double* po = P(o);
  auto closer = [&](int p, int q) {  // p, q collinear with o on the same ray
    const double* a = P(p);
    const double* b = P(q);
    return a[0] != b[0] ? std::fabs(a[0] - po[0]) < std::fabs(b[0] - po[0]) : a[1] < b[1];
  };
  std::sort(ord.begin(), ord.end(), [&](int p, int q) {
    const int s = orient2_fast(po, P(p), P(q));
    if (s != 0) return s > 0;
    return closer(p, q);
  });
  // Points on the last ray go outward-in so the polygon closes without overlap.
  std::size_t first_last = ord.size() - 1;
  while (first_last > 0 && orient2_fast(po, P(ord[first_last - 1]), P(ord.back())) == 0) --first_last;
  std::reverse(ord.begin() + static_cast<std::ptrdiff_t>(first_last), ord.end());
  ord.insert(ord.begin(), o);
  for (std::size_t i = 0; i < n; ++i) {
    const int a = ord[i], b = ord[(i + 1) % n];
    nxt[U(a)] = b;
    prv[U(b)] = a;
    onb[U(a)] = 1;
  }
  n_onb = n;
}

}  // namespace constrict
